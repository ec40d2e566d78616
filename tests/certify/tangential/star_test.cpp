// The stars (check 3) leave out of a cell's power tests the points farther from p than a radius
// rho >= 2.5R that also covers the power-protection claim (star.cpp, test_list). These tests put
// the one point that matters beyond 3R: the margin's lower bound must stay below its power,
// and a claim it violates must be found.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <vector>

#include "exact/number_types.hpp"
#include "tests/certify/support.hpp"

namespace delcert::certify::test {
namespace {

// On the unit sphere at p = (0, 0, 1): four neighbours at 0.1 (the star of p is the four
// triangles {p, q_i, q_i+1}; the cell {p, q1, q2} has its centre c = p + (w, w, 0), w ~ 0.05,
// R^2 = |c - p|^2 ~ 0.005) and a point d on the diagonal towards c, at distance ~3.07 R from p.
// d's power with respect to that cell (~0.0167, about 3.3 R^2) is the smallest of all points:
// the opposite neighbour q3 has ~0.020 (4 R^2).
struct Square {
  io::PointSet P;
  io::ManifoldSpec spec = io::read_spec("builtin:sphere-2");
  exact::ImplicitSystem system{spec.equations, spec.ambient_dimension};
  Square() {
    P.dimension = 3;
    auto on_sphere = [&](double x, double y) { P.push_back(std::vector<double>{x, y, std::sqrt(1 - x * x - y * y)}); };
    P.push_back(std::vector<double>{0, 0, 1});
    on_sphere(0.1, 0), on_sphere(0, 0.1), on_sphere(-0.1, 0), on_sphere(0, -0.1);
    on_sphere(0.1527, 0.1527);  // d, index 5
  }
  // The power of point q with respect to the cell {p, a, b} (centre in the tangent plane z = 1),
  // in floating point: a reference for the test's inequalities, which hold with a wide gap.
  double power(int a, int b, int q) const {
    auto x = [&](int i) { return P.point(i); };
    // c = (u, v, 1): |c - a|^2 = |c - p|^2 <=> 2 (a_x u + a_y v) = a_x^2 + a_y^2 + (1 - a_z)^2.
    const double ra = x(a)[0] * x(a)[0] + x(a)[1] * x(a)[1] + (1 - x(a)[2]) * (1 - x(a)[2]);
    const double rb = x(b)[0] * x(b)[0] + x(b)[1] * x(b)[1] + (1 - x(b)[2]) * (1 - x(b)[2]);
    const double det = 2 * (x(a)[0] * x(b)[1] - x(a)[1] * x(b)[0]);
    const double u = (ra * x(b)[1] - rb * x(a)[1]) / det, v = (x(a)[0] * rb - x(b)[0] * ra) / det;
    const double R2 = u * u + v * v;
    const double dx = x(q)[0] - u, dy = x(q)[1] - v, dz = x(q)[2] - 1;
    return dx * dx + dy * dy + dz * dz - R2;
  }
};

const CellReport* cell(const StarReport& r, const Simplex& s) {
  for (const auto& c : r.star)
    if (c.simplex == s) return &c;
  return nullptr;
}

TEST(Stars, TheMarginBoundStaysBelowAPointJustBeyondThreeRadii) {
  Square sq;
  const double d = sq.power(1, 2, 5), q3 = sq.power(1, 2, 3);
  ASSERT_LT(d, 0.9 * q3);  // the setting: d, not q3, has the smallest power
  detail::PointGrid grid(sq.P, 2);
  StarSettings S{&sq.P, &sq.system, &grid, 2, std::nullopt, std::nullopt};
  exact::FilterContext ctx;
  StarReport r = analyse_star(S, 0, nullptr, ctx);
  ASSERT_EQ(r.state, StarReport::State::proven);
  ASSERT_EQ(r.star.size(), 4u);
  const CellReport* c = cell(r, {0, 1, 2});
  ASSERT_NE(c, nullptr);
  // A lower bound of the smallest power: below d's (the test's double evaluation is accurate to
  // far better than the 10% gap to q3's).
  EXPECT_LE(c->margin.lo, d);
  EXPECT_GT(c->margin.lo, 0);
}

TEST(Stars, AProtectionClaimViolatedOnlyBeyondThreeRadiiIsFound) {
  Square sq;
  const double d = sq.power(1, 2, 5), q3 = sq.power(1, 2, 3);
  // A claim between d's power and q3's: only d violates it, and d lies beyond 3R.
  const double claim = 0.5 * (d + q3);
  detail::PointGrid grid(sq.P, 2);
  StarSettings S{&sq.P, &sq.system, &grid, 2, exact::to_rational(claim), std::nullopt};
  exact::FilterContext ctx;
  StarReport r = analyse_star(S, 0, nullptr, ctx);
  ASSERT_EQ(r.star.size(), 4u);
  const CellReport* c = cell(r, {0, 1, 2});
  ASSERT_NE(c, nullptr);
  EXPECT_EQ(c->protection_point, 5);
  EXPECT_LT(c->protection_sign, 0);
}

}  // namespace
}  // namespace delcert::certify::test
