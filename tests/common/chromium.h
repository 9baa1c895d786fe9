#pragma once
// Headless Chromium (Debian `chromium`) for the browser tests: where it is,
// how to start it on a page with a fresh profile (the DOM after load to one
// file, its log to another), and the page's console messages in that log.
// The browser tests skip when find_chromium() finds none.
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <memory>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "tests/common/background_process.h"

namespace vesper::test {

// $VESPER_CHROMIUM, else the first of the usual names on PATH; empty if none.
inline std::string find_chromium() {
  if (const char* env = std::getenv("VESPER_CHROMIUM"); env && *env) return env;
  const char* path = std::getenv("PATH");
  std::string dirs = path ? path : "/usr/bin:/bin";
  for (const char* name : {"chromium", "chromium-browser", "google-chrome"}) {
    size_t start = 0;
    while (start <= dirs.size()) {
      const size_t end = std::min(dirs.find(':', start), dirs.size());
      const std::filesystem::path candidate =
          std::filesystem::path(dirs.substr(start, end - start)) / name;
      if (::access(candidate.c_str(), X_OK) == 0) return candidate.string();
      start = end + 1;
    }
  }
  return "";
}

// Chromium's own log lines for page console messages ("INFO:CONSOLE(..)",
// "ERROR:CONSOLE"), and uncaught exceptions.
inline std::vector<std::string> console_lines(const std::string& log) {
  std::vector<std::string> lines;
  static const std::regex console(R"re(:CONSOLE|Uncaught)re");
  std::istringstream in(log);
  for (std::string line; std::getline(in, line);)
    if (std::regex_search(line, console)) lines.push_back(line);
  return lines;
}

struct BrowserRun {
  std::filesystem::path dom, log;
  std::unique_ptr<BackgroundProcess> process;
};

// `extra` flags before the URL (--screenshot=..., --virtual-time-budget=...);
// a fresh profile per run so two can run at once.
inline BrowserRun start_chromium(const std::string& chromium, const std::string& url,
                                 const std::filesystem::path& work, const std::string& name,
                                 const std::vector<std::string>& extra) {
  BrowserRun run{work / (name + ".dom.html"), work / (name + ".log"), nullptr};
  std::vector<std::string> argv{chromium,
                                "--headless",
                                "--disable-gpu",
                                "--no-sandbox",
                                "--no-first-run",
                                "--disable-extensions",
                                "--disable-background-networking",
                                "--user-data-dir=" + (work / (name + "-profile")).string(),
                                "--enable-logging=stderr",
                                "--v=0",
                                "--dump-dom"};
  argv.insert(argv.end(), extra.begin(), extra.end());
  argv.push_back(url);
  run.process = std::make_unique<BackgroundProcess>(argv, run.dom, run.log);
  return run;
}

}  // namespace vesper::test
