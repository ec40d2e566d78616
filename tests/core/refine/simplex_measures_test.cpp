#include "core/refine/simplex_measures.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <cmath>
#include <vector>

#include "core/sampling/random.hpp"

namespace delcert::refine {
namespace {

using Points = std::vector<std::vector<double>>;

SimplexGeometry geometry(const Points& pts) {
  std::vector<std::span<const double>> v;
  for (const auto& p : pts) v.emplace_back(p);
  return SimplexGeometry(v);
}

// The same simplex moved into R^N by a random rotation and translation.
Points embed(const Points& pts, int N, std::uint64_t seed) {
  sampling::Random rng(seed);
  Eigen::MatrixXd A(N, N);
  for (int i = 0; i < N; ++i)
    for (int j = 0; j < N; ++j) A(i, j) = rng.normal();
  Eigen::HouseholderQR<Eigen::MatrixXd> qr(A);
  Eigen::MatrixXd Q = qr.householderQ();
  Eigen::VectorXd shift(N);
  for (int i = 0; i < N; ++i) shift[i] = rng.uniform(-3, 3);
  Points out;
  for (const auto& p : pts) {
    Eigen::VectorXd x = Eigen::VectorXd::Zero(N);
    for (std::size_t j = 0; j < p.size(); ++j) x[static_cast<Eigen::Index>(j)] = p[j];
    Eigen::VectorXd y = Q * x + shift;
    out.emplace_back(y.data(), y.data() + N);
  }
  return out;
}

TEST(SimplexMeasures, RightTriangleKnownAnswers) {
  for (int N : {2, 3, 6}) {
    auto g = geometry(embed({{0, 0}, {1, 0}, {0, 1}}, N, 7 + N));
    EXPECT_NEAR(g.longest_edge(), std::sqrt(2.0), 1e-14);
    EXPECT_NEAR(g.shortest_edge(), 1.0, 1e-14);
    EXPECT_NEAR(g.altitude(0), 1 / std::sqrt(2.0), 1e-14);
    EXPECT_NEAR(g.altitude(1), 1.0, 1e-14);
    EXPECT_NEAR(g.altitude(2), 1.0, 1e-14);
    // Υ = min altitude / (j Δ) = (1/√2) / (2 √2) = 1/4
    EXPECT_NEAR(g.thickness(), 0.25, 1e-14);
    EXPECT_NEAR(g.gram_determinant(g.all()), 1.0, 1e-13);  // (2! area)^2
  }
}

TEST(SimplexMeasures, RegularSimplicesKnownThickness) {
  // Regular triangle: altitude √3/2, Υ = √3/4. Regular tetrahedron: altitude √(2/3), Υ = √(2/3)/3.
  auto tri = geometry(embed({{0, 0}, {1, 0}, {0.5, std::sqrt(3.0) / 2}}, 5, 3));
  EXPECT_NEAR(tri.thickness(), std::sqrt(3.0) / 4, 1e-13);
  const double s = 1 / std::sqrt(2.0);
  auto tet = geometry(embed({{s, 0, 0}, {0, s, 0}, {0, 0, s}, {s, s, s}}, 6, 4));  // edges all 1
  EXPECT_NEAR(tet.longest_edge(), 1.0, 1e-14);
  EXPECT_NEAR(tet.shortest_edge(), 1.0, 1e-14);
  EXPECT_NEAR(tet.thickness(), std::sqrt(2.0 / 3.0) / 3, 1e-13);
  // Faces: a triangle face of the regular tetrahedron is a regular triangle.
  EXPECT_NEAR(tet.thickness(0b0111), std::sqrt(3.0) / 4, 1e-13);
  EXPECT_DOUBLE_EQ(tet.thickness(0b0011), 1.0);  // an edge
  EXPECT_DOUBLE_EQ(tet.thickness(0b0001), 1.0);  // a vertex
  EXPECT_TRUE(tet.is_good(0.5));                 // 0.433 >= 0.25 and 0.272 >= 0.125
  EXPECT_EQ(tet.quality(0.5), SimplexQuality::good);
  EXPECT_FALSE(tet.is_good(0.7));                // 0.433 < 0.49: its triangles are bad
  EXPECT_EQ(tet.quality(0.7), SimplexQuality::bad);
}

TEST(SimplexMeasures, AltitudeMatchesLeastSquaresDistance) {
  sampling::Random rng(12);
  for (int trial = 0; trial < 50; ++trial) {
    const int k = 2 + trial % 4, N = k + 2;
    Points pts(k + 1, std::vector<double>(N));
    for (auto& p : pts)
      for (auto& c : p) c = rng.normal();
    auto g = geometry(pts);
    for (int u = 0; u <= k; ++u) {
      // Distance from pts[u] to the affine hull of the others, by a direct least-squares solve.
      int o = u == 0 ? 1 : 0;
      Eigen::MatrixXd E(N, k - 1);
      int c = 0;
      for (int v = 0; v <= k; ++v)
        if (v != u && v != o) {
          for (int j = 0; j < N; ++j) E(j, c) = pts[v][j] - pts[o][j];
          ++c;
        }
      Eigen::VectorXd b(N);
      for (int j = 0; j < N; ++j) b[j] = pts[u][j] - pts[o][j];
      Eigen::VectorXd lam = E.colPivHouseholderQr().solve(b);
      EXPECT_NEAR(g.altitude(u), (b - E * lam).norm(), 1e-10);
    }
  }
}

TEST(SimplexMeasures, DegenerateSimplicesGiveZeroThicknessWithoutNaN) {
  // Collinear triangle.
  auto line = geometry({{0, 0, 0}, {1, 1, 1}, {3, 3, 3}});
  EXPECT_EQ(line.thickness(), 0.0);
  EXPECT_NEAR(line.altitude(1), 0.0, 1e-7);
  EXPECT_FALSE(line.is_good(0.01));
  // Coincident vertices.
  auto twice = geometry({{1, 2}, {1, 2}, {0, 0}});
  EXPECT_EQ(twice.thickness(), 0.0);
  EXPECT_EQ(twice.thickness(0b011), 0.0);  // a zero-length edge
  EXPECT_EQ(geometry({{1, 2}, {1, 2}}).quality(0.1), SimplexQuality::bad);  // bad, but a flake needs dimension 2
  EXPECT_TRUE(std::isfinite(twice.altitude(2)));
  EXPECT_NEAR(twice.altitude(2), std::sqrt(5.0), 1e-12);  // distance from (0,0) to the "hull" {(1,2)}
  // Flat tetrahedron in R^3; the apex over a degenerate (collinear) base: least squares.
  auto flat = geometry({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}});
  EXPECT_EQ(flat.thickness(), 0.0);
  auto apex = geometry({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {0, 3, 4}});
  EXPECT_NEAR(apex.altitude(3), 5.0, 1e-12);
  EXPECT_EQ(apex.thickness(), 0.0);
  // All points equal.
  auto point = geometry({{1, 1}, {1, 1}, {1, 1}});
  EXPECT_EQ(point.thickness(), 0.0);
  EXPECT_EQ(point.longest_edge(), 0.0);
  EXPECT_TRUE(std::isfinite(point.altitude(0)));
}

// A sliver: four nearly cocircular points lifted alternately by ±h. Its triangles are fat,
// the tetrahedron is flat: a Γ0-flake for Γ0 between the two.
Points sliver(double h) { return {{1, 0, h}, {0, 1, -h}, {-1, 0, h}, {0, -1, -h}}; }

TEST(SimplexMeasures, SliverIsAFlake) {
  auto g = geometry(embed(sliver(0.01), 5, 9));
  // Every triangle: nearly a right isosceles triangle, Υ ≈ 1/4.
  for (FaceMask f : {0b0111u, 0b1011u, 0b1101u, 0b1110u}) EXPECT_NEAR(g.thickness(f), 0.25, 0.01);
  EXPECT_LT(g.thickness(), 0.01);
  const double gamma0 = 0.3;  // triangles need 0.09, the tetrahedron 0.027
  EXPECT_EQ(g.quality(gamma0), SimplexQuality::flake);
  EXPECT_FALSE(g.is_good(gamma0));
  EXPECT_LT(g.goodness_ratio(gamma0), 1.0);
  // Thickness grows with the lift; a lift of 0.5 is good.
  EXPECT_EQ(geometry(sliver(0.5)).quality(gamma0), SimplexQuality::good);
  // A flat triangle inside makes the tetrahedron bad but not a flake.
  auto needle = geometry({{0, 0, 0}, {1, 0, 0}, {2, 0.001, 0}, {0, 1, 1}});
  EXPECT_EQ(needle.quality(gamma0), SimplexQuality::bad);
}

TEST(SimplexMeasures, MakeSimplexFromPointSet) {
  io::PointSet ps;
  ps.dimension = 2;
  ps.coordinates = {0, 0, 1, 0, 0, 1, 5, 5};
  std::vector<int> idx{0, 1, 2};
  EXPECT_NEAR(make_simplex(ps, idx).thickness(), 0.25, 1e-15);
  std::vector<double> x{1, 1};
  std::vector<int> idx2{1, 2};
  auto g = make_simplex(x, ps, idx2);
  EXPECT_EQ(g.num_vertices(), 3);
  EXPECT_NEAR(g.squared_distance(0, 1), 1.0, 1e-15);
}

}  // namespace
}  // namespace delcert::refine
