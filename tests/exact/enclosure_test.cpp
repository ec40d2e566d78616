#include "exact/enclosure.hpp"

#include <gtest/gtest.h>
#include <mpfr.h>

#include <functional>
#include <stdexcept>
#include <string>

#include "exact/number_types.hpp"
#include "exact/simplex_predicates.hpp"
#include "exact/tangent_predicates.hpp"
#include "exact/polynomial.hpp"
#include "support.hpp"

namespace delcert::exact {
namespace {

using testing::Q;

// A 200-bit MPFR reference value, computed independently with round-to-nearest.
class Ref {
 public:
  Ref() { mpfr_init2(x, 200); }
  explicit Ref(const Q& q) : Ref() { mpfr_set_q(x, q.get_mpq_t(), MPFR_RNDN); }
  ~Ref() { mpfr_clear(x); }
  Ref(const Ref&) = delete;
  Ref& operator=(const Ref&) = delete;
  mpfr_t x;
};

// e contains the reference, and is narrow: width <= max_rel_width * max(|value|, floor).
void expect_contains(const Enclosure& e, const Ref& r, double max_rel_width = 1e-30, double floor = 1e-300) {
  EXPECT_TRUE(e.contains(r.x)) << e.to_string(40) << " does not contain " << mpfr_get_d(r.x, MPFR_RNDN);
  const double v = std::abs(mpfr_get_d(r.x, MPFR_RNDN));
  EXPECT_LE(e.width(), max_rel_width * std::max(v, floor)) << e.to_string(40);
  EXPECT_LE(e.lower(), e.upper());
  // lower_string() is a decimal that is a certified lower bound (as an exact rational).
  EXPECT_LE(parse_rational(e.lower_string()), e.lower_exact());
  EXPECT_GE(parse_rational(e.upper_string()), e.upper_exact());
}

TEST(Enclosure, RationalsAndArithmetic) {
  testing::Rng rng(3);
  for (int t = 0; t < 500; ++t) {
    const Q a(rng.integer(-100000, 100000), rng.integer(1, 9999)), b(rng.integer(1, 100000), rng.integer(1, 9999));
    Enclosure ea(a), eb(b);
    EXPECT_TRUE(ea.contains(a));
    expect_contains(ea, Ref(a));
    expect_contains(ea + eb, Ref(a + b), 1e-30);
    expect_contains(ea * eb, Ref(a * b));
    expect_contains(ea / eb, Ref(a / b));
    if (a - b != 0) expect_contains(ea - eb, Ref(a - b), 1e-25);
    expect_contains(square(ea), Ref(a * a));
    expect_contains(-ea, Ref(-a));
    EXPECT_EQ(ea.lower() <= a.get_d() && a.get_d() <= ea.upper(), true);
  }
  EXPECT_THROW(Enclosure(Q(1)) / Enclosure::between(Q(-1), Q(1)), std::domain_error);
  Enclosure exact_point(0.5);
  EXPECT_EQ(exact_point.width(), 0.0);
  EXPECT_EQ(exact_point.lower_string(), "0.5");
}

TEST(Enclosure, ElementaryFunctionsContainReferences) {
  testing::Rng rng(4);
  for (int prec : {53, 128, 190}) {
    const double rel = std::ldexp(1.0, -prec + 8);
    for (int t = 0; t < 300; ++t) {
      const Q x(rng.integer(1, 1000000), rng.integer(1, 1000000));  // > 0
      const Q u(rng.integer(-900000, 900000), 1000000);               // in [-0.9, 0.9]
      const Q y(rng.integer(-1000, 1000), rng.integer(1, 100));
      const Q z(rng.integer(-1000, 1000), rng.integer(1, 100));
      Ref rx(x), ru(u), ry(y), rz(z), out;
      mpfr_sqrt(out.x, rx.x, MPFR_RNDN);
      expect_contains(sqrt(Enclosure(x, prec)), out, rel);
      mpfr_acos(out.x, ru.x, MPFR_RNDN);
      expect_contains(acos(Enclosure(u, prec)), out, rel);
      mpfr_asin(out.x, ru.x, MPFR_RNDN);
      if (u != 0) expect_contains(asin(Enclosure(u, prec)), out, rel);
      mpfr_atan(out.x, ry.x, MPFR_RNDN);
      if (y != 0) expect_contains(atan(Enclosure(y, prec)), out, rel);
      if (y != 0 || z != 0) {
        mpfr_atan2(out.x, ry.x, rz.x, MPFR_RNDN);
        if (mpfr_zero_p(out.x)) {
          EXPECT_TRUE(atan2(Enclosure(y, prec), Enclosure(z, prec)).contains(out.x));
        } else {
          expect_contains(atan2(Enclosure(y, prec), Enclosure(z, prec)), out, rel);
        }
      }
      mpfr_cos(out.x, ry.x, MPFR_RNDN);
      expect_contains(cos(Enclosure(y, prec)), out, rel * 1e3, 1.0);
      mpfr_sin(out.x, ry.x, MPFR_RNDN);
      expect_contains(sin(Enclosure(y, prec)), out, rel * 1e3, 1.0);
    }
    Ref pi;
    mpfr_const_pi(pi.x, MPFR_RNDN);
    expect_contains(Enclosure::pi(prec), pi, rel);
  }
}

TEST(Enclosure, BranchCutsAndDomainEdges) {
  // atan2 on the negative x axis: y = 0 exactly gives pi; y = +-tiny gives +-(pi - tiny).
  Ref pi;
  mpfr_const_pi(pi.x, MPFR_RNDN);
  EXPECT_TRUE(atan2(Enclosure(0.0), Enclosure(-1.0)).contains(pi.x));
  Enclosure a = atan2(Enclosure(Q(-1, 1000000)), Enclosure(-1.0));
  EXPECT_TRUE(a.is_negative());
  Enclosure b = atan2(Enclosure(Q(1, 1000000)), Enclosure(-1.0));
  EXPECT_TRUE(b.is_positive());
  EXPECT_THROW(atan2(Enclosure::between(Q(-1), Q(1)), Enclosure::between(Q(-1), Q(1))), std::domain_error);
  // acos at the ends of its domain, and arguments that poke out of it only by rounding.
  Ref zero;
  mpfr_set_zero(zero.x, 1);
  EXPECT_TRUE(acos(Enclosure(1.0)).contains(zero.x));
  EXPECT_TRUE(acos(Enclosure(-1.0)).contains(pi.x));
  EXPECT_TRUE(acos(Enclosure::between(Q(1) - Q(1, 1000), Q(1) + Q(1, 1000))).contains(zero.x));
  EXPECT_THROW(acos(Enclosure(2.0)), std::domain_error);
  EXPECT_THROW(sqrt(Enclosure(-1.0)), std::domain_error);
  EXPECT_TRUE(sqrt(Enclosure::between(Q(-1, 100), Q(4))).contains(Q(2)));
  EXPECT_TRUE(sqrt(Enclosure(0.0)).contains(Q(0)));
}

// Geodesic distance on the unit sphere: 2 asin(|x - y| / 2) = acos(x . y), two formulas.
TEST(Enclosure, GeodesicDistanceTwoWays) {
  testing::Rng rng(6);
  for (int t = 0; t < 200; ++t) {
    double x[3], y[3], nx = 0, ny = 0;
    for (int i = 0; i < 3; ++i) {
      x[i] = rng.normal();
      y[i] = rng.normal();
      nx += x[i] * x[i];
      ny += y[i] * y[i];
    }
    // exact rational points on the unit sphere via rational parametrisation
    Q sx[3], sy[3];
    {
      const Q a = to_rational(x[0] / (1 + std::sqrt(nx))), b = to_rational(x[1] / (1 + std::sqrt(nx)));
      const Q d = 1 + a * a + b * b;
      sx[0] = 2 * a / d, sx[1] = 2 * b / d, sx[2] = (1 - a * a - b * b) / d;
      const Q c = to_rational(y[0] / (1 + std::sqrt(ny))), e = to_rational(y[1] / (1 + std::sqrt(ny)));
      const Q f = 1 + c * c + e * e;
      sy[0] = 2 * c / f, sy[1] = 2 * e / f, sy[2] = (1 - c * c - e * e) / f;
    }
    Q dot = 0, d2 = 0;
    for (int i = 0; i < 3; ++i) {
      dot += sx[i] * sy[i];
      d2 += (sx[i] - sy[i]) * (sx[i] - sy[i]);
    }
    Enclosure g1 = acos(Enclosure(dot));
    Enclosure g2 = Enclosure(2L) * asin(sqrt(Enclosure(d2)) / Enclosure(2L));
    Ref r(d2), h, out;
    mpfr_sqrt(h.x, r.x, MPFR_RNDN);
    mpfr_div_ui(h.x, h.x, 2, MPFR_RNDN);
    mpfr_asin(out.x, h.x, MPFR_RNDN);
    mpfr_mul_ui(out.x, out.x, 2, MPFR_RNDN);
    expect_contains(g1, out, 1e-20);
    expect_contains(g2, out, 1e-30);
  }
}

// Margins from the predicates' exact values, enclosed and checked against 200-bit references.
TEST(Enclosure, PredicateMargins) {
  testing::Rng rng(7);
  ImplicitSystem F = ImplicitSystem::parse({"x1^2 + x2^2 - 1", "x3^2 + x4^2 - 1"}, 4);
  const auto M = testing::test_manifolds()[2];
  for (int t = 0; t < 30; ++t) {
    auto p = testing::sample_near(M, rng);
    TangentSpace T(F, p);
    std::vector<std::vector<double>> pts;
    for (int i = 0; i < 4; ++i) pts.push_back(testing::sample_near(M, rng));
    std::vector<const double*> ptr;
    for (auto& x : pts) ptr.push_back(x.data());
    TangentChart chart(T, ptr);
    FilterContext ctx;
    TangentCell cell = chart.cell(std::vector<int>{0, 1, 2}, ctx);
    if (cell.degenerate()) continue;
    const Q delta2(1, 400);
    const Q margin = cell.power_exact(3) - delta2;
    Enclosure e(margin);
    expect_contains(e, Ref(margin));
    EXPECT_EQ(e.is_positive(), margin > 0);
    EXPECT_EQ(cell.power_sign(3, RationalConstant(delta2), ctx), margin > 0 ? 1 : -1);
    // R_p(s) = sqrt(R^2)
    const Q r2 = cell.squared_radius_exact();
    Ref rr(r2), root;
    mpfr_sqrt(root.x, rr.x, MPFR_RNDN);
    expect_contains(sqrt(Enclosure(r2)), root);
    // Thickness of the ambient triangle: sqrt(Upsilon^2)
    const Q ups2 = thickness_squared_exact(std::vector<const double*>{p.data(), ptr[0], ptr[1]}, 4);
    Ref ru(ups2), ups;
    mpfr_sqrt(ups.x, ru.x, MPFR_RNDN);
    expect_contains(sqrt(Enclosure(ups2)), ups);
  }
}

}  // namespace
}  // namespace delcert::exact
