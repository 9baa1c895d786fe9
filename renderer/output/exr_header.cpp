#include "renderer/output/exr_header.h"

#include <charconv>
#include <climits>
#include <sstream>

#include "renderer/output/exr_io.h"
#include "renderer/output/metadata_keys.h"
#include "renderer/output/metadata_text.h"

namespace vesper {
namespace {

using metadata_key::metadata_type;
using metadata_key::MetadataType;

template <typename T>
bool parse_number(std::string_view text, T& v) {
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  return !text.empty() && ec == std::errc() && end == text.data() + text.size();
}

bool parse_matrix(const std::string& text, float (&m)[16]) {
  std::istringstream in(text);
  std::string word;
  int n = 0;
  while (in >> word) {
    double v = 0;
    if (n == 16 || !parse_number(std::string_view(word), v)) return false;
    m[n++] = float(v);
  }
  return n == 16;
}

[[noreturn]] void bad_value(const std::string& file, const std::string& key,
                            const std::string& value, const char* expected) {
  throw ImageIoError("cannot write " + file + ": metadata '" + key + "': expected " + expected +
                     ", got '" + value + "'");
}

void put_typed(OIIO::ImageSpec& spec, const std::string& key, const std::string& value,
               const std::string& file) {
  switch (metadata_type(key)) {
    case MetadataType::Text:
      spec.attribute(key, value);
      return;
    case MetadataType::Int: {
      long long v = 0;
      if (!parse_number(std::string_view(value), v)) bad_value(file, key, value, "an integer");
      // EXR's int is 32-bit: a larger count stays exact as text.
      if (v < INT_MIN || v > INT_MAX) return spec.attribute(key, value);
      spec.attribute(key, int(v));
      return;
    }
    case MetadataType::Double: {
      double v = 0;
      if (!parse_number(std::string_view(value), v)) bad_value(file, key, value, "a number");
      spec.attribute(key, OIIO::TypeDesc::DOUBLE, &v);
      return;
    }
    case MetadataType::Matrix44: {
      float m[16];
      if (!parse_matrix(value, m)) bad_value(file, key, value, "16 numbers");
      spec.attribute(key, OIIO::TypeMatrix44, m);
      return;
    }
  }
}

}  // namespace

void put_metadata(OIIO::ImageSpec& spec, const std::map<std::string, std::string>& metadata,
                  const std::string& file) {
  for (const auto& [k, v] : metadata) put_typed(spec, k, v, file);
}

std::string attribute_text(const OIIO::ParamValue& p) {
  const OIIO::TypeDesc t = p.type();
  if (t == OIIO::TypeString) return p.get_string();
  if (t == OIIO::TypeInt) return std::to_string(*static_cast<const int*>(p.data()));
  if (t == OIIO::TypeDesc::DOUBLE) return metadata_number(*static_cast<const double*>(p.data()));
  if (t == OIIO::TypeFloat) return metadata_number(*static_cast<const float*>(p.data()));
  if (t == OIIO::TypeMatrix44) {
    const float* m = static_cast<const float*>(p.data());
    std::array<double, 16> d{};
    for (int i = 0; i < 16; ++i) d[size_t(i)] = m[i];
    return metadata_matrix(d);
  }
  return p.get_string();
}

std::map<std::string, std::string> read_metadata(const OIIO::ImageSpec& spec) {
  std::map<std::string, std::string> out;
  for (const auto& p : spec.extra_attribs) {
    const std::string name = p.name().string();
    if (name.rfind(metadata_key::kPrefix, 0) == 0) out[name] = attribute_text(p);
  }
  return out;
}

}  // namespace vesper
