#pragma once
// The `cryptomatte/<key>/...` header attributes of an EXR file (read_exr
// keeps only the vesper:* metadata), for comparing two files' manifests.
#include <OpenImageIO/imageio.h>

#include <filesystem>
#include <map>
#include <string>

namespace vesper::test {

inline std::map<std::string, std::string> crypto_header(const std::filesystem::path& exr) {
  std::map<std::string, std::string> out;
  auto in = OIIO::ImageInput::open(exr.string());
  if (!in) return out;
  const OIIO::ImageSpec spec = in->spec();
  for (const auto& attr : spec.extra_attribs) {
    const std::string name = attr.name().string();
    if (name.rfind("cryptomatte/", 0) == 0) out[name] = spec.get_string_attribute(name);
  }
  return out;
}

// How many of them are manifests (one per Cryptomatte type).
inline int manifest_count(const std::map<std::string, std::string>& header) {
  int n = 0;
  for (const auto& [k, v] : header) n += k.ends_with("/manifest") && v.size() > 2;
  return n;
}

}  // namespace vesper::test
