// The filter-then-exact helper (exact/detail/filtered.hpp) and a public predicate built on it.
#include "exact/detail/filtered.hpp"

#include <gtest/gtest.h>

#include "exact/interval.hpp"
#include "exact/simplex_predicates.hpp"

namespace delcert::exact {
namespace {

using detail::EX;
using detail::filtered_sign;
using detail::IA;

TEST(FilteredSign, AnIntervalThatExcludesZeroDecidesWithoutTheExactPath) {
  FilterContext ctx;
  bool exact_called = false;
  bool upward_inside = false;
  const int s = filtered_sign(
      ctx, PredicateKind::power,
      [&] {
        upward_inside = rounding_is_upward();
        return IA(-3, -1);
      },
      [&] {
        exact_called = true;
        return EX(-2);
      });
  EXPECT_EQ(s, -1);
  EXPECT_FALSE(exact_called);
  EXPECT_TRUE(upward_inside);  // the interval formula runs under upward rounding ...
  EXPECT_TRUE(rounding_is_nearest());  // ... and the caller's mode is restored
  const auto& c = ctx.stats[PredicateKind::power];
  EXPECT_EQ(c.calls, 1u);
  EXPECT_EQ(c.filter_failures, 0u);
  EXPECT_EQ(c.zero_results, 0u);
  // A point interval [0, 0] certifies an exact zero.
  EXPECT_EQ(filtered_sign(ctx, PredicateKind::power, [] { return IA(0); }, [] { return EX(1); }), 0);
  EXPECT_EQ(c.calls, 2u);
  EXPECT_EQ(c.filter_failures, 0u);
  EXPECT_EQ(c.zero_results, 1u);
}

TEST(FilteredSign, AnIntervalContainingZeroFallsBackToTheExactValue) {
  FilterContext ctx;
  EXPECT_EQ(filtered_sign(ctx, PredicateKind::thickness, [] { return IA(-1, 1); }, [] { return EX(0.5); }), 1);
  EXPECT_EQ(filtered_sign(ctx, PredicateKind::thickness, [] { return IA(0, 1); }, [] { return EX(0); }), 0);
  // A filter that decides a sign itself may also say "undecided"; the exact side may give a sign.
  EXPECT_EQ(filtered_sign(ctx, PredicateKind::thickness, [] { return detail::kUndecided; }, [] { return -1; }), -1);
  const auto& c = ctx.stats[PredicateKind::thickness];
  EXPECT_EQ(c.calls, 3u);
  EXPECT_EQ(c.filter_failures, 3u);
  EXPECT_EQ(c.zero_results, 1u);
  // Other kinds are untouched.
  EXPECT_EQ(ctx.stats.total_calls(), 3u);
}

TEST(FilteredSign, ForceExactAndUnusableFiltersSkipTheInterval) {
  FilterContext ctx;
  int interval_calls = 0;
  auto interval = [&] {
    ++interval_calls;
    return IA(1, 2);
  };
  EXPECT_EQ(filtered_sign(ctx, PredicateKind::ambient_power, false, interval, [] { return EX(-1); }), -1);
  ctx.force_exact = true;
  EXPECT_EQ(filtered_sign(ctx, PredicateKind::ambient_power, interval, [] { return EX(3); }), 1);
  EXPECT_EQ(interval_calls, 0);
  EXPECT_EQ(ctx.stats[PredicateKind::ambient_power].calls, 2u);
  EXPECT_EQ(ctx.stats[PredicateKind::ambient_power].filter_failures, 2u);
}

// Through a public predicate: a clear comparison is decided by the filter, an exact tie is not.
TEST(FilteredSign, SquaredDistancePredicateCountsItsPath) {
  FilterContext ctx;
  const double a[2] = {0, 0}, b[2] = {3, 4};
  EXPECT_EQ(compare_squared_distance(a, b, RationalConstant(mpq_class(24)), 2, ctx), 1);
  const auto& c = ctx.stats[PredicateKind::squared_distance];
  EXPECT_EQ(c.calls, 1u);
  EXPECT_EQ(c.filter_failures, 0u);
  EXPECT_EQ(compare_squared_distance(a, b, RationalConstant(mpq_class(25)), 2, ctx), 0);  // |a - b|^2 = 25 exactly
  EXPECT_EQ(c.calls, 2u);
  EXPECT_EQ(c.filter_failures, 1u);
  EXPECT_EQ(c.zero_results, 1u);
  const double d[2] = {4, 3};
  EXPECT_EQ(compare_squared_distances(a, b, a, d, 2, ctx), 0);
  EXPECT_EQ(c.calls, 3u);
  EXPECT_EQ(c.filter_failures, 2u);
  EXPECT_EQ(c.zero_results, 2u);
}

}  // namespace
}  // namespace delcert::exact
