// The filter-then-exact evaluation (exact/detail/filtered.hpp), through the public predicates built
// on it: a call the interval decides, a call that needs the exact path, and the counters of each.
// (The helper itself needs CGAL's number types, which tests do not compile.)
#include <gtest/gtest.h>

#include "exact/filter_stats.hpp"
#include "exact/interval.hpp"
#include "exact/number_types.hpp"
#include "exact/simplex_predicates.hpp"

namespace delcert::exact {
namespace {

TEST(FilteredSign, IntervalDecidesAClearCaseAndExactDecidesATie) {
  FilterContext ctx;
  const double a[2] = {0, 0}, b[2] = {3, 4}, d[2] = {4, 3};
  const auto& c = ctx.stats[PredicateKind::squared_distance];
  // |a - b|^2 = 25 > 24: the interval excludes 0.
  EXPECT_EQ(compare_squared_distance(a, b, RationalConstant(mpq_class(24)), 2, ctx), 1);
  EXPECT_EQ(c.calls, 1u);
  EXPECT_EQ(c.filter_failures, 0u);
  EXPECT_EQ(c.zero_results, 0u);
  // = 25 exactly: the interval contains 0 and another value, the exact path answers 0.
  EXPECT_EQ(compare_squared_distance(a, b, RationalConstant(mpq_class(25)), 2, ctx), 0);
  EXPECT_EQ(c.calls, 2u);
  EXPECT_EQ(c.filter_failures, 1u);
  EXPECT_EQ(c.zero_results, 1u);
  EXPECT_EQ(compare_squared_distances(a, b, a, d, 2, ctx), 0);
  EXPECT_EQ(c.calls, 3u);
  EXPECT_EQ(c.filter_failures, 2u);
  EXPECT_EQ(c.zero_results, 2u);
  EXPECT_EQ(ctx.stats.total_calls(), 3u);  // no other kind counted
  EXPECT_TRUE(rounding_is_nearest());      // the rounding guard restored the caller's mode
}

TEST(FilteredSign, ForceExactTakesTheExactPathWithTheSameAnswer) {
  FilterContext ctx;
  ctx.force_exact = true;
  const double a[2] = {0, 0}, b[2] = {3, 4};
  EXPECT_EQ(compare_squared_distance(a, b, RationalConstant(mpq_class(24)), 2, ctx), 1);
  EXPECT_EQ(ctx.stats[PredicateKind::squared_distance].filter_failures, 1u);
}

TEST(FilteredSign, AmbientPowerOfAnExactCentre) {
  FilterContext ctx;
  const double p[2] = {0, 0}, q[2] = {1, 1};
  // |x - q|^2 - |x - p|^2 = 2 - 2 (x_0 + x_1). x = (1/3, 5): < 0, decided by the interval.
  EXPECT_EQ(ambient_power_sign(RationalPoint({mpq_class(1, 3), mpq_class(5)}), p, q, ctx), -1);
  // x = (1/3, 2/3) is equidistant from p and q, and 1/3, 2/3 are not doubles: only the exact
  // path can show the tie.
  EXPECT_EQ(ambient_power_sign(RationalPoint({mpq_class(1, 3), mpq_class(2, 3)}), p, q, ctx), 0);
  const auto& c = ctx.stats[PredicateKind::ambient_power];
  EXPECT_EQ(c.calls, 2u);
  EXPECT_EQ(c.filter_failures, 1u);
  EXPECT_EQ(c.zero_results, 1u);
}

}  // namespace
}  // namespace delcert::exact
