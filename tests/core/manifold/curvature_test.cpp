// Manifold::max_normal_curvature (the curvature sizing field's κ_max, from the spec's exact
// Hessians): known answers on a sphere, an ellipsoid at its axis points, a torus of revolution at
// its outer and inner equators, and in codimension 2 the Clifford torus.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "core/manifold/manifold.hpp"
#include "io/spec.hpp"

namespace delcert::manifold {
namespace {

// A bounding box [-4, 4]^N (the reader asks one for sampling; unused here).
std::string box(int N) {
  std::string b = R"("bounding_box": [)";
  for (int i = 0; i < N; ++i) b += std::string(i ? ", " : "") + R"(["-4", "4"])";
  return b + "]";
}

Manifold make(const std::string& equations, int m, int N) {
  const std::string text = R"({"format": "delcert-manifold v1", "name": "t", "intrinsic_dimension": )" + std::to_string(m) +
                           R"(, "ambient_dimension": )" + std::to_string(N) + R"(, "equations": [)" + equations + "], " + box(N) + "}";
  return Manifold(io::parse_spec(text, "test.json"));
}

double kappa(const Manifold& M, std::vector<double> x) {
  const auto k = M.max_normal_curvature(x);
  EXPECT_TRUE(k.has_value());
  return k.value_or(-1);
}

TEST(MaxNormalCurvature, SphereOfRadiusR) {
  const Manifold M = make(R"eq("x1^2 + x2^2 + x3^2 - 9/4")eq", 2, 3);  // r = 3/2
  EXPECT_NEAR(kappa(M, {1.5, 0, 0}), 1 / 1.5, 1e-12);
  const double c = 1.5 / std::sqrt(3.0);
  EXPECT_NEAR(kappa(M, {c, -c, c}), 1 / 1.5, 1e-12);
}

TEST(MaxNormalCurvature, EllipsoidAtItsAxisPoints) {
  // x^2/a^2 + y^2/b^2 + z^2/c^2 = 1, a = 4, b = 2, c = 1: at (a, 0, 0) the normal curvatures are
  // a/b^2 and a/c^2; at (0, 0, c), c/a^2 and c/b^2.
  const Manifold M = make(R"eq("x1^2/16 + x2^2/4 + x3^2 - 1")eq", 2, 3);
  EXPECT_NEAR(kappa(M, {4, 0, 0}), 4.0 / 1.0, 1e-12);
  EXPECT_NEAR(kappa(M, {0, 2, 0}), 2.0 / 1.0, 1e-12);
  EXPECT_NEAR(kappa(M, {0, 0, 1}), 1.0 / 4.0, 1e-12);
}

TEST(MaxNormalCurvature, TorusOfRevolution) {
  // (x^2 + y^2 + z^2 + R^2 - r^2)^2 = 4 R^2 (x^2 + y^2), R = 2, r = 1/2: the tube's curvature 1/r
  // dominates everywhere; at the outer equator the other one is 1/(R + r), at the inner 1/(R - r).
  const Manifold M = make(R"eq("(x1^2 + x2^2 + x3^2 + 15/4)^2 - 16*(x1^2 + x2^2)")eq", 2, 3);
  EXPECT_NEAR(kappa(M, {2.5, 0, 0}), 2.0, 1e-10);
  EXPECT_NEAR(kappa(M, {0, 1.5, 0}), 2.0, 1e-10);
  EXPECT_NEAR(kappa(M, {0, 2, 0.5}), 2.0, 1e-10);  // the top circle: 1/r across the tube, 0 along it
}

TEST(MaxNormalCurvature, CliffordTorusInCodimensionTwo) {
  // x1^2 + x2^2 = 1/2, x3^2 + x4^2 = 1/2: a product of two circles of radius 1/sqrt(2), each of
  // curvature sqrt(2); the largest normal curvature is sqrt(2) (an estimate over normal
  // directions in codimension 2, here attained at a sampled direction).
  const Manifold M = make(R"eq("x1^2 + x2^2 - 1/2", "x3^2 + x4^2 - 1/2")eq", 2, 4);
  const double h = 0.5;
  EXPECT_NEAR(kappa(M, {h, h, h, -h}), std::sqrt(2.0), 1e-6);
  EXPECT_NEAR(kappa(M, {std::sqrt(0.5), 0, 0, std::sqrt(0.5)}), std::sqrt(2.0), 1e-6);
}

TEST(MaxNormalCurvature, SO3InCodimensionSix) {
  // SO(3) in R^9 with the Frobenius metric: a unit-speed one-parameter subgroup exp(tK), |K| = 1,
  // K = (e1 e2ᵀ - e2 e1ᵀ)/sqrt(2), has acceleration K² of norm 1/sqrt(2), normal to SO(3); no
  // direction is more curved. Homogeneous: the same at every rotation.
  const Manifold M(io::read_spec("builtin:so3"));
  EXPECT_NEAR(kappa(M, {1, 0, 0, 0, 1, 0, 0, 0, 1}), 1 / std::sqrt(2.0), 1e-9);
  EXPECT_NEAR(kappa(M, {0, -1, 0, 1, 0, 0, 0, 0, 1}), 1 / std::sqrt(2.0), 1e-9);
}

TEST(MaxNormalCurvature, FlatIsZero) {
  const Manifold M = make(R"eq("x3 - x1/2")eq", 2, 3);
  EXPECT_NEAR(kappa(M, {1, 7, 0.5}), 0.0, 1e-14);
}

}  // namespace
}  // namespace delcert::manifold
