#include "exact/manifold_distance.hpp"

#include <gtest/gtest.h>

#include <array>
#include <vector>

#include "exact/enclosure.hpp"
#include "exact/number_types.hpp"

namespace delcert::exact {
namespace {

std::vector<Polynomial> parse_all(const std::vector<std::string>& eqs, int N) {
  std::vector<Polynomial> out;
  for (const auto& e : eqs) out.push_back(Polynomial::parse(e, N));
  return out;
}

const std::vector<std::string> kSo3 = {"x1^2 + x2^2 + x3^2 - 1", "x4^2 + x5^2 + x6^2 - 1", "x7^2 + x8^2 + x9^2 - 1",
                                       "x1*x4 + x2*x5 + x3*x6",  "x1*x7 + x2*x8 + x3*x9",  "x4*x7 + x5*x8 + x6*x9"};
const char* kDet = "x1*(x5*x9 - x6*x8) - x2*(x4*x9 - x6*x7) + x3*(x4*x8 - x5*x7)";

// The exact distance from p to the unit sphere, |p| - 1, enclosed.
Enclosure distance_to_unit_sphere(std::span<const double> p) {
  mpq_class s = 0;
  for (double c : p) s += to_rational(c) * to_rational(c);
  return sqrt(Enclosure(s)) - Enclosure(1L);
}

TEST(ManifoldDistance, PointsExactlyOnTheSphereGetATinyBound) {
  ManifoldDistance S(parse_all({"x1^2 + x2^2 + x3^2 - 1"}, 3), 3);
  for (std::array<double, 3> p : {std::array<double, 3>{1, 0, 0}, {0, -1, 0}, {0, 0, 1}, {0.6, 0.8, 0}, {0, -0.8, 0.6}}) {
    DistanceCertificate d = S.certify(p);
    ASSERT_TRUE(d.certified) << d.failure;
    EXPECT_GE(d.distance_upper, 0.0);
    EXPECT_LE(d.distance_upper, 1e-15);
    ASSERT_EQ(d.zero_box.size(), 3u);
    for (int v = 0; v < 3; ++v) EXPECT_TRUE(d.zero_box[v].contains(p[v]));  // p itself is the zero
  }
}

TEST(ManifoldDistance, PointMovedAlongTheNormalGetsATightBound) {
  ManifoldDistance S(parse_all({"x1^2 + x2^2 + x3^2 - 1"}, 3), 3);
  for (double e : {1e-6, -1e-6, 1e-9, 1e-3}) {
    SCOPED_TRACE(e);
    std::array<double, 3> p{0.6 * (1 + e), 0.8 * (1 + e), 0};
    const Enclosure truth = distance_to_unit_sphere(p);  // |p| - 1, about e
    const double lo = std::abs(truth.lower()) < std::abs(truth.upper()) ? std::abs(truth.lower()) : std::abs(truth.upper());
    const double hi = std::max(std::abs(truth.lower()), std::abs(truth.upper()));
    DistanceCertificate d = S.certify(p);
    ASSERT_TRUE(d.certified) << d.failure;
    EXPECT_GE(d.distance_upper, lo);               // it is an upper bound of the true distance
    EXPECT_LE(d.distance_upper, hi + 1e-15);       // and a tight one
    EXPECT_NEAR(d.distance_upper, std::abs(e), std::abs(e) * 1e-9 + 1e-15);
  }
}

TEST(ManifoldDistance, So3PointOffTheManifoldByOneMillionth) {
  // diag(1 + e, 1, 1) is at distance e from SO(3) (its polar factor is I); e = fl(1 + 1e-6) - 1
  // exactly (Sterbenz).
  const Polynomial det = Polynomial::parse(kDet, 9);
  ManifoldDistance S(parse_all(kSo3, 9), 9, &det);
  std::array<double, 9> p{1 + 1e-6, 0, 0, 0, 1, 0, 0, 0, 1};
  const double e = p[0] - 1;
  DistanceCertificate d = S.certify(p);
  ASSERT_TRUE(d.certified) << d.failure;
  EXPECT_GE(d.distance_upper, e);
  EXPECT_LE(d.distance_upper, e + 1e-14);
  ASSERT_EQ(d.region.size(), 9u);
  // The wrong component: det = -1 there, the selector refuses it.
  std::array<double, 9> q{-1, 0, 0, 0, 1, 0, 0, 0, 1};
  DistanceCertificate w = S.certify(q);
  EXPECT_FALSE(w.certified);
  EXPECT_NE(w.failure.find("selector"), std::string::npos) << w.failure;
}

TEST(ManifoldDistance, RankDeficientJacobianOnMIsNeverCertified) {
  // The sphere written as (|x|^2 - 1)^2 = 0: the same zero set, but J_F = 0 on it. A residual
  // of 1e-9 here is a distance of about 1.6e-5; no point may get a distance bound.
  ManifoldDistance S(parse_all({"(x1^2 + x2^2 + x3^2 - 1)^2"}, 3), 3);
  for (double e : {0.0, 1e-16, -1e-12, 1e-6, 1.6e-5}) {
    SCOPED_TRACE(e);
    for (std::array<double, 3> p : {std::array<double, 3>{1 + e, 0, 0}, {0.6 * (1 + e), 0.8 * (1 + e), 0},
                                    {0.8947368421052632, 0.3157894736842105, -0.31578947368421056}}) {
      DistanceCertificate d = S.certify(p);
      EXPECT_FALSE(d.certified) << d.distance_upper;
      EXPECT_FALSE(d.failure.empty());
    }
  }
  // Two equations, one of them squared (a circle in R^3 as sphere n (x3^2 = 0)).
  ManifoldDistance C(parse_all({"x1^2 + x2^2 + x3^2 - 1", "x3^2"}, 3), 3);
  for (std::array<double, 3> p : {std::array<double, 3>{1, 0, 0}, {0.6, 0.8, 1e-9}})
    EXPECT_FALSE(C.certify(p).certified);
}

TEST(ManifoldDistance, ZeroOutsideTheReachOfNewtonIsRefusedNotMisreported) {
  // x1^2 + 1 = 0 has no real zero: nothing can be certified, whatever the point.
  ManifoldDistance S(parse_all({"x1^2 + 1"}, 2), 2);
  for (std::array<double, 2> p : {std::array<double, 2>{0, 0}, {1, 5}, {-3, 0.5}}) {
    DistanceCertificate d = S.certify(p);
    EXPECT_FALSE(d.certified);
  }
  // A non-finite coordinate or an overflowing evaluation is a failure, not an exception.
  ManifoldDistance T(parse_all({"x1^2 + x2^2 - 1"}, 2), 2);
  EXPECT_FALSE(T.certify(std::array<double, 2>{1e300, 1e300}).certified);
  EXPECT_FALSE(T.certify(std::array<double, 2>{INFINITY, 0}).certified);
}

TEST(ManifoldDistance, CliffordTorusTwoEquations) {
  // x1^2 + x2^2 = 1/2, x3^2 + x4^2 = 1/2: the point (a, 0, 0, b) with a, b off by e1, e2 is at
  // distance sqrt(e1^2 + e2^2) from it.
  ManifoldDistance S(parse_all({"x1^2 + x2^2 - 1/2", "x3^2 + x4^2 - 1/2"}, 4), 4);
  const double a = 0.5, b = 0.5;  // (0.5, 0.5) is exactly on the circle x^2 + y^2 = 1/2
  std::array<double, 4> on{a, b, -b, a};
  DistanceCertificate d0 = S.certify(on);
  ASSERT_TRUE(d0.certified) << d0.failure;
  EXPECT_LE(d0.distance_upper, 1e-15);
  std::array<double, 4> off{a * (1 + 1e-6), b * (1 + 1e-6), -b, a};
  DistanceCertificate d1 = S.certify(off);
  ASSERT_TRUE(d1.certified) << d1.failure;
  const double e = std::sqrt(off[0] * off[0] + off[1] * off[1]) - std::sqrt(0.5);
  EXPECT_GE(d1.distance_upper, e * (1 - 1e-9));
  EXPECT_LE(d1.distance_upper, e * (1 + 1e-9));
}

// Spheres of radius 2^k for k far from 0: at 2^-600 the equation's values (about 2^-1200) are
// below the double range, so the test needs the scaled coordinates; the bound must contain the
// exact distance | |p| - 2^k | and be at rounding level relative to 2^k.
TEST(ManifoldDistance, WorksAtEveryScaleWithTheScaleExponent) {
  for (int k : {-600, -300, 300, 450}) {
    const mpq_class r2 = k >= 0 ? mpq_class(mpz_class(1) << (2 * k)) : mpq_class(1) / mpq_class(mpz_class(1) << (-2 * k));
    const std::string eq = "x1^2 + x2^2 + x3^2 - (" + r2.get_str() + ")";
    ManifoldDistance scaled(parse_all({eq}, 3), 3, nullptr, k);
    const double t = std::ldexp(1.0, k);
    for (std::array<double, 3> p : {std::array<double, 3>{t, 0, 0}, {0.6 * t, 0.8 * t, 0}, {0, -0.8 * t, std::nextafter(0.6 * t, 0.0)}}) {
      DistanceCertificate d = scaled.certify(p);
      ASSERT_TRUE(d.certified) << "k = " << k << ": " << d.failure;
      mpq_class s = 0;
      for (double c : p) s += to_rational(c) * to_rational(c);
      const Enclosure exact_distance = sqrt(Enclosure(s)) - sqrt(Enclosure(r2));
      EXPECT_GE(d.distance_upper, std::max(std::abs(exact_distance.lower()), std::abs(exact_distance.upper())) * (1 - 1e-9)) << k;
      EXPECT_LE(d.distance_upper, t * 1e-14) << k;
    }
  }
  // Without the scale exponent the tiny sphere cannot be certified (never certified wrongly).
  ManifoldDistance unscaled(parse_all({"x1^2 + x2^2 + x3^2 - (" +
                                       mpq_class(mpq_class(1) / mpq_class(mpz_class(1) << 1200)).get_str() + ")"},
                                      3),
                            3);
  const double t = std::ldexp(1.0, -600);
  EXPECT_FALSE(unscaled.certify(std::array<double, 3>{t, 0, 0}).certified);
}

}  // namespace
}  // namespace delcert::exact
