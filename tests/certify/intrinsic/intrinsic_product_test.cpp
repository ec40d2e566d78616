// Del_M on products of round spheres by geodesic Voronoi cells (certify/intrinsic_product.cpp,
// certify/detail/param_cell.cpp GEODESIC): S^2 x S^1 (the product no other engine handles), and
// cross-checks against the two engines built on other arguments (the sphere's hull engine, the
// flat torus's lattice engine in intrinsic_torus_test.cpp), ties, mutants and witnesses re-checked
// in long double by the test's own geodesic distance.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "certify/certify.hpp"
#include "certify/detail/grid.hpp"
#include "certify/intrinsic/intrinsic.hpp"
#include "io/points.hpp"
#include "io/spec.hpp"
#include "tests/certify/support.hpp"

namespace delcert::certify {
namespace {

using Simplices = std::set<std::vector<int>>;

// S^2 (radius 1, x1..x3) x S^1 (radius `circle`, x4, x5).
io::ManifoldSpec s2xs1(const std::string& circle) {
  return io::parse_spec(R"({"format": "delcert-manifold v1", "intrinsic_dimension": 3, "ambient_dimension": 5,
    "bounding_box": [["-3", "3"], ["-3", "3"], ["-3", "3"], ["-3", "3"], ["-3", "3"]],
    "equations": ["x1^2 + x2^2 + x3^2 - 1", "x4^2 + x5^2 - )" + circle + "^2\"]," +
                            R"("metric": {"type": "product", "factors": [
      {"type": "sphere", "coordinates": [1, 2, 3], "radius": "1"},
      {"type": "sphere", "coordinates": [4, 5], "radius": ")" + circle + R"("}]}})",
                        "s2xs1.json");
}

// Dart throwing on S^2 x S^1(R): uniform on each factor (z and the angle uniform on S^2), kept at
// ambient distance >= d from every kept point.
io::PointSet s2xs1_sample(double R, int n, double d, std::uint64_t seed) {
  test::Rng rng(seed);
  std::vector<std::vector<double>> pts;
  for (int tries = 0; tries < 400000 && static_cast<int>(pts.size()) < n; ++tries) {
    const double z = 2 * rng.uniform() - 1, a = 2 * M_PI * rng.uniform(), b = 2 * M_PI * rng.uniform();
    const double s = std::sqrt(1 - z * z);
    const std::vector<double> x{s * std::cos(a), s * std::sin(a), z, R * std::cos(b), R * std::sin(b)};
    bool ok = true;
    for (const auto& q : pts) {
      double e = 0;
      for (int k = 0; k < 5; ++k) e += (x[k] - q[k]) * (x[k] - q[k]);
      ok = ok && e >= d * d;
    }
    if (ok) pts.push_back(x);
  }
  return test::make_points(5, pts);
}

// The test's own d_M^2 on S^2 x S^1(R) in long double, from the points' projections.
long double geodesic2(const std::vector<long double>& x, std::span<const double> q, long double R) {
  auto angle = [](const long double* u, const double* v, int k) {
    long double dot = 0, nu = 0, nv = 0;
    for (int i = 0; i < k; ++i) dot += u[i] * v[i], nu += u[i] * u[i], nv += (long double)v[i] * v[i];
    return std::acos(std::clamp(dot / std::sqrt(nu * nv), -1.0L, 1.0L));
  };
  const long double a = angle(x.data(), q.data(), 3), b = angle(x.data() + 3, q.data() + 3, 2);
  return a * a + R * R * b * b;
}

// Every (m-1)-face in exactly two m-simplices, every point a vertex, and chi = sum (-1)^k f_k.
void expect_closed_pseudomanifold(const Simplices& S, std::size_t n, int m, int chi) {
  std::map<std::vector<int>, int> facets;
  std::vector<std::set<std::vector<int>>> faces(m + 1);
  std::set<int> used;
  for (const auto& s : S) {
    for (int mask = 1; mask < (1 << (m + 1)); ++mask) {
      std::vector<int> f;
      for (int j = 0; j <= m; ++j)
        if (mask >> j & 1) f.push_back(s[j]);
      faces[f.size() - 1].insert(f);
    }
    for (int drop = 0; drop <= m; ++drop) {
      std::vector<int> f;
      for (int j = 0; j <= m; ++j)
        if (j != drop) f.push_back(s[j]);
      ++facets[f];
    }
    used.insert(s.begin(), s.end());
  }
  for (const auto& [f, c] : facets) EXPECT_EQ(c, 2) << "a facet in " << c << " simplices";
  EXPECT_EQ(used.size(), n);
  long e = 0;
  for (int k = 0; k <= m; ++k) e += (k % 2 ? -1 : 1) * static_cast<long>(faces[k].size());
  EXPECT_EQ(e, chi);
}

// Del_M of P by the geodesic cells, expected complete; its m-simplices.
Simplices complete_product(const io::ManifoldSpec& spec, const io::PointSet& P, IntrinsicDelaunay* out = nullptr) {
  IntrinsicDelaunay D = test::del_m(spec, P, {});
  EXPECT_TRUE(D.computed) << D.reason;
  EXPECT_EQ(D.metric, "product");
  EXPECT_TRUE(D.complete) << D.reason;
  const Simplices S = test::simplices(D);
  if (out) *out = std::move(D);
  return S;
}

// A well-spread S^2 x S^1 sample: Del_M complete, a closed pseudomanifold with chi = 0 (a closed
// 3-manifold), every witness re-checked (the vertex equidistant from its simplex, every other point
// farther by the margin), and mutants (a vertex replaced by a neighbour) never certified, each
// rejected by completeness.
TEST(IntrinsicProduct, SphereTimesCircleCompleteAndWitnessed) {
  const long double R = 2;
  const io::PointSet P = s2xs1_sample(2, 200, 0.55, 3);
  ASSERT_GE(P.size(), 100u);
  const io::ManifoldSpec spec = s2xs1("2");
  IntrinsicDelaunay D;
  const Simplices S = complete_product(spec, P, &D);
  ASSERT_TRUE(D.complete);
  expect_closed_pseudomanifold(S, P.size(), 3, 0);
  for (const auto& s : D.simplices) {
    std::vector<long double> x;
    for (const auto& iv : s.witness.at("vertex")) x.push_back(0.5L * (iv[0].get<double>() + iv[1].get<double>()));
    const long double r2 = geodesic2(x, P.point(s.simplex[0]), R);
    for (int v : s.simplex) EXPECT_NEAR(static_cast<double>(geodesic2(x, P.point(v), R)), static_cast<double>(r2), 1e-9);
    const double margin = std::stod(s.witness.at("margin").get<std::string>());
    EXPECT_GT(margin, 0);
    for (std::size_t q = 0; q < P.size(); ++q) {
      if (std::binary_search(s.simplex.begin(), s.simplex.end(), static_cast<int>(q))) continue;
      EXPECT_GT(static_cast<double>(geodesic2(x, P.point(q), R) - r2), margin - 1e-9) << q;
    }
  }
  // Mutants: each certified simplex with one vertex replaced by the next point not in it.
  std::vector<std::vector<int>> mutants;
  int k = 0;
  for (const auto& s : S) {
    if (k++ % 17) continue;
    std::vector<int> t = s;
    int q = (t[1] + 1) % static_cast<int>(P.size());
    while (std::binary_search(s.begin(), s.end(), q)) q = (q + 1) % static_cast<int>(P.size());
    t[1] = q;
    std::sort(t.begin(), t.end());
    if (!S.count(t)) mutants.push_back(t);
  }
  ASSERT_GE(mutants.size(), 10u);
  const IntrinsicDelaunay E = test::del_m(spec, P, mutants);
  EXPECT_EQ(test::simplices(E), S);  // (the candidates do not change what is computed)
  ASSERT_EQ(E.rejected.size(), std::set<std::vector<int>>(mutants.begin(), mutants.end()).size());
  for (const auto& r : E.rejected) EXPECT_EQ(r.witness.at("by"), "completeness");
  EXPECT_TRUE(E.undecided.empty());
}

// S^2 written as a one-factor product on the coordinates (2, 3, 1) (the same sphere, so the same
// geodesic distance): computed by geodesic cells, and equal to the hull engine's Del_M
// (certify/intrinsic_sphere.cpp), which proves its own completeness from these candidates.
TEST(IntrinsicProduct, SphereAgreesWithTheHullEngine) {
  const io::PointSet P = test::spread_sphere(3, 160, 0.24, 11);
  const io::ManifoldSpec product = io::parse_spec(R"({"format": "delcert-manifold v1", "intrinsic_dimension": 2,
    "ambient_dimension": 3, "equations": ["x1^2 + x2^2 + x3^2 - 1"],
    "bounding_box": [["-2", "2"], ["-2", "2"], ["-2", "2"]],
    "metric": {"type": "product", "factors": [{"type": "sphere", "coordinates": [2, 3, 1], "radius": "1"}]}})",
                                                  "s2.json");
  const Simplices S = complete_product(product, P);
  expect_closed_pseudomanifold(S, P.size(), 2, 2);
  const IntrinsicDelaunay H = test::del_m(io::read_spec("builtin:sphere-2"), P, {S.begin(), S.end()});
  EXPECT_EQ(H.metric, "sphere");
  ASSERT_TRUE(H.complete) << H.reason;
  EXPECT_EQ(test::simplices(H), S);
}

// Exact geodesic ties are never certified: a square grid in the angles of a flat torus written
// with its circles out of coordinate order (so the geodesic cells compute it) has only degenerate
// Voronoi vertices (4 points on each empty circle).
TEST(IntrinsicProduct, SquareGridTiesNeverCertified) {
  std::vector<std::vector<double>> pts;
  for (int i = 0; i < 10; ++i)
    for (int j = 0; j < 10; ++j) {
      const double a = 2 * M_PI * i / 10, b = 2 * M_PI * j / 10;
      pts.push_back({std::cos(a), std::sin(a), std::cos(b), std::sin(b)});
    }
  const io::PointSet P = test::make_points(4, pts);
  const io::ManifoldSpec spec = io::parse_spec(R"({"format": "delcert-manifold v1", "intrinsic_dimension": 2,
    "ambient_dimension": 4, "equations": ["x1^2 + x2^2 - 1", "x3^2 + x4^2 - 1"],
    "bounding_box": [["-2", "2"], ["-2", "2"], ["-2", "2"], ["-2", "2"]],
    "metric": {"type": "product", "factors": [{"type": "sphere", "coordinates": [3, 4], "radius": "1"},
                                              {"type": "sphere", "coordinates": [1, 2], "radius": "1"}]}})",
                                               "grid.json");
  const IntrinsicDelaunay D = test::del_m(spec, P, {{0, 1, 10}, {0, 1, 11}});
  ASSERT_TRUE(D.computed) << D.reason;
  EXPECT_FALSE(D.complete);
  EXPECT_TRUE(D.simplices.empty());
  EXPECT_TRUE(D.rejected.empty());
  EXPECT_EQ(D.undecided.size(), 2u);
}

// The whole certifier on the example spec fixtures/specs/s2xs1.json (the spec a user copies):
// check 14 CERTIFIED with every m-simplex of Del_M, check 15 decided (Del_RM is computed by the
// ambient engine, Del_M by the geodesic one: whichever way it goes, with witnesses).
TEST(IntrinsicProduct, WholeCertificateOnTheExampleSpec) {
  const test::TempDir dir("s2xs1");
  CertifyOptions o;
  o.manifold = test::fixture("specs/s2xs1.json");
  o.points = dir.file("points.txt");
  io::write_points(o.points, s2xs1_sample(2, 200, 0.55, 3));
  o.threads = 2;
  const Certificate c = run_certify(o);
  const CheckEntry& im = test::check(c, CheckId::intrinsic_delaunay);
  EXPECT_EQ(im.verdict, Verdict::certified) << im.summary;
  EXPECT_NE(im.summary.find("(all of them)"), std::string::npos) << im.summary;
  const CheckEntry& eq = test::check(c, CheckId::restricted_equals_intrinsic);
  EXPECT_NE(eq.verdict, Verdict::undecided) << eq.summary;
  if (eq.verdict == Verdict::refuted) {
    EXPECT_FALSE(eq.witnesses.empty());
  }
}

// A point whose block of a factor is 0 has no projection: Del_M not computed, the point named.
TEST(IntrinsicProduct, UndefinedProjectionIsNamed) {
  io::PointSet P = s2xs1_sample(2, 30, 0.9, 5);
  const std::vector<double> zero_circle{0.6, 0.8, 0, 0, 0};
  P.push_back(zero_circle);
  const IntrinsicDelaunay D = test::del_m(s2xs1("2"), P, {});
  EXPECT_FALSE(D.computed);
  EXPECT_NE(D.reason.find("point " + std::to_string(P.size() - 1) + " is 0 in the block of factor 2"), std::string::npos)
      << D.reason;
}

}  // namespace
}  // namespace delcert::certify
