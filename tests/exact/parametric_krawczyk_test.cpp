// The parametric Krawczyk operator (exact/krawczyk.hpp): for every u in U exactly one root in
// the box, or none, checked against exact roots.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "exact/krawczyk.hpp"
#include "exact/number_types.hpp"
#include "support.hpp"

namespace delcert::exact {
namespace {

using testing::Q;

ParametricSystem parse_parametric(const std::vector<std::string>& eqs, int m) {
  std::vector<Polynomial> p;
  for (const auto& e : eqs) p.push_back(Polynomial::parse(e, m + static_cast<int>(eqs.size())));
  return ParametricSystem(std::move(p), m);
}

// True when sqrt(s) lies in [lo, hi] (lo >= 0), decided exactly.
bool sqrt_in(const Interval& i, const Q& s) {
  const Q lo = to_rational(i.lo), hi = to_rational(i.hi);
  return lo >= 0 && lo * lo <= s && s <= hi * hi;
}

TEST(ParametricKrawczyk, SquareRootOverAParameterBox) {
  // x^2 - u = 0 (variables: u = x1, x = x2).
  const ParametricSystem S = parse_parametric({"x2^2 - x1"}, 1);
  EXPECT_EQ(S.size(), 1);
  EXPECT_EQ(S.num_parameters(), 1);
  for (double a = 0.25; a < 4; a *= 1.5) {
    const Box U{{a, a * 1.125}};
    auto r = krawczyk(S, U, Box{{0.25, 3.0}});
    ASSERT_EQ(r.status, RootStatus::unique_root) << a;
    // Krawczyk stops contracting when a step gains little; restarting on its box contracts on.
    for (int again = 0; again < 6; ++again) {
      r = krawczyk(S, U, r.box);
      ASSERT_EQ(r.status, RootStatus::unique_root) << a;
    }
    // sqrt(u) lies in the box for every u in U: check the ends and samples exactly.
    for (int s = 0; s <= 16; ++s) {
      const Q u = to_rational(a) + to_rational(a * 0.125) * Q(s, 16);
      EXPECT_TRUE(sqrt_in(r.box[0], u)) << a << " " << s;
    }
    // ... and the box is not much wider than the range of sqrt over U (plus rounding).
    EXPECT_LT(r.box[0].width(), 2.0 * (std::sqrt(a * 1.125) - std::sqrt(a)) + 1e-12);
  }
}

TEST(ParametricKrawczyk, NoRootForAnyParameter) {
  const ParametricSystem S = parse_parametric({"x2^2 - x1"}, 1);
  // x^2 >= 4 > u on H = [2, 3] for u in [1, 2].
  EXPECT_EQ(krawczyk(S, Box{{1.0, 2.0}}, Box{{2.0, 3.0}}).status, RootStatus::no_root);
  // Two unknowns, two parameters: x - u1 = 0, y - u2 = 0 with the parameter box away from H.
  const ParametricSystem L = parse_parametric({"x3 - x1", "x4 - x2"}, 2);
  EXPECT_EQ(krawczyk(L, Box{{0.0, 1.0}, {0.0, 1.0}}, Box{{1.5, 2.0}, {0.0, 1.0}}).status, RootStatus::no_root);
  EXPECT_EQ(krawczyk(L, Box{{0.0, 1.0}, {0.0, 1.0}}, Box{{-0.5, 1.5}, {-0.5, 1.5}}).status, RootStatus::unique_root);
}

TEST(ParametricKrawczyk, NeverUniqueWhereSomeParameterHasTwoRootsOrNone) {
  const ParametricSystem S = parse_parametric({"x2^2 - x1"}, 1);
  // u in [-0.1, 0.1]: no root for u < 0, two roots for u > 0, a double root at 0.
  for (const Box& H : {Box{{-1.0, 1.0}}, Box{{-0.01, 0.4}}, Box{{0.0, 0.5}}, Box{{-0.5, 0.0}}})
    EXPECT_NE(krawczyk(S, Box{{-0.1, 0.1}}, H).status, RootStatus::unique_root);
  // u in [0.01, 0.04] has two roots in [-1, 1] for every u.
  EXPECT_NE(krawczyk(S, Box{{0.01, 0.04}}, Box{{-1.0, 1.0}}).status, RootStatus::unique_root);
}

TEST(ParametricKrawczyk, CentredFormIsNeededForWideParameterBoxes) {
  // x - (u1 - u2) = 0 over a large U with a tight H only works because G(U, c) is enclosed
  // well; the point is that the answer stays correct: unique exactly when H covers u1 - u2.
  const ParametricSystem S = parse_parametric({"x3 - x1 + x2"}, 2);
  const Box U{{1.0, 1.5}, {0.0, 0.25}};  // u1 - u2 in [0.75, 1.5]
  EXPECT_EQ(krawczyk(S, U, Box{{0.5, 2.0}}).status, RootStatus::unique_root);
  EXPECT_NE(krawczyk(S, U, Box{{0.8, 2.0}}).status, RootStatus::unique_root);
  EXPECT_EQ(krawczyk(S, U, Box{{1.6, 2.0}}).status, RootStatus::no_root);
}

TEST(ParametricKrawczyk, RejectsBadBoxes) {
  const ParametricSystem S = parse_parametric({"x2^2 - x1"}, 1);
  EXPECT_THROW(krawczyk(S, Box{}, Box{{0.0, 1.0}}), std::invalid_argument);
  EXPECT_THROW(krawczyk(S, Box{{1.0, 0.0}}, Box{{0.0, 1.0}}), std::invalid_argument);
  EXPECT_THROW(krawczyk(S, Box{{0.0, HUGE_VAL}}, Box{{0.0, 1.0}}), std::invalid_argument);
  EXPECT_THROW(ParametricSystem({Polynomial::parse("x1 - x2", 2)}, 2), std::invalid_argument);
  EXPECT_THROW(ParametricSystem({Polynomial::parse("x1", 1)}, -1), std::invalid_argument);
}

TEST(ParametricKrawczyk, HugeAndTinyMagnitudesAreNeverWrong) {
  // x^2 - u with u ~ 1e-300 (x ~ 1e-150) and u ~ 1e300 (x ~ 1e150): either undecided or a
  // correct enclosure.
  const ParametricSystem S = parse_parametric({"x2^2 - x1"}, 1);
  for (double a : {1e-300, 1e-200, 1e200, 1e300}) {
    const Box U{{a, a * 1.01}};
    const double s = std::sqrt(a);
    const auto r = krawczyk(S, U, Box{{0.5 * s, 2 * s}});
    if (r.status == RootStatus::unique_root) {
      EXPECT_TRUE(sqrt_in(r.box[0], to_rational(a)));
      EXPECT_TRUE(sqrt_in(r.box[0], to_rational(a * 1.01)));
    }
    EXPECT_NE(krawczyk(S, U, Box{{-0.5 * s, 0.5 * s}}).status, RootStatus::unique_root);
  }
}

// AffineExtension: rows known only by enclosures of their coefficients.
// The answers must hold for EVERY row within them: exact point enclosures reproduce the exact
// system's answers; a constant whose enclosure admits both a root and none in the box is never
// decided either way.
TEST(ParametricKrawczyk, EnclosedAffineRowsAnswerForEveryRowWithinThem) {
  // Head: the circle x^2 + y^2 - 1 = 0 with y as the parameter (variables x1 = y, x2 = x).
  const ParametricSystem circle = parse_parametric({"x2^2 + x1^2 - 1"}, 1);
  // Tail: y - x/2 = 0, i.e. 0 + 1 y - 0.5 x, exactly as enclosures of width 0.
  const AffineExtension enclosed(circle, {{0, 0}, {1, 1}, {-0.5, -0.5}});
  const SquareSystem exact(circle, {Polynomial::parse("x1 - x2/2", 2)});
  const Box around{{0.35, 0.55}, {0.8, 1.0}};  // (y, x) around (1/sqrt5, 2/sqrt5)
  const auto e = krawczyk(enclosed, around), x = krawczyk(exact, around);
  ASSERT_EQ(e.status, RootStatus::unique_root);
  ASSERT_EQ(x.status, RootStatus::unique_root);
  // Point enclosures: the same evaluations as the exact system's, so the same boxes, bit for bit.
  for (int i = 0; i < 2; ++i) {
    EXPECT_EQ(e.box[i].lo, x.box[i].lo) << i;
    EXPECT_EQ(e.box[i].hi, x.box[i].hi) << i;
  }
  EXPECT_EQ(e.iterations, x.iterations);
  // The root x = 2/sqrt(5) lies in the enclosed system's box (checked exactly: x >= 0 there).
  EXPECT_TRUE(to_rational(e.box[1].lo) * to_rational(e.box[1].lo) * 5 <= 4);
  EXPECT_TRUE(to_rational(e.box[1].hi) * to_rational(e.box[1].hi) * 5 >= 4);
  EXPECT_EQ(krawczyk(enclosed, Box{{2, 3}, {2, 3}}).status, RootStatus::no_root);
  // c + y - x/2 = 0 for some c in [-0.6, 0.1]: in the box, c = 0 has the root above and c = -0.6
  // none (y = x/2 + 0.6 >= 1 there); neither answer may be claimed.
  const auto w = krawczyk(AffineExtension(circle, {{-0.6, 0.1}, {1, 1}, {-0.5, -0.5}}), around);
  EXPECT_NE(w.status, RootStatus::unique_root);
  EXPECT_NE(w.status, RootStatus::no_root);
  // y - s x = 0 for s in [0.4, 0.6]: s = 1/2 has its root in the box below, s = 0.4 has it at
  // y = 0.371, outside; not unique either.
  EXPECT_NE(krawczyk(AffineExtension(circle, {{0, 0}, {1, 1}, {-0.6, -0.4}}), Box{{0.38, 0.45}, {0.88, 0.93}}).status,
            RootStatus::unique_root);
  // Bad shapes and enclosures are refused.
  using Row = std::vector<Interval>;
  EXPECT_THROW(AffineExtension(circle, Row{{0, 0}, {1, 1}}), std::invalid_argument);
  EXPECT_THROW(AffineExtension(circle, Row{{0, 0}, {1, 1}, {0, 0}, {0, 0}, {1, 1}, {0, 0}}), std::invalid_argument);
  EXPECT_THROW(AffineExtension(circle, Row{{1, 0}, {1, 1}, {-0.5, -0.5}}), std::invalid_argument);
  EXPECT_THROW(AffineExtension(circle, Row{{0, INFINITY}, {1, 1}, {-0.5, -0.5}}), std::invalid_argument);
  EXPECT_TRUE(rounding_is_nearest());
}

}  // namespace
TEST(StackedSystem, SharesTheHeadAndDecidesLikeTheSystemWrittenOut) {
  // Head: the unit circle as a chart-like parametric system G(u, h) = u^2 + h^2 - 1 (u = x1,
  // h = x2); tail: the line h = 2u - 1/2 written as an affine polynomial. The stacked square
  // system must be the system {G, tail} over (u, h) and give the same Krawczyk answers.
  const ParametricSystem head = parse_parametric({"x1^2 + x2^2 - 1"}, 1);
  const std::vector<Q> linear{Q(-2), Q(1)};
  const Polynomial line = Polynomial::affine(Q(1, 2), linear);
  EXPECT_EQ(line, Polynomial::parse("x2 - 2*x1 + 1/2", 2));
  const SquareSystem stacked(head, {line});
  const SquareSystem written({Polynomial::parse("x1^2 + x2^2 - 1", 2), line});
  ASSERT_EQ(stacked.size(), 2);
  EXPECT_EQ(stacked.equations(), written.equations());
  for (const Box& X : {Box{{0.5, 1.0}, {0.0, 1.0}}, Box{{-0.5, 0.2}, {-1.0, -0.5}}, Box{{-1.0, 1.0}, {-1.0, 1.0}},
                       Box{{2.0, 3.0}, {0.0, 1.0}}}) {
    const KrawczykResult a = krawczyk(stacked, X), b = krawczyk(written, X);
    EXPECT_EQ(a.status, b.status);
    ASSERT_EQ(a.box.size(), b.box.size());
    for (std::size_t i = 0; i < a.box.size(); ++i) EXPECT_TRUE(a.box[i].lo == b.box[i].lo && a.box[i].hi == b.box[i].hi);
  }
  // Wrong shapes are refused: the tail must complete the head to a square system.
  EXPECT_THROW(SquareSystem(head, {}), std::invalid_argument);
  EXPECT_THROW(SquareSystem(head, {line, line}), std::invalid_argument);
  EXPECT_THROW(SquareSystem(head, {Polynomial::parse("x1 + x3", 3)}), std::invalid_argument);
}

TEST(Polynomial, AffineDropsZeroCoefficients) {
  const std::vector<Q> linear{Q(0), Q(3, 7), Q(0)};
  EXPECT_EQ(Polynomial::affine(Q(0), linear), Polynomial::parse("3/7*x2", 3));
  EXPECT_TRUE(Polynomial::affine(Q(0), std::vector<Q>(2, Q(0))).is_zero());
}

}  // namespace delcert::exact
