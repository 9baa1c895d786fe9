#pragma once
// The text of a number in the metadata map: the shortest that reads back as
// the same double (std::to_chars), which is also what read_exr() gives for a
// double attribute, so that a written and re-read image has the same map.
#include <array>
#include <charconv>
#include <string>

namespace vesper {

inline std::string metadata_number(double v) {
  std::array<char, 32> buf{};
  const auto r = std::to_chars(buf.data(), buf.data() + buf.size(), v);
  return std::string(buf.data(), r.ptr);
}

// A float attribute's value: the shortest text that reads back as that float.
inline std::string metadata_number(float v) {
  std::array<char, 32> buf{};
  const auto r = std::to_chars(buf.data(), buf.data() + buf.size(), v);
  return std::string(buf.data(), r.ptr);
}

// 16 numbers separated by spaces (a row-major 4x4 matrix), each rounded to
// float as EXR's M44f holds it.
inline std::string metadata_matrix(const std::array<double, 16>& m) {
  std::string out;
  for (double v : m) out += (out.empty() ? "" : " ") + metadata_number(float(v));
  return out;
}

}  // namespace vesper
