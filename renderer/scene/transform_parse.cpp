// Parses the transform `T`: either {"translate", "rotate", "scale"} applied as
// scale, then rotate, then translate, or {"matrix": 16 numbers, row-major}.
#include <cmath>
#include <numbers>

#include "renderer/scene/scene_parse.h"

namespace vesper {
namespace {

Transform translation(const Vec3d& t) {
  Transform m;
  m.m[3] = t.x, m.m[7] = t.y, m.m[11] = t.z;
  return m;
}

Transform scaling(const Vec3d& s) {
  Transform m;
  m.m[0] = s.x, m.m[5] = s.y, m.m[10] = s.z;
  return m;
}

// Right-handed rotation about a unit axis (Rodrigues): counter-clockwise when
// the axis points toward the viewer.
Transform rotation(const Vec3d& axis, double degrees) {
  const double a = degrees * std::numbers::pi / 180.0;
  const double c = std::cos(a), s = std::sin(a), t = 1 - c;
  const double x = axis.x, y = axis.y, z = axis.z;
  Transform m;
  m.m = {t * x * x + c,
         t * x * y - s * z,
         t * x * z + s * y,
         0,
         t * x * y + s * z,
         t * y * y + c,
         t * y * z - s * x,
         0,
         t * x * z - s * y,
         t * y * z + s * x,
         t * z * z + c,
         0,
         0,
         0,
         0,
         1};
  return m;
}

double determinant3(const Transform& t) {
  const auto& m = t.m;
  return m[0] * (m[5] * m[10] - m[6] * m[9]) - m[1] * (m[4] * m[10] - m[6] * m[8]) +
         m[2] * (m[4] * m[9] - m[5] * m[8]);
}

Transform parse_matrix(JsonReader node) {
  const std::vector<double> v = node.as_number_array();
  if (v.size() != 16) {
    node.fail("expected 16 numbers (row-major 4x4), got " + std::to_string(v.size()));
  }
  Transform t;
  std::copy(v.begin(), v.end(), t.m.begin());
  if (t.m[12] != 0 || t.m[13] != 0 || t.m[14] != 0 || t.m[15] != 1) {
    node.fail("expected an affine matrix whose last row is [0, 0, 0, 1]");
  }
  // Relative test, so that a uniformly tiny but valid scale (1e-4 scenes) passes.
  double largest = 0;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) largest = std::max(largest, std::abs(t.m[r * 4 + c]));
  }
  const double det = determinant3(t);
  if (!(std::abs(det) > 1e-12 * largest * largest * largest)) {
    node.fail("expected a non-singular matrix, got an upper 3x3 block with determinant " +
              describe_json(det));
  }
  return t;
}

}  // namespace

Transform compose(const Transform& a, const Transform& b) {
  Transform out;
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c) {
      double sum = 0;
      for (int k = 0; k < 4; ++k) sum += a.m[r * 4 + k] * b.m[k * 4 + c];
      out.m[r * 4 + c] = sum;
    }
  }
  return out;
}

Transform parse_transform(JsonReader node) {
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
    t = scaling(s);
  }
  if (rotate) {
    JsonReader r = *rotate;
    r.expect_object();
    const Vec3d axis = read_vec3(r, "axis");
    const double angle = r.number("angle");
    r.finish();
    if (!(length(axis) > 0)) r.fail_key("axis", "expected a non-zero rotation axis");
    t = compose(rotation(normalize(axis), angle), t);
  }
  if (translate) t = compose(translation(as_vec3(*translate)), t);
  return t;
}

}  // namespace vesper
