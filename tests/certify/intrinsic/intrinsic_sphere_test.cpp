// Del_M on round spheres (certify/intrinsic_sphere.cpp, checks 14 and 15): known answers, the
// projection convention (radial scaling never changes Del_M, while it changes Del_RM), exact ties,
// adversarial magnitudes, a metric that does not match the equations, mutants of a claimed Del_M.
#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "certify/certify.hpp"
#include "certify/detail/grid.hpp"
#include "certify/intrinsic/intrinsic.hpp"
#include "exact/number_types.hpp"
#include "io/complex.hpp"
#include "io/points.hpp"
#include "io/spec.hpp"
#include "tests/certify/reference/restricted_delaunay_reference.hpp"
#include "tests/certify/support.hpp"

namespace delcert::certify::test {
namespace {

using Simplex = std::vector<int>;

std::vector<Simplex> all_triples(int n) {
  std::vector<Simplex> t;
  for (int a = 0; a < n; ++a)
    for (int b = a + 1; b < n; ++b)
      for (int c = b + 1; c < n; ++c) t.push_back({a, b, c});
  return t;
}

// The side of r relative to the plane through the projections of a, b, c (long double, for
// re-checking witnesses whose margins are far above rounding).
int side(const io::PointSet& P, const Simplex& s, int r) {
  long double x[4][3];
  const int idx[4] = {s[0], s[1], s[2], r};
  for (int i = 0; i < 4; ++i) {
    long double n = 0;
    for (int v = 0; v < 3; ++v) n += (long double)P.point(idx[i])[v] * P.point(idx[i])[v];
    for (int v = 0; v < 3; ++v) x[i][v] = P.point(idx[i])[v] / std::sqrt(n);
  }
  long double e[3][3];
  for (int i = 0; i < 3; ++i)
    for (int v = 0; v < 3; ++v) e[i][v] = x[i + 1][v] - x[0][v];
  const long double d = e[0][0] * (e[1][1] * e[2][2] - e[1][2] * e[2][1]) - e[0][1] * (e[1][0] * e[2][2] - e[1][2] * e[2][0]) +
                        e[0][2] * (e[1][0] * e[2][1] - e[1][1] * e[2][0]);
  return d > 0 ? 1 : d < 0 ? -1 : 0;
}

TEST(IntrinsicSphere, OctahedronKnownAnswer) {
  const io::ManifoldSpec spec = io::read_spec("builtin:sphere-2");
  const io::PointSet P = io::read_points(fixture("points/octahedron.off"));
  const IntrinsicDelaunay D = del_m(spec, P, all_triples(6));
  ASSERT_TRUE(D.computed) << D.reason;
  EXPECT_TRUE(D.complete) << D.reason;
  EXPECT_EQ(D.simplices.size(), 8u);  // the faces: one positive or negative coordinate each
  for (const auto& s : D.simplices) {
    std::set<int> axes;
    for (int v : s.simplex) axes.insert(v / 2);  // the fixture lists +e_i, -e_i in pairs
    EXPECT_EQ(axes.size(), 3u);
  }
  EXPECT_EQ(D.rejected.size(), 12u);  // every triple holding an antipodal pair
  for (const auto& r : D.rejected) {
    const auto both = r.witness["points_on_both_sides"].get<std::vector<int>>();
    EXPECT_NE(side(P, r.simplex, both[0]), side(P, r.simplex, both[1]));
  }
}

// Radial scaling moves no projection (up to the rounding of the scaled doubles, far below the
// sample's margins): Del_M is unchanged, while Del_RM of the scaled points changes, and check 15
// refutes Del_RM = Del_M with witnesses that re-check.
TEST(IntrinsicSphere, RadialScalingChangesDelRMButNotDelM) {
  const io::PointSet F = fibonacci_sphere(200);
  io::PointSet P;
  P.dimension = 3;
  for (std::size_t i = 0; i < F.size(); ++i) {
    const double s = 1 + 0.03 * (static_cast<int>((i * 7) % 5) - 2);
    const std::vector<double> x{s * F.point(i)[0], s * F.point(i)[1], s * F.point(i)[2]};
    P.push_back(x);
  }
  TempDir dir("intrinsic-scaled");
  CertifyOptions o;
  o.manifold = dir.file("sphere.json");
  write_text(o.manifold, R"({"format": "delcert-manifold v1", "name": "unit sphere, loose residual tolerance",
    "intrinsic_dimension": 2, "ambient_dimension": 3, "equations": ["x1^2 + x2^2 + x3^2 - 1"],
    "metric": {"type": "sphere", "center": ["0", "0", "0"], "radius": "1"}, "residual_tolerance": "1",
    "bounding_box": [["-2", "2"], ["-2", "2"], ["-2", "2"]], "expected": {"euler_characteristic": 2}})");
  o.points = dir.file("points.txt");
  io::write_points(o.points, P);
  o.threads = 2;
  const Certificate c = run_certify(o);
  const CheckEntry& eq = check(c, CheckId::restricted_equals_intrinsic);
  ASSERT_EQ(eq.verdict, Verdict::refuted) << eq.summary;
  // Del_TM and Del_RM miss some of Del_M's triangles here: gift wrapping completes it.
  EXPECT_EQ(check(c, CheckId::intrinsic_delaunay).verdict, Verdict::certified) << check(c, CheckId::intrinsic_delaunay).summary;
  int rechecked = 0;
  for (const auto& w : eq.witnesses)
    if (w.contains("intrinsic_witness")) {
      const auto both = w["intrinsic_witness"]["points_on_both_sides"].get<std::vector<int>>();
      const Simplex s = w["simplex"].get<Simplex>();
      EXPECT_NE(side(P, s, both[0]), side(P, s, both[1])) << w.dump();
      ++rechecked;
    }
  EXPECT_GT(rechecked, 0);

  // Del_M of the scaled points = Del_M of the unscaled ones (all of it, certified both times).
  const io::ManifoldSpec unit = io::read_spec("builtin:sphere-2");
  const IntrinsicDelaunay D0 = del_m(unit, F, [&] {
    std::vector<Simplex> t;
    const Audit A = audit("builtin:sphere-2", F);
    for (auto s : A.complex.simplices) {
      std::sort(s.begin(), s.end());
      t.push_back(s);
    }
    return t;
  }());
  ASSERT_TRUE(D0.complete) << D0.reason;
  EXPECT_EQ(D0.simplices.size(), 396u);
  const std::set<Simplex> S0 = simplices(D0);
  const IntrinsicDelaunay D1 = del_m(unit, P, std::vector<Simplex>(S0.begin(), S0.end()));
  EXPECT_TRUE(D1.complete) << D1.reason;
  EXPECT_EQ(simplices(D1), S0);

  // Independent reference: on the sphere Del_M = Del_RM, so the test-only reference (CGAL's 3D
  // Delaunay + exact root counting) on the projections, rounded to doubles (the sample is far from
  // any tie), must give the same triangles.
  io::PointSet Q;
  Q.dimension = 3;
  for (std::size_t i = 0; i < P.size(); ++i) {
    const auto p = P.point(i);
    const double n = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
    const std::vector<double> x{p[0] / n, p[1] / n, p[2] / n};
    Q.push_back(x);
  }
  const reference::RestrictedDelaunayReference ref = reference::restricted_delaunay_reference(Q, reference::surface_equation(unit));
  ASSERT_TRUE(ref.decided());
  std::set<Simplex> truth;
  for (const auto& t : ref.triangles()) truth.insert({int(t[0]), int(t[1]), int(t[2])});
  EXPECT_EQ(simplices(D1), truth);
}

// Gift wrapping: from one certified facet the whole hull is found (each new facet proposed in
// floating point and then decided like any candidate).
TEST(IntrinsicSphere, OneFacetGrowsIntoTheWholeComplex) {
  const io::PointSet F = fibonacci_sphere(200);
  const io::ManifoldSpec unit = io::read_spec("builtin:sphere-2");
  const Audit A = audit("builtin:sphere-2", F);
  Simplex seed = A.complex.simplices[0];
  std::sort(seed.begin(), seed.end());
  const IntrinsicDelaunay D = del_m(unit, F, {seed});
  EXPECT_TRUE(D.complete) << D.reason;
  EXPECT_EQ(D.simplices.size(), 396u);
  std::set<Simplex> tm;
  for (auto s : A.complex.simplices) {
    std::sort(s.begin(), s.end());
    tm.insert(s);
  }
  EXPECT_EQ(simplices(D), tm);  // Del_TM = Del_M on this sample (check 13 and 15 say the same)
  // S^3: from one seed too.
  const io::PointSet S3 = spread_sphere(4, 80, 0.45, 11);
  const Audit A3 = audit("builtin:sphere-3", S3);
  Simplex seed3 = A3.complex.simplices[0];
  std::sort(seed3.begin(), seed3.end());
  const IntrinsicDelaunay D3 = del_m(io::read_spec("builtin:sphere-3"), S3, {seed3});
  EXPECT_TRUE(D3.complete) << D3.reason;
  EXPECT_EQ(D3.simplices.size(), A3.complex.simplices.size());
}

// The cube's vertices project to the cube inscribed in the unit sphere: each square face is four
// cocircular points, an exact tie. Never certified; the ties are reported as such.
TEST(IntrinsicSphere, CubeHasExactTiesAndIsNeverComplete) {
  std::vector<std::vector<double>> cube;
  for (int i = 0; i < 8; ++i) cube.push_back({i & 1 ? 1.0 : -1.0, i & 2 ? 1.0 : -1.0, i & 4 ? 1.0 : -1.0});
  const IntrinsicDelaunay D = del_m(io::read_spec("builtin:sphere-2"), make_points(3, cube), all_triples(8));
  ASSERT_TRUE(D.computed);
  EXPECT_FALSE(D.complete);
  EXPECT_TRUE(D.simplices.empty());  // every triangle of a face has the fourth vertex on its circle
  ASSERT_FALSE(D.undecided.empty());
  EXPECT_NE(D.undecided[0].reason.find("exactly on the boundary"), std::string::npos) << D.undecided[0].reason;
}

// Adversarial magnitudes: the octahedron on spheres of radius 2^k; the interval filter overflows
// or underflows, the exact path decides.
TEST(IntrinsicSphere, ScaledOctahedronAtExtremeMagnitudes) {
  for (int k : {-1000, -300, 300, 500}) {
    SCOPED_TRACE(k);
    const double s = std::ldexp(1.0, k);
    std::vector<std::vector<double>> pts;
    for (int a = 0; a < 3; ++a)
      for (double sign : {1.0, -1.0}) {
        std::vector<double> x(3, 0.0);
        x[a] = sign * s * (1 + 0x1p-30 * (a + 1));  // off the sphere: the projection matters
        pts.push_back(x);
      }
    io::ManifoldSpec spec = io::read_spec("builtin:sphere-2");
    const mpq_class S = exact::to_rational(s);
    spec.equations[0] = exact::Polynomial::parse("x1^2 + x2^2 + x3^2 - " + exact::rational_to_string(S * S), 3);
    spec.metric->radius = S;
    const IntrinsicDelaunay D = del_m(spec, make_points(3, pts), all_triples(6));
    EXPECT_TRUE(D.complete) << D.reason;
    EXPECT_EQ(D.simplices.size(), 8u);
  }
}

TEST(IntrinsicSphere, NotComputedWithoutATrustworthyMetric) {
  const io::PointSet P = io::read_points(fixture("points/octahedron.off"));
  io::ManifoldSpec spec = io::read_spec("builtin:sphere-2");
  spec.metric->radius = 2;  // the equations say radius 1
  IntrinsicDelaunay D = del_m(spec, P, all_triples(6));
  EXPECT_FALSE(D.computed);
  EXPECT_NE(D.reason.find("not used"), std::string::npos) << D.reason;
  spec.metric.reset();
  D = del_m(spec, P, all_triples(6));
  EXPECT_FALSE(D.computed);
  EXPECT_NE(D.reason.find("no closed-form geodesic distance"), std::string::npos) << D.reason;
  // A point at the centre has no projection.
  std::vector<std::vector<double>> pts{{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, 0, 0}, {0, 0, 1}};
  D = del_m(io::read_spec("builtin:sphere-2"), make_points(3, pts), all_triples(5));
  EXPECT_FALSE(D.computed);
  EXPECT_NE(D.reason.find("centre"), std::string::npos) << D.reason;
}

// --kind intrinsic: the octahedron is Del_M; a dropped face is refuted by its certified vertex, a
// replaced one as not intrinsic.
TEST(IntrinsicSphere, ClaimedIntrinsicComplexAndItsMutants) {
  TempDir dir("intrinsic-claim");
  CertifyOptions o;
  o.manifold = "builtin:sphere-2";
  o.points = fixture("points/octahedron.off");
  o.complex = fixture("complexes/octahedron.off");
  o.kind = ComplexKind::intrinsic;
  const Certificate c = run_certify(o);
  EXPECT_EQ(c.parameters["kind"], "intrinsic");
  EXPECT_EQ(check(c, CheckId::intrinsic_delaunay).verdict, Verdict::certified) << check(c, CheckId::intrinsic_delaunay).summary;
  EXPECT_EQ(check(c, CheckId::tangential_equals_restricted).verdict, Verdict::report);
  EXPECT_EQ(c.overall(), Verdict::certified);

  io::ComplexFile f = io::read_complex(o.complex);
  io::Complex dropped = f.complex;
  dropped.simplices.pop_back();
  o.complex = dir.file("dropped.txt");
  io::write_complex(o.complex, dropped);
  const Certificate d = run_certify(o);
  ASSERT_EQ(check(d, CheckId::intrinsic_delaunay).verdict, Verdict::refuted);
  EXPECT_EQ(check(d, CheckId::intrinsic_delaunay).witnesses[0]["kind"], "intrinsic_voronoi_vertex");

  io::Complex replaced = f.complex;
  replaced.simplices[0] = {0, 1, 2};  // holds the antipodal pair 0, 1
  o.complex = dir.file("replaced.txt");
  io::write_complex(o.complex, replaced);
  const Certificate r = run_certify(o);
  ASSERT_EQ(check(r, CheckId::intrinsic_delaunay).verdict, Verdict::refuted);
  bool not_intrinsic = false;
  for (const auto& w : check(r, CheckId::intrinsic_delaunay).witnesses) not_intrinsic |= w["kind"] == "not_intrinsic";
  EXPECT_TRUE(not_intrinsic);

}

}  // namespace
}  // namespace delcert::certify::test
