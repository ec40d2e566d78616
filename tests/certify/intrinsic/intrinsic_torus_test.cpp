// Del_M on flat tori (certify/intrinsic_torus.cpp, issue 12) against an independent reference:
// CGAL's periodic Delaunay triangulations (Periodic_2_Delaunay_triangulation_2 for T^2,
// Periodic_3_Delaunay_triangulation_3 for T^3) of the angle coordinates, in the tests only
// (outside the trust boundary). Radii 1, so the domain is [0, 2 pi)^m.
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Periodic_2_Delaunay_triangulation_2.h>
#include <CGAL/Periodic_2_Delaunay_triangulation_traits_2.h>
#include <CGAL/Periodic_2_triangulation_face_base_2.h>
#include <CGAL/Periodic_2_triangulation_vertex_base_2.h>
#include <CGAL/Periodic_3_Delaunay_triangulation_3.h>
#include <CGAL/Periodic_3_Delaunay_triangulation_traits_3.h>
#include <CGAL/Periodic_3_triangulation_ds_cell_base_3.h>
#include <CGAL/Periodic_3_triangulation_ds_vertex_base_3.h>
#include <CGAL/Triangulation_data_structure_2.h>
#include <CGAL/Triangulation_data_structure_3.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <set>
#include <vector>

#include "certify/detail/grid.hpp"
#include "certify/intrinsic/engines.hpp"
#include "certify/intrinsic/intrinsic.hpp"
#include "io/spec.hpp"
#include "tests/certify/support.hpp"

namespace delcert::certify {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Simplices = std::set<std::vector<int>>;

constexpr double kTwoPi = 2 * M_PI;

// Angle of (x, y) in [0, 2 pi) as a double.
double angle(double x, double y) {
  double a = std::atan2(y, x);
  if (a < 0) a += kTwoPi;
  if (a >= kTwoPi) a -= kTwoPi;
  return a;
}

std::vector<std::vector<double>> angles_of(const io::PointSet& P) {
  std::vector<std::vector<double>> A;
  for (std::size_t p = 0; p < P.size(); ++p) {
    auto x = P.point(p);
    std::vector<double> a;
    for (int i = 0; 2 * i < P.dimension; ++i) a.push_back(angle(x[2 * i], x[2 * i + 1]));
    A.push_back(a);
  }
  return A;
}

io::PointSet random_torus(int m, int n, std::uint64_t seed) {
  test::Rng rng(seed);
  io::PointSet P;
  P.dimension = 2 * m;
  for (int k = 0; k < n; ++k) {
    std::vector<double> x;
    for (int i = 0; i < m; ++i) {
      const double a = kTwoPi * rng.uniform();
      x.push_back(std::cos(a));
      x.push_back(std::sin(a));
    }
    P.push_back(x);
  }
  return P;
}

// Reference Del_M of T^2 (radii 1): CGAL's periodic Delaunay triangulation of the angles.
Simplices reference_t2(const io::PointSet& P) {
  using Gt = CGAL::Periodic_2_Delaunay_triangulation_traits_2<K>;
  using Vbb = CGAL::Periodic_2_triangulation_vertex_base_2<Gt>;
  using Vb = CGAL::Triangulation_vertex_base_with_info_2<int, Gt, Vbb>;
  using Fb = CGAL::Periodic_2_triangulation_face_base_2<Gt>;
  using Tds = CGAL::Triangulation_data_structure_2<Vb, Fb>;
  using DT = CGAL::Periodic_2_Delaunay_triangulation_2<Gt, Tds>;
  DT T(Gt::Iso_rectangle_2(0, 0, kTwoPi, kTwoPi));
  const auto A = angles_of(P);
  for (std::size_t p = 0; p < A.size(); ++p) T.insert(Gt::Point_2(A[p][0], A[p][1]))->info() = static_cast<int>(p);
  EXPECT_TRUE(T.is_1_cover()) << "the sample is too sparse for the reference";
  Simplices S;
  for (auto f = T.faces_begin(); f != T.faces_end(); ++f) {
    std::vector<int> s{f->vertex(0)->info(), f->vertex(1)->info(), f->vertex(2)->info()};
    std::sort(s.begin(), s.end());
    S.insert(s);
  }
  EXPECT_EQ(S.size(), 2 * P.size());  // Euler characteristic 0: F = 2V
  return S;
}

// Reference Del_M of T^3 (radii 1): CGAL's periodic 3D Delaunay triangulation of the angles.
Simplices reference_t3(const io::PointSet& P) {
  using Gt = CGAL::Periodic_3_Delaunay_triangulation_traits_3<K>;
  using VbDS = CGAL::Periodic_3_triangulation_ds_vertex_base_3<>;
  using Vbb = CGAL::Triangulation_vertex_base_3<Gt, VbDS>;
  using Vb = CGAL::Triangulation_vertex_base_with_info_3<int, Gt, Vbb>;
  using CbDS = CGAL::Periodic_3_triangulation_ds_cell_base_3<>;
  using Cb = CGAL::Triangulation_cell_base_3<Gt, CbDS>;
  using Tds = CGAL::Triangulation_data_structure_3<Vb, Cb>;
  using DT = CGAL::Periodic_3_Delaunay_triangulation_3<Gt, Tds>;
  DT T(Gt::Iso_cuboid_3(0, 0, 0, kTwoPi, kTwoPi, kTwoPi));
  const auto A = angles_of(P);
  for (std::size_t p = 0; p < A.size(); ++p)
    T.insert(Gt::Point_3(A[p][0], A[p][1], A[p][2]))->info() = static_cast<int>(p);
  EXPECT_TRUE(T.is_1_cover()) << "the sample is too sparse for the reference";
  Simplices S;
  for (auto c = T.cells_begin(); c != T.cells_end(); ++c) {
    std::vector<int> s{c->vertex(0)->info(), c->vertex(1)->info(), c->vertex(2)->info(), c->vertex(3)->info()};
    std::sort(s.begin(), s.end());
    S.insert(s);
  }
  return S;
}

// Squared flat-torus distance between angle vectors (radii 1), in double (test only).
double torus_d2(const std::vector<double>& a, const std::vector<double>& b, const std::vector<double>& radii) {
  double d2 = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    double d = std::fabs(a[i] - b[i]);
    d = radii[i] * std::min(d, kTwoPi - d);
    d2 += d * d;
  }
  return d2;
}

// Candidates independent of the reference: every point with every m-subset of its k nearest
// neighbours (flat torus distance, brute force).
std::vector<std::vector<int>> neighbour_candidates(const io::PointSet& P, int m, int k, std::vector<double> radii = {}) {
  radii.resize(m, 1.0);
  const auto A = angles_of(P);
  const int n = static_cast<int>(A.size());
  std::set<std::vector<int>> C;
  for (int p = 0; p < n; ++p) {
    std::vector<std::pair<double, int>> d;
    for (int q = 0; q < n; ++q)
      if (q != p) d.push_back({torus_d2(A[p], A[q], radii), q});
    std::partial_sort(d.begin(), d.begin() + k, d.end());
    std::vector<int> pick(k, 0);
    std::fill(pick.begin(), pick.begin() + m, 1);
    std::sort(pick.begin(), pick.end());
    do {
      std::vector<int> s{p};
      for (int j = 0; j < k; ++j)
        if (pick[j]) s.push_back(d[j].second);
      std::sort(s.begin(), s.end());
      C.insert(s);
    } while (std::next_permutation(pick.begin(), pick.end()));
  }
  return {C.begin(), C.end()};
}

io::ShapeSpec unit_circles(int m) {
  io::ShapeSpec g;
  g.kind = io::ShapeSpec::Kind::product_of_circles;
  g.radii.assign(m, mpq_class(1));
  return g;
}

IntrinsicDelaunay run(const io::PointSet& P, int m, const std::vector<std::vector<int>>& candidates, int threads = 2) {
  detail::PointGrid grid(P, m);
  return detail::intrinsic_delaunay_flat_torus(unit_circles(m), P, grid, candidates, threads);
}

Simplices certified_set(const IntrinsicDelaunay& D) {
  Simplices S;
  for (const auto& s : D.simplices) S.insert(s.simplex);
  return S;
}

// The empty-ball test of the shortest lifts, in doubles (the test's own, independent of the
// engine): is q strictly inside the circumcircle of triangle s (T^2, radii 1)?
bool inside_circumcircle_t2(const std::vector<std::vector<double>>& A, const std::vector<int>& s, int q,
                            std::array<double, 2> radii = {1, 1}) {
  auto lift = [&](int p) {
    std::array<double, 2> v;
    for (int i = 0; i < 2; ++i) {
      double d = A[p][i] - A[s[0]][i];
      d -= kTwoPi * std::nearbyint(d / kTwoPi);
      v[i] = radii[i] * d;
    }
    return v;
  };
  auto b = lift(s[1]), c = lift(s[2]), x = lift(q);
  // circumcentre of 0, b, c
  const double D = 2 * (b[0] * c[1] - b[1] * c[0]);
  const double b2 = b[0] * b[0] + b[1] * b[1], c2 = c[0] * c[0] + c[1] * c[1];
  const double ux = (c[1] * b2 - b[1] * c2) / D, uy = (b[0] * c2 - c[0] * b2) / D;
  const double R2 = ux * ux + uy * uy;
  double best = 1e300;
  for (int i = -1; i <= 1; ++i)
    for (int j = -1; j <= 1; ++j) {
      const double dx = x[0] + i * kTwoPi * radii[0] - ux, dy = x[1] + j * kTwoPi * radii[1] - uy;
      best = std::min(best, dx * dx + dy * dy);
    }
  return best < R2 * (1 - 1e-9);
}

class TorusKnownAnswer : public ::testing::TestWithParam<std::pair<int, std::uint64_t>> {};

// (1) The certified set equals the periodic Delaunay triangulation, complete, on random samples;
// candidates are the reference's triangles and every near-neighbour triangle (most of them not
// Delaunay: each is rejected with a witness that the test re-checks).
TEST_P(TorusKnownAnswer, T2AgreesWithPeriodicDelaunay) {
  const auto [n, seed] = GetParam();
  const io::PointSet P = random_torus(2, n, seed);
  const Simplices ref = reference_t2(P);
  auto candidates = neighbour_candidates(P, 2, 6);
  candidates.insert(candidates.end(), ref.begin(), ref.end());
  const IntrinsicDelaunay D = run(P, 2, candidates);
  ASSERT_TRUE(D.computed) << D.reason;
  EXPECT_EQ(D.metric, "product_of_circles");
  EXPECT_TRUE(D.complete) << D.reason;
  EXPECT_EQ(D.reason, "");
  EXPECT_EQ(certified_set(D), ref);
  EXPECT_TRUE(D.undecided.empty()) << D.undecided.front().reason;
  const auto A = angles_of(P);
  std::set<std::vector<int>> all(candidates.begin(), candidates.end());
  EXPECT_EQ(D.simplices.size() + D.rejected.size() + D.undecided.size(), all.size());
  EXPECT_GT(D.rejected.size(), 0u);
  for (const auto& r : D.rejected) {
    EXPECT_EQ(r.witness.at("kind"), "not_intrinsic");
    EXPECT_FALSE(ref.count(r.simplex));
    if (r.witness.contains("point"))
      EXPECT_TRUE(inside_circumcircle_t2(A, r.simplex, r.witness.at("point").get<int>()));
    else
      EXPECT_EQ(r.witness.at("by"), "completeness");
  }
  for (const auto& s : D.simplices) {
    EXPECT_EQ(s.witness.at("kind"), "intrinsic_voronoi_vertex");
    EXPECT_EQ(s.witness.at("centre_angles").size(), 2u);
    EXPECT_GT(std::stod(s.witness.at("margin").get<std::string>()), 0);
    EXPECT_LT(std::stod(s.witness.at("radius")[1].get<std::string>()), M_PI / 2);
  }
}

INSTANTIATE_TEST_SUITE_P(Samples, TorusKnownAnswer,
                         ::testing::Values(std::pair<int, std::uint64_t>{200, 12}, std::pair<int, std::uint64_t>{400, 7},
                                           std::pair<int, std::uint64_t>{400, 2026}));

// Deterministic: the result does not depend on the number of threads.
TEST(IntrinsicTorus, ThreadsDoNotChangeTheResult) {
  const io::PointSet P = random_torus(2, 150, 3);
  const auto candidates = neighbour_candidates(P, 2, 5);
  const IntrinsicDelaunay a = run(P, 2, candidates, 1), b = run(P, 2, candidates, 3);
  ASSERT_EQ(a.simplices.size(), b.simplices.size());
  for (std::size_t k = 0; k < a.simplices.size(); ++k) {
    EXPECT_EQ(a.simplices[k].simplex, b.simplices[k].simplex);
    EXPECT_EQ(a.simplices[k].witness, b.simplices[k].witness);
  }
  EXPECT_EQ(a.rejected.size(), b.rejected.size());
  EXPECT_EQ(a.undecided.size(), b.undecided.size());
  EXPECT_EQ(a.complete, b.complete);
}

// (2) Mutants: one Delaunay triangle missing -> not complete; a non-Delaunay triangle is rejected
// (with a witness inside its circumcircle) when the rest is complete, and only UNDECIDED when not.
TEST(IntrinsicTorus, MutantsAreNeverCertifiedComplete) {
  const io::PointSet P = random_torus(2, 200, 99);
  const Simplices ref = reference_t2(P);
  const auto A = angles_of(P);
  std::vector<std::vector<int>> missing(ref.begin(), ref.end());
  const std::vector<int> dropped = missing[37];
  missing.erase(missing.begin() + 37);
  // A missing cell is found again by gift wrapping (proposed across its open edges, decided).
  const IntrinsicDelaunay D1 = run(P, 2, missing);
  ASSERT_TRUE(D1.computed);
  EXPECT_TRUE(D1.complete) << D1.reason;
  EXPECT_EQ(certified_set(D1), ref);

  // A non-Delaunay triangle: a flip of a Delaunay edge (the two apexes and one edge vertex).
  std::vector<int> bad;
  for (const auto& s : ref) {
    for (const auto& t : ref) {
      std::vector<int> common;
      std::set_intersection(s.begin(), s.end(), t.begin(), t.end(), std::back_inserter(common));
      if (common.size() != 2 || s == t) continue;
      std::vector<int> cand;
      std::set_union(s.begin(), s.end(), t.begin(), t.end(), std::back_inserter(cand));
      cand.erase(std::find(cand.begin(), cand.end(), common[0]));
      bad = cand;
      break;
    }
    if (!bad.empty()) break;
  }
  ASSERT_EQ(bad.size(), 3u);
  ASSERT_FALSE(ref.count(bad));
  std::vector<std::vector<int>> with_bad(ref.begin(), ref.end());
  with_bad.push_back(bad);
  const IntrinsicDelaunay D2 = run(P, 2, with_bad);
  EXPECT_TRUE(D2.complete) << D2.reason;
  ASSERT_EQ(D2.rejected.size(), 1u);
  EXPECT_EQ(D2.rejected[0].simplex, bad);
  const int q = D2.rejected[0].witness.at("point").get<int>();
  EXPECT_TRUE(inside_circumcircle_t2(A, bad, q));
  EXPECT_EQ(certified_set(D2), ref);

  missing.push_back(bad);  // the dropped cell is recovered, so the rejection stands
  const IntrinsicDelaunay D3 = run(P, 2, missing);
  EXPECT_TRUE(D3.complete) << D3.reason;
  ASSERT_EQ(D3.rejected.size(), 1u);
  EXPECT_EQ(D3.rejected[0].simplex, bad);
  EXPECT_EQ(certified_set(D3), ref);
  EXPECT_TRUE(certified_set(D3).count(dropped));

  // Duplicate candidates are decided once.
  std::vector<std::vector<int>> twice(ref.begin(), ref.end());
  twice.insert(twice.end(), ref.begin(), ref.end());
  const IntrinsicDelaunay D4 = run(P, 2, twice);
  EXPECT_TRUE(D4.complete);
  EXPECT_EQ(D4.simplices.size(), ref.size());
}

// Every triangle of a square grid in angle space (both diagonals of each square).
std::vector<std::vector<int>> grid_candidates(int k) {
  std::set<std::vector<int>> C;
  auto id = [k](int i, int j) { return ((i + k) % k) * k + (j + k) % k; };
  for (int i = 0; i < k; ++i)
    for (int j = 0; j < k; ++j) {
      const int a = id(i, j), b = id(i + 1, j), c = id(i, j + 1), d = id(i + 1, j + 1);
      for (std::vector<int> s : {std::vector<int>{a, b, c}, {a, b, d}, {a, c, d}, {b, c, d}}) {
        std::sort(s.begin(), s.end());
        C.insert(s);
      }
    }
  return {C.begin(), C.end()};
}

// (3) Exact ties: a square grid in angle space from exactly representable points. Angles k pi / 2
// (coordinates 0, +-1; circumradius pi / (2 sqrt 2) < pi / 2) and k pi / 4 (the directions (+-1, 0),
// (+-1, +-1), (0, +-1), off M but exactly cocircular after projection): every candidate UNDECIDED
// "not protected" (a tie), never certified, never complete. The angle pi (x = -1, y = 0) is on
// atan2's branch cut: it must stay a tight enclosure.
TEST(IntrinsicTorus, ExactTiesAreUndecided) {
  for (int k : {4, 8}) {
    const std::vector<std::array<double, 2>> dirs =
        k == 4 ? std::vector<std::array<double, 2>>{{1, 0}, {0, 1}, {-1, 0}, {0, -1}}
               : std::vector<std::array<double, 2>>{{1, 0}, {1, 1}, {0, 1}, {-1, 1}, {-1, 0}, {-1, -1}, {0, -1}, {1, -1}};
    io::PointSet P;
    P.dimension = 4;
    for (int i = 0; i < k; ++i)
      for (int j = 0; j < k; ++j) P.push_back(std::vector<double>{dirs[i][0], dirs[i][1], dirs[j][0], dirs[j][1]});
    const auto candidates = grid_candidates(k);
    const IntrinsicDelaunay D = run(P, 2, candidates);
    ASSERT_TRUE(D.computed) << D.reason;
    EXPECT_TRUE(D.simplices.empty()) << "k = " << k;
    EXPECT_TRUE(D.rejected.empty()) << "k = " << k;
    EXPECT_FALSE(D.complete);
    EXPECT_EQ(D.undecided.size(), candidates.size());
    for (const auto& u : D.undecided)
      EXPECT_NE(u.reason.find("not protected"), std::string::npos) << u.reason;
    if (k != 8) continue;
    // Incomplete (nothing certified, so nothing to wrap around): a triangle with a grid point
    // strictly inside its circumcircle is only UNDECIDED, with the witness in the reason.
    auto with_bad = candidates;
    const std::vector<int> bad{0, 2, 16};  // (0, 0), (0, 2), (2, 0): (1, 0) at distance 1 < sqrt 2
    with_bad.push_back(bad);
    const IntrinsicDelaunay E = run(P, 2, with_bad);
    EXPECT_FALSE(E.complete);
    EXPECT_TRUE(E.rejected.empty());
    EXPECT_TRUE(E.simplices.empty());
    const auto it = std::find_if(E.undecided.begin(), E.undecided.end(), [&](const auto& u) { return u.simplex == bad; });
    ASSERT_NE(it, E.undecided.end());
    EXPECT_NE(it->reason.find("strictly inside"), std::string::npos) << it->reason;
  }
}

// A point with a zero planar component has no angle: not computed, with the reason.
TEST(IntrinsicTorus, UndefinedAngleIsNotComputed) {
  io::PointSet P = random_torus(2, 30, 5);
  P.push_back(std::vector<double>{0.5, 0.5, 0, 0});
  const IntrinsicDelaunay D = run(P, 2, {{0, 1, 2}});
  EXPECT_FALSE(D.computed);
  EXPECT_EQ(D.metric, "product_of_circles");
  EXPECT_NE(D.reason.find("point 30"), std::string::npos) << D.reason;
}

// Through the dispatcher with the built-in spec: points near M (radially scaled) give the same
// Del_M (the convention projects them).
TEST(IntrinsicTorus, BuiltinSpecAndPointsNearM) {
  const io::ManifoldSpec spec = io::read_spec("builtin:clifford-torus-2");
  io::PointSet P = random_torus(2, 200, 12);
  const Simplices ref = reference_t2(P);
  test::Rng rng(4);
  for (std::size_t p = 0; p < P.size(); ++p)
    for (int i = 0; i < 2; ++i) {
      const double s = 1 + 1e-3 * (rng.uniform() - 0.5);
      P.coordinates[4 * p + 2 * i] *= s;
      P.coordinates[4 * p + 2 * i + 1] *= s;
    }
  detail::PointGrid grid(P, 2);
  const IntrinsicDelaunay D = compute_intrinsic_delaunay(spec, P, grid, {ref.begin(), ref.end()}, 2);
  ASSERT_TRUE(D.computed) << D.reason;
  EXPECT_TRUE(D.complete) << D.reason;
  EXPECT_EQ(certified_set(D), ref);
}

// The same metrics written as products (issue 12's format): circles on (x1, x2), (x3, x4) give
// the flat torus's Del_M (this engine); the circles listed in the other order are computed by the
// geodesic Voronoi cells (certify/intrinsic_product.cpp, another argument entirely) and agree with
// the periodic reference; four points of S^2 x S^1 are too few for its charts (not complete).
TEST(IntrinsicTorus, ProductMetricsAsFactors) {
  const io::PointSet P = random_torus(2, 200, 12);
  const Simplices ref = reference_t2(P);
  std::string text = io::builtin_spec_text("clifford-torus-2");
  const std::string shorthand = R"("metric": {"type": "product_of_circles", "radii": ["1", "1"]})";
  auto with_metric = [&](const std::string& metric) {
    std::string t = text;
    t.replace(t.find(shorthand), shorthand.size(), "\"metric\": " + metric);
    return io::parse_spec(t, "product.json");
  };
  detail::PointGrid grid(P, 2);
  const IntrinsicDelaunay D = compute_intrinsic_delaunay(
      with_metric(R"({"type": "product", "factors": [{"type": "sphere", "coordinates": [1, 2], "radius": "1"},
                                                     {"type": "sphere", "coordinates": [3, 4], "radius": "1"}]})"),
      P, grid, {ref.begin(), ref.end()}, 2);
  EXPECT_TRUE(D.complete) << D.reason;
  EXPECT_EQ(D.metric, "product_of_circles");
  EXPECT_EQ(certified_set(D), ref);
  const IntrinsicDelaunay E = compute_intrinsic_delaunay(
      with_metric(R"({"type": "product", "factors": [{"type": "sphere", "coordinates": [3, 4], "radius": "1"},
                                                     {"type": "sphere", "coordinates": [1, 2], "radius": "1"}]})"),
      P, grid, {ref.begin(), ref.end()}, 2);
  ASSERT_TRUE(E.computed) << E.reason;
  EXPECT_EQ(E.metric, "product");
  EXPECT_TRUE(E.complete) << E.reason;
  EXPECT_EQ(certified_set(E), ref);

  const io::ManifoldSpec s2s1 = io::parse_spec(R"({"format": "delcert-manifold v1", "intrinsic_dimension": 3,
    "ambient_dimension": 5, "equations": ["x1^2 + x2^2 + x3^2 - 1", "x4^2 + x5^2 - 4"],
    "metric": {"type": "product", "factors": [{"type": "sphere", "coordinates": [1, 2, 3], "radius": "1"},
                                              {"type": "sphere", "coordinates": [4, 5], "radius": "2"}]},
    "parametrization": {"name": "product", "factors": [{"type": "sphere", "coordinates": [1, 2, 3], "radius": "1"},
                                                       {"type": "sphere", "coordinates": [4, 5], "radius": "2"}]}})",
                                               "s2xs1.json");
  const io::PointSet Q = test::make_points(5, {{1, 0, 0, 2, 0}, {0, 1, 0, 0, 2}, {0, 0, 1, -2, 0}, {-1, 0, 0, 0, -2}});
  detail::PointGrid qgrid(Q, 3);
  const IntrinsicDelaunay F = compute_intrinsic_delaunay(s2s1, Q, qgrid, {{0, 1, 2, 3}}, 1);
  EXPECT_TRUE(F.computed);
  EXPECT_EQ(F.metric, "product");
  EXPECT_FALSE(F.complete);
  EXPECT_TRUE(F.simplices.empty());
  ASSERT_EQ(F.undecided.size(), 1u);
  EXPECT_NE(F.undecided[0].reason.find("no stereographic chart per factor covers the geodesic ball"), std::string::npos)
      << F.undecided[0].reason;
}

// Radii (1, 3/2) on points of the unit circles (off M in the second plane, projected radially),
// against a brute-force reference in doubles (every triangle among 40 nearest neighbours whose
// circumcircle of the shortest lifts, in the scaled angle coordinates, is empty): equal,
// complete, 2n triangles (Euler characteristic 0); the same for the homothetic radii (2, 3).
TEST(IntrinsicTorus, UnequalRadiiAgreeWithBruteForce) {
  const io::PointSet P = random_torus(2, 400, 8);
  const auto A = angles_of(P);
  const int n = static_cast<int>(P.size());
  for (const auto& radii : {std::vector<mpq_class>{1, mpq_class(3, 2)}, std::vector<mpq_class>{2, 3}}) {
    const std::array<double, 2> r{radii[0].get_d(), radii[1].get_d()};
    const auto near = neighbour_candidates(P, 2, 40, {r[0], r[1]});
    Simplices ref;
    for (const auto& s : near) {
      bool empty = true;
      for (int q = 0; q < n && empty; ++q)
        if (!std::binary_search(s.begin(), s.end(), q) && inside_circumcircle_t2(A, s, q, r)) empty = false;
      if (empty) ref.insert(s);
    }
    ASSERT_EQ(ref.size(), 2 * P.size());
    auto candidates = neighbour_candidates(P, 2, 6, {r[0], r[1]});
    candidates.insert(candidates.end(), ref.begin(), ref.end());
    io::ShapeSpec g = unit_circles(2);
    g.radii = radii;
    detail::PointGrid grid(P, 2);
    const IntrinsicDelaunay D = detail::intrinsic_delaunay_flat_torus(g, P, grid, candidates, 2);
    ASSERT_TRUE(D.computed) << D.reason;
    EXPECT_TRUE(D.complete) << D.reason;
    EXPECT_EQ(certified_set(D), ref);
  }
}

// (4) T^3 (clifford-torus-3): complete and equal to the periodic 3D Delaunay triangulation.
TEST(IntrinsicTorus, T3AgreesWithPeriodicDelaunay) {
  const io::PointSet P = random_torus(3, 400, 31);
  const Simplices ref = reference_t3(P);
  auto candidates = neighbour_candidates(P, 3, 5);
  candidates.insert(candidates.end(), ref.begin(), ref.end());
  const io::ManifoldSpec spec = io::read_spec("builtin:clifford-torus-3");
  detail::PointGrid grid(P, 3);
  const IntrinsicDelaunay D = compute_intrinsic_delaunay(spec, P, grid, candidates, 2);
  ASSERT_TRUE(D.computed) << D.reason;
  EXPECT_TRUE(D.complete) << D.reason;
  EXPECT_EQ(certified_set(D), ref);
  EXPECT_TRUE(D.undecided.empty());
  EXPECT_GT(D.rejected.size(), 0u);
}

// Gift wrapping (issue 12): from ONE certified seed simplex the certified set grows into the whole
// periodic Delaunay tessellation, complete (T^2 and T^3, 400 points each).
TEST(IntrinsicTorus, OneSeedGrowsIntoTheWholeComplex) {
  for (int m : {2, 3}) {
    const io::PointSet P = random_torus(m, 400, 1000 + m);
    const Simplices ref = m == 2 ? reference_t2(P) : reference_t3(P);
    const std::vector<int> seed = *std::next(ref.begin(), static_cast<long>(ref.size() / 2));
    for (int threads : {1, 3}) {
      const IntrinsicDelaunay D = run(P, m, {seed}, threads);
      ASSERT_TRUE(D.computed) << D.reason;
      EXPECT_TRUE(D.complete) << "m = " << m << ": " << D.reason;
      EXPECT_EQ(certified_set(D), ref) << "m = " << m;
      EXPECT_TRUE(D.undecided.empty());
    }
  }
}

// Gift wrapping completes a sampled candidate set that misses cells (nearest-neighbour triangles
// and tetrahedra from too few neighbours).
TEST(IntrinsicTorus, WrappingCompletesCandidatesThatMissCells) {
  for (int m : {2, 3}) {
    const io::PointSet P = random_torus(m, 300, 77 + m);
    const Simplices ref = m == 2 ? reference_t2(P) : reference_t3(P);
    const auto candidates = neighbour_candidates(P, m, m + 1);
    const Simplices given(candidates.begin(), candidates.end());
    const auto missed = std::count_if(ref.begin(), ref.end(), [&](const auto& s) { return !given.count(s); });
    ASSERT_GT(missed, 0) << "m = " << m << ": the candidates must miss cells for this test";
    const IntrinsicDelaunay D = run(P, m, candidates);
    ASSERT_TRUE(D.computed) << D.reason;
    EXPECT_TRUE(D.complete) << "m = " << m << ": " << D.reason;
    EXPECT_EQ(certified_set(D), ref) << "m = " << m;
    EXPECT_TRUE(D.undecided.empty());
  }
}

}  // namespace
}  // namespace delcert::certify
