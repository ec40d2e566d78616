// FarFilter (certify/detail/far_filter.hpp) against the exact projected squared distance: whenever
// it says "beyond", the exact t = b^T G^-1 b (b = U^T (x - p), rationals) exceeds the threshold, at
// every magnitude from 10^-310 to 10^308, in every rounding mode, with thresholds just around t.
#include "certify/tangential/far_filter.hpp"

#include <gmpxx.h>
#include <gtest/gtest.h>

#include <cfenv>
#include <cmath>
#include <random>
#include <vector>

#include "exact/linear_algebra.hpp"
#include "exact/number_types.hpp"

namespace delcert::certify::detail {
namespace {

struct Frame {
  int N = 0, m = 0;
  std::vector<double> p;
  std::vector<mpq_class> U, Gi;  // exact basis (N x m) and exact G^-1 (m x m)
  std::vector<double> ulo, uhi, glo, ghi;
};

// A random full-rank basis with entries of magnitude ~ u_scale, at a point of magnitude p_scale.
Frame make_frame(int N, int m, double p_scale, double u_scale, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> uni(-1, 1);
  Frame F;
  F.N = N, F.m = m;
  for (int i = 0; i < N; ++i) F.p.push_back(uni(rng) * p_scale);
  for (int k = 0; k < N * m; ++k) F.U.emplace_back(uni(rng) * u_scale);
  std::vector<mpq_class> G(m * m, mpq_class(0));
  for (int a = 0; a < m; ++a)
    for (int b = 0; b < m; ++b)
      for (int i = 0; i < N; ++i) G[a * m + b] += F.U[i * m + a] * F.U[i * m + b];
  auto inv = exact::inverse(G, m);
  EXPECT_TRUE(inv.has_value());
  F.Gi = *inv;
  for (const auto& u : F.U) {
    auto e = exact::enclose(u);
    F.ulo.push_back(e.lo), F.uhi.push_back(e.hi);
  }
  for (const auto& g : F.Gi) {
    auto e = exact::enclose(g);
    F.glo.push_back(e.lo), F.ghi.push_back(e.hi);
  }
  return F;
}

mpq_class exact_t(const Frame& F, const std::vector<double>& x) {
  std::vector<mpq_class> b(F.m, mpq_class(0));
  for (int i = 0; i < F.N; ++i) {
    const mpq_class d = mpq_class(x[i]) - mpq_class(F.p[i]);
    for (int a = 0; a < F.m; ++a) b[a] += F.U[i * F.m + a] * d;
  }
  mpq_class t = 0;
  for (int a = 0; a < F.m; ++a)
    for (int k = 0; k < F.m; ++k) t += b[a] * F.Gi[a * F.m + k] * b[k];
  return t;
}

struct RoundingMode {
  explicit RoundingMode(int mode) : old_(std::fegetround()) { std::fesetround(mode); }
  ~RoundingMode() { std::fesetround(old_); }
  int old_;
};

// Every "beyond" is true; returns how many queries said "beyond" (to show the filter is not vacuous).
int check_frame(const Frame& F, double x_scale, std::mt19937_64& rng, int queries) {
  std::uniform_real_distribution<double> uni(-1, 1);
  int said = 0;
  for (int k = 0; k < queries; ++k) {
    std::vector<double> x(F.N);
    bool finite = true;
    for (int i = 0; i < F.N; ++i) x[i] = F.p[i] + uni(rng) * x_scale, finite = finite && std::isfinite(x[i]);
    if (!finite) continue;
    const mpq_class t = exact_t(F, x);
    // Thresholds around t: far below, just below, at, just above (td = t.get_d() is t truncated,
    // so its successor is above t), and 0.
    const double td = t.get_d();
    for (double th : {td / 4, td * (1 - 0x1p-40), td, std::nextafter(td, INFINITY), td * (1 + 0x1p-40), 0.0}) {
      if (!(th >= 0) || !std::isfinite(th)) continue;
      for (int mode : {FE_TONEAREST, FE_UPWARD, FE_DOWNWARD, FE_TOWARDZERO}) {
        bool beyond = false;
        {
          RoundingMode r(mode);
          FarFilter far(F.p, F.ulo, F.uhi, F.glo, F.ghi, F.m, th);
          beyond = far.beyond(x);
          // The unrolled instances check 7 uses are the same test; other fixed dimensions than
          // the constructor's prove nothing.
          if (F.N == 3 && F.m == 2) {
            EXPECT_EQ((far.beyond_in<3, 2>(x.data())), beyond);
          }
          if (F.N == 4 && F.m == 3) {
            EXPECT_EQ((far.beyond_in<4, 3>(x.data())), beyond);
          } else {
            EXPECT_FALSE((far.beyond_in<4, 3>(x.data())));
          }
        }
        if (beyond) {
          ++said;
          EXPECT_GT(t, mpq_class(th)) << "FarFilter said beyond, but the exact t = " << t.get_d() << " <= threshold " << th
                                       << " (N = " << F.N << ", m = " << F.m << ", x scale " << x_scale << ", mode " << mode << ")";
        }
      }
    }
  }
  return said;
}

TEST(FarFilter, NeverClaimsBeyondWhenTheExactProjectionIsNot) {
  std::mt19937_64 rng(14);
  for (int N : {2, 3, 4, 7})
    for (int m = 1; m < N && m <= 4; ++m)
      for (double u_scale : {1e-150, 1e-20, 1.0, 1e20, 1e150}) {
        Frame F = make_frame(N, m, 1.0, u_scale, rng);
        check_frame(F, 1e-3, rng, 20);
      }
}

TEST(FarFilter, AdversarialMagnitudes) {
  std::mt19937_64 rng(15);
  int said = 0;
  for (double p_scale : {0.0, 1e-310, 1e-300, 1.0, 1e300, 1e308})
    for (double x_scale : {1e-310, 1e-308, 1e-200, 1e-16, 1.0, 1e200, 1e307}) {
      Frame F = make_frame(4, 3, p_scale, 1.0, rng);
      said += check_frame(F, x_scale, rng, 10);
    }
  EXPECT_GT(said, 0);
}

// The error bound itself: basis enclosures whose midpoints are off the exact basis (lo = U - 3w,
// hi = U + w), likewise for G^-1, and points far along the normal (b = U^T (x - p) cancels). A filter that compared
// its floating-point t with the threshold without the bound fails here.
TEST(FarFilter, WideEnclosuresAndCancellation) {
  std::mt19937_64 rng(16);
  std::uniform_real_distribution<double> uni(-1, 1);
  int said = 0;
  for (int trial = 0; trial < 200; ++trial) {
    Frame F = make_frame(3, 2, 1.0, 1.0, rng);
    const double w = trial % 8 < 4 ? 0x1p-30 : 0x1p-45;
    if (trial % 4 != 2)
      for (std::size_t k = 0; k < F.U.size(); ++k) {
        const double u = F.U[k].get_d();
        F.ulo[k] = u - 3 * w * std::abs(u), F.uhi[k] = u + w * std::abs(u);
      }
    if (trial % 4 >= 2)  // G^-1's enclosure (alone when trial % 4 == 2), its midpoint above the exact value
      for (std::size_t k = 0; k < F.Gi.size(); ++k) {
        const double g = F.Gi[k].get_d();
        F.glo[k] = g - w * std::abs(g), F.ghi[k] = g + 3 * w * std::abs(g);
      }
    // n: the cross product of U's columns (the normal, in doubles).
    const double a0 = F.U[0].get_d(), a1 = F.U[2].get_d(), a2 = F.U[4].get_d();
    const double b0 = F.U[1].get_d(), b1 = F.U[3].get_d(), b2 = F.U[5].get_d();
    const double n[3] = {a1 * b2 - a2 * b1, a2 * b0 - a0 * b2, a0 * b1 - a1 * b0};
    for (double L : {0.0, 1e2, 1e6, 1e9}) {
      std::vector<double> x(3);
      for (int i = 0; i < 3; ++i) x[i] = F.p[i] + n[i] * L + uni(rng) * 1e-3;
      const mpq_class t = exact_t(F, x);
      const double td = t.get_d();
      for (double th : {td / 2, td, std::nextafter(td, INFINITY), td * (1 + 0x1p-45)})
        for (int mode : {FE_TONEAREST, FE_UPWARD, FE_DOWNWARD}) {
          RoundingMode r(mode);
          FarFilter far(F.p, F.ulo, F.uhi, F.glo, F.ghi, F.m, th);
          if (far.beyond(x)) {
            ++said;
            EXPECT_GT(t, mpq_class(th)) << "w = " << w << ", L = " << L << ", mode " << mode;
          }
        }
    }
  }
  EXPECT_GT(said, 0);
}

TEST(FarFilter, DiscardsWhatIsClearlyFarAndKeepsWhatIsNear) {
  // An orthonormal tangent plane {x_3 = 0} of R^3 at the origin: t = x_1^2 + x_2^2.
  const std::vector<double> p{0, 0, 0}, u{1, 0, 0, 1, 0, 0}, g{1, 0, 0, 1};
  FarFilter far(p, u, u, g, g, 2, 1.0);
  EXPECT_TRUE(far.beyond(std::vector<double>{1.001, 0, 5}));  // t = 1.002: beyond, whatever the normal part
  EXPECT_TRUE(far.beyond(std::vector<double>{0.8, 0.7, -3}));
  EXPECT_FALSE(far.beyond(std::vector<double>{0.999, 0, 0}));  // t < 1
  EXPECT_FALSE(far.beyond(std::vector<double>{1, 0, 0}));      // t = 1: not strictly beyond
  EXPECT_FALSE(far.beyond(std::vector<double>{0, 0, 100}));    // far in space, projected onto p
  // Non-finite input or enclosures: never "beyond".
  EXPECT_FALSE(far.beyond(std::vector<double>{INFINITY, 0, 0}));
  EXPECT_FALSE(far.beyond(std::vector<double>{NAN, 0, 0}));
  const std::vector<double> wide_lo{-INFINITY, 0, 0, 1, 0, 0}, wide_hi{INFINITY, 0, 0, 1, 0, 0};
  FarFilter wide(p, wide_lo, wide_hi, g, g, 2, 1.0);
  EXPECT_FALSE(wide.beyond(std::vector<double>{10, 10, 0}));
  FarFilter nan_threshold(p, u, u, g, g, 2, NAN);
  EXPECT_FALSE(nan_threshold.beyond(std::vector<double>{10, 10, 0}));
  EXPECT_THROW(FarFilter(p, u, u, g, g, 3, 1.0), std::invalid_argument);
}

}  // namespace
}  // namespace delcert::certify::detail
