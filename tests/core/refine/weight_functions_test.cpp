#include "core/refine/weight_functions.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <cmath>
#include <limits>
#include <vector>

#include "core/sampling/random.hpp"

namespace delcert::refine {
namespace {

using Points = std::vector<std::vector<double>>;

std::vector<std::span<const double>> spans(const Points& pts) {
  std::vector<std::span<const double>> v;
  for (const auto& p : pts) v.emplace_back(p);
  return v;
}
SimplexGeometry geometry(const Points& pts) { return SimplexGeometry(spans(pts)); }

double dist2(const Eigen::VectorXd& c, const std::vector<double>& p) {
  double s = 0;
  for (std::size_t j = 0; j < p.size(); ++j) s += std::pow(c[static_cast<Eigen::Index>(j)] - p[j], 2);
  return s;
}

Points random_simplex(sampling::Random& rng, int k, int N) {
  Points pts(k + 1, std::vector<double>(N));
  for (auto& p : pts)
    for (auto& c : p) c = rng.normal();
  return pts;
}

TEST(WeightFunctions, ZeroWeightIsTheCircumsphere) {
  Points tri{{0, 0, 0}, {2, 0, 0}, {0, 2, 0}};
  auto g = geometry(tri);
  for (int v = 0; v < 3; ++v) EXPECT_NEAR(weighted_radius2(g, v, 0), 2.0, 1e-14);
  auto c = weighted_centre(spans(tri), 1, 0);
  ASSERT_TRUE(c);
  EXPECT_NEAR((*c - Eigen::Vector3d(1, 1, 0)).norm(), 0, 1e-14);
}

TEST(WeightFunctions, EdgeClosedForm) {
  // Edge [a, b] of length l, weight t on b: C at distance s = (l^2 - t) / (2 l) from a, R^2 = s^2.
  const double l = 3;
  Points e{{0, 0}, {l, 0}};
  auto g = geometry(e);
  for (double t : {0.0, 0.5, 2.0}) {
    const double s = (l * l - t) / (2 * l);
    EXPECT_NEAR(weighted_radius2(g, 1, t), s * s, 1e-13);
    auto c = weighted_centre(spans(e), 1, t);
    ASSERT_TRUE(c);
    EXPECT_NEAR((*c)[0], s, 1e-13);
  }
  auto q = weighted_radius_quadratic(g, 1);
  ASSERT_TRUE(q);
  EXPECT_NEAR(q->c0, l * l / 4, 1e-13);
  EXPECT_NEAR(q->c1, -0.5, 1e-14);
  EXPECT_NEAR(q->c2, 1 / (4 * l * l), 1e-14);
}

TEST(WeightFunctions, CentreSatisfiesTheDefiningEquations) {
  sampling::Random rng(5);
  for (int trial = 0; trial < 60; ++trial) {
    const int k = 1 + trial % 5, N = k + 1 + trial % 3;
    Points pts = random_simplex(rng, k, N);
    auto g = geometry(pts);
    const int v = trial % (k + 1);
    const double L = g.shortest_edge();
    const double t = rng.uniform(0, 0.2 * L * L);
    auto c = weighted_centre(spans(pts), v, t);
    ASSERT_TRUE(c);
    const double r2 = weighted_radius2(g, v, t);
    for (int u = 0; u <= k; ++u) EXPECT_NEAR(dist2(*c, pts[u]) - (u == v ? t : 0.0), r2, 1e-9 * (1 + r2));
    // C lies in aff(τ): its component orthogonal to the edge vectors vanishes.
    Eigen::MatrixXd E(N, k);
    for (int u = 1; u <= k; ++u)
      for (int j = 0; j < N; ++j) E(j, u - 1) = pts[u][j] - pts[0][j];
    Eigen::VectorXd w = *c - Eigen::Map<const Eigen::VectorXd>(pts[0].data(), N);
    Eigen::VectorXd lam = E.colPivHouseholderQr().solve(w);
    EXPECT_LT((E * lam - w).norm(), 1e-9);
  }
}

TEST(WeightFunctions, PaperLemma41Bounds) {
  // (1) R(face, ω|face) <= R(τ, ω);  (2) Δ(τ) <= 2 R(τ, ω) / (1 - δ0^2) for ω <= δ0 L.
  sampling::Random rng(17);
  const double delta0 = 0.4;
  for (int trial = 0; trial < 200; ++trial) {
    const int k = 2 + trial % 4, N = k + 1;
    Points pts = random_simplex(rng, k, N);
    auto g = geometry(pts);
    const int v = trial % (k + 1);
    const double L = g.shortest_edge();
    const double t = rng.uniform(0, delta0 * delta0 * L * L);
    const double R2 = weighted_radius2(g, v, t);
    ASSERT_TRUE(std::isfinite(R2));
    EXPECT_LE(g.longest_edge(), 2 * std::sqrt(R2) / (1 - delta0 * delta0) * (1 + 1e-12));
    // Drop one vertex (not v, or v: then the restriction is zero).
    const int drop = (trial / 7) % (k + 1);
    Points face;
    int fv = -1;
    for (int u = 0; u <= k; ++u)
      if (u != drop) {
        if (u == v) fv = static_cast<int>(face.size());
        face.push_back(pts[u]);
      }
    auto fg = geometry(face);
    const double Rf2 = fv >= 0 ? weighted_radius2(fg, fv, t) : weighted_radius2(fg, 0, 0);
    EXPECT_LE(Rf2, R2 * (1 + 1e-9));
  }
}

TEST(WeightFunctions, MinimumOverElementaryWeightsMatchesAScan) {
  sampling::Random rng(23);
  const double delta0 = 0.45;
  for (int trial = 0; trial < 40; ++trial) {
    const int k = 1 + trial % 5, N = k + 2;
    Points pts = random_simplex(rng, k, N);
    auto g = geometry(pts);
    auto best = min_weighted_radius2(g, delta0);
    const double L = g.shortest_edge(), tmax = delta0 * delta0 * L * L;
    double scan = std::numeric_limits<double>::infinity();
    for (int v = 0; v <= k; ++v)
      for (int s = 0; s <= 400; ++s) scan = std::min(scan, weighted_radius2(g, v, tmax * s / 400));
    EXPECT_LE(best.radius2, scan * (1 + 1e-12));
    EXPECT_GE(best.radius2, scan - 1e-6 * scan);  // the scan's grid is fine enough
    EXPECT_LE(best.radius2, weighted_radius2(g, 0, 0) * (1 + 1e-12));
    EXPECT_GE(best.t, 0);
    EXPECT_LE(best.t, tmax);
    EXPECT_NEAR(weighted_radius2(g, best.vertex, best.t), best.radius2, 1e-12 * (1 + best.radius2));
  }
}

TEST(WeightFunctions, DegenerateSimplexHasNoWeightedCentre) {
  Points line{{0, 0, 0}, {1, 1, 1}, {2, 2, 2}};
  auto g = geometry(line);
  EXPECT_FALSE(weighted_radius_quadratic(g, 0));
  EXPECT_TRUE(std::isinf(weighted_radius2(g, 1, 0.1)));
  EXPECT_FALSE(weighted_centre(spans(line), 2, 0.0));
  EXPECT_TRUE(std::isinf(min_weighted_radius2(g, 0.2).radius2));
  Points same{{1, 1}, {1, 1}};
  EXPECT_TRUE(std::isinf(min_weighted_radius2(geometry(same), 0.2).radius2));
  Points single{{1, 1}};
  EXPECT_FALSE(weighted_radius_quadratic(geometry(single), 0));
}

}  // namespace
}  // namespace delcert::refine
