#include "core/refine/hitting_sets.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <vector>

#include "core/refine/simplex_measures.hpp"
#include "core/refine/weight_functions.hpp"
#include "core/sampling/random.hpp"

namespace delcert::refine {
namespace {

TEST(HittingSets, SliverCompletedByTheCandidateIsAHit) {
  // Three points of a sliver; x is its fourth vertex: x * S is a Γ0-flake of radius ≈ 1.
  const double h = 0.01;
  io::PointSet ps;
  ps.dimension = 3;
  ps.push_back(std::vector<double>{0, 1, -h});
  ps.push_back(std::vector<double>{-1, 0, h});
  ps.push_back(std::vector<double>{0, -1, -h});
  ps.push_back(std::vector<double>{5, 5, 5});  // far away: never a candidate
  spatial::NeighbourIndex index(ps);
  std::vector<double> x{1, 0, h};
  HittingQuery q;
  q.gamma0 = 0.3;
  q.delta0 = 0.1;
  q.max_set_size = 3;
  q.radius_bound = 1.5;
  HittingStats stats;
  auto hit = find_hitting_set(x, ps, index, q, &stats);
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->points, (std::vector<std::size_t>{0, 1, 2}));
  EXPECT_LT(hit->radius2, 1.5 * 1.5);
  EXPECT_GT(hit->radius2, 0.9);
  EXPECT_EQ(stats.flakes, 1u);
  EXPECT_EQ(stats.candidates, 3u);
  // The same flake with a smaller radius bound does not hit.
  q.radius_bound = 0.9;
  EXPECT_FALSE(find_hitting_set(x, ps, index, q));
  // Only two points of S: the triangles are good, no flake.
  q.radius_bound = 1.5;
  q.max_set_size = 2;
  EXPECT_FALSE(find_hitting_set(x, ps, index, q));
  // x lifted far off the sliver's plane: x * S is thick, not a flake.
  q.max_set_size = 3;
  std::vector<double> y{0, 0, 1};
  EXPECT_FALSE(find_hitting_set(y, ps, index, q));
}

// Brute force over every subset of the candidates: the first hitting set by (size, lexicographic).
std::optional<std::vector<std::size_t>> brute_force(std::span<const double> x, const io::PointSet& ps,
                                                    const HittingQuery& q) {
  const double reach = 2 * q.radius_bound / (1 - q.delta0 * q.delta0);
  std::vector<std::size_t> cand;
  for (std::size_t i = 0; i < ps.size(); ++i) {
    double s = 0;
    for (int j = 0; j < ps.dimension; ++j) s += std::pow(ps.point(i)[j] - x[j], 2);
    if (s <= reach * reach) cand.push_back(i);
  }
  const std::size_t n = cand.size();
  for (int k = 2; k <= q.max_set_size; ++k) {
    std::vector<std::size_t> idx(k);
    std::function<std::optional<std::vector<std::size_t>>(int, std::size_t)> rec =
        [&](int depth, std::size_t from) -> std::optional<std::vector<std::size_t>> {
      if (depth == k) {
        std::vector<std::span<const double>> v{x};
        std::vector<std::size_t> S;
        for (int i = 0; i < k; ++i) S.push_back(cand[idx[i]]), v.push_back(ps.point(cand[idx[i]]));
        SimplexGeometry g(v);
        if (g.quality(q.gamma0) == SimplexQuality::flake &&
            min_weighted_radius2(g, q.delta0).radius2 < q.radius_bound * q.radius_bound)
          return S;
        return std::nullopt;
      }
      for (std::size_t i = from; i < n; ++i) {
        idx[depth] = i;
        if (auto r = rec(depth + 1, i + 1)) return r;
      }
      return std::nullopt;
    };
    if (auto r = rec(0, 0)) return r;
  }
  return std::nullopt;
}

TEST(HittingSets, AgreesWithBruteForceOnRandomClouds) {
  sampling::Random rng(31);
  int hits = 0, misses = 0;
  for (int trial = 0; trial < 120; ++trial) {
    io::PointSet ps;
    ps.dimension = 3;
    const int n = 12 + trial % 10;
    for (int i = 0; i < n; ++i) ps.push_back(std::vector<double>{rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-0.15, 0.15)});
    spatial::NeighbourIndex index(ps);
    std::vector<double> x{rng.uniform(-0.5, 0.5), rng.uniform(-0.5, 0.5), rng.uniform(-0.1, 0.1)};
    HittingQuery q;
    q.gamma0 = 0.4;
    q.delta0 = 0.2;
    q.max_set_size = 3;
    q.radius_bound = rng.uniform(0.15, 0.7);
    auto fast = find_hitting_set(x, ps, index, q);
    auto slow = brute_force(x, ps, q);
    ASSERT_EQ(fast.has_value(), slow.has_value()) << "trial " << trial;
    if (fast) {
      EXPECT_EQ(fast->points, *slow) << "trial " << trial;
      ++hits;
    } else {
      ++misses;
    }
  }
  EXPECT_GT(hits, 10);
  EXPECT_GT(misses, 10);
}

}  // namespace
}  // namespace delcert::refine
