// exact/angle_series.hpp: the enclosures of g(u) = acos(1 - u)^2 and g'(u) = 2 theta / sin theta
// against MPFI (128 bits) at adversarial arguments: subnormal and tiny u (down to 1e-310), u
// near 1 (the series' switch), u near 2 (the cut locus), wide intervals, and intervals poking out
// of [0, 2] by rounding.
#include <gmpxx.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include "exact/angle_series.hpp"
#include "exact/enclosure.hpp"
#include "exact/interval.hpp"

namespace delcert::exact {
namespace {

using IA = IntervalNumber;

// MPFI's enclosure of theta(u) = acos(1 - u) at the double u (exact input), as 2 asin(sqrt(u / 2))
// (1 - cos theta = 2 sin^2(theta / 2)): relative precision even at u = 1e-310, where 1 - u itself
// is not representable in 128 bits.
Enclosure theta_mpfi(double u) { return Enclosure(2L) * asin(sqrt(Enclosure(u) / Enclosure(2L))); }
Enclosure g_mpfi(double u) {
  const Enclosure t = theta_mpfi(u);
  return t * t;
}

// [lo, hi] encloses the value that the 128-bit ref encloses, up to ref's own relative error
// (2^-100: a wrong series, coefficient or rounding is off by far more).
::testing::AssertionResult encloses(double lo, double hi, const Enclosure& ref) {
  const mpq_class a = ref.lower_exact(), b = ref.upper_exact(), slack_a = abs(a) / mpq_class(mpz_class(1) << 100),
                  slack_b = abs(b) / mpq_class(mpz_class(1) << 100);
  if (mpq_class(lo) <= a + slack_a && mpq_class(hi) >= b - slack_b) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "[" << lo << ", " << hi << "] misses " << ref.to_string(20);
}

std::vector<double> arguments() {
  std::vector<double> u = {0.0, 4.9e-324, 1e-310, 2.2250738585072014e-308, 1e-200, 1e-30, 1e-16, 1e-8, 1e-3,
                           0.1, 0.25, 0.5, 0.75, 0.999, std::nextafter(1.0, 0.0), 1.0, std::nextafter(1.0, 2.0),
                           1.001, 1.25, 1.5, 1.9, 1.999999, std::nextafter(2.0, 0.0), 2.0};
  for (int k = 1; k < 40; ++k) u.push_back(2.0 * k / 40 + 1e-3 * k);  // a sweep
  return u;
}

TEST(AngleSeries, PointEnclosuresContainMpfiAndAreTight) {
  for (double u : arguments()) {
    if (u > 2) continue;
    IA g;
    {
      UpwardRounding up;
      g = acos_squared(IA(u));
    }
    EXPECT_TRUE(encloses(g.inf(), g.sup(), g_mpfi(u))) << u;
    // Relative tightness: a few hundred ulps at most (absolute 1e-300 for g near 0).
    EXPECT_LE(g.sup() - g.inf(), 4e-14 * g.sup() + 1e-300) << u;
    EXPECT_LE(g.inf(), g.sup());
  }
  UpwardRounding up;
  // g(0) = 0 exactly; g(2) = pi^2; g(1) = (pi / 2)^2.
  EXPECT_EQ(acos_squared(IA(0)).inf(), 0.0);
  EXPECT_LE(acos_squared(IA(2)).inf(), M_PI * M_PI);
  EXPECT_GE(acos_squared(IA(2)).sup(), M_PI * M_PI);
  EXPECT_LE(acos_squared(IA(1)).inf(), M_PI * M_PI / 4);
  EXPECT_GE(acos_squared(IA(1)).sup(), M_PI * M_PI / 4);
}

// Ranges: every point of a wide interval (both sides of 1 included) is enclosed; the part
// outside [0, 2] is ignored; an interval missing [0, 2] throws.
TEST(AngleSeries, RangesEncloseEveryPoint) {
  const std::vector<std::pair<double, double>> ranges = {
      {0, 1e-310}, {0, 0.3}, {0.2, 0.9}, {0.5, 1.5}, {0.99, 1.01}, {1.2, 2}, {-1e-17, 0.1}, {1.9, 2 + 1e-15}, {0, 2}};
  for (const auto& [lo, hi] : ranges) {
    IA g;
    {
      UpwardRounding up;
      g = acos_squared(IA(lo, hi));
    }
    for (int k = 0; k <= 64; ++k) {
      const double u = std::clamp(lo + (hi - lo) * k / 64, 0.0, 2.0);
      EXPECT_TRUE(encloses(g.inf(), g.sup(), g_mpfi(u))) << lo << " " << hi << " at " << u;
    }
  }
  UpwardRounding up;
  EXPECT_THROW(acos_squared(IA(-1, -0.5)), std::domain_error);
  EXPECT_THROW(acos_squared(IA(2.5, 3)), std::domain_error);
}

// g'(u) = 2 theta / sin theta (2 at u = 0), enclosed on [0, 1] only.
TEST(AngleSeries, SlopeEnclosesTheDerivative) {
  for (double u : arguments()) {
    std::optional<IA> s;
    {
      UpwardRounding up;
      s = acos_squared_slope(IA(u));
    }
    if (u > 1) {
      EXPECT_FALSE(s) << u;
      continue;
    }
    ASSERT_TRUE(s) << u;
    if (u > 0) {
      const Enclosure t = theta_mpfi(u);
      EXPECT_TRUE(encloses(s->inf(), s->sup(), Enclosure(2L) * t / sin(t))) << u;
    } else {
      EXPECT_TRUE(s->inf() <= 2 && s->sup() >= 2);
    }
    EXPECT_LE(s->sup() - s->inf(), 4e-14 * s->sup()) << u;
  }
  UpwardRounding up;
  const std::optional<IA> w = acos_squared_slope(IA(0.1, 0.6));
  ASSERT_TRUE(w);
  for (double u : {0.1, 0.35, 0.6}) {
    const Enclosure t = theta_mpfi(u);
    EXPECT_TRUE(encloses(w->inf(), w->sup(), Enclosure(2L) * t / sin(t))) << u;
  }
  EXPECT_FALSE(acos_squared_slope(IA(0.5, 1.5)));
}

}  // namespace
}  // namespace delcert::exact
