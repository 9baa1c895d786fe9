// Parses the transform `T`: either {"translate", "rotate", "scale"} applied as
// scale, then rotate, then translate, or {"matrix": 16 numbers, row-major}.
#include <algorithm>
#include <cmath>
#include <limits>

#include "renderer/scene/scene_parse.h"

namespace vesper {
namespace {

double determinant3(const Matrix4& m) {
  return m(0, 0) * (m(1, 1) * m(2, 2) - m(1, 2) * m(2, 1)) -
         m(0, 1) * (m(1, 0) * m(2, 2) - m(1, 2) * m(2, 0)) +
         m(0, 2) * (m(1, 0) * m(2, 1) - m(1, 1) * m(2, 0));
}

Transform parse_matrix(JsonReader node) {
  const std::vector<double> v = node.as_number_array();
  if (v.size() != 16) {
    node.fail("expected 16 numbers (row-major 4x4), got " + std::to_string(v.size()));
  }
  Matrix4 m;
  std::copy(v.begin(), v.end(), m.m.begin());
  if (!m.is_affine()) node.fail("expected an affine matrix whose last row is [0, 0, 0, 1]");
  // Relative test, so that a uniformly tiny but valid scale (1e-4 scenes) passes.
  double largest = 0;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) largest = std::max(largest, std::abs(m(r, c)));
  }
  const double det = determinant3(m);
  if (!(std::abs(det) > 1e-12 * largest * largest * largest)) {
    node.fail("expected a non-singular matrix, got an upper 3x3 block with determinant " +
              describe_json(det));
  }
  return Transform(m);
}

// Either form, as written (parse_transform checks the result).
Transform parse_transform_form(JsonReader node);

}  // namespace

bool transform_fits(const Transform& t, double limit) {
  for (const Matrix4* m : {&t.matrix(), &t.inverse_matrix()})
    for (const double v : m->m)
      if (!(std::abs(v) <= limit)) return false;  // NaN and infinity too
  return true;
}

Transform parse_transform(JsonReader node) {
  const Transform t = parse_transform_form(node);
  // A scale of 1e-310 is not zero, but its inverse is infinite (and a
  // translate near the double range overflows once combined): every user
  // of a transform needs its inverse too.
  if (!transform_fits(t, std::numeric_limits<double>::max()))
    node.fail(
        "expected a transform whose matrix and inverse are finite, got one that "
        "overflows (a scale too close to 0 or values too large)");
  return t;
}

namespace {

Transform parse_transform_form(JsonReader node) {
  node.expect_object();
  const auto matrix = node.optional_child("matrix");
  const auto translate = node.optional_child("translate");
  const auto rotate = node.optional_child("rotate");
  const auto scale = node.optional_child("scale");
  node.finish();
  if (matrix) {
    if (translate || rotate || scale) {
      node.fail("use either 'matrix' or 'translate'/'rotate'/'scale', not both forms");
    }
    return parse_matrix(*matrix);
  }

  Transform t;
  if (scale) {
    Vec3d s;
    if (scale->json().is_number()) {
      s = Vec3d(scale->as_number());
    } else if (scale->json().is_array()) {
      s = as_vec3(*scale);
    } else {
      scale->fail("expected a number or an array of 3 numbers, got " +
                  describe_json(scale->json()));
    }
    if (s.x == 0 || s.y == 0 || s.z == 0) scale->fail("expected non-zero scale factors");
    t = Transform::scale(s);
  }
  if (rotate) {
    JsonReader r = *rotate;
    r.expect_object();
    const Vec3d axis = read_vec3(r, "axis");
    const double angle = r.number("angle");
    r.finish();
    if (!(length(axis) > 0)) r.fail_key("axis", "expected a non-zero rotation axis");
    t = Transform::rotate(normalize(axis), angle) * t;
  }
  if (translate) t = Transform::translate(as_vec3(*translate)) * t;
  return t;
}

}  // namespace

}  // namespace vesper
