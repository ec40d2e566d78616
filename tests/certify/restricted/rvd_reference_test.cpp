// The certified restricted Voronoi diagram engine (certify/rvd.hpp) against the independent
// reference for codimension 1 (tests/certify/reference/: CGAL's 3D Delaunay triangulation and exact
// Sturm root counting on the dual Voronoi edges). Issue 11, "Tests": on seeded random samples of a
// sphere, an ellipsoid and a torus of revolution, the m-simplices of Del_RM(P) found by the engine
// (the union over every point p of the simplices of the restricted Voronoi vertices of p's cell)
// must EQUAL the reference's restricted triangles. Besides, every cell must be complete, the
// reference must meet no degenerate case, each vertex must be found at every one of its simplex's
// cells, and each vertex enclosure is re-checked here, independently of the engine's code.
#include <CGAL/FPU.h>
#include <CGAL/Interval_nt.h>
#include <CGAL/gmpxx.h>
#include <gtest/gtest.h>

#include <gmpxx.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <set>
#include <span>
#include <sstream>
#include <string>
#include <vector>

#include "certify/detail/grid.hpp"
#include "certify/restricted/rvd.hpp"
#include "exact/polynomial.hpp"
#include "exact/tangent_space.hpp"
#include "io/points.hpp"
#include "tests/certify/reference/restricted_delaunay_reference.hpp"
#include "tests/certify/support.hpp"
#include "tests/test_support.hpp"

namespace delcert::certify::test {
namespace {

using Simplex = std::vector<int>;
using IA = CGAL::Interval_nt<false>;  // used only inside a CGAL::Protect_FPU_rounding<true> scope

// ------------------------------------------------------------------------------------ samples

// Dart throwing on M: `draw` returns a point of M (in real arithmetic; rounded to doubles here, so
// the sample lies NEAR M, which is fine: Del_RM(P) is defined for any P and both sides read the
// doubles as exact rationals). A candidate is kept when it is at least `spacing` from every point
// kept so far; `tries` candidates are drawn in all, enough to saturate: every point of M is then
// (with high probability) within `spacing` of the sample, which bounds the size of the restricted
// Voronoi cells. Seeded (splitmix64), so the sample is the same on every platform.
template <class Draw>
io::PointSet dart_throwing(Draw draw, double spacing, int tries, std::uint64_t seed) {
  Rng rng(seed);
  std::vector<std::array<double, 3>> pts;
  for (int t = 0; t < tries; ++t) {
    const std::array<double, 3> x = draw(rng);
    bool ok = true;
    for (const auto& q : pts) {
      const double d0 = x[0] - q[0], d1 = x[1] - q[1], d2 = x[2] - q[2];
      if (d0 * d0 + d1 * d1 + d2 * d2 < spacing * spacing) {
        ok = false;
        break;
      }
    }
    if (ok) pts.push_back(x);
  }
  io::PointSet P;
  P.dimension = 3;
  for (const auto& p : pts) P.push_back(p);
  return P;
}

// A uniformly distributed point of the unit sphere (normalised Gaussian, Box-Muller).
std::array<double, 3> unit_sphere_point(Rng& rng) {
  std::array<double, 3> x{};
  double s = 0;
  for (auto& v : x) {
    const double u1 = rng.uniform() + 1e-300, u2 = rng.uniform();
    v = std::sqrt(-2 * std::log(u1)) * std::cos(2 * M_PI * u2);
    s += v * v;
  }
  for (auto& v : x) v /= std::sqrt(s);
  return x;
}

// --------------------------------------------------------------------------- both computations

struct Agreement {
  std::vector<RestrictedCellReport> cells;
  std::set<Simplex> engine;     // union of the cells' vertex simplices
  std::set<Simplex> reference;  // the reference's restricted triangles
  reference::RestrictedDelaunayReference ref;
};

std::string describe(const std::vector<double>& x) {
  std::ostringstream s;
  s << "(";
  for (std::size_t i = 0; i < x.size(); ++i) s << (i ? ", " : "") << x[i];
  s << ")";
  return s.str();
}
std::string describe(const Simplex& s) {
  std::ostringstream o;
  o << "{";
  for (std::size_t i = 0; i < s.size(); ++i) o << (i ? ", " : "") << s[i];
  o << "}";
  return o.str();
}

Agreement compute(const std::string& name, const std::string& equation, const io::PointSet& P, double graph_radius,
                  int max_depth = RestrictedCellOptions{}.max_depth) {
  Agreement out;
  const exact::ImplicitSystem system = exact::ImplicitSystem::parse({equation}, 3);
  const detail::PointGrid grid(P, 2);
  RestrictedCellOptions opt;
  opt.graph_radius = graph_radius;
  opt.max_depth = max_depth;
  const auto t0 = std::chrono::steady_clock::now();  // printed only, never asserted
  long boxes = 0, calls = 0, failures = 0, chart_failures = 0;
  double eps = 0;
  for (std::size_t p = 0; p < P.size(); ++p) {
    out.cells.push_back(analyse_restricted_cell(system, P, grid, static_cast<int>(p), opt));
    const RestrictedCellReport& R = out.cells.back();
    for (const auto& v : R.vertices) out.engine.insert(v.simplex);
    boxes += R.boxes, calls += R.krawczyk_calls, failures += R.krawczyk_failures, chart_failures += R.chart_failures;
    eps = std::max(eps, R.covering_bound);
  }
  const double engine_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const auto t1 = std::chrono::steady_clock::now();
  out.ref = reference::restricted_delaunay_reference(P, exact::Polynomial::parse(equation, 3));
  const double reference_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count();
  for (const auto& t : out.ref.triangles())
    out.reference.insert({static_cast<int>(t[0]), static_cast<int>(t[1]), static_cast<int>(t[2])});
  std::printf(
      "[ rvd vs reference ] %s, %zu points, graph radius %.4f, depth %d: engine %zu simplices, %.1f boxes/point, "
      "%.1f Krawczyk calls/point, %ld Krawczyk failures, %ld chart failures, covering bound %.4f (%.2f s); "
      "reference %zu triangles of %zu Delaunay triangles, %zu segments exact, %zu degenerate (%.2f s)\n",
      name.c_str(), P.size(), graph_radius, max_depth, out.engine.size(), double(boxes) / P.size(), double(calls) / P.size(),
      failures, chart_failures, eps, engine_seconds, out.reference.size(), out.ref.delaunay_triangles,
      out.ref.exact_segments, out.ref.degenerate.size(), reference_seconds);
  return out;
}

// ------------------------------------------------------------------------------- assertions

// 1. Every cell complete (no undecided box, covering bound below the graph radius); the reference
//    decided every triangle.
void expect_decided(const Agreement& a) {
  for (const auto& R : a.cells) {
    std::ostringstream why;
    why << "cell " << R.point << " incomplete: " << R.reason << " (covering bound " << R.covering_bound << " at "
        << describe(R.covering_location) << ")";
    for (std::size_t i = 0; i < R.undecided.size() && i < 5; ++i)
      why << "\n  undecided at " << describe(R.undecided[i].location) << ", candidates "
          << describe(R.undecided[i].candidates) << ": " << R.undecided[i].reason;
    EXPECT_TRUE(R.complete) << why.str();
  }
  std::ostringstream deg;
  for (const auto& t : a.ref.degenerate)
    deg << "\n  {" << t.vertices[0] << ", " << t.vertices[1] << ", " << t.vertices[2]
        << "}: " << reference::to_string(t.degeneracy);
  EXPECT_TRUE(a.ref.degenerate.empty()) << "the reference met degenerate cases:" << deg.str();
}

// 2. Set equality, with the first differences (and the reference's witness for a missing one).
void expect_equal_sets(const Agreement& a) {
  std::vector<Simplex> missing, extra;  // in the reference only / in the engine only
  std::set_difference(a.reference.begin(), a.reference.end(), a.engine.begin(), a.engine.end(),
                      std::back_inserter(missing));
  std::set_difference(a.engine.begin(), a.engine.end(), a.reference.begin(), a.reference.end(),
                      std::back_inserter(extra));
  std::ostringstream s;
  for (std::size_t i = 0; i < missing.size() && i < 5; ++i) {
    s << "\n  missing from the engine: " << describe(missing[i]);
    for (const auto& t : a.ref.restricted)
      if (static_cast<int>(t.vertices[0]) == missing[i][0] && static_cast<int>(t.vertices[1]) == missing[i][1] &&
          static_cast<int>(t.vertices[2]) == missing[i][2] && t.edge.roots.isolating) {
        // Narrow the isolating interval by exact bisection (Sturm counts) to locate the point.
        auto [t0, t1] = *t.edge.roots.isolating;
        for (int i = 0; i < 60 && t0 != t1; ++i) {
          const mpq_class mid = (t0 + t1) / 2;
          if (reference::count_distinct_roots(t.edge.restricted, t0, mid) > 0) t1 = mid;
          else t0 = mid;
        }
        const auto x = t.edge.point(t0);
        s << " (reference: " << t.edge.roots.distinct_roots << " root(s) on its Voronoi "
          << (t.edge.ray ? "ray" : "segment") << ", one at (" << x[0].get_d() << ", " << x[1].get_d() << ", "
          << x[2].get_d() << "))";
      }
  }
  for (std::size_t i = 0; i < extra.size() && i < 5; ++i) s << "\n  extra in the engine: " << describe(extra[i]);
  EXPECT_TRUE(missing.empty() && extra.empty())
      << missing.size() << " missing, " << extra.size() << " extra:" << s.str();
}

// 3. The free cross-check: a vertex of simplex s found at p is found at every other point of s.
//    With `allow_undecided`, a cell q that misses it must instead hold an undecided box whose
//    candidate set contains s (certify/rvd.hpp: every restricted Voronoi vertex of q is found or lies
//    in an undecided box, whose candidates include every point nearest to it).
void expect_consistent(const Agreement& a, bool allow_undecided = false) {
  for (const auto& R : a.cells)
    for (const auto& v : R.vertices)
      for (int q : v.simplex) {
        bool found = false;
        for (const auto& w : a.cells[q].vertices) found = found || w.simplex == v.simplex;
        if (!found && allow_undecided)
          for (const auto& u : a.cells[q].undecided)
            found = found || std::includes(u.candidates.begin(), u.candidates.end(), v.simplex.begin(), v.simplex.end());
        EXPECT_TRUE(found) << "the vertex of " << describe(v.simplex) << " found at " << R.point << " is not found at "
                           << q << (allow_undecided ? " nor inside one of its undecided boxes" : "");
      }
}

// 4. Each vertex enclosure X re-checked here, not with the engine's code:
//    * for p, a in the simplex and q in P outside it: e_pq(x) = |x - q|^2 - |x - p|^2 =
//      |q|^2 - |p|^2 - 2 x.(q - p) is affine in x, so its range over the box X is
//      [c - 2 sum_k max(...), c - 2 sum_k min(...)] with the extremes at corners; the interval
//      evaluation below encloses that range (a filter), and where it cannot decide, the extreme over
//      the corners is computed in exact rationals.
//      Required: e_pq > 0 on all of X (q strictly farther than the simplex's points), and e_pa's
//      range contains 0 (the equidistant point can be in X);
//    * F's interval enclosure over X contains 0 (a point of M can be in X), and X is small.
//    Intervals: CGAL::Interval_nt<false> under CGAL::Protect_FPU_rounding<true> (upward rounding);
//    a double coordinate is an exact interval, and CGAL computes both bounds of every operation
//    rounded outward (the lower one by negation under upward rounding), so each result encloses
//    the exact result of its operands; an overflow would give an infinite bound, never a wrong
//    finite one (the values here are below 100 in magnitude; underflow only widens).
struct ExactPoints {
  std::vector<std::array<mpq_class, 3>> q;
  explicit ExactPoints(const io::PointSet& P) : q(P.size()) {
    for (std::size_t i = 0; i < P.size(); ++i)
      for (int k = 0; k < 3; ++k) q[i][k] = P.point(i)[k];
  }
};

// The exact minimum (max when `maximum`) of |x - q|^2 - |x - p|^2 over the corners of X.
mpq_class exact_extreme(const ExactPoints& E, const exact::Box& X, std::size_t p, std::size_t q, bool maximum) {
  mpq_class c = 0;
  for (int k = 0; k < 3; ++k) c += E.q[q][k] * E.q[q][k] - E.q[p][k] * E.q[p][k];
  for (int k = 0; k < 3; ++k) {
    const mpq_class d = E.q[q][k] - E.q[p][k];
    const mpq_class lo = mpq_class(X[k].lo) * d, hi = mpq_class(X[k].hi) * d;
    // -2 x_k d_k: its minimum uses the larger of x_k d_k over [lo, hi], its maximum the smaller.
    c -= 2 * (maximum ? std::min(lo, hi) : std::max(lo, hi));
  }
  return c;
}

void expect_vertices_recheck(const Agreement& a, const io::PointSet& P, const std::string& equation) {
  const auto t0 = std::chrono::steady_clock::now();  // printed only
  const exact::Polynomial F = exact::Polynomial::parse(equation, 3);
  const ExactPoints E(P);
  long checked = 0, exact_fallbacks = 0;
  CGAL::Protect_FPU_rounding<true> upward;
  std::vector<IA> coef;
  for (const auto& t : F.terms()) coef.push_back(IA(CGAL::to_interval(t.coefficient)));
  for (const auto& R : a.cells)
    for (const auto& v : R.vertices) {
      ++checked;
      const exact::Box& X = v.x;
      ASSERT_EQ(X.size(), 3u);
      std::array<IA, 3> x;
      for (int k = 0; k < 3; ++k) {
        ASSERT_LE(X[k].lo, X[k].hi);
        EXPECT_LT(X[k].hi - X[k].lo, 1e-6) << "vertex of " << describe(v.simplex) << " at " << R.point;
        x[k] = IA(X[k].lo, X[k].hi);
      }
      const IA f = F.evaluate_with<IA>(std::span<const IA>(x), [&](std::size_t i) { return coef[i]; });
      EXPECT_TRUE(f.inf() <= 0 && 0 <= f.sup())
          << "F excludes 0 on the enclosure of the vertex of " << describe(v.simplex) << " at " << R.point;
      const auto e = [&](std::size_t p, std::size_t q) {
        IA s(0);
        for (int k = 0; k < 3; ++k) {
          const IA d = IA(P.point(q)[k]) - IA(P.point(p)[k]);
          s += (IA(P.point(q)[k]) + IA(P.point(p)[k])) * d - IA(2) * x[k] * d;
        }
        return s;
      };
      const std::size_t p0 = v.simplex[0];
      for (std::size_t j = 1; j < v.simplex.size(); ++j) {
        const std::size_t aj = v.simplex[j];
        const IA s = e(p0, aj);
        bool contains = s.inf() <= 0 && 0 <= s.sup();
        if (!contains) {  // decide exactly
          ++exact_fallbacks;
          contains = exact_extreme(E, X, p0, aj, false) <= 0 && 0 <= exact_extreme(E, X, p0, aj, true);
        }
        EXPECT_TRUE(contains) << "the points of " << describe(v.simplex) << " are not equidistant anywhere on the "
                              << "enclosure found at " << R.point;
      }
      for (std::size_t q = 0; q < P.size(); ++q) {
        if (std::binary_search(v.simplex.begin(), v.simplex.end(), static_cast<int>(q))) continue;
        for (int pi : v.simplex) {
          const std::size_t p = pi;
          if (e(p, q).inf() > 0) continue;
          ++exact_fallbacks;
          EXPECT_GT(exact_extreme(E, X, p, q, false), 0)
              << "point " << q << " is not strictly farther than " << p << " on the enclosure of the vertex of "
              << describe(v.simplex) << " found at " << R.point;
        }
      }
    }
  std::printf("[ rvd vs reference ] %ld vertex enclosures re-checked against every point (%ld exact fallbacks, %.2f s)\n",
              checked, exact_fallbacks, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
}

// One sample per seed: seed, seed + 1000, ... (DELCERT_TEST_SCALE = k >= 2 runs k samples, a long
// run on demand; the default 1 and the sanitizer run's 0.1 run one).
template <class Draw>
void expect_agreement(const std::string& name, const std::string& equation, Draw draw, double spacing, int tries,
                      std::uint64_t seed, double graph_radius) {
  const int samples = std::max(1, static_cast<int>(std::floor(delcert::test::test_scale())));
  for (int i = 0; i < samples; ++i) {
    const std::uint64_t s = seed + 1000 * static_cast<std::uint64_t>(i);
    SCOPED_TRACE(name + ", seed " + std::to_string(s));
    const io::PointSet P = dart_throwing(draw, spacing, tries, s);
    const Agreement a = compute(name + " (seed " + std::to_string(s) + ")", equation, P, graph_radius);
    expect_decided(a);
    expect_equal_sets(a);
    expect_consistent(a);
    expect_vertices_recheck(a, P, equation);
    EXPECT_FALSE(a.engine.empty());
  }
}

// ---------------------------------------------------------------------------------- the cases

// The unit sphere: reach 1, graph radius r < 1/2 (certify/rvd.hpp, THE GRAPH ASSUMPTION; for the
// sphere itself anything below sqrt 2 would do, but the test keeps to the general lemma).
TEST(RestrictedCellVersusReference, UnitSphere) {
  const std::string F = "x1^2 + x2^2 + x3^2 - 1";
  expect_agreement("sphere 60", F, unit_sphere_point, 0.37, 3000, 21, 0.49);
  expect_agreement("sphere 200", F, unit_sphere_point, 0.2, 8000, 22, 0.49);
}

// Points OFF the sphere (as a mesher's vertices, computed by bisection, are only near M): radial
// noise up to 3/100. Del_RM(P) is then no longer the convex hull, and the Voronoi vertices of P
// are no longer at the origin. Graph radius: the sphere's cap in B(p, r) is a graph over the plane
// orthogonal to p (= ker J_F(p)) for r < 1/2 and |p| in [0.97, 1.03].
std::array<double, 3> noisy_sphere_point(Rng& rng) {
  const auto s = unit_sphere_point(rng);
  const double rho = 1 + 0.03 * (2 * rng.uniform() - 1);
  return {rho * s[0], rho * s[1], rho * s[2]};
}

TEST(RestrictedCellVersusReference, PointsNearButOffTheSphere) {
  expect_agreement("sphere, points off M", "x1^2 + x2^2 + x3^2 - 1", noisy_sphere_point, 0.3, 5000, 25, 0.49);
}

// The ellipsoid x^2/a^2 + y^2/b^2 + z^2/c^2 = 1 with a = 3/2, b = 5/4, c = 1 (rational
// coefficients 4/9, 16/25, 1). Its reach is 2/3:
//   * by Aamari, Kim, Chazal, Michel, Rinaldo, Wasserman (Estimating the reach of a manifold, EJS
//     2019, Thm 3.4) the reach of a closed C^2 submanifold is min(1 / kappa_max, Delta / 2), with
//     kappa_max the largest normal curvature and Delta the length of the shortest "bottleneck", a
//     segment xy (x != y on M) normal to M at both ends;
//   * curvature: with D = diag(1/a^2, 1/b^2, 1/c^2), M = {x^T D x = 1}, the normal curvature at x
//     in a unit tangent direction v is v^T D v / |D x|. Here v^T D v <= 1/c^2, and
//     1 = x^T D x <= |x| |D x| <= a |D x| (|x| <= a on M), so kappa <= a / c^2, attained at
//     x = (a, 0, 0), v = e_3: 1 / kappa_max = c^2 / a = 2/3;
//   * bottlenecks: y - x parallel to D x and to D y makes D x = lambda D y, so x = lambda y, and
//     x^T D x = lambda^2 y^T D y gives lambda = -1 (x != y); then y - x = 2y is parallel to D y:
//     y is an eigenvector of D, a vertex on an axis (a, b, c distinct). So Delta = 2c = 2, Delta/2 = 1.
// Reach 2/3: the graph radius must be below 1/3.
std::array<double, 3> ellipsoid_point(Rng& rng) {
  const auto s = unit_sphere_point(rng);
  return {1.5 * s[0], 1.25 * s[1], s[2]};
}

TEST(RestrictedCellVersusReference, Ellipsoid) {
  expect_agreement("ellipsoid", "4/9*x1^2 + 16/25*x2^2 + x3^2 - 1", ellipsoid_point, 0.27, 6000, 23, 0.33);
}

// The torus of revolution R = 1, r = 1/2 about the x3 axis: (|x|^2 + R^2 - r^2)^2 - 4 R^2 (x1^2 + x2^2).
// Its reach is min(r, R - r) = 1/2: principal curvatures 1/r (meridian) and
// cos v / (R + r cos v) (|.| <= 1/(R - r) = 2), so 1 / kappa_max = r = 1/2; the shortest bottleneck
// is the segment through the axis between the inner equator's opposite points, length 2 (R - r) = 1
// (the other double normals are diameters of meridian circles, length 2r = 1, and longer ones).
// Graph radius below 1/4. Points uniform in area: the angle v is accepted with probability
// (R + r cos v) / (R + r).
std::array<double, 3> torus_point(Rng& rng) {
  const double R = 1, r = 0.5;
  double v = 0;
  do {
    v = 2 * M_PI * rng.uniform();
  } while (rng.uniform() * (R + r) > R + r * std::cos(v));
  const double u = 2 * M_PI * rng.uniform();
  return {(R + r * std::cos(v)) * std::cos(u), (R + r * std::cos(v)) * std::sin(u), r * std::sin(v)};
}

TEST(RestrictedCellVersusReference, TorusOfRevolution) {
  expect_agreement("torus", "(x1^2 + x2^2 + x3^2 + 3/4)^2 - 4*(x1^2 + x2^2)", torus_point, 0.19, 12000, 24, 0.24);
}

// Near-degenerate input: the 8 vertices of the cube [-1, 1]^3 (on the sphere of radius sqrt 3, where
// every square face is cocircular: TheCubeOnItsCircumsphereIsDegenerate, CubeOnItsSphereIsNeverDecided)
// moved by seeded perturbations of size e. The reference decides every triangle; the two restricted
// Voronoi vertices of a face are about e apart, so the engine needs depth about log2(1/e) to tell
// them apart. Below that depth it may leave cells incomplete, but what it claims must stay sound:
// its simplices are a SUBSET of the reference's, and every triangle it misses has a vertex whose cell
// is incomplete. With enough depth it agrees in full. Graph radius 2.2: for a sphere of radius rho
// the cap M ∩ B(p, r) is a graph over the plane orthogonal to p for r < rho sqrt 2 = 2.449 (the cap
// stays on p's side of the equator; the points are within 1e-3 of the sphere); the cells here reach
// 1.76 from their point.
TEST(RestrictedCellVersusReference, NearlyCocircularCubeIsSoundAtAnyDepth) {
  const std::string F = "x1^2 + x2^2 + x3^2 - 3";
  for (double e : {1e-3, 1e-6, 1e-9}) {
    Rng rng(7);
    std::vector<std::vector<double>> pts;
    for (int i = 0; i < 8; ++i) {
      pts.push_back({});
      for (int k = 0; k < 3; ++k) pts.back().push_back(((i >> k) & 1 ? 1.0 : -1.0) + e * (rng.uniform() - 0.5));
    }
    const io::PointSet P = make_points(3, pts);
    char label[64];
    std::snprintf(label, sizeof label, "perturbed cube, e = %g", e);
    SCOPED_TRACE(label);
    const Agreement shallow = compute(label, F, P, 2.2, 24);
    EXPECT_TRUE(shallow.ref.degenerate.empty());
    EXPECT_EQ(shallow.reference.size(), 12u);  // two triangles per face of the cube, one diagonal each
    EXPECT_TRUE(std::includes(shallow.reference.begin(), shallow.reference.end(), shallow.engine.begin(),
                              shallow.engine.end()))
        << "the engine claims a triangle the reference refutes";
    // Every reference triangle is accounted for at each of its three cells: found there, or inside
    // an undecided box of that cell whose candidates include it (its restricted Voronoi vertex is
    // within 1.76 < 2.2 of each of the three points, see the deep run).
    for (const auto& t : shallow.reference)
      for (int a : t) {
        bool accounted = false;
        for (const auto& v : shallow.cells[a].vertices) accounted = accounted || v.simplex == t;
        for (const auto& u : shallow.cells[a].undecided)
          accounted = accounted || std::includes(u.candidates.begin(), u.candidates.end(), t.begin(), t.end());
        EXPECT_TRUE(accounted) << describe(t) << " is neither found nor undecided at " << a;
      }
    expect_consistent(shallow, true);
    expect_vertices_recheck(shallow, P, F);
    const Agreement deep = compute(label, F, P, 2.2, 48);
    expect_decided(deep);
    expect_equal_sets(deep);
    expect_consistent(deep);
    expect_vertices_recheck(deep, P, F);
  }
}

}  // namespace
}  // namespace delcert::certify::test
