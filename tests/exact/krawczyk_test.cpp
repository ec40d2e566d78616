#include "exact/krawczyk.hpp"

#include <gtest/gtest.h>
#include <mpfr.h>

#include <array>
#include <stdexcept>

#include "exact/number_types.hpp"
#include "exact/simplex_predicates.hpp"
#include "support.hpp"

namespace delcert::exact {
namespace {

using testing::Q;

SquareSystem parse_system(const std::vector<std::string>& eqs) {
  std::vector<Polynomial> p;
  for (const auto& e : eqs) p.push_back(Polynomial::parse(e, static_cast<int>(eqs.size())));
  return SquareSystem(std::move(p));
}

Box cube(int n, double lo, double hi) { return Box(n, Interval{lo, hi}); }

// 200-bit value of (sign) * sqrt(num / den).
struct Root200 {
  mpfr_t x;
  Root200(int sign, long num, long den) {
    mpfr_init2(x, 200);
    mpfr_set_si(x, num, MPFR_RNDN);
    mpfr_div_si(x, x, den, MPFR_RNDN);
    mpfr_sqrt(x, x, MPFR_RNDN);
    if (sign < 0) mpfr_neg(x, x, MPFR_RNDN);
  }
  ~Root200() { mpfr_clear(x); }
  Root200(const Root200&) = delete;
  Root200& operator=(const Root200&) = delete;
};

bool interval_contains(const Interval& i, const mpfr_t v) { return mpfr_cmp_d(v, i.lo) >= 0 && mpfr_cmp_d(v, i.hi) <= 0; }
bool interval_contains(const Interval& i, const Q& v) { return to_rational(i.lo) <= v && v <= to_rational(i.hi); }

bool disjoint(const Box& a, const Box& b) {
  for (std::size_t i = 0; i < a.size(); ++i)
    if (a[i].hi < b[i].lo || b[i].hi < a[i].lo) return true;
  return false;
}

void expect_pairwise_disjoint(const std::vector<Box>& boxes) {
  for (std::size_t i = 0; i < boxes.size(); ++i)
    for (std::size_t j = i + 1; j < boxes.size(); ++j) EXPECT_TRUE(disjoint(boxes[i], boxes[j]));
}

TEST(Krawczyk, CircleLineIrrationalRoots) {
  // x^2 + y^2 = 1, y = x / 2: roots +-(2/sqrt5, 1/sqrt5).
  SquareSystem S = parse_system({"x1^2 + x2^2 - 1", "x2 - x1/2"});
  auto r = find_roots(S, cube(2, -2, 2));
  ASSERT_EQ(r.roots.size(), 2u);
  EXPECT_TRUE(r.complete());
  expect_pairwise_disjoint(r.roots);
  int found = 0;
  for (int s : {1, -1}) {
    Root200 x(s, 4, 5), y(s, 1, 5);
    for (const auto& b : r.roots)
      if (interval_contains(b[0], x.x) && interval_contains(b[1], y.x)) {
        ++found;
        EXPECT_LT(b[0].width(), 1e-12);
        EXPECT_LT(b[1].width(), 1e-12);
      }
  }
  EXPECT_EQ(found, 2);
}

TEST(Krawczyk, CircleLineRationalRoots) {
  // (x - 1/3)^2 + (y - 1/4)^2 = 1/4, x = 1/3 + 3/10: roots (19/30, 13/20) and (19/30, -3/20).
  SquareSystem S = parse_system({"(x1 - 1/3)^2 + (x2 - 1/4)^2 - 1/4", "x1 - 1/3 - 3/10"});
  auto r = find_roots(S, cube(2, -3, 3));
  ASSERT_EQ(r.roots.size(), 2u);
  EXPECT_TRUE(r.complete());
  int found = 0;
  for (const Q& y : {Q(13, 20), Q(-3, 20)})
    for (const auto& b : r.roots) found += interval_contains(b[0], Q(19, 30)) && interval_contains(b[1], y);
  EXPECT_EQ(found, 2);
}

TEST(Krawczyk, SingleBoxAnswers) {
  SquareSystem S = parse_system({"x1^2 + x2^2 - 1", "x2 - x1/2"});
  // A box around one root: unique, contracted.
  auto u = krawczyk(S, Box{{0.8, 1.0}, {0.35, 0.55}});
  EXPECT_EQ(u.status, RootStatus::unique_root);
  Root200 x(1, 4, 5);
  EXPECT_TRUE(interval_contains(u.box[0], x.x));
  EXPECT_LT(u.box[0].width(), 1e-12);
  // A box far from the circle: no root.
  auto n = krawczyk(S, Box{{2, 3}, {2, 3}});
  EXPECT_EQ(n.status, RootStatus::no_root);
  // A box containing both roots cannot be unique.
  auto both = krawczyk(S, cube(2, -2, 2));
  EXPECT_NE(both.status, RootStatus::unique_root);
  EXPECT_NE(both.status, RootStatus::no_root);
  // Bad boxes.
  EXPECT_THROW(krawczyk(S, cube(3, 0, 1)), std::invalid_argument);
  EXPECT_THROW(krawczyk(S, Box{{1, 0}, {0, 1}}), std::invalid_argument);
  EXPECT_TRUE(rounding_is_nearest());
}

TEST(Krawczyk, ARootOnTheBoxBoundaryIsANearbyRoot) {
  // The root (sqrt 2, 0) of {x1^2 - 2, x2} lies within an ulp of the plane x1 = s = sqrt(2.0) (the
  // double) that splits [1, 2] x [-1, 1]. Neither half holds it strictly inside a contraction;
  // each half is then decided by Krawczyk (unique root, or none) or reports the root proved unique
  // in a box around it (`nearby_root`, tight): it holds that root or nothing. Never plainly
  // undecided, and the root is reported by at least one half.
  SquareSystem S = parse_system({"x1^2 - 2", "x2"});
  const double s = std::sqrt(2.0);
  int reported = 0;
  for (const Box& B : {Box{{1, s}, {-1, 1}}, Box{{s, 2}, {-1, 1}}}) {
    auto r = krawczyk(S, B);
    ASSERT_TRUE(r.status != RootStatus::undecided || r.nearby_root.has_value());
    if (r.status == RootStatus::no_root) continue;
    const Box& root = r.status == RootStatus::unique_root ? r.box : *r.nearby_root;
    EXPECT_LE(root[0].lo, s);  // encloses sqrt 2, within a few ulps of s
    EXPECT_GE(root[0].hi, s);
    EXPECT_LT(root[0].width(), 1e-12);
    ++reported;
  }
  EXPECT_GE(reported, 1);
  // Strictly inside: unique, no nearby root; far away: no root, no nearby root.
  EXPECT_FALSE(krawczyk(S, Box{{1.25, 1.5}, {-1, 1}}).nearby_root.has_value());
  auto far = krawczyk(S, Box{{2, 3}, {2, 3}});
  EXPECT_EQ(far.status, RootStatus::no_root);
  EXPECT_FALSE(far.nearby_root.has_value());
}

TEST(Krawczyk, TangencyIsUndecided) {
  // The line y = 1 touches the unit circle at (0, 1): a double root, never certified unique.
  SquareSystem S = parse_system({"x1^2 + x2^2 - 1", "x2 - 1"});
  auto single = krawczyk(S, Box{{-0.5, 0.5}, {0.5, 1.5}});
  EXPECT_EQ(single.status, RootStatus::undecided);
  RootSearchOptions opt;
  opt.max_depth = 30;
  auto r = find_roots(S, cube(2, -2, 2), opt);
  EXPECT_TRUE(r.roots.empty());
  ASSERT_FALSE(r.undecided.empty());
  bool covers = false;
  for (const auto& b : r.undecided) {
    covers = covers || (b[0].contains(0.0) && b[1].contains(1.0));
    EXPECT_GT(b[0].hi, -0.1);
    EXPECT_LT(b[0].lo, 0.1);
    EXPECT_GT(b[1].hi, 0.9);
    EXPECT_LT(b[1].lo, 1.1);
  }
  EXPECT_TRUE(covers);
  // A nearby secant line y = 1 - 2^-20 has two close simple roots: both are isolated.
  SquareSystem secant = parse_system({"x1^2 + x2^2 - 1", "x2 - 1 + 1/1048576"});
  auto s = find_roots(secant, cube(2, -2, 2));
  EXPECT_EQ(s.roots.size(), 2u);
  EXPECT_TRUE(s.complete());
}

// The Voronoi 2-flat of a triangle meets the Clifford torus T^2 in R^4 in isolated points.
TEST(Krawczyk, VoronoiFlatOfATriangleMeetsTheCliffordTorus) {
  const std::vector<std::string> torus{"x1^2 + x2^2 - 1", "x3^2 + x4^2 - 1"};
  // v0 = (1,0,1,0), v1 = (0,1,1,0), v2 = (1,0,0,1), all on the torus: equidistant points of the
  // torus satisfy x.v0 = x.v1 = x.v2, i.e. x1 = x2 and x3 = x4: four roots (+-s, +-s, +-s, +-s)
  // with s = 1/sqrt 2 (signs pairwise equal).
  {
    const std::array<double, 4> v0{1, 0, 1, 0}, v1{0, 1, 1, 0}, v2{1, 0, 0, 1};
    const std::vector<const double*> tri{v0.data(), v1.data(), v2.data()};
    std::vector<Polynomial> eqs;
    for (const auto& e : torus) eqs.push_back(Polynomial::parse(e, 4));
    for (auto& e : equidistance_equations(tri, 4)) eqs.push_back(e);
    SquareSystem S(eqs);
    auto r = find_roots(S, cube(4, -1.5, 1.5));
    EXPECT_TRUE(r.complete());
    ASSERT_EQ(r.roots.size(), 4u);
    expect_pairwise_disjoint(r.roots);
    int found = 0;
    for (int a : {1, -1})
      for (int b : {1, -1}) {
        Root200 sa(a, 1, 2), sb(b, 1, 2);
        for (const auto& box : r.roots)
          found += interval_contains(box[0], sa.x) && interval_contains(box[1], sa.x) &&
                   interval_contains(box[2], sb.x) && interval_contains(box[3], sb.x);
      }
    EXPECT_EQ(found, 4);
    // Restricted-Delaunay use: at the root (s,s,s,s) the point q = (-1,0,-1,0) is certainly
    // farther than the triangle's vertices.
    const std::array<double, 4> q{-1, 0, -1, 0};
    for (const auto& box : r.roots)
      if (box[0].lo > 0 && box[2].lo > 0) {
        EXPECT_EQ(ambient_power_sign_on_box(box, v0.data(), q.data()), 1);
      }
  }
  // v2 = (1, 0, 3/5, 4/5): x1 = x2 and x3 = 2 x4: roots (+-s, +-s) x +-(2/sqrt5, 1/sqrt5).
  {
    SquareSystem S = parse_system({torus[0], torus[1], "-2*x1 + 2*x2", "-0.8*x3 + 1.6*x4"});
    auto r = find_roots(S, cube(4, -1.5, 1.5));
    EXPECT_TRUE(r.complete());
    ASSERT_EQ(r.roots.size(), 4u);
    int found = 0;
    for (int a : {1, -1})
      for (int b : {1, -1}) {
        Root200 sa(a, 1, 2), x3(b, 4, 5), x4(b, 1, 5);
        for (const auto& box : r.roots)
          found += interval_contains(box[0], sa.x) && interval_contains(box[1], sa.x) &&
                   interval_contains(box[2], x3.x) && interval_contains(box[3], x4.x);
      }
    EXPECT_EQ(found, 4);
  }
}

TEST(Krawczyk, EquidistanceEquationsAreExact) {
  const std::array<double, 3> a{0.1, 0.2, 0.3}, b{-0.7, 0.25, 1e-3};
  auto eqs = equidistance_equations(std::vector<const double*>{a.data(), b.data()}, 3);
  ASSERT_EQ(eqs.size(), 1u);
  // The midpoint is on the bisector, exactly.
  std::vector<Q> mid(3);
  for (int i = 0; i < 3; ++i) mid[i] = (to_rational(a[i]) + to_rational(b[i])) / 2;
  EXPECT_EQ(eqs[0].evaluate(std::span<const Q>(mid)), 0);
  std::vector<Q> av(3);
  for (int i = 0; i < 3; ++i) av[i] = to_rational(a[i]);
  EXPECT_NE(eqs[0].evaluate(std::span<const Q>(av)), 0);
}

}  // namespace
}  // namespace delcert::exact
