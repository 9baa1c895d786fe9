#pragma once
// Reading back what the HTML report wrote: the page's text, its src= targets,
// one section's markup.
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

namespace vesper::test {

inline std::string read_text(const std::filesystem::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

// Every src="..." value, in page order.
inline std::vector<std::string> src_attributes(const std::string& html) {
  std::vector<std::string> out;
  static const std::regex src(R"re(\bsrc="([^"]*)")re");
  for (auto it = std::sregex_iterator(html.begin(), html.end(), src); it != std::sregex_iterator();
       ++it)
    out.push_back((*it)[1].str());
  return out;
}

// The markup from the element with id="<id>" up to the next occurrence of
// `end` (e.g. the next scene's id), or to the end of the page.
inline std::string section_of(const std::string& html, const std::string& id,
                              const std::string& end) {
  const size_t a = html.find("id=\"" + id + "\"");
  if (a == std::string::npos) return "";
  const size_t b = end.empty() ? std::string::npos : html.find(end, a + 1);
  return html.substr(a, b == std::string::npos ? std::string::npos : b - a);
}

inline size_t count_of(const std::string& text, const std::string& what) {
  size_t n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

}  // namespace vesper::test
