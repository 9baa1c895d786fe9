#include "renderer/scene/json_values.h"

#include <cmath>
#include <limits>

namespace vesper {

Vec3d as_vec3(const JsonReader& node) {
  if (!node.json().is_array() || node.size() != 3) {
    node.fail("expected an array of 3 numbers, got " + describe_json(node.json()));
  }
  Vec3d v;
  for (int i = 0; i < 3; ++i) v[i] = node.element(size_t(i)).as_number();
  return v;
}

Rgb as_rgb(const JsonReader& node, const Range& range) {
  if (!node.json().is_array() || node.size() != 3) {
    node.fail("expected an RGB array of 3 numbers, got " + describe_json(node.json()));
  }
  Rgb c;
  for (int i = 0; i < 3; ++i) {
    const JsonReader e = node.element(size_t(i));
    const double v = e.as_number(range);
    // The renderer stores colours as float: a double beyond FLT_MAX would become inf.
    if (std::abs(v) > double(std::numeric_limits<float>::max())) {
      e.fail("expected a number representable as a float, got " + describe_json(e.json()));
    }
    c[i] = float(v);
  }
  return c;
}

Vec3d read_vec3(JsonReader& node, std::string_view key) { return as_vec3(node.child(key)); }

Rgb read_rgb(JsonReader& node, std::string_view key, const Range& component_range) {
  return as_rgb(node.child(key), component_range);
}

Rgb read_rgb(JsonReader& node, std::string_view key, Rgb fallback, const Range& component_range) {
  const auto c = node.optional_child(key);
  return c ? as_rgb(*c, component_range) : fallback;
}

}  // namespace vesper
