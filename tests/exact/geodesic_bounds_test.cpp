// Curvature bounds and the chord-to-arc comparison (exact/geodesic_bounds.hpp). The curvature
// bound must be at least the exact maximal normal curvature of M at a point of M inside the box
// (compared in rationals), and close to it on small boxes where the derivation is tight; Φ_K and its
// slack must be at least an MPFR reference rounded DOWN at 256 bits (or more) and close to it.
#include "exact/geodesic_bounds.hpp"

#include <gtest/gtest.h>
#include <mpfr.h>

#include <cmath>
#include <limits>
#include <stdexcept>

#include "exact/number_types.hpp"
#include "support.hpp"

namespace delcert::exact {
namespace {

using testing::Q;
constexpr double kInf = std::numeric_limits<double>::infinity();

ImplicitSystem system_of(const std::vector<std::string>& equations, int N) { return ImplicitSystem::parse(equations, N); }

// The sphere |x|^2 = R^2 in R^3, R a double taken exactly (R^2 an exact rational).
ImplicitSystem sphere(double R) {
  const Q r = to_rational(R);
  return ImplicitSystem({Polynomial::parse("x1^2 + x2^2 + x3^2", 3) - Polynomial::constant(r * r, 3)}, 3);
}

Box box_around(const std::vector<double>& p, double half_width) {
  Box X;
  for (double x : p) X.push_back({x - half_width, x + half_width});
  return X;
}

// bound >= exact, with exact = sqrt(exact2) (exact2 rational): bound >= 0 and bound^2 >= exact2.
bool at_least(double bound, const Q& exact2) {
  return bound == kInf || (bound >= 0 && to_rational(bound) * to_rational(bound) >= exact2);
}

// The unit sphere: |II(u, u)| = 1 at every point and in every direction. On a box of half width w
// around a point of the sphere the derivation gives 1 / inf|x| (Hessian 2 I: |H|_2 = 2, bound (b)
// gives |b|^2 <= 4; G = 4 |x|^2), about 1 + sqrt(3) w.
TEST(GeodesicBounds, UnitSphereIsCloseToOne) {
  const ImplicitSystem F = sphere(1.0);
  const CurvatureBound K(F);
  testing::Rng rng(7);
  const testing::TestManifold S2 = testing::test_manifolds()[0];
  for (int trial = 0; trial < 50; ++trial) {
    const std::vector<double> p = testing::sample_near(S2, rng);
    for (double w : {1e-12, 1e-8, 1e-4, 1e-2}) {
      const double k = K(box_around(p, w));
      EXPECT_TRUE(at_least(k, 1)) << k;
      EXPECT_LE(k, 1.1) << "w = " << w;
      EXPECT_EQ(k, curvature_bound(F, box_around(p, w)));
    }
  }
}

// Spheres of radius R from 1e-300 to 1e300 (|II| = 1/R exactly): the bound is >= 1/R, checked in
// rationals, and within 1% on boxes of relative half width 1e-6 around (R, 0, 0) (exactly on the
// sphere) and around R u for random unit u. Below about 1e-308, 1/R is not a double: +infinity.
TEST(GeodesicBounds, ScaledSpheresScaleAsOneOverR) {
  testing::Rng rng(11);
  const testing::TestManifold S2 = testing::test_manifolds()[0];
  for (double R : {1e-300, 1e-200, 1e-160, 1e-100, 1e-10, 1.0, 1e10, 1e100, 1e160, 1e200, 1e300}) {
    const ImplicitSystem F = sphere(R);
    const Q r = to_rational(R), exact2 = 1 / (r * r);
    std::vector<std::vector<double>> points{{R, 0, 0}};
    for (int i = 0; i < 5; ++i) {
      std::vector<double> u = testing::sample_near(S2, rng);
      for (double& x : u) x *= R;
      points.push_back(u);
    }
    for (const auto& p : points) {
      const double k = curvature_bound(F, box_around(p, R * 1e-6));
      EXPECT_TRUE(at_least(k, exact2)) << "R = " << R << ": " << k;
      EXPECT_LE(k * R, 1.01) << "R = " << R;
    }
  }
  // R = 1e-310 (subnormal): 1/R overflows, so no finite bound exists.
  const double R = 1e-310;
  const double k = curvature_bound(sphere(R), {{R * 0.999, R * 1.001}, {-R / 1000, R / 1000}, {-R / 1000, R / 1000}});
  EXPECT_EQ(k, kInf);
}

// Flat: planes (second derivatives identically 0) have K = 0 exactly, in codimension 1 and 2.
TEST(GeodesicBounds, PlanesAreFlat) {
  const ImplicitSystem P1 = system_of({"0.1*x1 + 0.3*x2 - x3 + 7"}, 3);
  EXPECT_EQ(curvature_bound(P1, box_around({1, 2, 7.7}, 1.0)), 0.0);
  EXPECT_EQ(curvature_bound(P1, box_around({1e300, 2, 7.7}, 1e290)), 0.0);
  const ImplicitSystem P2 = system_of({"x1 + x2 - 1e-200", "x3 - 1/3*x4"}, 4);
  EXPECT_EQ(curvature_bound(P2, box_around({1, -1, 1, 3}, 0.5)), 0.0);
}

// The Clifford torus C x C in R^4, C the circle of radius r = 1/sqrt(2) (x1^2 + x2^2 = 1/2,
// x3^2 + x4^2 = 1/2). A unit tangent vector is u = α t1 + β t2 (t_i unit tangents of the two
// circles, α^2 + β^2 = 1); a curve with velocity u has normal acceleration
// II(u, u) = -(α^2 / r) n1 - (β^2 / r) n2 (n_i the circles' unit outward normals, orthogonal), so
// |II(u, u)|^2 = (α^4 + β^4) / r^2 <= 1 / r^2 = 2, with equality at α = 1: max |II| = sqrt(2) at
// every point. The derivation's bound (b) is tight here: h_e = 2, A = 2 I, |b|^2 <= 4, G = 2 I.
// The 3-torus of unit circles in R^6: max |II| = 1 by the same computation.
TEST(GeodesicBounds, CliffordToriAreSharp) {
  const ImplicitSystem T2 = system_of({"x1^2 + x2^2 - 1/2", "x3^2 + x4^2 - 1/2"}, 4);
  const ImplicitSystem T3 = system_of({"x1^2 + x2^2 - 1", "x3^2 + x4^2 - 1", "x5^2 + x6^2 - 1"}, 6);
  testing::Rng rng(3);
  for (int trial = 0; trial < 30; ++trial) {
    const double a = rng.uniform(0, 6.28), b = rng.uniform(0, 6.28), c = rng.uniform(0, 6.28);
    const double s = std::sqrt(0.5);
    const std::vector<double> p2{s * std::cos(a), s * std::sin(a), s * std::cos(b), s * std::sin(b)};
    const std::vector<double> p3{std::cos(a), std::sin(a), std::cos(b), std::sin(b), std::cos(c), std::sin(c)};
    for (double w : {1e-9, 1e-5, 1e-3}) {
      const double k2 = curvature_bound(T2, box_around(p2, w)), k3 = curvature_bound(T3, box_around(p3, w));
      EXPECT_TRUE(at_least(k2, 2)) << k2;
      EXPECT_LE(k2, 1.1 * std::sqrt(2.0));
      EXPECT_TRUE(at_least(k3, 1)) << k3;
      EXPECT_LE(k3, 1.1);
    }
  }
}

// The ellipsoid x^2/a^2 + y^2/b^2 + z^2/c^2 = 1, a = 2, b = 3/2, c = 1. At (a, 0, 0) the normal
// sections are the ellipses of semi-axes (a, b) and (a, c), of curvature a/b^2 = 8/9 and a/c^2 = 2
// there: the largest normal curvature of the whole ellipsoid is a/c^2 = 2 (attained there). At
// (0, 0, c): c/a^2 = 1/4 and c/b^2 = 4/9. There |H|_2 = 2/c^2 = 2 and |grad F| = 2/c = 2: the
// bound is 1, valid but above 4/9 (the derivation does not see the direction).
TEST(GeodesicBounds, EllipsoidEndOfTheMajorAxis) {
  const ImplicitSystem E = system_of({"x1^2/4 + 4/9*x2^2 + x3^2 - 1"}, 3);
  for (double w : {1e-10, 1e-6, 1e-3}) {
    const double k = curvature_bound(E, box_around({2, 0, 0}, w));
    EXPECT_TRUE(at_least(k, 4)) << k;
    EXPECT_LE(k, 2.02);
    const double k_top = curvature_bound(E, box_around({0, 0, 1}, w));
    EXPECT_TRUE(at_least(k_top, Q(16, 81))) << k_top;
    EXPECT_LE(k_top, 1.01);
  }
}

// A box holding a singular point of F (J_F = 0 at the sphere's centre): no bound.
TEST(GeodesicBounds, SingularPointGivesInfinity) {
  const ImplicitSystem F = sphere(1.0);
  EXPECT_EQ(curvature_bound(F, box_around({0, 0, 0}, 0.1)), kInf);
  EXPECT_EQ(curvature_bound(F, box_around({0, 0, 0}, 2.0)), kInf);
  EXPECT_EQ(curvature_bound(F, box_around({1e-3, 0, 0}, 2e-3)), kInf);
  // Overflow of the derivatives' enclosures (4 x1^3 beyond the doubles).
  EXPECT_EQ(curvature_bound(system_of({"x1^4 + x2^2 + x3^2 - 1"}, 3), box_around({1e110, 0, 0}, 1e109)), kInf);
  EXPECT_THROW(curvature_bound(F, box_around({0, 0}, 1)), std::invalid_argument);
  EXPECT_THROW(curvature_bound(F, Box{{1, 0}, {0, 1}, {0, 1}}), std::invalid_argument);
}

// λ_min of G = [[100, 2], [2, 1/20]] (J = [[10, 0], [1/5, 1/10]]) is about 0.009995: plain
// Gershgorin fails (1/20 - 2 < 0), the scaled discs give 1/20 (1 - 2/sqrt(5)) ~ 0.0053. Checked
// exactly: λ_min is the smaller root of λ^2 - tr λ + det, so lower <= λ_min iff lower <= tr/2 and
// lower^2 - tr lower + det >= 0; and upper >= λ_max iff upper >= tr/2 and the same polynomial >= 0.
TEST(GeodesicBounds, GramEigenvalueBoundsScaleTheDiscs) {
  const std::vector<Interval> J{enclose(Q(10)), enclose(Q(0)), enclose(Q(1, 5)), enclose(Q(1, 10))};
  const GramEigenvalueBounds g = gram_eigenvalue_bounds(J, 2, 2);
  ASSERT_GT(g.lower, 0.005);
  const Q tr = Q(100) + Q(1, 20), det = Q(100) * Q(1, 20) - 4;
  auto p = [&](double l) -> Q {
    const Q x = to_rational(l);
    return x * x - tr * x + det;
  };
  EXPECT_TRUE(to_rational(g.lower) <= tr / 2 && p(g.lower) >= 0);
  EXPECT_TRUE(to_rational(g.upper) >= tr / 2 && p(g.upper) >= 0);
  EXPECT_LE(g.upper, 103);
  // A zero row: nothing positive.
  const std::vector<Interval> Z{{1, 1}, {0, 0}, {0, 0}, {0, 0}};
  EXPECT_LE(gram_eigenvalue_bounds(Z, 2, 2).lower, 0);
}

// ---- Φ_K(t) = (2/K) asin(K t / 2) ----

struct Ref {
  mpfr_t x;
  explicit Ref(mpfr_prec_t p) { mpfr_init2(x, p); }
  ~Ref() { mpfr_clear(x); }
};

// s = K t / 2 (exact at 256 bits); < 1?
bool below_one(double K, double t, Ref& s) {
  mpfr_set_d(s.x, K, MPFR_RNDN);
  mpfr_mul_d(s.x, s.x, t, MPFR_RNDN);
  mpfr_div_2ui(s.x, s.x, 1, MPFR_RNDN);
  return mpfr_cmp_ui(s.x, 1) < 0;
}

const double kKs[] = {0x1p-1074, 1e-310, 1e-300, 1e-200, 1e-100, 1e-10, 0.1, 1, 3, 1e10, 1e100, 1e200, 1e300};
const double kTs[] = {0x1p-1074, 1e-310, 1e-300, 1e-200, 1e-100, 1e-8, 0.5, 1, 1.9, 1e8, 1e100, 1e200, 1e300};

// Against (2/K) asin(s) rounded down at 256 bits (a lower bound of the true value): the result must
// be >= it, and within 2^-50 relative (or one subnormal step).
TEST(GeodesicBounds, ChordToGeodesicAgainstMpfr) {
  int finite = 0;
  for (double K : kKs)
    for (double t : kTs) {
      Ref s(256), lo(256), hi(256);
      const double phi = chord_to_geodesic_upper(K, t);
      if (!below_one(K, t, s)) {
        EXPECT_EQ(phi, kInf) << K << " " << t;
        continue;
      }
      ++finite;
      mpfr_asin(lo.x, s.x, MPFR_RNDD);
      mpfr_mul_2ui(lo.x, lo.x, 1, MPFR_RNDD);
      mpfr_div_d(lo.x, lo.x, K, MPFR_RNDD);
      EXPECT_LE(mpfr_cmp_d(lo.x, phi), 0) << "phi below the reference: K = " << K << ", t = " << t;
      mpfr_mul_d(hi.x, lo.x, 1 + 0x1p-50, MPFR_RNDU);
      EXPECT_LE(phi, mpfr_get_d(hi.x, MPFR_RNDU)) << K << " " << t;
      EXPECT_GE(phi, t);
    }
  EXPECT_GT(finite, 60);
}

TEST(GeodesicBounds, ChordToGeodesicEdges) {
  EXPECT_EQ(chord_to_geodesic_upper(0, 5), 5);
  EXPECT_EQ(chord_to_geodesic_upper(0, 1e300), 1e300);
  EXPECT_EQ(chord_to_geodesic_upper(7, 0), 0);
  // K t / 2 just below 1, at 1, just above.
  const double below = 2 * (1 - 0x1p-53);
  const double phi = chord_to_geodesic_upper(1, below);
  EXPECT_GE(phi, 3.1415926);  // 2 asin(1 - 2^-53) = pi - 2^-25.5 (about)
  EXPECT_LE(phi, 3.14159266);
  EXPECT_EQ(chord_to_geodesic_upper(1, 2), kInf);
  EXPECT_EQ(chord_to_geodesic_upper(1, std::nextafter(2.0, 3.0)), kInf);
  // t the largest double with K t / 2 < 1, decided exactly (for K = 2^-1074, Φ_K(DBL_MAX) > DBL_MAX).
  for (double K : {1e300, 3.0, 1e-10, 1e-300}) {
    double t = 2 / K;
    Ref s(256);
    while (!below_one(K, t, s)) t = std::nextafter(t, 0.0);
    EXPECT_LT(chord_to_geodesic_upper(K, t), kInf) << K;
    EXPECT_EQ(chord_to_geodesic_upper(K, std::nextafter(t, kInf)), kInf) << K;
  }
  EXPECT_EQ(chord_to_geodesic_upper(kInf, 1), kInf);
  EXPECT_EQ(chord_to_geodesic_upper(1, kInf), kInf);
  EXPECT_EQ(chord_to_geodesic_upper(std::nan(""), 1), kInf);
  EXPECT_EQ(geodesic_slack_upper(1, std::nan("")), kInf);
  EXPECT_THROW(chord_to_geodesic_upper(-1, 1), std::invalid_argument);
  EXPECT_THROW(geodesic_slack_upper(1, -1), std::invalid_argument);
}

// The slack Φ_K(r) - r = (2/K)(asin(s) - s) against a reference rounded down at 256 bits plus twice
// the bits lost to the cancellation (asin(s) - s ~ s^3 / 6): >= it, and within 2^-30 relative (or
// one subnormal step). Also Φ_K(t) - t <= slack(K, r) for t <= r (monotonicity).
TEST(GeodesicBounds, GeodesicSlackAgainstMpfr) {
  for (double K : kKs)
    for (double t : kTs) {
      Ref s(256);
      const double slack = geodesic_slack_upper(K, t);
      if (!below_one(K, t, s)) {
        EXPECT_EQ(slack, kInf);
        continue;
      }
      const long lost = std::max<long>(0, -mpfr_get_exp(s.x));
      Ref s2(256 + 2 * lost), lo(256 + 2 * lost), hi(256 + 2 * lost);
      mpfr_set(s2.x, s.x, MPFR_RNDN);
      mpfr_asin(lo.x, s2.x, MPFR_RNDD);
      mpfr_sub(lo.x, lo.x, s2.x, MPFR_RNDD);
      mpfr_mul_2ui(lo.x, lo.x, 1, MPFR_RNDD);
      mpfr_div_d(lo.x, lo.x, K, MPFR_RNDD);
      ASSERT_GT(mpfr_sgn(lo.x), 0);
      EXPECT_LE(mpfr_cmp_d(lo.x, slack), 0) << "slack below the reference: K = " << K << ", r = " << t;
      mpfr_mul_d(hi.x, lo.x, 1 + 0x1p-30, MPFR_RNDU);
      EXPECT_LE(slack, mpfr_get_d(hi.x, MPFR_RNDU)) << K << " " << t;
      // Monotone: a smaller chord has a smaller slack (by the reference at t / 2).
      const double half = t / 2;
      if (half > 0) {
        EXPECT_LE(geodesic_slack_upper(K, half), slack);
      }
    }
  EXPECT_EQ(geodesic_slack_upper(0, 1e300), 0);
  EXPECT_EQ(geodesic_slack_upper(1e300, 0), 0);
}

}  // namespace
}  // namespace delcert::exact
