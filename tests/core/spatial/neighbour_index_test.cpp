#include "core/spatial/neighbour_index.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "core/sampling/random.hpp"

namespace delcert::spatial {
namespace {

TEST(NeighbourIndex, BallAndNearestMatchBruteForceWhileGrowing) {
  sampling::Random rng(4);
  io::PointSet ps;
  ps.dimension = 5;
  for (int i = 0; i < 300; ++i) {
    std::vector<double> v(5);
    for (auto& c : v) c = rng.uniform(-1, 1);
    ps.push_back(v);
  }
  NeighbourIndex index(ps);
  for (int round = 0; round < 700; ++round) {
    std::vector<double> v(5);
    for (auto& c : v) c = rng.uniform(-1, 1);
    ps.push_back(v);
    index.push_back(v);
    ASSERT_EQ(index.size(), ps.size());
    if (round % 37 != 0) continue;
    std::vector<double> q(5);
    for (auto& c : q) c = rng.uniform(-1, 1);
    const double r2 = 0.5;
    std::vector<std::size_t> brute;
    double best = INFINITY;
    std::size_t best_i = 0;
    for (std::size_t i = 0; i < ps.size(); ++i) {
      double s = 0;
      for (int j = 0; j < 5; ++j) s += std::pow(ps.point(i)[j] - q[j], 2);
      if (s <= r2) brute.push_back(i);
      if (s < best) best = s, best_i = i;
    }
    EXPECT_EQ(index.ball(q, r2), brute);
    std::vector<std::size_t> visited;
    index.for_each_in_ball(q, r2, [&](std::size_t i, double) { visited.push_back(i); });
    std::sort(visited.begin(), visited.end());
    EXPECT_EQ(visited, brute);
    std::size_t nn;
    EXPECT_DOUBLE_EQ(index.nearest_distance2(q, &nn), best);
    EXPECT_EQ(nn, best_i);
  }
}

TEST(NeighbourIndex, StaticQueriesAgreeWithBruteForce) {
  sampling::Random rng(5);
  io::PointSet ps;
  ps.dimension = 4;
  for (int i = 0; i < 3000; ++i) ps.coordinates.push_back(rng.uniform(-1, 1));
  const NeighbourIndex tree(ps);
  for (int t = 0; t < 50; ++t) {
    std::vector<double> q(4);
    for (double& v : q) v = rng.uniform(-1, 1);
    double r2 = rng.uniform(0, 0.3);
    std::vector<std::size_t> brute;
    std::vector<std::pair<double, std::size_t>> all;
    for (std::size_t i = 0; i < ps.size(); ++i) {
      double s = 0;
      for (int k = 0; k < 4; ++k) s += std::pow(ps.point(i)[k] - q[k], 2);
      if (s <= r2) brute.push_back(i);
      all.emplace_back(s, i);
    }
    EXPECT_EQ(tree.ball(q, r2), brute);
    std::sort(all.begin(), all.end());
    std::vector<std::pair<double, std::size_t>> nn;
    tree.nearest(q, 9, nn);
    ASSERT_EQ(nn.size(), 9u);
    for (int k = 0; k < 9; ++k) EXPECT_EQ(nn[k], all[k]);
  }
}

}  // namespace
}  // namespace delcert::spatial
