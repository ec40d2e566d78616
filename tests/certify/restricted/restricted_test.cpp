// Checks 11-13 of the certificate (certify/restricted.hpp): the certified covering radius, Del_RM(P)
// and Del_TM(P) = Del_RM(P), on known answers, mutants and exactly degenerate input.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <set>

#include "certify/certify.hpp"
#include "certify/restricted/restricted.hpp"
#include "exact/number_types.hpp"
#include "exact/polynomial.hpp"
#include "io/complex.hpp"
#include "io/input_error.hpp"
#include "io/points.hpp"
#include "tests/certify/reference/restricted_delaunay_reference.hpp"
#include "tests/certify/support.hpp"

namespace delcert::certify::test {
namespace {

const CheckEntry& entry(const Certificate& c, CheckId id) {
  for (const auto& e : c.checks)
    if (e.id == id) return e;
  throw std::logic_error("no such check");
}

Certificate certify_points(const std::string& spec, const io::PointSet& P, const TempDir& dir,
                           const std::string& complex = "", const std::string& claims = "") {
  CertifyOptions o;
  o.manifold = spec;
  o.points = dir.file("points.txt");
  io::write_points(o.points, P);
  o.complex = complex;
  if (!claims.empty()) {
    o.claims = dir.file("claims.json");
    write_text(o.claims, claims);
  }
  return run_certify(o);
}

double covering_upper(const CheckEntry& e) { return std::stod(e.margin["covering_radius"]["certified_upper_bound"].get<std::string>()); }
double covering_lower(const CheckEntry& e) { return std::stod(e.margin["covering_radius"]["certified_lower_bound"].get<std::string>()); }

// The octahedron on the unit sphere: Del_RM = Del_TM = its 8 faces; the farthest points of S^2
// from its vertices are the face centres (±1, ±1, ±1)/sqrt 3, at distance sqrt(2 - 2/sqrt 3) =
// 0.91940 (the true covering radius, which both certified bounds must bracket).
TEST(RestrictedChecks, OctahedronKnownAnswers) {
  TempDir dir("restricted-octahedron");
  CertifyOptions o;
  o.manifold = "builtin:sphere-2";
  o.points = fixture("points/octahedron.off");
  const Certificate audit = run_certify(o);
  const double truth = std::sqrt(2 - 2 / std::sqrt(3.0));
  const CheckEntry& cov = entry(audit, CheckId::covering);
  EXPECT_EQ(cov.verdict, Verdict::certified) << cov.summary;
  EXPECT_GE(covering_upper(cov), truth);
  EXPECT_LE(covering_lower(cov), truth);
  EXPECT_GT(covering_lower(cov), truth - 1e-6);  // the face centres are restricted Voronoi vertices
  EXPECT_LT(covering_upper(cov), 1.0);
  EXPECT_EQ(entry(audit, CheckId::restricted_delaunay).verdict, Verdict::certified);
  EXPECT_EQ(entry(audit, CheckId::restricted_delaunay).details["m_simplices"], 8);
  EXPECT_EQ(entry(audit, CheckId::tangential_equals_restricted).verdict, Verdict::certified);
  EXPECT_EQ(audit.overall(), Verdict::certified);

  // The OFF octahedron is claimed to be restricted Delaunay (the default kind for OFF).
  o.complex = fixture("complexes/octahedron.off");
  const Certificate verify = run_certify(o);
  EXPECT_EQ(verify.parameters["kind"], "restricted");
  EXPECT_EQ(entry(verify, CheckId::restricted_delaunay).verdict, Verdict::certified)
      << entry(verify, CheckId::restricted_delaunay).summary;
  EXPECT_EQ(entry(verify, CheckId::tangential_equals_restricted).verdict, Verdict::report);
  EXPECT_EQ(verify.overall(), Verdict::certified);
}

// The covering claim: below the certified upper bound it is not certified; below the farthest
// certified vertex it is refuted, with that vertex as witness.
TEST(RestrictedChecks, CoveringClaimIsDecidedEitherWay) {
  TempDir dir("restricted-claims");
  const io::PointSet P = io::read_points(fixture("points/octahedron.off"));
  auto verdict_for = [&](const std::string& claim) {
    const Certificate c = certify_points("builtin:sphere-2", P, dir, "",
                                         R"({"format": "delcert-claims v2", "covering": ")" + claim + "\"}");
    return entry(c, CheckId::covering);
  };
  const CheckEntry high = verdict_for("1");
  EXPECT_EQ(high.verdict, Verdict::certified);
  const CheckEntry low = verdict_for("0.9");
  ASSERT_EQ(low.verdict, Verdict::refuted);
  ASSERT_FALSE(low.witnesses.empty());
  EXPECT_EQ(low.witnesses[0]["kind"], "restricted_voronoi_vertex");
  // Re-check the witness independently: its enclosure is at distance >= 0.9 from every point.
  for (const auto& w : low.witnesses) {
    std::vector<std::pair<double, double>> box;
    for (const auto& iv : w["vertex_enclosure"]) box.push_back({std::stod(iv[0].get<std::string>()), std::stod(iv[1].get<std::string>())});
    for (std::size_t q = 0; q < P.size(); ++q) {
      double d2 = 0;  // squared distance from the point to the box (a lower bound for every x in it)
      for (int k = 0; k < 3; ++k) {
        const double x = P.point(q)[k];
        const double g = x < box[k].first ? box[k].first - x : x > box[k].second ? x - box[k].second : 0;
        d2 += g * g;
      }
      EXPECT_GT(d2, 0.9 * 0.9 * (1 - 1e-12)) << q;
    }
  }
  // Between the two certified bounds nothing is decided (the vertex at (1, 1, 1)/sqrt(3) is at
  // distance sqrt(2 - 2/sqrt(3)) = 0.91940 from its points; the upper bound depends on the boxes).
  const double lower = std::stod(high.margin["covering_radius"]["certified_lower_bound"].get<std::string>()),
               upper = std::stod(high.margin["covering_radius"]["certified_upper_bound"].get<std::string>());
  EXPECT_NEAR(lower, 0.919401686761965, 1e-12);
  ASSERT_LT(lower, upper);
  char between[64];
  std::snprintf(between, sizeof between, "%.17g", (lower + upper) / 2);
  EXPECT_EQ(verdict_for(between).verdict, Verdict::undecided) << between;
}

// Del_TM = Del_RM on a good sample of S^2, certified.
TEST(RestrictedChecks, GoodSphereSampleHasEqualComplexes) {
  TempDir dir("restricted-sphere");
  const io::PointSet P = fibonacci_sphere(200);
  const Certificate c = certify_points("builtin:sphere-2", P, dir);
  EXPECT_EQ(entry(c, CheckId::covering).verdict, Verdict::certified) << entry(c, CheckId::covering).summary;
  EXPECT_EQ(entry(c, CheckId::restricted_delaunay).verdict, Verdict::certified)
      << entry(c, CheckId::restricted_delaunay).summary;
  EXPECT_EQ(entry(c, CheckId::tangential_equals_restricted).verdict, Verdict::certified);
  EXPECT_EQ(entry(c, CheckId::restricted_delaunay).details["m_simplices"], 2 * 200 - 4);  // a triangulated S^2
}

// Mutants of Del_RM of a sphere mesh (OFF: claimed restricted) are never CERTIFIED: a dropped
// triangle is refuted by its certified vertex; an added or replaced one is refuted as not
// restricted (Del_RM is complete here).
TEST(RestrictedChecks, MutantsOfARestrictedMeshAreNeverCertified) {
  TempDir dir("restricted-mutants");
  const io::PointSet P = fibonacci_sphere(60);
  const Certificate audit_cert = certify_points("builtin:sphere-2", P, dir);
  ASSERT_EQ(entry(audit_cert, CheckId::restricted_delaunay).verdict, Verdict::certified);
  const Audit A = audit("builtin:sphere-2", P);  // Del_TM, equal to Del_RM here (check 13)
  ASSERT_EQ(entry(audit_cert, CheckId::tangential_equals_restricted).verdict, Verdict::certified);
  auto run_mutant = [&](const io::Complex& K) {
    CertifyOptions o;
    o.manifold = "builtin:sphere-2";
    o.points = dir.file("points.txt");
    o.complex = dir.file("mutant.txt");
    o.kind = ComplexKind::restricted;
    io::write_complex(o.complex, K);
    return run_certify(o);
  };
  {
    const Certificate base = run_mutant(A.complex);
    EXPECT_EQ(entry(base, CheckId::restricted_delaunay).verdict, Verdict::certified);
  }
  io::Complex dropped = A.complex;
  const std::vector<int> gone = dropped.simplices[7];
  dropped.simplices.erase(dropped.simplices.begin() + 7);
  const Certificate d = run_mutant(dropped);
  const CheckEntry& dd = entry(d, CheckId::restricted_delaunay);
  ASSERT_EQ(dd.verdict, Verdict::refuted);
  std::vector<int> gone_sorted = gone;
  std::sort(gone_sorted.begin(), gone_sorted.end());
  EXPECT_EQ(dd.witnesses[0]["simplex"].get<std::vector<int>>(), gone_sorted);
  EXPECT_EQ(dd.witnesses[0]["kind"], "restricted_voronoi_vertex");

  io::Complex added = A.complex;
  added.simplices.push_back({0, 1, 30});  // not a restricted Delaunay triangle
  EXPECT_NE(run_mutant(added).overall(), Verdict::certified);
  EXPECT_EQ(entry(run_mutant(added), CheckId::restricted_delaunay).verdict, Verdict::refuted);

  io::Complex edge = A.complex;  // an isolated edge between the two poles: Del_RM is pure
  edge.simplices.push_back({0, 59});
  const Certificate e = run_mutant(edge);
  ASSERT_EQ(entry(e, CheckId::restricted_delaunay).verdict, Verdict::refuted);
  EXPECT_EQ(entry(e, CheckId::restricted_delaunay).witnesses[0]["kind"], "not_a_face_of_an_m_simplex");

  io::Complex replaced = A.complex;
  replaced.simplices[3] = {replaced.simplices[3][0], replaced.simplices[3][1], (replaced.simplices[3][2] + 17) % 60};
  EXPECT_EQ(entry(run_mutant(replaced), CheckId::restricted_delaunay).verdict, Verdict::refuted);
}

// A sample with a hole: every point within angle 0.7 of the north pole removed. The covering
// bound is at least the distance from the pole to the nearest point.
TEST(RestrictedChecks, TheReachIsAnAssumptionStatedWhereTheGraphLemmaIsUsed) {
  // The flat torus S^1 x S^1 in R^6 with x5 = x6 = 0: codimension 4, where a declared reach lets
  // THE GRAPH LEMMA (certify/rvd.cpp) take chart slabs. With the reach, check 11 must say that it
  // assumed it; without it, that nothing was assumed. The same Del_RM and both certified.
  TempDir dir("reach");
  io::PointSet T = torus2_lattice(12, 14, 0.3, 9);
  std::vector<std::vector<double>> pts;
  for (std::size_t i = 0; i < T.size(); ++i) {
    std::vector<double> x(T.point(i).begin(), T.point(i).end());
    x.push_back(0), x.push_back(0);
    pts.push_back(std::move(x));
  }
  const io::PointSet P = make_points(6, pts);
  auto spec = [&](bool reach) {
    const std::string path = dir.file(reach ? "with.json" : "without.json");
    write_text(path, std::string(R"({"format": "delcert-manifold v1", "name": "flat-torus-in-r6", "intrinsic_dimension": 2,
 "ambient_dimension": 6, "equations": ["x1^2 + x2^2 - 1", "x3^2 + x4^2 - 1", "x5", "x6"],)") +
                         (reach ? R"( "reach": {"value": "1", "kind": "exact"},)" : "") +
                         R"( "bounding_box": [["-1.25", "1.25"], ["-1.25", "1.25"], ["-1.25", "1.25"], ["-1.25", "1.25"],
 ["-1", "1"], ["-1", "1"]], "expected": {"euler_characteristic": 0, "betti_z2": [1, 2, 1]}})");
    return path;
  };
  const Certificate with = certify_points(spec(true), P, dir), without = certify_points(spec(false), P, dir);
  const CheckEntry& cw = check(with, CheckId::covering);
  const CheckEntry& co = check(without, CheckId::covering);
  ASSERT_EQ(cw.verdict, Verdict::certified) << with.to_text(false);
  ASSERT_EQ(co.verdict, Verdict::certified) << without.to_text(false);
  const std::string charts_with = cw.details["assumptions"]["charts"], charts_without = co.details["assumptions"]["charts"];
  EXPECT_NE(charts_with.find("the reach of M is at least 1"), std::string::npos) << charts_with;
  EXPECT_EQ(charts_without.find("none: no reach"), 0u) << charts_without;
  EXPECT_EQ(check(with, CheckId::restricted_delaunay).verdict, Verdict::certified);
  EXPECT_EQ(check(without, CheckId::restricted_delaunay).verdict, Verdict::certified);
  EXPECT_EQ(check(with, CheckId::restricted_delaunay).details["m_simplices"],
            check(without, CheckId::restricted_delaunay).details["m_simplices"]);
  EXPECT_EQ(check(with, CheckId::tangential_equals_restricted).verdict,
            check(without, CheckId::tangential_equals_restricted).verdict);
}

TEST(RestrictedChecks, CoveringBoundSeesAHole) {
  TempDir dir("restricted-hole");
  const io::PointSet all = fibonacci_sphere(300);
  std::vector<std::vector<double>> kept;
  double to_pole = INFINITY;
  for (std::size_t i = 0; i < all.size(); ++i) {
    const auto x = all.point(i);
    if (std::acos(std::clamp(x[2], -1.0, 1.0)) < 0.7) continue;
    kept.push_back({x[0], x[1], x[2]});
    to_pole = std::min(to_pole, std::hypot(x[0], x[1], x[2] - 1));
  }
  const Certificate c = certify_points("builtin:sphere-2", make_points(3, kept), dir);
  const CheckEntry& cov = entry(c, CheckId::covering);
  ASSERT_EQ(cov.verdict, Verdict::certified) << cov.summary;
  EXPECT_GE(covering_upper(cov), to_pole);
  EXPECT_GE(covering_lower(cov), 0.5 * to_pole);
}

// Exactly degenerate inputs are never CERTIFIED: the cube on its circumsphere (every face's
// centre is equidistant from 4 points) and a square grid on the flat torus.
TEST(RestrictedChecks, ExactlyDegenerateInputIsNeverCertified) {
  TempDir dir("restricted-degenerate");
  std::vector<std::vector<double>> cube;
  for (int i = 0; i < 8; ++i) cube.push_back({i & 1 ? 1.0 : -1.0, i & 2 ? 1.0 : -1.0, i & 4 ? 1.0 : -1.0});
  const std::string spec = dir.file("sphere-sqrt3.json");
  write_text(spec, R"({"format": "delcert-manifold v1", "name": "sphere of radius sqrt 3", "intrinsic_dimension": 2,
                      "ambient_dimension": 3, "equations": ["x1^2 + x2^2 + x3^2 - 3"],
                      "bounding_box": [["-2", "2"], ["-2", "2"], ["-2", "2"]]})");
  const Certificate c = certify_points(spec, make_points(3, cube), dir);
  EXPECT_NE(entry(c, CheckId::covering).verdict, Verdict::certified);
  EXPECT_NE(entry(c, CheckId::restricted_delaunay).verdict, Verdict::certified);
  EXPECT_NE(c.overall(), Verdict::certified);

  CertifyOptions o;
  o.manifold = "builtin:clifford-torus-2";
  o.points = fixture("certify/clifford-square-grid.txt");
  const Certificate grid = run_certify(o);
  EXPECT_NE(entry(grid, CheckId::restricted_delaunay).verdict, Verdict::certified);
  EXPECT_NE(grid.overall(), Verdict::certified);
}

// Adversarial magnitudes: the octahedron scaled by 2^k on the sphere of radius 2^k. Whatever the
// verdicts, a certified covering bound is never below the true value sqrt(2 - 2/sqrt 3) 2^k.
// A cell that runs out of its box budget nearly done (its only undecided boxes the few left) is
// analysed again with 4 times the budget: with a budget below what the cells of a sphere sample
// need, every cell still completes, in a later round, with the same Del_RM as a large budget.
TEST(RestrictedChecks, ACellOutOfBoxesNearlyDoneIsRetriedWithALargerBudget) {
  const io::PointSet P = spread_sphere(3, 60, 0.3, 11);
  const exact::ImplicitSystem F = exact::ImplicitSystem::parse({"x1^2 + x2^2 + x3^2 - 1"}, 3);
  const detail::PointGrid grid(P, 2);
  RestrictedDelaunayOptions o;
  const RestrictedDelaunay full = compute_restricted_delaunay(F, P, grid, o);
  ASSERT_TRUE(full.covering_certified) << full.reason;
  long most = 0;
  for (const auto& c : full.cells) most = std::max(most, c.boxes);
  o.cell.max_boxes = most * 3 / 4;  // some cells run out
  const RestrictedDelaunay small = compute_restricted_delaunay(F, P, grid, o);
  EXPECT_TRUE(small.covering_certified) << small.reason;
  EXPECT_GT(small.rounds_used, 1);
  ASSERT_EQ(small.simplices.size(), full.simplices.size());
  for (std::size_t i = 0; i < full.simplices.size(); ++i) EXPECT_EQ(small.simplices[i].simplex, full.simplices[i].simplex);
  std::printf("[ box budget ] largest cell %ld boxes; with a budget of %ld: %d rounds\n", most, o.cell.max_boxes,
              small.rounds_used);
}

// The expected complex only picks the first radii: the true one (first radii about 5/4 of the
// covering radius, one round), a wrong one whose largest triangle is tiny (first radii below the
// covering radius: every cell is analysed again) and one with a huge triangle (the old radii)
// give the same Del_RM and a certified covering bound, never below the farthest vertex.
TEST(RestrictedChecks, TheExpectedComplexChangesOnlyTheWork) {
  const io::PointSet P = spread_sphere(3, 60, 0.3, 11);
  const exact::ImplicitSystem F = exact::ImplicitSystem::parse({"x1^2 + x2^2 + x3^2 - 1"}, 3);
  const detail::PointGrid grid(P, 2);
  RestrictedDelaunayOptions o;
  const RestrictedDelaunay plain = compute_restricted_delaunay(F, P, grid, o);
  ASSERT_TRUE(plain.covering_certified) << plain.reason;
  std::vector<std::vector<int>> truth, tiny, huge;
  for (const auto& s : plain.simplices) truth.push_back(s.simplex);
  auto d2 = [&](int i, int j) {
    double d = 0;
    for (int v = 0; v < 3; ++v) d += std::pow(P.point(i)[v] - P.point(j)[v], 2);
    return d;
  };
  int a = 0, b = 1, c = 2;  // the closest pair and the point nearest to both: a small triangle
  for (int i = 0; i < static_cast<int>(P.size()); ++i)
    for (int j = i + 1; j < static_cast<int>(P.size()); ++j)
      if (d2(i, j) < d2(a, b)) a = i, b = j;
  for (int i = 0; i < static_cast<int>(P.size()); ++i)
    if (i != a && i != b && (c == a || c == b || std::max(d2(i, a), d2(i, b)) < std::max(d2(c, a), d2(c, b)))) c = i;
  tiny.push_back({a, b, c});
  huge.push_back({0, 1, 2});
  huge.push_back(truth[0]);
  for (auto* expected : {&truth, &tiny, &huge}) {
    o.expected = expected;
    const RestrictedDelaunay R = compute_restricted_delaunay(F, P, grid, o);
    EXPECT_TRUE(R.covering_certified) << R.reason;
    ASSERT_EQ(R.simplices.size(), plain.simplices.size());
    for (std::size_t i = 0; i < R.simplices.size(); ++i) EXPECT_EQ(R.simplices[i].simplex, plain.simplices[i].simplex);
    EXPECT_GE(R.covering, R.vertex_distance_lower);
    EXPECT_NEAR(R.vertex_distance_lower, plain.vertex_distance_lower, 1e-12);
    if (expected == &truth) {
      EXPECT_EQ(R.rounds_used, 1);
      EXPECT_LT(R.min_radius, plain.min_radius);
    }
    if (expected == &tiny) {
      EXPECT_GT(R.rounds_used, 1);  // (the regrowing path is exercised)
    }
    std::printf("[ first radii ] expected complex %s: %d rounds, %ld boxes (none given: %d, %ld)\n",
                expected == &truth ? "true" : expected == &tiny ? "tiny" : "huge", R.rounds_used, R.boxes,
                plain.rounds_used, plain.boxes);
  }
}

TEST(RestrictedChecks, ScaledOctahedronNeverUnderstatesTheCoveringRadius) {
  TempDir dir("restricted-scaled");
  int certified = 0;
  for (int k : {-1000, -520, -300, 300, 500}) {
    std::vector<std::vector<double>> pts;
    const double s = std::ldexp(1.0, k);
    for (int a = 0; a < 3; ++a)
      for (double sign : {1.0, -1.0}) {
        std::vector<double> x(3, 0.0);
        x[a] = sign * s;
        pts.push_back(x);
      }
    const mpq_class S = exact::to_rational(s);
    const std::string spec = dir.file("sphere.json");
    const std::string b = exact::rational_to_string(2 * S);
    write_text(spec, R"({"format": "delcert-manifold v1", "name": "scaled sphere", "intrinsic_dimension": 2,
                        "ambient_dimension": 3, "equations": ["x1^2 + x2^2 + x3^2 - )" +
                         exact::rational_to_string(S * S) + R"("], "bounding_box": [["-)" + b + "\", \"" + b +
                         R"("], ["-)" + b + "\", \"" + b + R"("], ["-)" + b + "\", \"" + b + R"("]]})");
    Certificate c;
    try {
      c = certify_points(spec, make_points(3, pts), dir);
    } catch (const io::InputError& e) {
      ADD_FAILURE() << k << ": " << e.what();
      continue;
    }
    const CheckEntry& cov = entry(c, CheckId::covering);
    std::printf("octahedron scaled by 2^%d: covering %s: %s\n", k, to_string(cov.verdict), cov.summary.c_str());
    if (cov.verdict != Verdict::certified) continue;
    ++certified;
    EXPECT_GE(covering_upper(cov) / s, std::sqrt(2 - 2 / std::sqrt(3.0)) * (1 - 1e-12)) << k;
    EXPECT_LE(covering_lower(cov) / s, std::sqrt(2 - 2 / std::sqrt(3.0)) * (1 + 1e-12)) << k;
  }
  std::printf("%d of 5 scaled octahedra certified\n", certified);
}

// An impure Del_RM(P) (the configuration of RestrictedCell.AFacePointProvesAnEdgeInNoMSimplex):
// the north pole p, q = (0, 0, 0.9) inside the sphere, a Fibonacci sample below polar angle 1.
// The cell of p is the cap z > 0.95 bounded by the bisector of p and q alone, so the edge {p, q}
// is in Del_RM and in no triangle. The mesh of Del_RM's triangles (the independent reference,
// which agrees) is claimed restricted: REFUTED, the witness a face point on that circle; the
// reference has no triangle with that edge either. The mesh's triangles are exactly Del_RM(P)'s, so
// the certificate blames the sample, not the mesh (issue 39): "Del_RM(P) is not pure: it
// triangulates nothing", and the edge is not counted as missing from the mesh.
TEST(RestrictedChecks, AnImpureDelRMIsRefutedWithItsFacePoint) {
  TempDir dir("restricted-impure");
  const io::PointSet S = fibonacci_sphere(300);
  io::PointSet P;
  P.dimension = 3;
  P.push_back(std::vector<double>{0, 0, 1});
  P.push_back(std::vector<double>{0, 0, 0.9});
  for (std::size_t i = 0; i < S.size(); ++i)
    if (S.point(i)[2] <= std::cos(1.0)) P.push_back(std::vector<double>{S.point(i)[0], S.point(i)[1], S.point(i)[2]});
  const reference::RestrictedDelaunayReference ref =
      reference::restricted_delaunay_reference(P, reference::surface_equation(io::read_spec("builtin:sphere-2")));
  ASSERT_TRUE(ref.decided());
  io::Complex mesh;
  mesh.num_vertices = P.size();
  for (const auto& t : ref.triangles()) {
    mesh.simplices.push_back({static_cast<int>(t[0]), static_cast<int>(t[1]), static_cast<int>(t[2])});
    EXPECT_FALSE(t[0] == 0 && t[1] == 1) << "the reference has a triangle on the edge {p, q}";
  }
  const std::string off = dir.file("mesh.off");
  io::write_off(off, P, mesh);
  CertifyOptions o;
  o.manifold = "builtin:sphere-2";
  o.points = o.complex = off;
  const Certificate c = run_certify(o);
  // Check 11 is not a claim here (no covering radius claimed): reported, its decision CERTIFIED.
  EXPECT_EQ(entry(c, CheckId::covering).decision(), Verdict::certified) << entry(c, CheckId::covering).summary;
  const CheckEntry& rd = entry(c, CheckId::restricted_delaunay);
  ASSERT_EQ(rd.verdict, Verdict::refuted) << rd.summary;
  EXPECT_EQ(rd.details["pure"], false);
  EXPECT_EQ(rd.details["lower_faces_in_no_m_simplex"], 1);
  EXPECT_EQ(rd.details["missing_simplices"], 0);  // the edge is Del_RM(P)'s fault, not the mesh's
  EXPECT_EQ(rd.details["extra_simplices"], 0);    // the triangles agree with the reference
  EXPECT_EQ(rd.details["m_simplices_equal_to_the_complex"], true);
  EXPECT_NE(rd.summary.find("triangulates nothing"), std::string::npos) << rd.summary;
  EXPECT_EQ(rd.summary.find("missing"), std::string::npos) << rd.summary;
  EXPECT_NE(rd.details["reason"].get<std::string>().find("not pure: it triangulates nothing"), std::string::npos);
  EXPECT_EQ(rd.details["m_simplices"], mesh.simplices.size());
  ASSERT_EQ(rd.witnesses.size(), 1u);
  const auto& w = rd.witnesses[0];
  EXPECT_EQ(w["kind"], "face_point");
  EXPECT_EQ(w["simplex"].get<std::vector<int>>(), (std::vector<int>{0, 1}));
  // Re-check: the centre of the enclosure is on S^2, on the plane z = 0.95, and nearer to p and q
  // than to every other point.
  std::vector<double> x;
  for (const auto& i : w["point_enclosure"])
    x.push_back((std::stod(i[0].get<std::string>()) + std::stod(i[1].get<std::string>())) / 2);
  ASSERT_EQ(x.size(), 3u);
  EXPECT_NEAR(x[0] * x[0] + x[1] * x[1] + x[2] * x[2], 1, 1e-9);
  EXPECT_NEAR(x[2], 0.95, 1e-9);
  auto d2 = [&](std::size_t q) {
    double d = 0;
    for (int k = 0; k < 3; ++k) d += (x[k] - P.point(q)[k]) * (x[k] - P.point(q)[k]);
    return d;
  };
  for (std::size_t q = 2; q < P.size(); ++q) EXPECT_GT(d2(q), d2(0) + 1e-3) << q;
}

// Issue 11, item 5: a surface mesher's vertices are found by bisection, so they lie only NEAR M.
// Simulated here: each vertex is the 12th bisection midpoint of F(t d) = 0 on a ray t d (d a
// Fibonacci direction, t in [1/2, 2]), so |t - 1| <= 3.7e-4 and no vertex is on the sphere (the
// midpoints are dyadic, 1 is not reached). The mesh is Del_RM of those vertices as computed by
// the independent reference (CGAL's 3D Delaunay + exact Sturm counting, tests only). The OFF file
// is claimed restricted (the default for OFF): accepted, checks that need T_p M not computed,
// Del_RM certified equal to it; a dropped triangle is refuted with its restricted Voronoi vertex;
// the same points without a restricted claim, or with a claim about Del_TM, are not certified.
TEST(RestrictedChecks, MeshVerticesOffTheSurfaceAreAcceptedForARestrictedClaim) {
  TempDir dir("restricted-off-M");
  const io::PointSet D = fibonacci_sphere(150);
  io::PointSet P;
  P.dimension = 3;
  for (std::size_t i = 0; i < D.size(); ++i) {
    double lo = 0.5, hi = 2, t = 0;
    for (int it = 0; it < 12; ++it) {
      t = (lo + hi) / 2;
      (t * t > 1 ? hi : lo) = t;  // F(t d) = t^2 - 1 (|d| ~ 1): the sign picks the half
    }
    const std::vector<double> x{t * D.point(i)[0], t * D.point(i)[1], t * D.point(i)[2]};
    P.push_back(x);
  }
  const io::ManifoldSpec spec = io::read_spec("builtin:sphere-2");
  const reference::RestrictedDelaunayReference ref =
      reference::restricted_delaunay_reference(P, reference::surface_equation(spec));
  ASSERT_TRUE(ref.decided());
  io::Complex mesh;
  mesh.num_vertices = P.size();
  for (const auto& t : ref.triangles())
    mesh.simplices.push_back({static_cast<int>(t[0]), static_cast<int>(t[1]), static_cast<int>(t[2])});
  ASSERT_EQ(mesh.simplices.size(), 2 * 150u - 4);
  const std::string off = dir.file("mesh.off");
  io::write_off(off, P, mesh);

  CertifyOptions o;
  o.manifold = "builtin:sphere-2";
  o.points = off;
  o.complex = off;
  const Certificate c = run_certify(o);
  const CheckEntry& sanity = entry(c, CheckId::input_sanity);
  EXPECT_EQ(sanity.details["off_manifold_points"], 150);
  EXPECT_LT(std::stod(sanity.margin["max_distance_to_M"]["certified_upper_bound"].get<std::string>()), 4e-4);
  EXPECT_EQ(entry(c, CheckId::restricted_delaunay).verdict, Verdict::certified)
      << entry(c, CheckId::restricted_delaunay).summary;
  EXPECT_EQ(entry(c, CheckId::covering).decision(), Verdict::certified);  // reported (not claimed), decided
  for (CheckId id : {CheckId::stars, CheckId::consistency, CheckId::power_protection, CheckId::secure_simplices,
                     CheckId::theorem, CheckId::star_radius, CheckId::tangential_equals_restricted}) {
    EXPECT_EQ(entry(c, id).verdict, Verdict::report) << entry(c, id).summary;
    EXPECT_NE(entry(c, id).summary.find("off M"), std::string::npos) << entry(c, id).summary;
  }
  EXPECT_EQ(entry(c, CheckId::topology).decision(), Verdict::certified);  // reported (not claimed), decided
  EXPECT_EQ(c.overall(), Verdict::certified);

  // A dropped triangle: refuted, the witness is its certified restricted Voronoi vertex.
  io::Complex dropped = mesh;
  const std::vector<int> gone = dropped.simplices[11];
  dropped.simplices.erase(dropped.simplices.begin() + 11);
  const std::string off2 = dir.file("dropped.off");
  io::write_off(off2, P, dropped);
  o.points = o.complex = off2;
  const Certificate d = run_certify(o);
  const CheckEntry& dd = entry(d, CheckId::restricted_delaunay);
  ASSERT_EQ(dd.verdict, Verdict::refuted);
  EXPECT_EQ(dd.witnesses[0]["simplex"].get<std::vector<int>>(), gone);
  EXPECT_EQ(dd.witnesses[0]["kind"], "restricted_voronoi_vertex");

  // A claim about Del_TM (star_radius) cannot be decided without tangent spaces: UNDECIDED.
  o.points = o.complex = off;
  o.claims = dir.file("claims.json");
  write_text(o.claims, R"({"format": "delcert-claims v2", "star_radius": "1"})");
  const Certificate u = run_certify(o);
  EXPECT_EQ(entry(u, CheckId::star_radius).verdict, Verdict::undecided);
  EXPECT_EQ(u.overall(), Verdict::undecided);
  o.claims.clear();

  // Where T_p M is needed (audit mode; a complex claimed tangential) the points are refused.
  for (const bool audit : {true, false}) {
    CertifyOptions t = o;
    if (audit) t.complex.clear();
    else t.kind = ComplexKind::tangential;
    try {
      run_certify(t);
      ADD_FAILURE() << "points off M accepted for Del_TM (audit " << audit << ")";
    } catch (const io::InputError& e) {
      EXPECT_NE(std::string(e.what()).find("--kind restricted"), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace delcert::certify::test
