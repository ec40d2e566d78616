// The certified restricted Voronoi cells (certify/rvd.hpp) against known answers on spheres.
#include "certify/restricted/rvd.hpp"

#include <gtest/gtest.h>

#include <gmpxx.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>

#include "exact/number_types.hpp"
#include "io/points.hpp"
#include "io/spec.hpp"
#include "tests/certify/support.hpp"

namespace delcert::certify::test {
namespace {

using Simplex = std::vector<int>;

struct CellRuns {
  std::vector<RestrictedCellReport> cells;
  std::set<Simplex> simplices;  // union over the cells
};

CellRuns analyse_all(const std::string& equation, const io::PointSet& P, double r, int max_depth = 24,
                     double purity_width = RestrictedCellOptions{}.purity_width) {
  const exact::ImplicitSystem F = exact::ImplicitSystem::parse({equation}, 3);
  const detail::PointGrid grid(P, 2);
  RestrictedCellOptions opt;
  const auto start = std::chrono::steady_clock::now();  // printed only, never asserted
  opt.graph_radius = r;
  opt.max_depth = max_depth;
  opt.purity_width = purity_width;
  CellRuns out;
  for (std::size_t p = 0; p < P.size(); ++p) {
    out.cells.push_back(analyse_restricted_cell(F, P, grid, static_cast<int>(p), opt));
    for (const auto& v : out.cells.back().vertices) out.simplices.insert(v.simplex);
  }
  std::printf("%zu cells in %.3f s\n", P.size(),
              std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  return out;
}

// The facets of the convex hull by brute force: a triangle is a facet iff every other point is on
// one side of its plane (exact orientation in rationals; the samples are in general position).
std::set<Simplex> hull_facets(const io::PointSet& P) {
  const int n = static_cast<int>(P.size());
  std::vector<std::array<mpq_class, 3>> Q(n);
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < 3; ++k) Q[i][k] = exact::to_rational(P.point(i)[k]);
  auto orient = [&](int a, int b, int c, int d) {
    mpq_class u[3], v[3], w[3];
    for (int k = 0; k < 3; ++k) u[k] = Q[b][k] - Q[a][k], v[k] = Q[c][k] - Q[a][k], w[k] = Q[d][k] - Q[a][k];
    const mpq_class det = u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) +
                          u[2] * (v[0] * w[1] - v[1] * w[0]);
    return sgn(det);
  };
  std::set<Simplex> out;
  for (int a = 0; a < n; ++a)
    for (int b = a + 1; b < n; ++b)
      for (int c = b + 1; c < n; ++c) {
        bool pos = false, neg = false;
        for (int d = 0; d < n && !(pos && neg); ++d) {
          if (d == a || d == b || d == c) continue;
          const int s = orient(a, b, c, d);
          EXPECT_NE(s, 0) << "sample not in general position";
          pos = pos || s > 0;
          neg = neg || s < 0;
        }
        if (!(pos && neg)) out.insert({a, b, c});
      }
  return out;
}

void expect_consistent(const CellRuns& cells_run) {
  // Every vertex found at p is also found at its other vertices (the free cross-check of §2b).
  for (std::size_t p = 0; p < cells_run.cells.size(); ++p)
    for (const auto& v : cells_run.cells[p].vertices)
      for (int q : v.simplex) {
        bool found = false;
        for (const auto& w : cells_run.cells[q].vertices) found = found || w.simplex == v.simplex;
        EXPECT_TRUE(found) << "vertex of simplex at " << p << " not found at " << q;
      }
}

TEST(RestrictedCell, OctahedronOnTheUnitSphere) {
  const io::PointSet P = io::read_points(fixture("points/octahedron.off"));
  ASSERT_EQ(P.size(), 6u);
  const CellRuns cells_run = analyse_all("x1^2 + x2^2 + x3^2 - 1", P, 1.2);  // graph radius of S^2: sqrt 2
  const double eps = std::sqrt(2 - 2 / std::sqrt(3.0));
  const double c = 1 / std::sqrt(3.0);
  for (std::size_t p = 0; p < P.size(); ++p) {
    const auto& R = cells_run.cells[p];
    EXPECT_TRUE(R.complete) << p << ": " << R.reason;
    ASSERT_EQ(R.vertices.size(), 4u) << p;
    for (const auto& v : R.vertices) {
      // The vertex of {a, b, c} is (sum of the three points) / sqrt 3: enclosed by the box.
      for (int k = 0; k < 3; ++k) {
        double s = 0;
        for (int q : v.simplex) s += P.point(q)[k];
        EXPECT_TRUE(v.x[k].lo <= s * c + 1e-12 && s * c - 1e-12 <= v.x[k].hi) << p;
        EXPECT_LT(v.x[k].width(), 1e-9);
      }
    }
    EXPECT_GE(R.covering_bound, eps);
    EXPECT_LE(R.covering_bound, 1.05 * eps);
  }
  // The 8 faces of the octahedron: one point from each axis pair {0,1}, {2,3}, {4,5}.
  std::set<Simplex> faces;
  for (int a : {0, 1})
    for (int b : {2, 3})
      for (int d : {4, 5}) faces.insert({a, b, d});
  EXPECT_EQ(cells_run.simplices, faces);
  expect_consistent(cells_run);
}

TEST(RestrictedCell, RandomSphereSampleGivesTheConvexHull) {
  const io::PointSet P = spread_sphere(3, 60, 0.3, 11);
  ASSERT_EQ(P.size(), 60u);
  const CellRuns cells_run = analyse_all("x1^2 + x2^2 + x3^2 - 1", P, 0.9);
  long boxes = 0, calls = 0, failures = 0;
  double eps = 0;
  for (const auto& R : cells_run.cells) {
    EXPECT_TRUE(R.complete) << R.point << ": " << R.reason;
    EXPECT_TRUE(R.unresolved_faces.empty()) << R.point;  // Del_RM of a generic sample is pure
    boxes += R.boxes, calls += R.krawczyk_calls, failures += R.krawczyk_failures;
    eps = std::max(eps, R.covering_bound);
  }
  std::printf("sphere sample, %zu points: %.1f boxes/point, %.1f Krawczyk calls/point, %ld failures, eps <= %.4f\n",
              P.size(), double(boxes) / P.size(), double(calls) / P.size(), failures, eps);
  EXPECT_EQ(cells_run.simplices, hull_facets(P));
  expect_consistent(cells_run);
}

TEST(RestrictedCell, CoveringBoundSeesAHole) {
  const double theta = 0.7;
  const io::PointSet all = spread_sphere(3, 60, 0.3, 12);
  io::PointSet P;
  P.dimension = 3;
  for (std::size_t i = 0; i < all.size(); ++i)
    if (all.point(i)[2] < std::cos(theta)) P.push_back(all.point(i));
  ASSERT_LT(P.size(), all.size());
  // The ring of points left around the cap is nearly cocircular: near the pole two restricted
  // Voronoi vertices are ~1e-3 apart; depth 12 cannot separate them (UNDECIDED), 24 (default) can.
  const CellRuns cells_run = analyse_all("x1^2 + x2^2 + x3^2 - 1", P, 1.3);
  double eps = 0, to_pole = 1e9;
  for (const auto& R : cells_run.cells) {
    EXPECT_TRUE(R.complete) << R.point << ": " << R.reason;
    eps = std::max(eps, R.covering_bound);
  }
  for (std::size_t i = 0; i < P.size(); ++i) {
    const auto q = P.point(i);
    to_pole = std::min(to_pole, std::sqrt(q[0] * q[0] + q[1] * q[1] + (q[2] - 1) * (q[2] - 1)));
  }
  // The true covering radius is at least d(pole, P), itself at least the cap's chord.
  EXPECT_GE(to_pole, 2 * std::sin(theta / 2));
  EXPECT_GE(eps, to_pole);
  std::printf("hole of angular radius %.2f: eps <= %.4f, d(pole, P) = %.4f\n", theta, eps, to_pole);
  expect_consistent(cells_run);
}

TEST(RestrictedCell, CoveringBoundHoldsAtEverySampledPointOfTheCell) {
  // The covering bound of a cell (LAGRANGIAN COVERING BOUND in rvd.cpp: corners of the box and
  // bisector multipliers) against a dense sample of M: every sample point whose nearest point of
  // P is p is within the bound of p. On a torus of revolution, where a cell's farthest point need
  // not be a vertex. The bound must also be useful: within 5% of the sampled maximum (the sample's
  // spacing, ~0.026, alone can hide a few per cent).
  const io::PointSet P = torus_of_revolution(24, 10);
  const exact::ImplicitSystem F = exact::ImplicitSystem::parse({"(x1^2 + x2^2 + x3^2 + 3)^2 - 16*(x1^2 + x2^2)"}, 3);
  const detail::PointGrid grid(P, 2);
  RestrictedCellOptions opt;
  opt.graph_radius = 1.2;
  const int cells = 12;
  std::vector<double> sampled(cells, 0);
  double worst = 0;
  const int nu = 720, nv = 360;
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      const double u = 2 * M_PI * i / nu, v = 2 * M_PI * j / nv;
      const double x[3] = {(2 + std::cos(v)) * std::cos(u), (2 + std::cos(v)) * std::sin(u), std::sin(v)};
      int best = 0;
      double best_d = INFINITY;
      for (std::size_t q = 0; q < P.size(); ++q) {
        const double d = std::hypot(x[0] - P.point(q)[0], x[1] - P.point(q)[1], x[2] - P.point(q)[2]);
        if (d < best_d) best_d = d, best = static_cast<int>(q);
      }
      if (best < cells) sampled[best] = std::max(sampled[best], best_d);
    }
  for (int p = 0; p < cells; ++p) {
    const RestrictedCellReport R = analyse_restricted_cell(F, P, grid, p, opt);
    ASSERT_TRUE(R.complete) << p << ": " << R.reason;
    ASSERT_GT(sampled[p], 0) << p;
    EXPECT_GE(R.covering_bound, sampled[p]) << p;
    EXPECT_LE(R.covering_bound, 1.05 * sampled[p]) << p;
    worst = std::max(worst, R.covering_bound / sampled[p]);
  }
  std::printf("[ covering ] bound / sampled maximum <= %.4f over %d cells\n", worst, cells);
}

TEST(RestrictedCell, ACoveringTargetChangesTheWorkNotTheAnswer) {
  // The two passes with a shared target (RestrictedCell): the same vertices, and a covering bound
  // that is still an upper bound of the cell (at least its farthest vertex) and at most the target
  // plus the finest boxes' overestimate; a high target means less work.
  const io::PointSet P = spread_sphere(3, 60, 0.3, 11);
  const exact::ImplicitSystem F = exact::ImplicitSystem::parse({"x1^2 + x2^2 + x3^2 - 1"}, 3);
  const detail::PointGrid grid(P, 2);
  RestrictedCellOptions opt;
  opt.graph_radius = 0.9;
  for (int p = 0; p < 10; ++p) {
    const RestrictedCellReport alone = analyse_restricted_cell(F, P, grid, p, opt);
    RestrictedCell cell(F, P, grid, p, opt);
    const double lower = cell.first_pass();
    const double target = 2 * alone.covering_bound;
    const RestrictedCellReport shared = cell.second_pass(target);
    ASSERT_TRUE(alone.complete && shared.complete) << p;
    ASSERT_EQ(alone.vertices.size(), shared.vertices.size()) << p;
    for (std::size_t i = 0; i < alone.vertices.size(); ++i) EXPECT_EQ(alone.vertices[i].simplex, shared.vertices[i].simplex);
    EXPECT_GT(lower, 0);
    EXPECT_LE(lower, alone.covering_bound);
    EXPECT_GE(shared.covering_bound, lower);
    EXPECT_LE(shared.covering_bound, target);
    EXPECT_LE(shared.boxes, alone.boxes) << p;
  }
}

TEST(RestrictedCell, CombinedSignsChangeTheWorkNotTheAnswer) {
  // COMBINED SIGNS (two and m candidates at a time) against the subdivision without them, on S^2 and
  // S^3: the same vertex simplices at every point, nothing undecided either way, each covering
  // bound at least the farthest certified vertex of the other run (both are upper bounds of the
  // same cell) and within 5% of each other; fewer boxes and Krawczyk calls in all.
  struct Case {
    const char* equation;
    io::PointSet P;
    double r;
  };
  const Case cases[] = {{"x1^2 + x2^2 + x3^2 - 1", spread_sphere(3, 80, 0.25, 21), 0.8},
                        {"x1^2 + x2^2 + x3^2 + x4^2 - 1", spread_sphere(4, 120, 0.4, 22), 1.0}};
  for (const auto& c : cases) {
    const exact::ImplicitSystem F = exact::ImplicitSystem::parse({c.equation}, c.P.dimension);
    const detail::PointGrid grid(c.P, 2);
    RestrictedCellOptions with, without;
    with.graph_radius = without.graph_radius = c.r;
    without.combined_signs_max = 0;
    long boxes_with = 0, boxes_without = 0, calls_with = 0, calls_without = 0;
    for (int p = 0; p < 12; ++p) {
      const RestrictedCellReport a = analyse_restricted_cell(F, c.P, grid, p, with);
      const RestrictedCellReport b = analyse_restricted_cell(F, c.P, grid, p, without);
      ASSERT_TRUE(a.complete && b.complete) << c.equation << " point " << p << ": " << a.reason << " / " << b.reason;
      EXPECT_TRUE(a.unresolved_faces.empty() && b.unresolved_faces.empty()) << p;
      std::vector<std::vector<int>> sa, sb;
      double far_a = 0, far_b = 0;
      for (const auto* R : {&a, &b})
        for (const auto& v : R->vertices) {
          double d = 0;
          for (std::size_t i = 0; i < v.x.size(); ++i) d += std::pow(v.x[i].lo - c.P.point(p)[i], 2);
          (R == &a ? sa : sb).push_back(v.simplex);
          (R == &a ? far_a : far_b) = std::max(R == &a ? far_a : far_b, std::sqrt(d));
        }
      EXPECT_EQ(sa, sb) << c.equation << " point " << p;
      EXPECT_GE(a.covering_bound, far_b * (1 - 1e-9)) << p;
      EXPECT_GE(b.covering_bound, far_a * (1 - 1e-9)) << p;
      EXPECT_NEAR(a.covering_bound, b.covering_bound, 0.05 * b.covering_bound) << p;
      boxes_with += a.boxes, boxes_without += b.boxes, calls_with += a.krawczyk_calls, calls_without += b.krawczyk_calls;
    }
    EXPECT_LT(boxes_with, boxes_without) << c.equation;
    EXPECT_LT(calls_with, calls_without) << c.equation;
    std::printf("[ combined signs ] %s: boxes %ld -> %ld, Krawczyk calls %ld -> %ld (12 cells)\n", c.equation,
                boxes_without, boxes_with, calls_without, calls_with);
  }
}

TEST(RestrictedCell, GraphLemmaChangesTheWorkNotTheAnswer) {
  // THE GRAPH LEMMA (a reach, rvd.cpp) against the box-by-box exclusion of the other sheets, in
  // codimension 2 (Clifford torus T^2 in R^4, reach 1) and 3 (T^3 in R^6): the same vertex simplices
  // at every point, nothing undecided either way, covering bounds each at least the other run's
  // farthest vertex and within 5%; the lemma took slabs. With a reach too small for the ball
  // (0.05) its inequality never holds: no slab taken, the same answer.
  struct Case {
    std::vector<std::string> equations;
    io::PointSet P;
    double r;
  };
  // Radii inside the lemma's range (nearly the reach) and above each cell's extent.
  const Case cases[] = {{{"x1^2 + x2^2 - 1", "x3^2 + x4^2 - 1"}, torus2_lattice(12, 14, 0.3, 9), 0.8},
                        {{"x1^2 + x2^2 - 1", "x3^2 + x4^2 - 1", "x5^2 + x6^2 - 1"}, torus3_bcc(6, 0.3, 10), 0.9}};
  for (const auto& c : cases) {
    const exact::ImplicitSystem F = exact::ImplicitSystem::parse(c.equations, c.P.dimension);
    const detail::PointGrid grid(c.P, F.intrinsic_dimension());
    RestrictedCellOptions lemma, boxwise, small;
    lemma.graph_radius = boxwise.graph_radius = small.graph_radius = c.r;
    lemma.reach = 1, small.reach = 0.05;
    long slabs = 0;
    for (int p = 0; p < 8; ++p) {
      const RestrictedCellReport a = analyse_restricted_cell(F, c.P, grid, p, lemma);
      const RestrictedCellReport b = analyse_restricted_cell(F, c.P, grid, p, boxwise);
      const RestrictedCellReport z = analyse_restricted_cell(F, c.P, grid, p, small);
      ASSERT_TRUE(a.complete && b.complete && z.complete) << p << ": " << a.reason << " / " << b.reason << " / " << z.reason;
      EXPECT_EQ(b.reach_slabs, 0);
      EXPECT_EQ(z.reach_slabs, 0);
      slabs += a.reach_slabs;
      std::vector<std::vector<int>> sa, sb, sz;
      double far_a = 0, far_b = 0;
      for (const auto* R : {&a, &b, &z})
        for (const auto& v : R->vertices) {
          double d = 0;
          for (std::size_t i = 0; i < v.x.size(); ++i) d += std::pow(v.x[i].lo - c.P.point(p)[i], 2);
          (R == &a ? sa : R == &b ? sb : sz).push_back(v.simplex);
          if (R == &a) far_a = std::max(far_a, std::sqrt(d));
          if (R == &b) far_b = std::max(far_b, std::sqrt(d));
        }
      EXPECT_FALSE(sa.empty());
      EXPECT_EQ(sa, sb) << p;
      EXPECT_EQ(sz, sb) << p;
      EXPECT_GE(a.covering_bound, far_b * (1 - 1e-9)) << p;
      EXPECT_GE(b.covering_bound, far_a * (1 - 1e-9)) << p;
      EXPECT_NEAR(a.covering_bound, b.covering_bound, 0.05 * b.covering_bound) << p;
    }
    EXPECT_GT(slabs, 0);
  }
}

TEST(RestrictedCell, SO3CellsWithTheGraphLemma) {
  // SO(3), codimension 6 (reach sqrt 2, det > 0 selects it from O(3)): without the graph lemma no
  // cell ever finished (the other sheets are not excluded by interval signs in a 6-dimensional
  // slab). With it: the cells of p = 0 and of the other points of its first vertex complete, find
  // that vertex, and every vertex of p's cell re-checks in double from its enclosure (on SO(3),
  // equidistant from its simplex, every other point farther).
  const io::PointSet P = so3_net(2500, 0.45, 31);
  ASSERT_GT(P.size(), 300u);
  const io::ManifoldSpec spec = io::read_spec("builtin:so3");
  const exact::ImplicitSystem F(spec.equations, 9);
  const detail::PointGrid grid(P, 3);
  RestrictedCellOptions opt;
  opt.graph_radius = 0.9;
  opt.reach = std::sqrt(2.0) * (1 - 1e-15);
  opt.selector = &*spec.selector;
  const RestrictedCellReport a = analyse_restricted_cell(F, P, grid, 0, opt);
  ASSERT_TRUE(a.complete) << a.reason;
  EXPECT_GT(a.reach_slabs, 0);
  ASSERT_GE(a.vertices.size(), 4u);
  for (const auto& v : a.vertices) {
    std::vector<double> x(9);
    double width = 0;
    for (int i = 0; i < 9; ++i) x[i] = v.x[i].midpoint(), width = std::max(width, v.x[i].width());
    EXPECT_LT(width, 1e-6);
    const double Rx[9] = {x[0], x[1], x[2], x[3], x[4], x[5], x[6], x[7], x[8]};
    for (int i = 0; i < 3; ++i)  // R^T R = I
      for (int j = 0; j < 3; ++j) {
        double s = 0;
        for (int k = 0; k < 3; ++k) s += Rx[3 * k + i] * Rx[3 * k + j];
        EXPECT_NEAR(s, i == j ? 1 : 0, 1e-6);
      }
    auto dist = [&](int q) {
      double d = 0;
      for (int i = 0; i < 9; ++i) d += (P.point(q)[i] - x[i]) * (P.point(q)[i] - x[i]);
      return std::sqrt(d);
    };
    const double d0 = dist(v.simplex[0]);
    for (int q : v.simplex) EXPECT_NEAR(dist(q), d0, 1e-6);
    for (int q = 0; q < static_cast<int>(P.size()); ++q) {
      if (std::binary_search(v.simplex.begin(), v.simplex.end(), q)) continue;
      EXPECT_GT(dist(q), d0 + 1e-9) << q;
    }
  }
  const std::vector<int> first = a.vertices[0].simplex;
  for (int q : first) {
    if (q == 0) continue;
    const RestrictedCellReport b = analyse_restricted_cell(F, P, grid, q, opt);
    ASSERT_TRUE(b.complete) << q << ": " << b.reason;
    EXPECT_TRUE(std::any_of(b.vertices.begin(), b.vertices.end(), [&](const auto& w) { return w.simplex == first; })) << q;
  }
  std::printf("[ so3 ] %zu points; cell 0: %zu vertices, %ld boxes, %ld slabs from the graph lemma\n", P.size(),
              a.vertices.size(), a.boxes, a.reach_slabs);
}

TEST(RestrictedCell, AVertexOnASplitPlaneIsDecided) {
  // A hexagonal lattice on the Clifford torus, 26 points in each of 30 rows (every other row
  // shifted by half a step). Each row has identical (x3, x4), and at point 0 = (1, 0, 1, 0) the
  // chart coordinate u1 = 2 x2 of the vertices beside the row is -sin(pi / 26) * 2 = -(the row's
  // chord) = -r / 2 for the radius r = 2 x the nearest distance: exactly a split plane at every
  // depth. Epsilon inflation proves the vertex in a box around the two that share the plane;
  // each of them is then decided (it holds that vertex or none), and no box is left undecided.
  std::vector<std::vector<double>> pts;
  for (int j = 0; j < 30; ++j)
    for (int i = 0; i < 26; ++i) {
      const double a = 2 * M_PI * (i + 0.5 * (j % 2)) / 26, b = 2 * M_PI * j / 30;
      pts.push_back({std::cos(a), std::sin(a), std::cos(b), std::sin(b)});
    }
  const io::PointSet P = make_points(4, pts);
  const exact::ImplicitSystem F = exact::ImplicitSystem::parse({"x1^2 + x2^2 - 1", "x3^2 + x4^2 - 1"}, 4);
  const detail::PointGrid grid(P, 2);
  double nearest = INFINITY;
  for (int q = 1; q < static_cast<int>(P.size()); ++q) {
    double d = 0;
    for (int k = 0; k < 4; ++k) d += std::pow(P.point(q)[k] - P.point(0)[k], 2);
    nearest = std::min(nearest, std::sqrt(d));
  }
  RestrictedCellOptions opt;
  opt.graph_radius = 2 * nearest;
  for (int p : {0, 1, 26, 27}) {
    const RestrictedCellReport R = analyse_restricted_cell(F, P, grid, p, opt);
    EXPECT_TRUE(R.complete) << p << ": " << R.reason;
    EXPECT_EQ(R.krawczyk_failures, 0) << p;
    EXPECT_EQ(R.vertices.size(), 6u) << p;  // a hexagonal cell
  }
}

// An impure Del_RM(P), on S^2 and on S^3. P: the north pole p of the unit sphere, q = 0.9 p
// inside it (off M: Del_RM takes any points), and a sample of the sphere below polar angle 1. The
// points of the sphere nearer to p than to q are the cap x_d > 0.95, and every other point of P
// is farther from it (the sample starts 0.68 rad below the cap's rim, q 0.32 from it): the cell
// of p is that cap, bounded by the sphere x_d = 0.95 alone, a restricted Voronoi face of {p, q}
// (a circle, a 2-sphere) with no vertex. So {p, q} is in Del_RM and in no m-simplex of it. The
// engine proves it by a FACE POINT, at p and at q (whose cell is the ring between the cap and the
// sample), and finds no vertex at p.
TEST(RestrictedCell, AFacePointProvesAnEdgeInNoMSimplex) {
  for (int d : {3, 4}) {
    const io::PointSet S = d == 3 ? fibonacci_sphere(300) : spread_sphere(4, 1500, 0.3, 5);
    std::vector<std::vector<double>> pts(2, std::vector<double>(d, 0.0));
    pts[0][d - 1] = 1, pts[1][d - 1] = 0.9;
    for (std::size_t i = 0; i < S.size(); ++i)
      if (S.point(i)[d - 1] <= std::cos(1.0)) pts.emplace_back(S.point(i).begin(), S.point(i).end());
    const io::PointSet P = make_points(d, pts);
    const exact::ImplicitSystem F =
        exact::ImplicitSystem::parse({d == 3 ? "x1^2 + x2^2 + x3^2 - 1" : "x1^2 + x2^2 + x3^2 + x4^2 - 1"}, d);
    const detail::PointGrid grid(P, d - 1);
    RestrictedCellOptions opt;
    opt.graph_radius = 0.8;
    // (A cell alone has no covering target: p's, with no vertex, would be refined for its covering
    // bound down to the default width everywhere, 128^m boxes.)
    opt.covering_width = 1.0 / 16;
    for (int p : {0, 1}) {
      const RestrictedCellReport R = analyse_restricted_cell(F, P, grid, p, opt);
      EXPECT_TRUE(R.complete) << d << " " << p << ": " << R.reason;
      EXPECT_TRUE(R.unresolved_faces.empty()) << d << " " << p;
      ASSERT_EQ(R.face_points.size(), 1u) << d << " " << p;
      const RestrictedVoronoiVertex& f = R.face_points[0];
      EXPECT_EQ(f.simplex, (Simplex{0, 1}));
      // Re-check: the enclosure meets the plane x_d = 0.95, its centre is on the sphere, and
      // nearer to p and q than to every other point (long double is enough at these margins).
      EXPECT_TRUE(f.x[d - 1].lo <= 0.95 && 0.95 <= f.x[d - 1].hi) << f.x[d - 1].lo << " " << f.x[d - 1].hi;
      std::vector<long double> c(d);
      for (int k = 0; k < d; ++k) c[k] = (static_cast<long double>(f.x[k].lo) + f.x[k].hi) / 2;
      auto dist2 = [&](std::size_t q) {
        long double s = 0;
        for (int k = 0; k < d; ++k) s += (c[k] - P.point(q)[k]) * (c[k] - P.point(q)[k]);
        return s;
      };
      long double n2 = 0;
      for (int k = 0; k < d; ++k) n2 += c[k] * c[k];
      EXPECT_NEAR(static_cast<double>(n2), 1.0, 1e-9);
      for (std::size_t q = 2; q < P.size(); ++q) EXPECT_GT(dist2(q), dist2(0)) << d << " " << q;
      EXPECT_EQ(R.vertices.empty(), p == 0);  // none at p; at q, the ring's outer rim
      for (const auto& v : R.vertices)
        EXPECT_FALSE(std::includes(v.simplex.begin(), v.simplex.end(), f.simplex.begin(), f.simplex.end()));
      std::printf("[ face point ] S^%d, cell of %d: %zu vertices, %ld boxes\n", d - 1, p, R.vertices.size(), R.boxes);
    }
  }
}

TEST(RestrictedCell, CubeOnItsSphereIsNeverDecided) {
  // Exactly degenerate: the centre of each face of the cube is equidistant from its 4 vertices.
  std::vector<std::vector<double>> pts;
  for (int i = 0; i < 8; ++i) pts.push_back({i & 1 ? 1.0 : -1.0, i & 2 ? 1.0 : -1.0, i & 4 ? 1.0 : -1.0});
  const io::PointSet P = make_points(3, pts);
  const CellRuns cells_run = analyse_all("x1^2 + x2^2 + x3^2 - 3", P, 2.2);
  for (const auto& R : cells_run.cells) {
    EXPECT_FALSE(R.complete) << R.point;
    // Its restricted Voronoi edges have no certified vertex, but are proven by face points: the
    // 3 cube edges at the point (its coordinates differ from p's in one place).
    ASSERT_EQ(R.face_points.size(), 3u) << R.point;
    for (const auto& f : R.face_points) {
      ASSERT_EQ(f.simplex.size(), 2u);
      EXPECT_EQ(__builtin_popcount(f.simplex[0] ^ f.simplex[1]), 1) << f.simplex[0] << " " << f.simplex[1];
    }
    EXPECT_TRUE(R.vertices.empty()) << R.point;  // no triangle is ever claimed
    ASSERT_FALSE(R.undecided.empty()) << R.point;
    int ties = 0;
    for (const auto& u : R.undecided) {
      if (u.reason == "box budget exhausted") continue;  // the purity refinement along the edges
      ++ties;
      EXPECT_EQ(u.candidates.size(), 4u);
      // Located at a face centre (+-sqrt 3 on one axis).
      double big = 0;
      for (double x : u.location) big = std::max(big, std::abs(x));
      EXPECT_NEAR(big, std::sqrt(3.0), 1e-2);
    }
    EXPECT_GT(ties, 0) << R.point;  // the 4-fold ties at the face centres are found, never resolved
  }
}

}  // namespace
}  // namespace delcert::certify::test
