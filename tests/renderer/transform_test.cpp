// renderer/math/transform.h: composition, inverse, points, vectors, normals.
#include "renderer/math/transform.h"

#include <gtest/gtest.h>

#include <cmath>

namespace vesper {
namespace {

void expect_near(const Vec3d& a, const Vec3d& b, double tol = 1e-12) {
  EXPECT_NEAR(a.x, b.x, tol);
  EXPECT_NEAR(a.y, b.y, tol);
  EXPECT_NEAR(a.z, b.z, tol);
}

// A transform with rotation, non-uniform scale and translation.
Transform general() {
  return Transform::translate({1, -2, 3}) * Transform::rotate(normalize(Vec3d{1, 2, 3}), 37) *
         Transform::scale({2, 0.5, -3});
}

TEST(Transform, DefaultIsIdentity) {
  const Transform t;
  EXPECT_EQ(t.matrix(), Matrix4{});
  EXPECT_EQ(t.inverse_matrix(), Matrix4{});
  EXPECT_EQ(t.apply_point({1, 2, 3}), (Vec3d{1, 2, 3}));
}

TEST(Transform, PointsTranslateVectorsDoNot) {
  const Transform t = Transform::translate({10, 20, 30});
  EXPECT_EQ(t.apply_point({1, 2, 3}), (Vec3d{11, 22, 33}));
  EXPECT_EQ(t.apply_vector({1, 2, 3}), (Vec3d{1, 2, 3}));
  EXPECT_EQ(t.apply_normal({0, 0, 1}), (Vec3d{0, 0, 1}));
}

TEST(Transform, ComposesRightToLeft) {
  // (a * b)(p) = a(b(p)): scale by 2, then translate by +1 in x.
  const Transform a = Transform::translate({1, 0, 0}), b = Transform::scale(Vec3d(2));
  EXPECT_EQ((a * b).apply_point({1, 1, 1}), (Vec3d{3, 2, 2}));
  EXPECT_EQ((b * a).apply_point({1, 1, 1}), (Vec3d{4, 2, 2}));
  const Transform t = general();
  const Vec3d p{0.3, -1.7, 2.2};
  expect_near(t.apply_point(p),
              Transform::translate({1, -2, 3})
                  .apply_point(Transform::rotate(normalize(Vec3d{1, 2, 3}), 37)
                                   .apply_point(Transform::scale({2, 0.5, -3}).apply_point(p))));
}

TEST(Transform, RotationIsRightHandedAboutItsAxis) {
  const Transform r = Transform::rotate({0, 0, 1}, 90);  // +x -> +y
  expect_near(r.apply_vector({1, 0, 0}), {0, 1, 0});
  expect_near(r.apply_vector({0, 0, 1}), {0, 0, 1});
}

TEST(Transform, InverseUndoesTheTransform) {
  const Transform t = general();
  ASSERT_TRUE(t.invertible());
  const Vec3d p{0.3, -1.7, 2.2};
  expect_near(inverse(t).apply_point(t.apply_point(p)), p);
  expect_near(inverse(t).apply_vector(t.apply_vector(p)), p);
  const Matrix4 id = t.matrix() * t.inverse_matrix();
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) EXPECT_NEAR(id(r, c), r == c ? 1.0 : 0.0, 1e-12);
  // inverse() swaps the matrices: applying it twice gives back the same bits.
  EXPECT_EQ(inverse(inverse(t)), t);
  EXPECT_EQ(inverse(t).matrix(), t.inverse_matrix());
}

TEST(Transform, NormalsStayPerpendicularUnderNonUniformScale) {
  const Transform t = general();
  // A plane through the origin spanned by u and v, with normal n.
  const Vec3d u{1, 0.2, -0.4}, v{0.1, 1, 0.7}, n = cross(u, v);
  const Vec3d tn = t.apply_normal(n);
  EXPECT_NEAR(dot(tn, t.apply_vector(u)), 0, 1e-12);
  EXPECT_NEAR(dot(tn, t.apply_vector(v)), 0, 1e-12);
  // Not a vector: the scaled vector is no longer perpendicular.
  EXPECT_GT(std::abs(dot(t.apply_vector(n), t.apply_vector(u))), 0.1);
}

TEST(Transform, SingularMatrixHasNoInverse) {
  const Transform flat = Transform::scale({1, 0, 1});
  EXPECT_FALSE(flat.invertible());
  EXPECT_TRUE(std::isnan(flat.inverse_matrix()(0, 0)));
  EXPECT_TRUE(general().invertible());
}

TEST(Transform, RejectsProjectiveMatrices) {
  Matrix4 m;
  m(3, 2) = 1;
  EXPECT_THROW(Transform{m}, std::invalid_argument);
}

TEST(Transform, CastsToFloatEntryByEntry) {
  const Transform t = general();
  const Transformf f = t.cast<float>();
  for (int i = 0; i < 16; ++i) {
    EXPECT_EQ(f.matrix().m[size_t(i)], float(t.matrix().m[size_t(i)]));
    EXPECT_EQ(f.inverse_matrix().m[size_t(i)], float(t.inverse_matrix().m[size_t(i)]));
  }
  const Vec3 p = f.apply_point({0.5f, 0.25f, -1.f});
  expect_near(Vec3d(p), t.apply_point({0.5, 0.25, -1}), 1e-5);
}

}  // namespace
}  // namespace vesper
