#include "core/refine/point_index.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/sampling/random.hpp"

namespace delcert::refine {
namespace {

TEST(PointIndex, BallQueriesMatchBruteForceWhileGrowing) {
  Random rng(4);
  io::PointSet ps;
  ps.dimension = 5;
  for (int i = 0; i < 300; ++i) {
    std::vector<double> v(5);
    for (auto& c : v) c = rng.uniform(-1, 1);
    ps.push_back(v);
  }
  PointIndex index(ps);
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
    std::size_t nn;
    EXPECT_DOUBLE_EQ(index.nearest_distance2(q, &nn), best);
    EXPECT_EQ(nn, best_i);
  }
}

}  // namespace
}  // namespace delcert::refine
