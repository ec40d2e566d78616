#include "exact/number_types.hpp"

#include <gtest/gtest.h>

#include <cfloat>
#include <cmath>
#include <limits>

#include "exact/filter_stats.hpp"
#include "exact/interval.hpp"
#include "exact/polynomial.hpp"
#include "support.hpp"

namespace delcert::exact {
namespace {

using testing::Q;

TEST(NumberTypes, DoublesAreExactRationals) {
  EXPECT_EQ(to_rational(0.5), Q(1, 2));
  EXPECT_EQ(to_rational(0.1), Q(mpz_class("3602879701896397"), mpz_class("36028797018963968")));
  EXPECT_EQ(to_rational(-3.0), Q(-3));
  EXPECT_EQ(to_rational(DBL_TRUE_MIN) * (mpz_class(1) << 1074), 1);
  EXPECT_TRUE(is_dyadic(to_rational(0.1)));
  EXPECT_FALSE(is_dyadic(Q(1, 10)));
  EXPECT_THROW(to_rational(std::nan("")), std::invalid_argument);
  EXPECT_THROW(to_rational(std::numeric_limits<double>::infinity()), std::invalid_argument);
}

TEST(NumberTypes, EnclosuresOfRationalsAreTight) {
  testing::Rng rng(1);
  for (int t = 0; t < 2000; ++t) {
    const Q q(rng.integer(-1000000, 1000000), rng.integer(1, 1000000));
    const Interval e = enclose(q);
    EXPECT_LE(to_rational(e.lo), q);
    EXPECT_GE(to_rational(e.hi), q);
    if (e.lo != e.hi) {
      EXPECT_EQ(std::nextafter(e.lo, INFINITY), e.hi);
    } else {
      EXPECT_EQ(to_rational(e.lo), q);
    }
  }
  // Independent of the rounding mode.
  for (int t = 0; t < 2000; ++t) {
    const Q q(rng.integer(-1000000, 1000000), rng.integer(1, 1000000));
    const Interval nearest = enclose(q);
    UpwardRounding up;
    const Interval e = enclose(q);
    EXPECT_EQ(e.lo, nearest.lo);
    EXPECT_EQ(e.hi, nearest.hi);
  }
  const Interval tiny = enclose(Q(1, mpz_class(1) << 2000));
  EXPECT_EQ(tiny.lo, 0.0);
  EXPECT_GT(tiny.hi, 0.0);
  const Interval huge = enclose(Q(mpz_class(1) << 2000));
  EXPECT_EQ(huge.lo, DBL_MAX);
  RationalConstant c(Q(2, 6));
  EXPECT_EQ(c.value(), Q(1, 3));
  EXPECT_EQ(c.sign(), 1);
}

TEST(NumberTypes, RoundingGuardsNestAndRestore) {
  EXPECT_TRUE(rounding_is_nearest());
  {
    UpwardRounding a;
    EXPECT_TRUE(rounding_is_upward());
    {
      UpwardRounding b;
      EXPECT_TRUE(rounding_is_upward());
      {
        NearestRounding n;
        EXPECT_TRUE(rounding_is_nearest());
      }
      EXPECT_TRUE(rounding_is_upward());
    }
    EXPECT_TRUE(rounding_is_upward());
  }
  EXPECT_TRUE(rounding_is_nearest());
}

TEST(NumberTypes, FilterStatsMerge) {
  FilterStats a, b;
  a[PredicateKind::power].calls = 3;
  a[PredicateKind::power].filter_failures = 1;
  b[PredicateKind::power].calls = 4;
  b[PredicateKind::thickness].zero_results = 2;
  a.merge(b);
  EXPECT_EQ(a[PredicateKind::power].calls, 7u);
  EXPECT_EQ(a[PredicateKind::thickness].zero_results, 2u);
  EXPECT_EQ(a.total_calls(), 7u);
  EXPECT_EQ(a.total_failures(), 1u);
  EXPECT_EQ(predicate_name(PredicateKind::power_threshold), "power_threshold");
}

// Polynomial arithmetic between operands over different numbers of variables (fixed in
// exact/polynomial.cpp: exponent vectors are padded).
TEST(NumberTypes, PolynomialMixedVariableCounts) {
  Polynomial zero;  // 0 variables
  Polynomial x = Polynomial::parse("x1 + 2*x2", 2);
  Polynomial s = zero + x;
  EXPECT_EQ(s, x);
  Polynomial c = Polynomial::constant(mpq_class(3), 1);  // over 1 variable
  Polynomial prod = c * x;
  EXPECT_EQ(prod, Polynomial::parse("3*x1 + 6*x2", 2));
  Polynomial sum = Polynomial::parse("x1", 1) + Polynomial::parse("x1 + x2", 2);
  EXPECT_EQ(sum, Polynomial::parse("2*x1 + x2", 2));
  EXPECT_EQ(sum.terms().size(), 2u);
}

}  // namespace
}  // namespace delcert::exact
