// Known answers for the independent restricted Delaunay reference (restricted_delaunay_reference.hpp):
// exact root counting, the sphere theorem, manifold sanity on an ellipsoid and a torus, and the
// degenerate inputs it must refuse to decide.
#include "restricted_delaunay_reference.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <map>
#include <numeric>
#include <random>
#include <set>

#include "io/spec.hpp"

namespace delcert::reference {
namespace {

mpq_class q(long n, long d = 1) { return mpq_class(n, d); }

// The root f of `a` lies in the analysis' isolating interval, and that interval holds exactly one.
void expect_isolating(const UPoly& f, const RootAnalysis& a) {
  ASSERT_TRUE(a.isolating.has_value());
  const auto& [t0, t1] = *a.isolating;
  if (t0 == t1) {
    EXPECT_EQ(f.sign_at(t0), 0);
  } else {
    EXPECT_LT(t0, t1);
    EXPECT_EQ(count_distinct_roots(f, t0, t1), 1) << f.to_string() << " on [" << t0 << ", " << t1 << "]";
  }
}

// ------------------------------------------------------------------------------------- Sturm

TEST(RestrictedDelaunayReference, SturmCountsDistinctRootsOnTheUnitInterval) {
  const UPoly f = UPoly::from_roots({q(1, 3), q(2, 3), q(2)});
  RootAnalysis a = analyse_roots(f, 0, q(1));
  EXPECT_EQ(a.distinct_roots, 2);
  EXPECT_FALSE(a.repeated_root || a.root_at_lo || a.root_at_hi || a.identically_zero);
  expect_isolating(f, a);
  // Two roots very close together are still told apart.
  const UPoly g = UPoly::from_roots({q(1, 1000), q(1001, 1000000)});
  a = analyse_roots(g, 0, q(1));
  EXPECT_EQ(a.distinct_roots, 2);
  expect_isolating(g, a);
  // No real root at all.
  EXPECT_EQ(analyse_roots(UPoly(std::vector<mpq_class>{1, 0, 1}), 0, q(1)).distinct_roots, 0);
  EXPECT_EQ(analyse_roots(UPoly(7), 0, q(1)).distinct_roots, 0);
}

TEST(RestrictedDelaunayReference, SturmReportsRepeatedRootsOnlyInsideTheInterval) {
  // (t - 1/2)^2 (t + 1): one distinct root in [0, 1], a double one (a tangency).
  RootAnalysis a = analyse_roots(UPoly::from_roots({q(1, 2), q(1, 2), q(-1)}), 0, q(1));
  EXPECT_EQ(a.distinct_roots, 1);
  EXPECT_TRUE(a.repeated_root);
  // (t - 3)^2 (t - 1/2): the double root is outside [0, 1].
  a = analyse_roots(UPoly::from_roots({q(3), q(3), q(1, 2)}), 0, q(1));
  EXPECT_EQ(a.distinct_roots, 1);
  EXPECT_FALSE(a.repeated_root);
  // (t - 1/2)^3 (t - 1/4)^2, scaled: two distinct roots, repeated.
  const UPoly h = UPoly::from_roots({q(1, 2), q(1, 2), q(1, 2), q(1, 4), q(1, 4)}) * UPoly(q(-7, 3));
  a = analyse_roots(h, 0, q(1));
  EXPECT_EQ(a.distinct_roots, 2);
  EXPECT_TRUE(a.repeated_root);
  expect_isolating(h, a);
  // A double root exactly at an endpoint.
  a = analyse_roots(UPoly::from_roots({q(1), q(1), q(2)}), 0, q(1));
  EXPECT_EQ(a.distinct_roots, 1);
  EXPECT_TRUE(a.root_at_hi && a.repeated_root);
}

TEST(RestrictedDelaunayReference, SturmSeesRootsAtTheEndpoints) {
  const UPoly f = UPoly::from_roots({q(0), q(1, 2), q(1)});
  const RootAnalysis a = analyse_roots(f, 0, q(1));
  EXPECT_EQ(a.distinct_roots, 3);
  EXPECT_TRUE(a.root_at_lo && a.root_at_hi);
  EXPECT_FALSE(a.repeated_root);
  EXPECT_EQ(count_distinct_roots(f, q(1, 4), q(1)), 2);
  EXPECT_EQ(count_distinct_roots(f, q(1, 4), q(3, 4)), 1);
  EXPECT_EQ(count_distinct_roots(f, q(1, 2), q(1, 2)), 1);  // a single point
  EXPECT_TRUE(analyse_roots(UPoly(), 0, q(1)).identically_zero);
}

TEST(RestrictedDelaunayReference, SturmOnRaysUsesTheSignAtInfinity) {
  // t^2 - 2: one root on [0, inf), irrational; its isolating interval brackets sqrt(2).
  const UPoly f(std::vector<mpq_class>{-2, 0, 1});
  RootAnalysis a = analyse_roots(f, 0, std::nullopt);
  EXPECT_EQ(a.distinct_roots, 1);
  expect_isolating(f, a);
  EXPECT_LE(a.isolating->first * a.isolating->first, 2);
  EXPECT_GE(a.isolating->second * a.isolating->second, 2);
  // Negative leading coefficient, three roots far out.
  const UPoly g = UPoly::from_roots({q(5), q(7), q(900)}) * UPoly(-1);
  a = analyse_roots(g, 0, std::nullopt);
  EXPECT_EQ(a.distinct_roots, 3);
  expect_isolating(g, a);
  EXPECT_EQ(analyse_roots(UPoly::from_roots({q(-1), q(-2)}), 0, std::nullopt).distinct_roots, 0);
  EXPECT_EQ(analyse_roots(UPoly(std::vector<mpq_class>{1, 0, 1}), 0, std::nullopt).distinct_roots, 0);
  a = analyse_roots(UPoly::from_roots({q(0), q(3), q(3)}), 0, std::nullopt);
  EXPECT_EQ(a.distinct_roots, 2);
  EXPECT_TRUE(a.root_at_lo && a.repeated_root);
}

TEST(RestrictedDelaunayReference, SturmAgreesWithKnownRootsOnRandomPolynomials) {
  std::mt19937_64 rng(11);
  for (int trial = 0; trial < 300; ++trial) {
    std::vector<mpq_class> roots;
    std::set<mpq_class> distinct_in, repeated_in;
    const int k = 1 + static_cast<int>(rng() % 6);
    for (int i = 0; i < k; ++i) {
      // Roots in [-1/2, 3/2] on a grid of 1/8, so that endpoints and repetitions occur.
      const mpq_class r(static_cast<long>(rng() % 17) - 4, 8);
      if (r >= 0 && r <= 1 && !distinct_in.insert(r).second) repeated_in.insert(r);
      roots.push_back(r);
    }
    const UPoly f = UPoly::from_roots(roots) * UPoly(std::vector<mpq_class>{1, 0, 1});  // and t^2 + 1
    const RootAnalysis a = analyse_roots(f, 0, q(1));
    EXPECT_EQ(a.distinct_roots, static_cast<int>(distinct_in.size())) << f.to_string();
    EXPECT_EQ(a.repeated_root, !repeated_in.empty()) << f.to_string();
    EXPECT_EQ(a.root_at_lo, distinct_in.count(0) == 1);
    EXPECT_EQ(a.root_at_hi, distinct_in.count(1) == 1);
    if (a.distinct_roots > 0) expect_isolating(f, a);
  }
}

TEST(RestrictedDelaunayReference, RestrictionToALineIsExact) {
  const exact::Polynomial F = exact::Polynomial::parse("x1^2 + x2^2 + x3^2 - 1", 3);
  // (1/2, 0, 0) + t (1, 1/3, 0): (1/2 + t)^2 + t^2/9 - 1.
  const UPoly f = restrict_to_line(F, {q(1, 2), q(0), q(0)}, {q(1), q(1, 3), q(0)});
  EXPECT_EQ(f, UPoly(std::vector<mpq_class>{q(-3, 4), q(1), q(10, 9)}));
}

// ------------------------------------------------------------------------- helpers on complexes

using Edge = std::array<std::size_t, 2>;

struct ManifoldReport {
  bool every_edge_twice = true;
  bool links_are_cycles = true;
  std::size_t vertices_used = 0, edges = 0, components = 0;
  long euler = 0;
};

// Is the triangle set a closed 2-manifold (every edge in exactly two triangles, every vertex link
// one cycle)? Its Euler characteristic and number of connected components.
ManifoldReport manifold_report(const std::vector<Triangle>& tris, std::size_t n) {
  ManifoldReport r;
  std::map<Edge, int> edges;
  std::vector<std::vector<Edge>> link(n);
  std::vector<std::size_t> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  const auto find = [&](std::size_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  for (const auto& t : tris) {
    for (int i = 0; i < 3; ++i) {
      const std::size_t a = t[i], b = t[(i + 1) % 3], c = t[(i + 2) % 3];
      ++edges[{std::min(a, b), std::max(a, b)}];
      link[a].push_back({std::min(b, c), std::max(b, c)});
      parent[find(a)] = find(b);
    }
  }
  for (const auto& [e, count] : edges) r.every_edge_twice = r.every_edge_twice && count == 2;
  std::set<std::size_t> roots;
  for (std::size_t v = 0; v < n; ++v) {
    if (link[v].empty()) continue;
    ++r.vertices_used;
    roots.insert(find(v));
    // The link is one cycle: every link vertex has degree 2 and walking from one edge visits all.
    std::map<std::size_t, std::vector<std::size_t>> adj;
    for (const auto& e : link[v]) {
      adj[e[0]].push_back(e[1]);
      adj[e[1]].push_back(e[0]);
    }
    bool ok = true;
    for (const auto& [w, nb] : adj) ok = ok && nb.size() == 2;
    if (ok) {
      std::size_t prev = link[v][0][0], cur = link[v][0][1], steps = 1;
      while (cur != link[v][0][0] && steps <= link[v].size()) {
        const auto& nb = adj[cur];
        const std::size_t next = nb[0] == prev ? nb[1] : nb[0];
        prev = cur;
        cur = next;
        ++steps;
      }
      ok = steps == link[v].size();
    }
    r.links_are_cycles = r.links_are_cycles && ok;
  }
  r.edges = edges.size();
  r.components = roots.size();
  r.euler = static_cast<long>(r.vertices_used) - static_cast<long>(r.edges) + static_cast<long>(tris.size());
  return r;
}

io::PointSet point_set(const std::vector<std::array<double, 3>>& pts) {
  io::PointSet P;
  P.dimension = 3;
  for (const auto& p : pts) P.push_back(p);
  return P;
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Every triangle's witness is right: at the root's isolating interval (its lower end) the point of
// the Voronoi edge is equidistant from the triangle's vertices and no point of P is closer
// (exactly), and F changes sign or vanishes on the interval (checked by expect_isolating).
void expect_witnesses(const io::PointSet& P, const std::vector<ReferenceTriangle>& tris) {
  std::vector<std::array<mpq_class, 3>> exact(P.size());
  for (std::size_t i = 0; i < P.size(); ++i)
    for (int k = 0; k < 3; ++k) exact[i][k] = P.point(i)[k];
  const auto d2 = [&](const std::array<mpq_class, 3>& x, std::size_t i) {
    mpq_class s = 0;
    for (int k = 0; k < 3; ++k) s += (x[k] - exact[i][k]) * (x[k] - exact[i][k]);
    return s;
  };
  // At most about 40 of them (every k-th): exact distances to every point are slow on big rationals.
  const std::size_t step = std::max<std::size_t>(1, tris.size() / 40);
  for (std::size_t ti = 0; ti < tris.size(); ti += step) {
    const ReferenceTriangle& t = tris[ti];
    expect_isolating(t.edge.restricted, t.edge.roots);
    for (const mpq_class& s : {t.edge.roots.isolating->first, t.edge.roots.isolating->second}) {
      const auto x = t.edge.point(s);
      const mpq_class r = d2(x, t.vertices[0]);
      ASSERT_EQ(d2(x, t.vertices[1]), r);
      ASSERT_EQ(d2(x, t.vertices[2]), r);
      for (std::size_t i = 0; i < P.size(); ++i) ASSERT_GE(d2(x, i), r) << "point " << i << " is closer";
    }
  }
}

// ------------------------------------------------------------------------------------ sphere

// Points EXACTLY on a sphere, as doubles: for a quaternion (a, b, c, d) of norm
// a^2 + b^2 + c^2 + d^2 = N, the rotated first axis (a^2+b^2-c^2-d^2, 2(ad+bc), 2(bd-ac)) has norm N,
// so it is an integer point of the sphere of radius N. (A point of the unit sphere computed in
// doubles is not on it, and the theorem below needs the points on M exactly.) Norm-N quaternions
// are drawn at random (a, b, c uniform, kept when N - a^2 - b^2 - c^2 is a square).
std::vector<std::array<double, 3>> integer_sphere_points(std::size_t n, long N, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  const long s = static_cast<long>(std::sqrt(double(N)));
  std::set<std::array<long, 3>> seen;
  std::vector<std::array<double, 3>> out;
  while (out.size() < n) {
    const auto pick = [&] { return static_cast<long>(rng() % static_cast<std::uint64_t>(2 * s + 1)) - s; };
    const long a = pick(), b = pick(), c = pick(), rest = N - a * a - b * b - c * c;
    if (rest < 0) continue;
    long d = static_cast<long>(std::llround(std::sqrt(double(rest))));
    if (d * d != rest) continue;
    if (rng() & 1) d = -d;
    const std::array<long, 3> p{a * a + b * b - c * c - d * d, 2 * (a * d + b * c), 2 * (b * d - a * c)};
    if (!seen.insert(p).second) continue;
    out.push_back({double(p[0]), double(p[1]), double(p[2])});
  }
  return out;
}

// Theorem (the spherical Delaunay triangulation is the convex hull). Let S be a sphere with centre o
// and P a finite set of points of S, not coplanar, no 4 of them coplanar. For x in S and p in P,
// |x - p|^2 = 2 R^2 - 2 (x - o).(p - o), so the points of P nearest to x are those maximising
// (x - o).p: abc has a point x of S in its Voronoi edge iff the plane through a, b, c supports
// conv(P) with outward normal x - o, i.e. iff abc is a facet of conv(P). So Del_RM(P) on S is the
// set of hull facets; the Voronoi ray of a hull facet meets S exactly once (at o + R n/|n|; the
// other point o - R n/|n| would make the plane support P on both sides), and no Voronoi edge of an
// interior triangle meets S. With every point of P on the hull, there are exactly 2|P| - 4 hull
// facets (Euler), so "every reference triangle has all of P on one side of its plane" and "there
// are 2|P| - 4 of them" together say the reference equals the hull, checked here without CGAL.
TEST(RestrictedDelaunayReference, OnASphereDelRMIsTheConvexHull) {
  using K = CGAL::Exact_predicates_inexact_constructions_kernel;
  const long N = 1000003;
  const exact::Polynomial F = exact::Polynomial::parse("x1^2 + x2^2 + x3^2 - " + std::to_string(N * N), 3);
  for (std::size_t n : {5u, 40u, 400u, 1200u}) {
    const io::PointSet P = point_set(integer_sphere_points(n, N, 1000 + n));
    const auto t0 = std::chrono::steady_clock::now();
    const RestrictedDelaunayReference ref = restricted_delaunay_reference(P, F);
    std::printf("[ reference ] sphere n=%zu: %zu Delaunay triangles (%zu on the hull, %zu segments exact), %zu in Del_RM, %.3f s\n", n,
                ref.delaunay_triangles, ref.hull_triangles, ref.exact_segments, ref.restricted.size(), seconds_since(t0));
    ASSERT_TRUE(ref.decided()) << to_string(ref.degenerate.front().degeneracy);
    EXPECT_EQ(ref.restricted.size(), 2 * n - 4);
    EXPECT_EQ(ref.hull_triangles, 2 * n - 4);
    std::vector<K::Point_3> pts;
    for (std::size_t i = 0; i < n; ++i) pts.emplace_back(P.point(i)[0], P.point(i)[1], P.point(i)[2]);
    for (const auto& t : ref.restricted) {
      EXPECT_TRUE(t.edge.ray);
      EXPECT_EQ(t.edge.roots.distinct_roots, 1);
      std::set<CGAL::Orientation> sides;
      for (std::size_t i = 0; i < n; ++i)
        if (i != t.vertices[0] && i != t.vertices[1] && i != t.vertices[2])
          sides.insert(CGAL::orientation(pts[t.vertices[0]], pts[t.vertices[1]], pts[t.vertices[2]], pts[i]));
      EXPECT_EQ(sides.size(), 1u) << "not a hull facet";
      EXPECT_EQ(sides.count(CGAL::COPLANAR), 0u);
    }
    expect_witnesses(P, ref.restricted);
  }
}

// ----------------------------------------------------------------------- ellipsoid and torus

// A well-spread sample: Fibonacci points of the unit sphere, each moved by a seeded random
// jitter (so that no 4 are cocircular), then mapped onto the ellipsoid (a x, b y, c z).
std::vector<std::array<double, 3>> ellipsoid_points(int n, double a, double b, double c, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> jitter(-0.3, 0.3);
  std::vector<std::array<double, 3>> out;
  const double g = M_PI * (3 - std::sqrt(5.0));
  for (int i = 0; i < n; ++i) {
    const double z = 1 - 2 * (i + 0.5 + jitter(rng)) / n, r = std::sqrt(std::max(0.0, 1 - z * z));
    const double t = g * i + jitter(rng) * 2 / std::sqrt(double(n));
    out.push_back({a * r * std::cos(t), b * r * std::sin(t), c * z});
  }
  return out;
}

TEST(RestrictedDelaunayReference, OnAnEllipsoidDelRMIsAClosedSurfaceOfEulerCharacteristicTwo) {
  const exact::Polynomial F = exact::Polynomial::parse("4/9*x1^2 + x2^2 + 16/9*x3^2 - 1", 3);  // a = 3/2, b = 1, c = 3/4
  for (int n : {300, 1500}) {
    const io::PointSet P = point_set(ellipsoid_points(n, 1.5, 1.0, 0.75, 7 + n));
    const auto t0 = std::chrono::steady_clock::now();
    const RestrictedDelaunayReference ref = restricted_delaunay_reference(P, F);
    std::printf("[ reference ] ellipsoid n=%d: %zu Delaunay triangles (%zu segments exact), %zu in Del_RM, %.3f s\n", n,
                ref.delaunay_triangles, ref.exact_segments, ref.restricted.size(), seconds_since(t0));
    ASSERT_TRUE(ref.decided());
    const ManifoldReport m = manifold_report(ref.triangles(), P.size());
    EXPECT_EQ(m.vertices_used, P.size()) << "a point is a vertex of no Del_RM triangle";
    EXPECT_TRUE(m.every_edge_twice);
    EXPECT_TRUE(m.links_are_cycles);
    EXPECT_EQ(m.components, 1u);
    EXPECT_EQ(m.euler, 2);
    expect_witnesses(P, ref.restricted);
  }
}

// A jittered (major x minor) angle grid on the torus of revolution R = 2, r = 1 (a plain grid is
// degenerate: its points are cocircular in fours).
std::vector<std::array<double, 3>> torus_points(int major, int minor, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> jitter(-0.3, 0.3);
  std::vector<std::array<double, 3>> out;
  for (int i = 0; i < major; ++i)
    for (int j = 0; j < minor; ++j) {
      const double u = 2 * M_PI * (i + jitter(rng)) / major, v = 2 * M_PI * (j + jitter(rng)) / minor;
      out.push_back({(2 + std::cos(v)) * std::cos(u), (2 + std::cos(v)) * std::sin(u), std::sin(v)});
    }
  return out;
}

TEST(RestrictedDelaunayReference, OnATorusDelRMIsAClosedSurfaceOfEulerCharacteristicZero) {
  const io::ManifoldSpec spec = io::read_spec("builtin:torus-of-revolution");
  const exact::Polynomial& F = surface_equation(spec);
  for (auto [major, minor] : {std::pair{40, 16}, std::pair{48, 18}}) {
    const io::PointSet P = point_set(torus_points(major, minor, 3));
    const auto t0 = std::chrono::steady_clock::now();
    const RestrictedDelaunayReference ref = restricted_delaunay_reference(P, F);
    std::printf("[ reference ] torus n=%zu: %zu Delaunay triangles (%zu segments exact), %zu in Del_RM, %.3f s\n", P.size(),
                ref.delaunay_triangles, ref.exact_segments, ref.restricted.size(), seconds_since(t0));
    ASSERT_TRUE(ref.decided());
    const ManifoldReport m = manifold_report(ref.triangles(), P.size());
    EXPECT_EQ(m.vertices_used, P.size());
    EXPECT_TRUE(m.every_edge_twice);
    EXPECT_TRUE(m.links_are_cycles);
    EXPECT_EQ(m.components, 1u);
    EXPECT_EQ(m.euler, 0);
    expect_witnesses(P, ref.restricted);
  }
}

// ------------------------------------------------------------------------------- degeneracies

// The 8 vertices of a cube on the sphere of radius sqrt(3): all 8 are cospherical, and each square
// face is 4 cocircular points whose common Voronoi ray (from the centre through the face centre)
// meets the sphere: which diagonal CGAL picks is arbitrary, so no triangle may be decided.
TEST(RestrictedDelaunayReference, TheCubeOnItsCircumsphereIsDegenerate) {
  std::vector<std::array<double, 3>> pts;
  for (int i = 0; i < 8; ++i) pts.push_back({i & 1 ? 1.0 : -1.0, i & 2 ? 1.0 : -1.0, i & 4 ? 1.0 : -1.0});
  const io::PointSet P = point_set(pts);
  const RestrictedDelaunayReference ref =
      restricted_delaunay_reference(P, exact::Polynomial::parse("x1^2 + x2^2 + x3^2 - 3", 3));
  EXPECT_FALSE(ref.decided());
  EXPECT_TRUE(ref.restricted.empty());
  EXPECT_EQ(ref.degenerate.size(), 12u);  // two triangles per square face
  for (const auto& t : ref.degenerate) EXPECT_EQ(t.degeneracy, Degeneracy::cocircular);
  EXPECT_GT(ref.cospherical_facets, 0u);
  // The same cube against the plane x3 = 0 through the common circumcentre: every Voronoi edge
  // starts at a Voronoi vertex on M (or is that single point).
  const RestrictedDelaunayReference plane = restricted_delaunay_reference(P, exact::Polynomial::parse("x3", 3));
  EXPECT_TRUE(plane.restricted.empty());
  EXPECT_EQ(plane.degenerate.size(), plane.delaunay_triangles);
  for (const auto& t : plane.degenerate)
    EXPECT_TRUE(t.degeneracy == Degeneracy::voronoi_vertex_on_manifold ||
                t.degeneracy == Degeneracy::edge_in_manifold);
}

// One tetrahedron (0, e1, e2, e3): circumcentre (1/2, 1/2, 1/2); the facet e1 e2 e3 has the ray
// (1/2, 1/2, 1/2) + t (1, 1, 1) (up to a positive factor), the others rays along -e1, -e2, -e3.
TEST(RestrictedDelaunayReference, TangencyVertexOnMAndEdgeInMAreNotDecided) {
  const io::PointSet P = point_set({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}});
  const Triangle far{1, 2, 3};
  // A sphere of radius sqrt(2) centred at (3, 1, 2): at distance sqrt(2) from the line through
  // (2, 2, 2) in direction (1, 1, 1), so tangent to the first ray there; the other rays miss it.
  RestrictedDelaunayReference ref =
      restricted_delaunay_reference(P, exact::Polynomial::parse("(x1-3)^2 + (x2-1)^2 + (x3-2)^2 - 2", 3));
  EXPECT_TRUE(ref.restricted.empty());
  ASSERT_EQ(ref.degenerate.size(), 1u);
  EXPECT_EQ(ref.degenerate[0].vertices, far);
  EXPECT_EQ(ref.degenerate[0].degeneracy, Degeneracy::tangency);
  // The same sphere with radius^2 = 2 - 1/100 misses the ray; with 2 + 1/100 it cuts it twice.
  EXPECT_TRUE(restricted_delaunay_reference(P, exact::Polynomial::parse("(x1-3)^2 + (x2-1)^2 + (x3-2)^2 - 199/100", 3))
                  .restricted.empty());
  ref = restricted_delaunay_reference(P, exact::Polynomial::parse("(x1-3)^2 + (x2-1)^2 + (x3-2)^2 - 201/100", 3));
  ASSERT_TRUE(ref.decided());
  ASSERT_EQ(ref.restricted.size(), 1u);
  EXPECT_EQ(ref.restricted[0].vertices, far);
  EXPECT_EQ(ref.restricted[0].edge.roots.distinct_roots, 2);
  expect_witnesses(P, ref.restricted);
  // A plane through the circumcentre: every ray starts on M.
  ref = restricted_delaunay_reference(P, exact::Polynomial::parse("x1 + x2 + x3 - 3/2", 3));
  EXPECT_TRUE(ref.restricted.empty());
  ASSERT_EQ(ref.degenerate.size(), 4u);
  for (const auto& t : ref.degenerate) EXPECT_EQ(t.degeneracy, Degeneracy::voronoi_vertex_on_manifold);
  // A plane holding the ray of e1 e2 e3: that edge lies in M.
  ref = restricted_delaunay_reference(P, exact::Polynomial::parse("x1 + x2 - 2*x3", 3));
  ASSERT_EQ(ref.degenerate.size(), 4u);
  for (const auto& t : ref.degenerate)
    EXPECT_EQ(t.degeneracy, t.vertices == far ? Degeneracy::edge_in_manifold : Degeneracy::voronoi_vertex_on_manifold);
}

TEST(RestrictedDelaunayReference, RefusesInputItCannotTriangulate) {
  const exact::Polynomial F = exact::Polynomial::parse("x1^2 + x2^2 + x3^2 - 1", 3);
  EXPECT_THROW(restricted_delaunay_reference(point_set({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}}), F),
               std::invalid_argument);
  EXPECT_THROW(restricted_delaunay_reference(point_set({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 0}}), F),
               std::invalid_argument);
  EXPECT_THROW(surface_equation(io::read_spec("builtin:clifford-torus-2")), std::invalid_argument);
}

}  // namespace
}  // namespace delcert::reference
