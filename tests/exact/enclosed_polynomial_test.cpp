// EnclosedPolynomial (exact/enclosed_polynomial.hpp): every operation's enclosures hold the exact
// result of the same operation on exact polynomials inside the operands' enclosures (checked
// against exact rational arithmetic on the polynomials the operands were enclosed from), over
// adversarial magnitudes (10^-310 ... 10^308: underflow, overflow); the chart-style parametric
// system built from enclosures decides like the exact one.
#include "exact/enclosed_polynomial.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <stdexcept>
#include <vector>

#include "exact/interval_arithmetic.hpp"
#include "exact/krawczyk.hpp"
#include "exact/number_types.hpp"
#include "support.hpp"

namespace delcert::exact {
namespace {

using testing::Q;
using testing::Rng;

// True when the exact q lies in i (an infinite bound holds everything beyond it).
bool holds(const Interval& i, const Q& q) {
  if (std::isnan(i.lo) || std::isnan(i.hi)) return false;
  const bool lo_ok = std::isinf(i.lo) ? i.lo < 0 : to_rational(i.lo) <= q;
  const bool hi_ok = std::isinf(i.hi) ? i.hi > 0 : q <= to_rational(i.hi);
  return lo_ok && hi_ok;
}

// Every exact coefficient is enclosed by the term with the same monomial; every other enclosed
// term holds 0 (a term the exact result cancelled).
void expect_encloses(const EnclosedPolynomial& e, const Polynomial& exact, const char* what) {
  std::map<std::vector<std::uint32_t>, Q> want;
  for (const auto& t : exact.terms()) {
    std::vector<std::uint32_t> ex(e.num_variables(), 0);
    for (std::size_t v = 0; v < t.monomial.exponents.size(); ++v) ex[v] = t.monomial.exponents[v];
    want[ex] = t.coefficient;
  }
  std::size_t matched = 0;
  for (std::size_t i = 0; i < e.size(); ++i) {
    const auto span = e.exponents(i);
    const std::vector<std::uint32_t> ex(span.begin(), span.end());
    const auto it = want.find(ex);
    const Q c = it == want.end() ? Q(0) : it->second;
    if (it != want.end()) ++matched;
    EXPECT_TRUE(holds(e.coefficient(i), c)) << what << ": term " << i << " [" << e.coefficient(i).lo << ", "
                                            << e.coefficient(i).hi << "] misses " << c.get_d();
  }
  EXPECT_EQ(matched, want.size()) << what << ": an exact term has no enclosed counterpart";
}

// A random polynomial in `vars` variables, degree <= 2 per variable, coefficients doubles of
// magnitude 2^e for e in [emin, emax] (exact as rationals).
Polynomial random_polynomial(Rng& rng, int vars, int terms, int emin, int emax) {
  Polynomial p(vars);
  for (int t = 0; t < terms; ++t) {
    Polynomial m = Polynomial::constant(to_rational(std::ldexp(rng.uniform(-1, 1), rng.integer(emin, emax))), vars);
    for (int v = 0; v < vars; ++v)
      for (int k = rng.integer(0, 2); k > 0; --k) m = m * Polynomial::variable(v, vars);
    p = p + m;
  }
  return p;
}

TEST(EnclosedPolynomial, OperationsEncloseTheExactResultsAtEveryMagnitude) {
  Rng rng(2026);
  // Ordinary magnitudes, then tiny (products underflow past the subnormals), then huge
  // (products overflow: the enclosures go infinite and still hold the exact values).
  const int ranges[][2] = {{-4, 4}, {-1030, -500}, {500, 1020}, {-1074, 1023}};
  int cases = 0;
  for (const auto& r : ranges)
    for (int trial = 0; trial < 40; ++trial) {
      const int vars = rng.integer(1, 4);
      const Polynomial a = random_polynomial(rng, vars, rng.integer(1, 6), r[0], r[1]);
      const Polynomial b = random_polynomial(rng, vars, rng.integer(1, 6), r[0], r[1]);
      const EnclosedPolynomial ea = EnclosedPolynomial::from_exact(a), eb = EnclosedPolynomial::from_exact(b);
      expect_encloses(ea, a, "from_exact");
      expect_encloses(ea + eb, a + b, "sum");
      expect_encloses(ea * eb, a * b, "product");
      expect_encloses((ea * eb) * ea, (a * b) * a, "triple product");
      const std::vector<EnclosedPolynomial> parts{ea, eb, ea * eb};
      expect_encloses(EnclosedPolynomial::sum(parts, vars), a + b + a * b, "sum of three");
      const double s = std::ldexp(rng.uniform(-1, 1), rng.integer(r[0], r[1]));
      expect_encloses(ea.scaled(Interval::point(s)), a.scaled(to_rational(s)), "scaled");
      for (int v = 0; v < vars; ++v) expect_encloses((ea * eb).derivative(v), (a * b).derivative(v), "derivative");
      ++cases;
    }
  EXPECT_EQ(cases, 160);
}

TEST(EnclosedPolynomial, WideEnclosuresStandForEveryPolynomialInThem) {
  // (c + x)^2 with c in [1, 2]: the coefficients must hold those of every c in between.
  const Interval c{1, 2};
  const std::vector<Interval> lin{{1, 1}};
  const EnclosedPolynomial a = EnclosedPolynomial::affine(c, lin);
  const EnclosedPolynomial sq = a * a;
  for (int s = 0; s <= 8; ++s) {
    const Q cq = Q(1) + Q(s, 8);
    const Polynomial exact = (Polynomial::constant(cq, 1) + Polynomial::variable(0, 1)) *
                             (Polynomial::constant(cq, 1) + Polynomial::variable(0, 1));
    expect_encloses(sq, exact, "square of a wide affine form");
  }
  // midpoints(): c^2 in [1, 4], 2c in [2, 4], 1; at x = 1: 2.5 + 3 + 1.
  EXPECT_EQ(sq.midpoints()(std::vector<double>{1.0}), 6.5);
}

TEST(EnclosedPolynomial, ExactZerosAreDroppedAndKnownZerosRemoved) {
  // [0, 0] coefficients (a chart's zero basis entries) leave no term; a tiny enclosure of 0 stays.
  const std::vector<Interval> lin{{0, 0}, {2, 2}, {-0x1p-60, 0x1p-60}};
  const EnclosedPolynomial a = EnclosedPolynomial::affine({1, 1}, lin);
  EXPECT_EQ(a.size(), 3u);  // 1, 2 x2, [-2^-60, 2^-60] x3
  EXPECT_EQ((a * EnclosedPolynomial::constant({0, 0}, 3)).size(), 0u);
  // without(): the caller's known zeros (here the terms linear in x3 alone) are removed.
  const EnclosedPolynomial w = (a * a).without([](std::span<const std::uint32_t> e) { return e[0] + e[1] == 0 && e[2] == 1; });
  EXPECT_EQ(w.size(), (a * a).size() - 1);
  for (std::size_t i = 0; i < w.size(); ++i) EXPECT_FALSE(w.exponents(i)[2] == 1 && w.exponents(i)[1] == 0);
  // midpoints(): the same values as DoublePolynomial of the exact polynomial it came from.
  Rng rng(7);
  for (int trial = 0; trial < 20; ++trial) {
    const Polynomial p = random_polynomial(rng, 3, 5, -3, 3);
    const DoublePolynomial d(p), m = EnclosedPolynomial::from_exact(p).midpoints();
    const std::vector<double> x{rng.uniform(-2, 2), rng.uniform(-2, 2), rng.uniform(-2, 2)};
    EXPECT_EQ(d(x), m(x)) << trial;  // dyadic coefficients: enclosures of width 0, same products
  }
}

TEST(EnclosedPolynomial, SystemsFromSharedRowsDecideLikeFromEnclosures) {
  // Two circles x^2 + y^2 = 4 and (x - 1)^2 + y^2 = 4 meet at (1/2, +-sqrt(15)/2); rows prepared
  // once (EnclosedRow) and shared by several systems give the same answers, bit for bit.
  const EnclosedPolynomial a = EnclosedPolynomial::from_exact(Polynomial::parse("x1^2 + x2^2 - 4", 2));
  const EnclosedPolynomial b = EnclosedPolynomial::from_exact(Polynomial::parse("x1^2 - 2*x1 + x2^2 - 3", 2));
  const std::vector<EnclosedRow> rows{EnclosedRow(a), EnclosedRow(b)};
  const ParametricSystem shared = ParametricSystem::from_rows(rows);
  const ParametricSystem reversed = ParametricSystem::from_rows(std::vector<EnclosedRow>{rows[1], rows[0]});
  const ParametricSystem direct = ParametricSystem::from_enclosures({a, b}, 0);
  for (const Box& X : {Box{{0.25, 0.75}, {1.75, 2.0}}, Box{{0.25, 0.75}, {-2.0, -1.75}}, Box{{1.5, 2.0}, {0.0, 0.5}},
                       Box{{0.0, 1.0}, {-2.0, 2.0}}}) {
    const auto s = krawczyk(shared, Box{}, X), r = krawczyk(reversed, Box{}, X), d = krawczyk(direct, Box{}, X);
    EXPECT_EQ(s.status, d.status);
    EXPECT_EQ(r.status, d.status);
    for (std::size_t i = 0; i < X.size() && s.status == RootStatus::unique_root; ++i) {
      EXPECT_EQ(s.box[i].lo, d.box[i].lo);
      EXPECT_EQ(s.box[i].hi, d.box[i].hi);
    }
  }
  EXPECT_EQ(krawczyk(shared, Box{}, Box{{0.25, 0.75}, {1.75, 2.0}}).status, RootStatus::unique_root);
  EXPECT_EQ(krawczyk(shared, Box{}, Box{{1.5, 2.0}, {0.0, 0.5}}).status, RootStatus::no_root);
  EXPECT_THROW(ParametricSystem::from_rows(std::vector<EnclosedRow>{rows[0]}), std::invalid_argument);  // 2 variables, 1 row
  EXPECT_THROW(ParametricSystem::from_rows(std::vector<EnclosedRow>{}), std::invalid_argument);
}

// The same two circles as an EnclosedFunction (values and Jacobian from their own enclosures, the
// first row's constant widened to [-4 - w, -4 + w]): Krawczyk decides as the polynomial system
// where w = 0, keeps deciding for the whole family when w is small, and concludes nothing when the
// function gives no enclosure.
struct TwoCircles final : EnclosedFunction {
  double w = 0;
  bool give = true;
  int size() const override { return 2; }
  bool values(std::span<const double> y, std::span<Interval> f) const override {
    if (!give) return false;
    const IntervalNumber x(y[0]), z(y[1]);
    UpwardRounding up;
    f[0] = to_interval(square(x) + square(z) - IntervalNumber(4 - w, 4 + w));
    f[1] = to_interval(square(x) - IntervalNumber(2) * x + square(z) - IntervalNumber(3));
    return true;
  }
  bool jacobian(const Box& X, std::span<Interval> J) const override {
    UpwardRounding up;
    const IntervalNumber x(X[0].lo, X[0].hi), z(X[1].lo, X[1].hi);
    J[0] = to_interval(IntervalNumber(2) * x), J[1] = to_interval(IntervalNumber(2) * z);
    J[2] = to_interval(IntervalNumber(2) * x - IntervalNumber(2)), J[3] = to_interval(IntervalNumber(2) * z);
    return true;
  }
};

TEST(EnclosedPolynomial, KrawczykOnAnEnclosedFunctionDecidesLikeThePolynomialSystem) {
  const ParametricSystem direct = ParametricSystem::from_enclosures(
      {EnclosedPolynomial::from_exact(Polynomial::parse("x1^2 + x2^2 - 4", 2)),
       EnclosedPolynomial::from_exact(Polynomial::parse("x1^2 - 2*x1 + x2^2 - 3", 2))},
      0);
  TwoCircles F;
  for (const Box& X : {Box{{0.25, 0.75}, {1.75, 2.0}}, Box{{0.25, 0.75}, {-2.0, -1.75}}, Box{{1.5, 2.0}, {0.0, 0.5}},
                       Box{{0.0, 1.0}, {-2.0, 2.0}}})
    EXPECT_EQ(krawczyk(F, X).status, krawczyk(direct, Box{}, X).status);
  const Box root{{0.25, 0.75}, {1.75, 2.0}};
  const KrawczykResult r = krawczyk(F, root);
  ASSERT_EQ(r.status, RootStatus::unique_root);
  EXPECT_TRUE(r.box[0].contains(0.5));
  EXPECT_TRUE(r.box[1].contains(std::sqrt(15.0) / 2));
  F.w = 1e-6;  // a family: one root each, all in the (wider) result
  const KrawczykResult wide = krawczyk(F, root);
  ASSERT_EQ(wide.status, RootStatus::unique_root);
  EXPECT_GT(wide.box[0].width() + wide.box[1].width(), r.box[0].width() + r.box[1].width());
  F.give = false;
  EXPECT_EQ(krawczyk(F, root).status, RootStatus::undecided);
  EXPECT_THROW(krawczyk(F, Box{{0.0, 1.0}}), std::invalid_argument);
  EXPECT_THROW(krawczyk(F, Box{{1.0, 0.0}, {0.0, 1.0}}), std::invalid_argument);
}

TEST(EnclosedPolynomial, ParametricSystemFromEnclosuresDecidesLikeTheExactOne) {
  // x2^2 - x1 (parameter x1 = u, unknown x2): sqrt(u) over parameter boxes.
  const Polynomial f = Polynomial::parse("x2^2 - x1", 2);
  const ParametricSystem exact({f}, 1);
  const ParametricSystem enclosed = ParametricSystem::from_enclosures({EnclosedPolynomial::from_exact(f)}, 1);
  for (double a = 0.25; a < 4; a *= 1.5) {
    const Box U{{a, a * 1.125}};
    const auto x = krawczyk(exact, U, Box{{0.25, 3.0}}), e = krawczyk(enclosed, U, Box{{0.25, 3.0}});
    EXPECT_EQ(x.status, e.status) << a;
    ASSERT_EQ(e.status, RootStatus::unique_root) << a;
    EXPECT_EQ(x.box[0].lo, e.box[0].lo);  // from_exact keeps the exact rows' terms and order
    EXPECT_EQ(x.box[0].hi, e.box[0].hi);
  }
  EXPECT_EQ(krawczyk(enclosed, Box{{1.0, 2.0}}, Box{{2.0, 3.0}}).status, RootStatus::no_root);
  const std::vector<Interval> z{{2, 2}, {1, 1}};
  EXPECT_TRUE(enclosed.enclose(0, z).contains(-1.0));
  EXPECT_TRUE(enclosed.enclose_derivative(0, 0, z).contains(2.0));
  // Powers are enclosed as powers: x2^2 over [-1, 2] is [0, 4] (x2 * x2 would give [-2, 4]).
  const std::vector<Interval> across{{0, 0}, {-1, 2}};
  EXPECT_EQ(enclosed.enclose(0, across).lo, 0.0);
  EXPECT_EQ(enclosed.enclose(0, across).hi, 4.0);
  EXPECT_EQ(exact.enclose(0, across).lo, 0.0);
  const ParametricSystem quartic({Polynomial::parse("x2^4 + x2^3 - x1", 2)}, 1);
  const Interval q = quartic.enclose(0, across);  // x^4 = (x^2)^2 in [0, 16], x^3 = x^2 x in [-4, 8]
  EXPECT_LE(q.lo, -27.0 / 256);  // the exact minimum of x^4 + x^3 is -27/256 at x = -3/4
  EXPECT_GE(q.hi, 24.0);
  EXPECT_GE(q.lo, -4.0);
  EXPECT_THROW(enclosed.equations(), std::logic_error);
  EXPECT_THROW(ParametricSystem::from_enclosures({EnclosedPolynomial(3)}, 1), std::invalid_argument);
  EXPECT_THROW(ParametricSystem::from_enclosures({}, 0), std::invalid_argument);
  EXPECT_THROW(EnclosedPolynomial(2) + EnclosedPolynomial(3), std::invalid_argument);
  EXPECT_THROW(EnclosedPolynomial(2) * EnclosedPolynomial(3), std::invalid_argument);
  const std::vector<EnclosedPolynomial> mixed{EnclosedPolynomial(2), EnclosedPolynomial(3)};
  EXPECT_THROW(EnclosedPolynomial::sum(mixed, 2), std::invalid_argument);
  EXPECT_EQ(EnclosedPolynomial::sum({}, 2).size(), 0u);
  EXPECT_THROW(EnclosedPolynomial(2).derivative(2), std::invalid_argument);
  EXPECT_TRUE(rounding_is_nearest());
}

}  // namespace
}  // namespace delcert::exact
