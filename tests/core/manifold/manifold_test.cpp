#include "core/manifold/manifold.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <cmath>
#include <stdexcept>

#include "core/sampling/sampling.hpp"
#include "io/spec.hpp"
#include "tests/test_support.hpp"

namespace delcert::manifold {
namespace {

class EveryBuiltin : public ::testing::TestWithParam<std::string> {
 protected:
  Manifold manifold{io::read_spec("builtin:" + GetParam())};
  io::PointSet sample(std::size_t n, std::uint64_t seed) const {
    sampling::Random rng(seed);
    io::PointSet ps;
    sampling::sample_manifold(manifold, n, rng, ps);
    return ps;
  }
};

TEST_P(EveryBuiltin, SamplesLieOnTheManifold) {
  auto ps = sample(200, 11);
  ASSERT_EQ(ps.size(), 200u);
  for (std::size_t i = 0; i < ps.size(); ++i) {
    EXPECT_LT(manifold.residual(ps.point(i)), 1e-12);
    EXPECT_TRUE(manifold.on_selected_component(ps.point(i)));
  }
}

TEST_P(EveryBuiltin, TangentBasesAreOrthonormalAndOrthogonalToEveryGradient) {
  const int m = manifold.intrinsic_dimension(), N = manifold.ambient_dimension();
  auto ps = sample(100, 12);
  for (std::size_t i = 0; i < ps.size(); ++i) {
    auto f = manifold.frame(ps.point(i));
    ASSERT_TRUE(f.has_value());
    ASSERT_EQ(f->tangent.rows(), N);
    ASSERT_EQ(f->tangent.cols(), m);
    ASSERT_EQ(f->normal.cols(), N - m);
    Eigen::MatrixXd Q(N, N);
    Q << f->tangent, f->normal;
    EXPECT_LT((Q.transpose() * Q - Eigen::MatrixXd::Identity(N, N)).cwiseAbs().maxCoeff(), 1e-13);
    Eigen::MatrixXd J = manifold.jacobian(ps.point(i));
    // Every gradient (row of J) is orthogonal to the tangent space, relative to its length.
    for (int r = 0; r < J.rows(); ++r)
      EXPECT_LT((J.row(r) * f->tangent).cwiseAbs().maxCoeff(), 1e-13 * J.row(r).norm());
  }
}

TEST_P(EveryBuiltin, PsiInvertsTheTangentProjection) {
  const int m = manifold.intrinsic_dimension();
  auto ps = sample(60, 13);
  sampling::Random rng(14);
  for (std::size_t i = 0; i < ps.size(); ++i) {
    Eigen::Map<const Eigen::VectorXd> p(ps.point(i).data(), manifold.ambient_dimension());
    auto f = manifold.frame(ps.point(i));
    ASSERT_TRUE(f.has_value());
    for (int k = 0; k < 5; ++k) {
      Eigen::VectorXd u(m);
      for (int j = 0; j < m; ++j) u[j] = rng.uniform(-0.2, 0.2);  // well inside the reach (>= 1)
      Eigen::VectorXd y = p + f->tangent * u;
      auto x = manifold.psi(ps.point(i), *f, y);
      ASSERT_TRUE(x.has_value());
      EXPECT_LT(manifold.residual(as_span(*x)), 1e-13);
      // pi_p(psi_p(y)) = y: the tangent coordinates of x equal u.
      Eigen::VectorXd back = p + f->tangent * (f->tangent.transpose() * (*x - p));
      EXPECT_LT((back - y).norm(), 1e-12);
    }
  }
}

TEST_P(EveryBuiltin, ProjectFindsTheClosestPoint) {
  auto ps = sample(40, 15);
  sampling::Random rng(16);
  const int N = manifold.ambient_dimension();
  for (std::size_t i = 0; i < ps.size(); ++i) {
    Eigen::Map<const Eigen::VectorXd> p(ps.point(i).data(), N);
    auto f = manifold.frame(ps.point(i));
    Eigen::VectorXd nu(N - manifold.intrinsic_dimension());
    for (int j = 0; j < nu.size(); ++j) nu[j] = rng.uniform(-0.1, 0.1);
    Eigen::VectorXd x = p + f->normal * nu;  // a point off M whose closest point is p
    auto z = manifold.project(as_span(x));
    ASSERT_TRUE(z.has_value());
    EXPECT_LT((*z - p).norm(), 1e-10);
  }
}

// m + 1 points of M around p (ψ_p of small tangent offsets): the point equidistant from them found
// from their circumcentre c (the point of their Voronoi flat nearest their centroid) is on M,
// equidistant to rounding, and within the circumradius r of c (M sags about κ r² / 2 below the
// simplex; simplices with r > 0.3, nearly degenerate, are skipped).
TEST_P(EveryBuiltin, EquidistantPointIsOnMAndEquidistant) {
  const int m = manifold.intrinsic_dimension(), N = manifold.ambient_dimension();
  auto ps = sample(30, 17);
  sampling::Random rng(18);
  int tested = 0;
  for (std::size_t i = 0; i < ps.size(); ++i) {
    Eigen::Map<const Eigen::VectorXd> p(ps.point(i).data(), N);
    auto f = manifold.frame(ps.point(i));
    ASSERT_TRUE(f.has_value());
    Eigen::MatrixXd V(N, m + 1);
    for (int k = 0; k <= m; ++k) {
      Eigen::VectorXd u(m);
      for (int j = 0; j < m; ++j) u[j] = rng.uniform(-0.1, 0.1);
      auto x = manifold.psi(ps.point(i), *f, p + f->tangent * u);
      ASSERT_TRUE(x.has_value());
      V.col(k) = *x;
    }
    const Eigen::VectorXd centroid = V.rowwise().mean();
    Eigen::MatrixXd A(m, N);
    Eigen::VectorXd b(m);
    for (int k = 1; k <= m; ++k) {
      A.row(k - 1) = (V.col(k) - V.col(0)).transpose();
      b[k - 1] = A.row(k - 1).dot((V.col(k) + V.col(0)) / 2);
    }
    const Eigen::VectorXd c = centroid + A.transpose() * (A * A.transpose()).ldlt().solve(b - A * centroid);
    const double radius = (c - V.col(0)).norm();
    if (!(radius < 0.3)) continue;
    auto x = manifold.equidistant_point(V, c);
    ASSERT_TRUE(x.has_value()) << "simplex " << i << ", circumradius " << radius;
    EXPECT_LT(manifold.residual(as_span(*x)), 1e-12);
    const double r2 = (*x - V.col(0)).squaredNorm();
    for (int k = 1; k <= m; ++k) EXPECT_NEAR((*x - V.col(k)).squaredNorm(), r2, 1e-12 * (1 + r2));
    EXPECT_LT((*x - c).norm(), radius);
    ++tested;
  }
  EXPECT_GE(tested, 20);  // most random simplices are not nearly degenerate
}

INSTANTIATE_TEST_SUITE_P(Builtins, EveryBuiltin,
                         ::testing::Values("sphere-2", "sphere-3", "clifford-torus-2", "clifford-torus-3",
                                           "torus-of-revolution", "so3"));

TEST(Manifold, PsiReportsFailureInsteadOfGarbage) {
  Manifold sphere(io::read_spec("builtin:sphere-2"));
  std::vector<double> p{0, 0, 1};
  auto f = sphere.frame(p);
  ASSERT_TRUE(f.has_value());
  // A point of T_p at distance 2 from p: the normal line through it misses the unit sphere.
  Eigen::VectorXd y = Eigen::Vector3d(0, 0, 1) + f->tangent.col(0) * 2.0;
  EXPECT_FALSE(sphere.psi(p, *f, y).has_value());
  // The centre of the sphere is singular for the Jacobian.
  std::vector<double> origin{0, 0, 0};
  EXPECT_FALSE(sphere.frame(origin).has_value());
}

// Known answers on the unit sphere: the points equidistant from e1, e2, e3 are ±(1, 1, 1)/√3, and
// Newton finds the one on its side; the flat x = y = 2 of (0,0,0), (4,0,0), (0,4,0) misses the sphere.
TEST(Manifold, EquidistantPointKnownAnswers) {
  Manifold sphere(io::read_spec("builtin:sphere-2"));
  Eigen::MatrixXd V = Eigen::MatrixXd::Identity(3, 3);
  const Eigen::Vector3d n = Eigen::Vector3d::Ones() / std::sqrt(3.0);
  auto x = sphere.equidistant_point(V, Eigen::Vector3d(0.3, 0.3, 0.3));
  ASSERT_TRUE(x.has_value());
  EXPECT_LT((*x - n).norm(), 1e-14);
  x = sphere.equidistant_point(V, Eigen::Vector3d(-0.4, -0.5, -0.6));
  ASSERT_TRUE(x.has_value());
  EXPECT_LT((*x + n).norm(), 1e-14);
  NewtonOptions near;
  near.max_distance = 0.1;  // the solution is 0.42 away: refused
  EXPECT_FALSE(sphere.equidistant_point(V, Eigen::Vector3d(0.3, 0.3, 0.3), near).has_value());
  Eigen::MatrixXd W(3, 3);
  W << 0, 4, 0, 0, 0, 4, 0, 0, 0;
  EXPECT_FALSE(sphere.equidistant_point(W, Eigen::Vector3d(2, 2, 0)).has_value());
  EXPECT_THROW(sphere.equidistant_point(Eigen::MatrixXd::Identity(3, 2), Eigen::Vector3d::Zero()), std::invalid_argument);
}

TEST(Manifold, GenericSpecSamplesByProjection) {
  Manifold ellipsoid(io::read_spec(test::fixture("specs/ellipsoid.json")));
  sampling::Random rng(3);
  io::PointSet ps;
  sampling::sample_manifold(ellipsoid, 100, rng, ps);
  ASSERT_EQ(ps.size(), 100u);
  for (std::size_t i = 0; i < ps.size(); ++i) EXPECT_LT(ellipsoid.residual(ps.point(i)), 1e-12);
}

}  // namespace
}  // namespace delcert::manifold
