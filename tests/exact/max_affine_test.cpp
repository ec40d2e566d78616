// exact/max_affine.hpp: known answers, and never below the exact value of its own expression on
// adversarial magnitudes (the lambda it chose is recovered from its output for one q).
#include "exact/max_affine.hpp"

#include <gtest/gtest.h>
#include <gmpxx.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "exact/number_types.hpp"

namespace delcert::exact {
namespace {

TEST(MaxAffine, KnownMinimumOverOneMultiplier) {
  // max(1 - t, t) is smallest at t = 1/2, where it is 1/2 (exact in binary).
  EXPECT_EQ(max_affine_upper_bound(std::vector<double>{1, 0}, std::vector<double>{-1, 1}, 1), 0.5);
  // No falling line: lambda stays 0 and the bound is max F.
  EXPECT_EQ(max_affine_upper_bound(std::vector<double>{3, 2}, std::vector<double>{1, 2}, 1), 3);
  // Every line falls but none rises: no crossing, lambda stays 0 (the caller's region would be
  // empty, which the caller's own signs decide), so max F.
  EXPECT_EQ(max_affine_upper_bound(std::vector<double>{1, 2}, std::vector<double>{-1, -1}, 1), 2);
  // Two multipliers: max(2 - l0, 2 - l1, l0 + l1) is 4/3 at best; coordinate descent may stop
  // higher (it is a heuristic), never lower, never above lambda = 0's value.
  const double two = max_affine_upper_bound(std::vector<double>{2, 2, 0}, std::vector<double>{-1, 0, 0, -1, 1, 1}, 2);
  EXPECT_GE(two, 4.0 / 3);
  EXPECT_LE(two, 2);
  // Two multipliers that each help alone: max(3 - l0, 1 + l0 - l1, 1 + l1) reaches 5/3 at
  // l0 = 4/3, l1 = 2/3; the descent gets below max F = 3.
  EXPECT_LT(max_affine_upper_bound(std::vector<double>{3, 1, 1}, std::vector<double>{-1, 0, 1, -1, 0, 1}, 2), 3);
  // No multipliers: max F.
  EXPECT_EQ(max_affine_upper_bound(std::vector<double>{-1, 5, 2}, std::vector<double>{}, 0), 5);
}

TEST(MaxAffine, NonFiniteInputsNeverGiveASmallBound) {
  const double inf = std::numeric_limits<double>::infinity(), nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(max_affine_upper_bound(std::vector<double>{nan, 0}, std::vector<double>{-1, 1}, 1), inf);
  EXPECT_EQ(max_affine_upper_bound(std::vector<double>{inf, 0}, std::vector<double>{-1, 1}, 1), inf);
  // An infinite coefficient with lambda = 0 adds nothing; with lambda > 0 it is never lowering.
  EXPECT_GE(max_affine_upper_bound(std::vector<double>{1, 0}, std::vector<double>{inf, 1}, 1), 1);
  EXPECT_GE(max_affine_upper_bound(std::vector<double>{1, 1}, std::vector<double>{-inf, inf}, 1), 1);
  EXPECT_THROW(max_affine_upper_bound(std::vector<double>{1, 0}, std::vector<double>{1}, 1), std::invalid_argument);
}

TEST(MaxAffine, NeverBelowTheExactMinimumOverLambda) {
  // For one multiplier the exact min over t >= 0 of max_c (F_c + t S_c) is computed in rationals
  // (at 0 and at every crossing of a rising and a falling line); the returned bound, the value
  // of the expression at one t >= 0 rounded up, can never be below it. Magnitudes 1e-310..1e308.
  std::mt19937_64 rng(7);
  const double scales[] = {1e-310, 1e-300, 1e-160, 1e-20, 1, 1e20, 1e150, 1e300, 1e308};
  int checked = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const int nc = 2 + static_cast<int>(rng() % 7);
    std::uniform_real_distribution<double> U(-1, 1);
    const double sf = scales[rng() % 9], ss = scales[rng() % 9];
    std::vector<double> F(nc), S(nc);
    for (int c = 0; c < nc; ++c) F[c] = U(rng) * sf, S[c] = U(rng) * ss;
    const double B = max_affine_upper_bound(F, S, 1);
    if (!std::isfinite(B)) continue;
    auto at = [&](const mpq_class& t) {
      mpq_class best = to_rational(F[0]) + t * to_rational(S[0]);
      for (int c = 1; c < nc; ++c) best = std::max<mpq_class>(best, to_rational(F[c]) + t * to_rational(S[c]));
      return best;
    };
    mpq_class lowest = at(0);
    for (int c = 0; c < nc; ++c)
      for (int e = 0; e < nc; ++e)
        if (S[c] > 0 && S[e] < 0) {
          const mpq_class t = (to_rational(F[e]) - to_rational(F[c])) / (to_rational(S[c]) - to_rational(S[e]));
          if (t > 0) lowest = std::min<mpq_class>(lowest, at(t));
        }
    ASSERT_GE(to_rational(B), lowest) << "trial " << trial;
    ++checked;
  }
  EXPECT_GT(checked, 2500);
  std::printf("[ max affine ] %d random cases checked against the exact minimum\n", checked);
}

}  // namespace
}  // namespace delcert::exact
