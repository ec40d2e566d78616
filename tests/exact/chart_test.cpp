// Chart enclosures (exact/chart.hpp): for every u in U exactly one point of M over u lies in
// X(U). Checked against exact solutions: closed form on the sphere (decided in rationals), and
// on the Clifford torus and SO(3) a rational Newton solve of F(p + T u + Nn h) = 0 written here
// from F itself (not from the chart's expanded system) to 2^-200.
#include "exact/chart.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "exact/number_types.hpp"
#include "support.hpp"

namespace delcert::exact {
namespace {

using testing::Q;

ImplicitSystem sphere(double r) {
  const Q r2 = to_rational(r) * to_rational(r);
  Polynomial f = Polynomial::parse("x1^2 + x2^2 + x3^2", 3) - Polynomial::constant(r2, 3);
  return ImplicitSystem({f}, 3);
}

// The chart of the sphere of radius r at (0, 0, r) with the obvious bases: x = (u1, u2, r + h).
ChartEnclosure sphere_chart(double r) {
  const double p[3] = {0, 0, r};
  return ChartEnclosure(sphere(r), p, {1, 0, 0, 1, 0, 0}, {0, 0, 1});
}

Q rational_at(const Interval& i, int s, int steps) {
  return to_rational(i.lo) + (to_rational(i.hi) - to_rational(i.lo)) * Q(s, steps);
}

// For a sphere chart at (0, 0, r) with T = diag(t1, t2) on top of zeros and Nn = (0, 0, n), n > 0
// (the obvious bases, or ChartEnclosure::at's scaled ones): the exact point over u is
// x = (t1 u1, t2 u2, sqrt(r^2 - x1^2 - x2^2)) with h = (x3 - r) / n. Checks that H and X hold it,
// exactly in rationals.
void expect_sphere_point_inside(const ChartResult& c, const ChartEnclosure& chart, double r, const Q& u1,
                                const Q& u2) {
  ASSERT_TRUE(chart.tangent(0, 1) == 0 && chart.tangent(1, 0) == 0 && chart.tangent(2, 0) == 0 &&
              chart.tangent(2, 1) == 0 && chart.normal(0, 0) == 0 && chart.normal(1, 0) == 0 &&
              chart.normal(2, 0) > 0);
  const Q x1 = chart.tangent(0, 0) * u1, x2 = chart.tangent(1, 1) * u2, n = chart.normal(2, 0);
  const Q R = to_rational(r), s = R * R - x1 * x1 - x2 * x2;
  ASSERT_GT(s, 0);
  const Q hlo = to_rational(c.H[0].lo) * n + R, hhi = to_rational(c.H[0].hi) * n + R;
  EXPECT_TRUE(hlo >= 0 && hlo * hlo <= s && s <= hhi * hhi) << "H misses the point";
  const Q xlo = to_rational(c.X[2].lo), xhi = to_rational(c.X[2].hi);
  EXPECT_TRUE(xlo >= 0 && xlo * xlo <= s && s <= xhi * xhi) << "X misses the point";
  EXPECT_TRUE(to_rational(c.X[0].lo) <= x1 && x1 <= to_rational(c.X[0].hi));
  EXPECT_TRUE(to_rational(c.X[1].lo) <= x2 && x2 <= to_rational(c.X[1].hi));
}

TEST(Chart, SphereGraphOverAGridOfBoxes) {
  for (double r : {1.0, 0.75, 3.0}) {
    const ChartEnclosure chart = sphere_chart(r);
    EXPECT_EQ(chart.intrinsic_dimension(), 2);
    EXPECT_EQ(chart.codimension(), 1);
    const int cells = 12;
    const double w = 1.2 * r / cells;
    int unique = 0, total = 0;
    double worst_ratio = 0;  // width of X3 over the range of x3 on U (1 = optimal)
    for (int i = 0; i < cells; ++i)
      for (int j = 0; j < cells; ++j) {
        const Box U{{-0.6 * r + i * w, -0.6 * r + (i + 1) * w}, {-0.6 * r + j * w, -0.6 * r + (j + 1) * w}};
        const ChartResult c = chart.enclose(U);
        ++total;
        if (c.status != ChartStatus::unique) continue;
        ++unique;
        for (int a = 0; a <= 4; ++a)
          for (int b = 0; b <= 4; ++b) expect_sphere_point_inside(c, chart, r, rational_at(U[0], a, 4), rational_at(U[1], b, 4));
        // Range of x3 over U: from the nearest and farthest corner (|u| monotone per quadrant).
        double dmin = 0, dmax = 0;
        for (int a = 0; a < 2; ++a) {
          const double lo = U[a].lo, hi = U[a].hi;
          const double near = (lo <= 0 && 0 <= hi) ? 0 : std::min(std::abs(lo), std::abs(hi));
          dmin += near * near;
          dmax += std::max(lo * lo, hi * hi);
        }
        const double range = std::sqrt(r * r - dmin) - std::sqrt(r * r - dmax);
        worst_ratio = std::max(worst_ratio, c.X[2].width() / range);
      }
    EXPECT_EQ(unique, total) << "r = " << r;
    EXPECT_LT(worst_ratio, 4.0);
    std::printf("[chart] sphere r=%g: %d/%d boxes of width %.3g unique, worst width(X3)/range(x3) = %.3f\n", r,
                unique, total, w, worst_ratio);
  }
}

TEST(Chart, SphereBoxesPastTheEquatorAreNeverUnique) {
  const double r = 1.0;
  const ChartEnclosure chart = sphere_chart(r);
  const std::vector<Box> boxes = {
      {{0.95, 1.05}, {-0.02, 0.02}}, {{0.9, 1.2}, {0.0, 0.1}},  {{-1.1, -0.8}, {-0.1, 0.1}},
      {{0.7, 0.72}, {0.7, 0.72}},    {{1.1, 1.2}, {0.0, 0.1}},  {{-0.5, 0.5}, {0.9, 1.000001}},
      {{-1.5, 1.5}, {-1.5, 1.5}},    {{0.999, 1.001}, {0, 0}},  {{1.0, 1.0}, {0.0, 0.0}},
  };
  for (const Box& U : boxes) {
    EXPECT_NE(chart.enclose(U).status, ChartStatus::unique) << U[0].lo << " " << U[1].lo;
    // Whatever H: u on or past the equator has no root, or a double root at h = -r.
    for (const Box& H : {Box{{-2.0, 0.5}}, Box{{-1.0, -0.5}}, Box{{-1.5, -0.999}}})
      EXPECT_NE(chart.enclose_in(U, H).status, ChartStatus::unique);
  }
  // Just inside the equator the graph is steep but still a graph: may succeed, must be right.
  const Box U{{0.97, 0.98}, {0.0, 0.01}};
  const ChartResult c = chart.enclose(U);
  if (c.status == ChartStatus::unique)
    for (int a = 0; a <= 4; ++a)
      for (int b = 0; b <= 4; ++b) expect_sphere_point_inside(c, chart, r, rational_at(U[0], a, 4), rational_at(U[1], b, 4));
}

TEST(Chart, NoneOnlyWhenTheGivenNormalBoxIsEmpty) {
  const ChartEnclosure chart = sphere_chart(1.0);
  // Over |u| <= 0.15 the sphere's upper sheet has h in [-0.012, 0], the lower one in [-2, -1.98].
  const Box U{{-0.1, 0.1}, {-0.1, 0.1}};
  EXPECT_EQ(chart.enclose_in(U, Box{{0.1, 0.5}}).status, ChartStatus::none);
  EXPECT_EQ(chart.enclose_in(U, Box{{-0.9, -0.5}}).status, ChartStatus::none);
  EXPECT_EQ(chart.enclose_in(U, Box{{-2.5, -2.1}}).status, ChartStatus::none);
  EXPECT_EQ(chart.enclose_in(U, Box{{-0.5, 0.1}}).status, ChartStatus::unique);
  // Both sheets in H: never unique.
  EXPECT_NE(chart.enclose_in(U, Box{{-2.5, 0.5}}).status, ChartStatus::unique);
  EXPECT_EQ(chart.enclose(U).status, ChartStatus::unique);
}

// ---- a reference solver for F(p + T u + Nn h) = 0, in rationals, written from F ----

Q round_dyadic(const Q& x, int bits) {
  const mpz_class scale = mpz_class(1) << bits;
  const Q t = x * Q(scale);
  mpz_class z = t.get_num() / t.get_den();
  Q out(z, scale);
  out.canonicalize();
  return out;
}

struct Reference {
  std::vector<Q> h, x;
  Q residual;  // max |F_i(x)|
};

Reference solve_chart(const ImplicitSystem& F, const ChartEnclosure& C, const std::vector<Q>& u) {
  const int N = C.ambient_dimension(), m = C.intrinsic_dimension(), k = C.codimension();
  std::vector<Polynomial> dF;
  for (const auto& f : F.equations())
    for (int v = 0; v < N; ++v) dF.push_back(f.derivative(v));
  Reference ref;
  ref.h.assign(k, Q(0));
  auto point = [&] {
    std::vector<Q> x(N);
    for (int v = 0; v < N; ++v) {
      x[v] = to_rational(C.base_point()[v]);
      for (int a = 0; a < m; ++a) x[v] += C.tangent(v, a) * u[a];
      for (int l = 0; l < k; ++l) x[v] += C.normal(v, l) * ref.h[l];
    }
    return x;
  };
  for (int it = 0; it < 40; ++it) {
    const std::vector<Q> x = point();
    std::vector<Q> g(k), A(static_cast<std::size_t>(k) * k, Q(0));
    for (int i = 0; i < k; ++i) {
      g[i] = F.equations()[i].evaluate(std::span<const Q>(x));
      for (int l = 0; l < k; ++l)
        for (int v = 0; v < N; ++v) A[i * k + l] += dF[i * N + v].evaluate(std::span<const Q>(x)) * C.normal(v, l);
    }
    const auto d = testing::solve(A, g, k);
    if (!d) break;
    bool converged = true;
    for (int l = 0; l < k; ++l) {
      converged = converged && abs((*d)[l]) < Q(1, mpz_class(1) << 215);
      ref.h[l] = round_dyadic(ref.h[l] - (*d)[l], 220);
    }
    if (converged) break;
  }
  ref.x = point();
  ref.residual = 0;
  for (int i = 0; i < k; ++i) ref.residual = std::max(ref.residual, Q(abs(F.equations()[i].evaluate(std::span<const Q>(ref.x)))));
  return ref;
}

// v lies in i with a margin far above the reference's error (~2^-200) and far below any box width.
bool inside(const Interval& i, const Q& v) {
  const Q margin(1, mpz_class(1) << 180);
  return to_rational(i.lo) <= v - margin && v + margin <= to_rational(i.hi);
}

struct Stats {
  int unique = 0, total = 0;
  double max_width = 0;  // widest side of X
};

// Boxes of half-width w centred at offsets c in the chart at p; samples a 3-per-side grid.
void check_manifold(const ImplicitSystem& F, std::span<const double> p, double w, testing::Rng& rng, int boxes,
                    Stats& stats) {
  const ChartEnclosure C = ChartEnclosure::at(F, p);
  const int m = C.intrinsic_dimension(), k = C.codimension();
  for (int b = 0; b < boxes; ++b) {
    Box U(m);
    for (int a = 0; a < m; ++a) {
      const double c = rng.uniform(-4 * w, 4 * w);
      U[a] = {c - w, c + w};
    }
    const ChartResult res = C.enclose(U);
    ++stats.total;
    if (res.status != ChartStatus::unique) continue;
    ++stats.unique;
    for (const auto& x : res.X) stats.max_width = std::max(stats.max_width, x.width());
    int samples = 1;
    for (int a = 0; a < m; ++a) samples *= 3;
    for (int s = 0; s < samples; ++s) {
      std::vector<Q> u(m);
      for (int a = 0, t = s; a < m; ++a, t /= 3) u[a] = rational_at(U[a], t % 3, 2);
      const Reference ref = solve_chart(F, C, u);
      ASSERT_LT(ref.residual, Q(1, mpz_class(1) << 190)) << "reference Newton did not converge";
      for (int l = 0; l < k; ++l) EXPECT_TRUE(inside(res.H[l], ref.h[l])) << "H misses the root, l = " << l;
      for (int v = 0; v < C.ambient_dimension(); ++v) EXPECT_TRUE(inside(res.X[v], ref.x[v])) << "X misses, v = " << v;
    }
  }
}

ImplicitSystem builtin(const std::string& name) {
  for (const auto& M : testing::test_manifolds())
    if (M.name == name) return ImplicitSystem::parse(M.equations, M.N);
  throw std::logic_error("no test manifold " + name);
}

TEST(Chart, CliffordTorusEnclosuresHoldTheExactPoints) {
  const ImplicitSystem F = builtin("clifford-torus-2");
  testing::Rng rng(11);
  for (double w : {0.05, 0.01}) {
    Stats st;
    for (int t = 0; t < 6; ++t) {
      const double a = rng.uniform(0, 6.283185307179586), b = rng.uniform(0, 6.283185307179586);
      const std::vector<double> p = {std::cos(a), std::sin(a), std::cos(b), std::sin(b)};
      check_manifold(F, p, w, rng, 6, st);
    }
    EXPECT_EQ(st.unique, st.total);
    std::printf("[chart] clifford-torus-2 half-width %g: %d/%d unique, widest side of X %.3g\n", w, st.unique,
                st.total, st.max_width);
  }
}

TEST(Chart, SO3EnclosuresHoldTheExactPoints) {
  const ImplicitSystem F = builtin("so3");
  testing::Rng rng(12);
  const testing::TestManifold so3 = testing::test_manifolds().back();
  for (double w : {0.05, 0.01}) {
    Stats st;
    // The identity (exactly on SO(3)) and rounded random rotations (off it by rounding).
    const std::vector<double> id = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    check_manifold(F, id, w, rng, 3, st);
    for (int t = 0; t < 3; ++t) check_manifold(F, testing::sample_near(so3, rng), w, rng, 3, st);
    EXPECT_EQ(st.unique, st.total);
    std::printf("[chart] so3 half-width %g: %d/%d unique, widest side of X %.3g\n", w, st.unique, st.total,
                st.max_width);
  }
}

// THE BASE POINT AND THE TILT (ChartEnclosure::base_point) against closed forms on an ellipse
// x1^2 + 4 x2^2 = 1 (off it, ker J_F(p) is not the tangent line at the foot p* on the normal line):
// the bounds hold and are not vacuous (up to the 2^-30-wide box U0 around u = 0); a selector must
// be proven positive.
TEST(Chart, BasePointBoundsTheTiltAndTheDistance) {
  const ImplicitSystem F = ImplicitSystem::parse({"x1^2 + 4*x2^2 - 1"}, 2);
  for (double t : {0.3, 1.0, 2.0, 4.0})
    for (double off : {1e-3, 1e-6, -1e-3, 0.0}) {
      const double p[2] = {(1 + off) * std::cos(t), (1 + off) * 0.5 * std::sin(t)};
      const ChartEnclosure C = ChartEnclosure::at(F, p);
      const ChartEnclosure::BasePoint b = C.base_point(F);
      ASSERT_TRUE(b.certified) << t << " " << off;
      // p* = p + h n on the normal line (the chart's Nn column): the root of a quadratic nearest 0.
      const double n0 = C.normal(0, 0).get_d(), n1 = C.normal(1, 0).get_d();
      const double A = n0 * n0 + 4 * n1 * n1, B = 2 * (p[0] * n0 + 4 * p[1] * n1),
                   c = p[0] * p[0] + 4 * p[1] * p[1] - 1, disc = std::sqrt(B * B - 4 * A * c);
      const double h = std::abs(-B + disc) < std::abs(-B - disc) ? (-B + disc) / (2 * A) : (-B - disc) / (2 * A);
      const double s0 = p[0] + h * n0, s1 = p[1] + h * n1;
      const double dist = std::abs(h) * std::hypot(n0, n1);
      // The tangents: perpendicular to (x1, 4 x2) at p (the chart's) and at p* (M's).
      const double cross = p[0] * 4 * s1 - 4 * p[1] * s0;
      const double true_sin = std::abs(cross) / (std::hypot(p[0], 4 * p[1]) * std::hypot(s0, 4 * s1));
      EXPECT_GE(b.distance, dist * (1 - 1e-9)) << t << " " << off;
      EXPECT_LE(b.distance, 2 * dist + 1e-8) << t << " " << off;
      EXPECT_GE(b.sin_tilt, true_sin * (1 - 1e-6)) << t << " " << off;
      EXPECT_LE(b.sin_tilt, 20 * true_sin + 1e-8) << t << " " << off;
      for (int v = 0; v < 2; ++v) EXPECT_TRUE(b.x[v].lo <= (v ? s1 : s0) + 1e-12 && (v ? s1 : s0) - 1e-12 <= b.x[v].hi);
      const Polynomial pos = Polynomial::parse("x1 + 10", 2), neg = Polynomial::parse("x1 - 10", 2);
      EXPECT_TRUE(C.base_point(F, &pos).certified);
      EXPECT_FALSE(C.base_point(F, &neg).certified);
    }
}

TEST(Chart, BasePointOnSO3) {
  const ImplicitSystem F = builtin("so3");
  const Polynomial det = Polynomial::parse("x1*x5*x9 - x1*x6*x8 - x2*x4*x9 + x2*x6*x7 + x3*x4*x8 - x3*x5*x7", 9);
  testing::Rng rng(14);
  const testing::TestManifold so3 = testing::test_manifolds().back();
  const std::vector<double> id = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  const ChartEnclosure::BasePoint at_id = ChartEnclosure::at(F, id).base_point(F, &det);
  ASSERT_TRUE(at_id.certified);
  EXPECT_LT(at_id.sin_tilt, 1e-7);  // on SO(3): only the tiny box U0 (2^-30 wide) and rounding
  for (int t = 0; t < 4; ++t) {
    const std::vector<double> p = testing::sample_near(so3, rng);  // rounded: off SO(3) by ~1e-16
    const ChartEnclosure C = ChartEnclosure::at(F, p);
    const ChartEnclosure::BasePoint b = C.base_point(F, &det);
    ASSERT_TRUE(b.certified);
    EXPECT_LT(b.sin_tilt, 1e-7);
    EXPECT_LT(b.distance, 1e-7);
    const Polynomial minus = -det;  // the other component: never certified
    EXPECT_FALSE(C.base_point(F, &minus).certified);
  }
}

TEST(Chart, AdversarialMagnitudesAreCorrectOrUndecided) {
  for (double r : {1e-300, 1e-150, 1e150, 1e300}) {
    int unique = 0, total = 0;
    const double p[3] = {0, 0, r};
    const ImplicitSystem F = sphere(r);
    for (const ChartEnclosure& chart : {sphere_chart(r), ChartEnclosure::at(F, p)}) {
      for (double c : {0.0, 0.1, 0.3}) {
        const Box U{{(c - 0.05) * r, (c + 0.05) * r}, {-0.05 * r, 0.05 * r}};
        const ChartResult res = chart.enclose(U);
        ++total;
        if (res.status != ChartStatus::unique) continue;
        ++unique;
        // x = p + T u + Nn h, decided exactly: x1^2 + x2^2 + x3^2 = r^2 at a grid of u.
        for (int a = 0; a <= 2; ++a)
          for (int b = 0; b <= 2; ++b)
            expect_sphere_point_inside(res, chart, r, rational_at(U[0], a, 2), rational_at(U[1], b, 2));
      }
    }
    std::printf("[chart] sphere r=%g: %d/%d unique\n", r, unique, total);
  }
}

// gram_bounds: below the exact smallest eigenvalues of T^T T and Nn^T Nn, and close to them; by
// interval Gershgorin for nearly orthogonal columns, by the exact route (det / trace) where
// Gershgorin fails; refused where the columns are dependent. The chart system's enclosures hold
// its exact values.
TEST(Chart, GramBoundsAndEquationEnclosures) {
  const double p[3] = {0, 0, 1};
  // T = [[1, 0.25], [0, 1], [0, 0]]: T^T T = [[1, 1/4], [1/4, 17/16]], smallest eigenvalue
  // (33 - sqrt(17)) / 32 = 0.902... ; Gershgorin gives 3/4.
  const ChartEnclosure a(sphere(1), p, {1, Q(1, 4), 0, 1, 0, 0}, {0, 0, 1});
  const auto ga = a.gram_bounds();
  EXPECT_EQ(ga.tangent, 0.75);
  EXPECT_EQ(ga.normal, 1.0);
  // T = [[1, 1], [0, 1/8], [0, 0]]: T^T T = [[1, 1], [1, 65/64]] (Gershgorin negative), smallest
  // eigenvalue (129 - sqrt(129^2 - 256)) / 128 = 0.00779...; det / trace = (1/64) / (129/64).
  const ChartEnclosure b(sphere(1), p, {1, 1, 0, Q(1, 8), 0, 0}, {0, 0, 1});
  const auto gb = b.gram_bounds();
  EXPECT_GT(gb.tangent, 0);
  EXPECT_LE(to_rational(gb.tangent), Q(1, 129));
  EXPECT_GE(gb.tangent, 0.99 / 129);
  const double lam = (129 - std::sqrt(129.0 * 129 - 256)) / 128;
  EXPECT_LT(gb.tangent, lam);
  // Dependent columns: no positive bound.
  const ChartEnclosure c(sphere(1), p, {1, 2, 0, 0, 0, 0}, {0, 0, 1});
  EXPECT_THROW(c.gram_bounds(), std::domain_error);
  // G(u, h) = u1^2 + u2^2 + (1 + h)^2 - 1 with the obvious bases; dG/dh = 2 (1 + h).
  const ChartEnclosure d(sphere(1), p, {1, 0, 0, 1, 0, 0}, {0, 0, 1});
  const std::vector<Interval> z{{0.5, 0.5}, {-0.25, 0.25}, {-0.125, 0.0}};
  const Interval g = d.chart_system().enclose(0, z), dg = d.chart_system().enclose_derivative(0, 0, z);
  // Exact range: u1^2 = 1/4, u2^2 in [0, 1/16], (1 + h)^2 - 1 in [-15/64, 0].
  EXPECT_LE(g.lo, 0.25 - 15.0 / 64);
  EXPECT_GE(g.hi, 0.25 + 1.0 / 16);
  EXPECT_LE(dg.lo, 1.75);
  EXPECT_GE(dg.hi, 2.0);
  EXPECT_GT(dg.lo, 1.5);
  EXPECT_THROW(d.chart_system().enclose(1, z), std::invalid_argument);
  EXPECT_THROW(d.chart_system().enclose_derivative(0, 1, z), std::invalid_argument);
  EXPECT_THROW(d.chart_system().enclose(0, std::vector<Interval>(2)), std::invalid_argument);
  EXPECT_EQ(d.tangent_enclosure().size(), 6u);
  EXPECT_EQ(d.normal_enclosure()[2].lo, 1.0);
  EXPECT_TRUE(rounding_is_nearest());
}

TEST(Chart, RejectsMismatchedInput) {
  const ImplicitSystem F = sphere(1.0);
  const double p[3] = {0, 0, 1};
  EXPECT_THROW(ChartEnclosure(F, p, {1, 0, 0}, {0, 0, 1}), std::invalid_argument);
  const double bad[3] = {0, 0, NAN};
  EXPECT_THROW(ChartEnclosure(F, bad, {1, 0, 0, 1, 0, 0}, {0, 0, 1}), std::invalid_argument);
  EXPECT_THROW(sphere_chart(1.0).enclose(Box{{0.0, 0.1}}), std::invalid_argument);
}

}  // namespace
}  // namespace delcert::exact
