// Check 7 (secure simplices): reusing the star analysis' enclosures of the tangent basis gives
// exactly the same answers as recomputing the exact tangent space, including on the exact
// fallback path (an interval comparison that cannot decide an exact equality).
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <array>
#include <cmath>

#include "exact/number_types.hpp"
#include "tests/certify/support.hpp"

namespace delcert::certify::test {
namespace {

// p = (0, 0, 1) (index 0) and four points at 0.1 from it in the plane z = 1 (1: +x, 2: +y, 3: -x, 4: -y).
io::PointSet north_pole_and_four() {
  io::PointSet P;
  P.dimension = 3;
  P.push_back(std::vector<double>{0, 0, 1});
  P.push_back(std::vector<double>{0.1, 0, 1});
  P.push_back(std::vector<double>{0, 0.1, 1});
  P.push_back(std::vector<double>{-0.1, 0, 1});
  P.push_back(std::vector<double>{0, -0.1, 1});
  return P;
}

// The star settings of check 7 on the unit sphere for the points P (kept here: the grid and the
// settings point to them).
struct OnSphere {
  io::PointSet P;
  io::ManifoldSpec spec = io::read_spec("builtin:sphere-2");
  exact::ImplicitSystem system{spec.equations, spec.ambient_dimension};
  detail::PointGrid grid;
  StarSettings S;
  explicit OnSphere(io::PointSet points)
      : P(std::move(points)), grid(P, 2), S{&P, &system, &grid, 2, std::nullopt, std::nullopt} {}
};

TEST(SecureSimplices, EnclosuresFromTheStarAnalysisGiveTheSameAnswersAndFallBackExactly) {
  // At p = (0, 0, 1) on the unit sphere the exact tangent basis is U = (2 e_x, 2 e_y), so the
  // projected squared distance from p to q1 = (0.1, 0, 1) is exactly 0.1^2 (the double 0.1),
  // a rational that the interval evaluation encloses but cannot compare exactly with
  // shortest^2 = 0.1^2: the cell {p, q1, q2} needs the exact fallback, whose answer is that the
  // edge is not shorter than mu0 eps (equality).
  OnSphere w(north_pole_and_four());
  const StarSettings& S = w.S;
  exact::FilterContext ctx;
  StarReport star = analyse_star(S, 0, nullptr, ctx);
  ASSERT_EQ(star.basis_enclosure.size(), 6u);
  ASSERT_EQ(star.gram_enclosure.size(), 4u);
  std::vector<Simplex> cells = {{0, 1, 2}, {0, 2, 3}, {0, 3, 4}, {0, 1, 4}};
  for (const mpq_class& delta : {mpq_class(1, 1000), mpq_class(1, 2)}) {
    SecureParams sp{mpq_class(1), delta, mpq_class(1, 100), exact::to_rational(0.1), {}, {}, {}, {}};
    sp.prepare();
    SecureReport fresh = analyse_secure(S, 0, cells, sp, ctx);
    SecureReport reused = analyse_secure(S, 0, cells, sp, ctx, &star);
    EXPECT_GT(fresh.exact_fallbacks, 0);
    EXPECT_EQ(fresh.secure, reused.secure);
    EXPECT_EQ(fresh.insecure, reused.insecure);
    EXPECT_EQ(fresh.undecided, reused.undecided);
    EXPECT_EQ(fresh.exact_fallbacks, reused.exact_fallbacks);
    EXPECT_EQ(fresh.failures, reused.failures);
    EXPECT_EQ(fresh.secure + fresh.insecure, 4);
    if (delta == mpq_class(1, 1000)) {
      EXPECT_EQ(fresh.secure, 4);  // every edge is exactly 0.1 or longer: nothing too short
    } else {
      EXPECT_EQ(fresh.insecure, 4);  // delta = 1/2: the neighbours are not delta-protected
    }
  }
}

TEST(SecureSimplices, APointFarAlongTheNormalButProjectedInsideIsTested) {
  // W = B(p, 5 eps) may hold points far from p along the normal whose projection onto T_p falls
  // inside a cell's circle: with eps = 1 the antipode q = (0, 0, -1) of p = (0, 0, 1) is in W
  // and projects onto p itself, at distance r from every projected circumcentre: no cell is
  // delta-protected, and q is the named point. Check 7 scans only the box of W where a point can
  // project within 2 r_max + delta; the box must reach down the normal to hold q.
  io::PointSet six = north_pole_and_four();
  six.push_back(std::vector<double>{0, 0, -1});
  OnSphere w(six);
  const StarSettings& S = w.S;
  exact::FilterContext ctx;
  StarReport star = analyse_star(S, 0, nullptr, ctx);
  std::vector<Simplex> cells = {{0, 1, 2}, {0, 2, 3}, {0, 3, 4}, {0, 1, 4}};
  SecureParams sp{mpq_class(1), mpq_class(1, 1000), mpq_class(1, 100), exact::to_rational(0.1), {}, {}, {}, {}};
  sp.prepare();
  for (bool exact_only : {false, true}) {
    exact::FilterContext c2;
    c2.force_exact = exact_only;
    for (const StarReport* report : std::array<const StarReport*, 2>{nullptr, &star}) {
      SecureReport R = analyse_secure(S, 0, cells, sp, c2, report);
      EXPECT_EQ(R.secure, 0);
      ASSERT_EQ(R.insecure, 4);
      for (const auto& [s, why] : R.failures) EXPECT_EQ(why, "not delta-protected (point 5)");
    }
  }
  // Without the antipode the same cells are secure (the test above).
  OnSphere five(north_pole_and_four());
  EXPECT_EQ(analyse_secure(five.S, 0, cells, sp, ctx).secure, 4);
}

TEST(SecureSimplices, TheLargestCellSetsHowFarPointsAreTested) {
  // Check 7 tests only the points projected within 2 r_max + delta of p, r_max the largest
  // projected circumradius of the star. At p = (0, 0, 1): a small cell {p, q1, q2} (r ~ 0.07)
  // and a large one {p, q3, q4} (r ~ 0.21, centre ~ (-0.15, -0.15)); d = (-0.2, -0.2, .) projects
  // at ~0.28 from p, beyond 2 r + delta of the small cell but inside the large cell's circle: the
  // large cell is not delta-protected because of d, the small one is secure.
  io::PointSet P;
  P.dimension = 3;
  auto on_sphere = [&](double x, double y) { P.push_back(std::vector<double>{x, y, std::sqrt(1 - x * x - y * y)}); };
  P.push_back(std::vector<double>{0, 0, 1});
  on_sphere(0.1, 0), on_sphere(0, 0.1), on_sphere(-0.3, 0), on_sphere(0, -0.3), on_sphere(-0.2, -0.2);
  OnSphere w(P);
  SecureParams sp{mpq_class(1), mpq_class(1, 1000), mpq_class(1, 100), exact::to_rational(0.1), {}, {}, {}, {}};
  sp.prepare();
  for (const std::vector<Simplex>& cells : {std::vector<Simplex>{{0, 1, 2}, {0, 3, 4}}, std::vector<Simplex>{{0, 3, 4}, {0, 1, 2}}}) {
    exact::FilterContext ctx;
    SecureReport R = analyse_secure(w.S, 0, cells, sp, ctx);
    EXPECT_EQ(R.secure, 1);
    ASSERT_EQ(R.insecure, 1);
    EXPECT_EQ(R.failures[0].first, (Simplex{0, 3, 4}));
    EXPECT_EQ(R.failures[0].second, "not delta-protected (point 5)");
  }
}

// A Fibonacci sample of the unit sphere (its poles are a little irregular).
io::PointSet fibonacci_points(int n) {
  io::PointSet P;
  P.dimension = 3;
  const double g = M_PI * (3 - std::sqrt(5.0));
  for (int i = 0; i < n; ++i) {
    const double z = 1 - 2 * (i + 0.5) / n, r = std::sqrt(1 - z * z), a = g * i;
    P.push_back(std::vector<double>{r * std::cos(a), r * std::sin(a), z});
  }
  return P;
}

struct SecureRun {
  TempDir dir{"secure"};
  CertifyOptions o;
  SecureRun(const io::PointSet& P, bool claim, const std::string& manifold = "builtin:sphere-2") {
    write_text(dir.file("points.txt"), io::format_points(P));
    write_text(dir.file("claims.json"), claim ? "{\"format\": \"delcert-claims v2\", \"secure\": true}\n"
                                              : "{\"format\": \"delcert-claims v2\"}\n");
    o.manifold = manifold;
    o.points = dir.file("points.txt");
    o.claims = dir.file("claims.json");
    o.threads = 2;
  }
};

TEST(SecureSimplices, ClaimedIsDecidedWithTheCertifiedCoveringRadiusAndTheWitnessesRecheck) {
  const io::PointSet P = fibonacci_points(200);
  SecureRun run(P, true);
  const Certificate c = run_certify(run.o);
  ASSERT_EQ(check(c, CheckId::covering).verdict, Verdict::certified);
  const CheckEntry& e = check(c, CheckId::secure_simplices);
  ASSERT_EQ(e.verdict, Verdict::refuted) << e.summary;
  EXPECT_EQ(c.overall(), Verdict::refuted);
  EXPECT_TRUE(e.details["parameters"]["eps_is_a_sampling_radius"].get<bool>());
  // eps is at least the certified covering radius.
  const double eps = exact::parse_rational(e.details["parameters"]["eps"].get<std::string>()).get_d();
  EXPECT_GE(eps, std::stod(check(c, CheckId::covering).margin["covering_radius"]["certified_upper_bound"].get<std::string>()));
  // Each witness: a simplex of the star at its vertex, and for "not delta-protected (point q)",
  // q projected onto T_p lies (in doubles, with slack) within r + delta of the projected
  // circumcentre, r the projected circumradius.
  const std::string delta_text = e.details["parameters"]["delta"].get<std::string>();  // "[lo, hi]"
  const double delta = std::stod(delta_text.substr(delta_text.find(',') + 1));
  ASSERT_FALSE(e.witnesses.empty());
  int rechecked = 0;
  for (const auto& w : e.witnesses) {
    const std::vector<int> s = w["simplex"].get<std::vector<int>>();
    const int p = w["at_vertex"].get<int>();
    ASSERT_EQ(s.size(), 3u);
    EXPECT_TRUE(std::find(s.begin(), s.end(), p) != s.end());
    const std::string why = w["failed"].get<std::string>();
    const std::string tag = "not delta-protected (point ";
    if (why.rfind(tag, 0) != 0) continue;
    const int q = std::stoi(why.substr(tag.size()));
    std::array<double, 3> n{};
    double len = 0;
    for (int k = 0; k < 3; ++k) n[k] = P.point(p)[k], len += n[k] * n[k];
    for (auto& x : n) x /= std::sqrt(len);
    auto project = [&](int i) {
      std::array<double, 3> v{};
      double d = 0;
      for (int k = 0; k < 3; ++k) v[k] = P.point(i)[k] - P.point(p)[k], d += v[k] * n[k];
      for (int k = 0; k < 3; ++k) v[k] -= d * n[k];
      return v;
    };
    // Circumcentre of the projected triangle (a, b, c) in its plane.
    const auto a = project(s[0]), b = project(s[1]), cc = project(s[2]);
    std::array<double, 3> u{}, v{};
    for (int k = 0; k < 3; ++k) u[k] = b[k] - a[k], v[k] = cc[k] - a[k];
    const double uu = u[0] * u[0] + u[1] * u[1] + u[2] * u[2], vv = v[0] * v[0] + v[1] * v[1] + v[2] * v[2],
                 uv = u[0] * v[0] + u[1] * v[1] + u[2] * v[2], det = 2 * (uu * vv - uv * uv);
    const double alpha = vv * (uu - uv) / det, beta = uu * (vv - uv) / det;
    std::array<double, 3> centre{};
    for (int k = 0; k < 3; ++k) centre[k] = a[k] + alpha * u[k] + beta * v[k];
    auto dist = [&](const std::array<double, 3>& x) {
      return std::sqrt((x[0] - centre[0]) * (x[0] - centre[0]) + (x[1] - centre[1]) * (x[1] - centre[1]) +
                       (x[2] - centre[2]) * (x[2] - centre[2]));
    };
    EXPECT_LE(dist(project(q)), dist(a) + delta + 1e-9) << "simplex at " << p << ", point " << q;
    ++rechecked;
  }
  EXPECT_GT(rechecked, 0);
}

// A nearly hexagonal lattice on the Clifford torus (unit circles): rows of 13 points at 15 values
// of the second angle, every other row shifted by half a step (15/13 is within 0.1% of 2/sqrt 3),
// each angle moved by up to `jitter` / 2.
io::PointSet hexagonal_torus(double jitter) {
  Rng rng(7);
  io::PointSet P;
  P.dimension = 4;
  for (int j = 0; j < 15; ++j)
    for (int i = 0; i < 13; ++i) {
      const double a = 2 * M_PI * (i + 0.5 * (j % 2)) / 13 + jitter * (rng.uniform() - 0.5);
      const double b = 2 * M_PI * j / 15 + jitter * (rng.uniform() - 0.5);
      P.push_back(std::vector<double>{std::cos(a), std::sin(a), std::cos(b), std::sin(b)});
    }
  return P;
}

TEST(SecureSimplices, ClaimedIsCertifiedOnANearlyHexagonalTorusAndNeverOnTheExactLattice) {
  // Jittered by 1e-4: every star simplex secure with eps the certified covering radius, so check 7
  // is CERTIFIED and so is the whole certificate (the REFUTED side: the Fibonacci test above).
  SecureRun good(hexagonal_torus(1e-4), true, "builtin:clifford-torus-2");
  const Certificate c = run_certify(good.o);
  ASSERT_EQ(check(c, CheckId::covering).verdict, Verdict::certified) << check(c, CheckId::covering).summary;
  const CheckEntry& e = check(c, CheckId::secure_simplices);
  EXPECT_EQ(e.verdict, Verdict::certified) << e.summary;
  EXPECT_NE(e.summary.find("1170 of 1170"), std::string::npos) << e.summary;
  EXPECT_TRUE(e.witnesses.empty());
  const double eps = exact::parse_rational(e.details["parameters"]["eps"].get<std::string>()).get_d();
  EXPECT_GE(eps, std::stod(check(c, CheckId::covering).margin["covering_radius"]["certified_upper_bound"].get<std::string>()));
  EXPECT_EQ(c.overall(), Verdict::certified);

  // The exact lattice (15 rows of identical (x3, x4), 13 points a row) has exact ties: no positive
  // protection margin and no certified covering radius, and check 7 is not CERTIFIED.
  SecureRun exact_lattice(hexagonal_torus(0), true, "builtin:clifford-torus-2");
  const Certificate d = run_certify(exact_lattice.o);
  EXPECT_NE(check(d, CheckId::covering).verdict, Verdict::certified);
  EXPECT_EQ(check(d, CheckId::secure_simplices).verdict, Verdict::undecided) << check(d, CheckId::secure_simplices).summary;
  EXPECT_NE(d.overall(), Verdict::certified);
}

TEST(SecureSimplices, UnclaimedIsAReportAndWithoutACertifiedCoveringRadiusUndecided) {
  const io::PointSet P = fibonacci_points(200);
  SecureRun unclaimed(P, false);
  const Certificate c = run_certify(unclaimed.o);
  const CheckEntry& e = check(c, CheckId::secure_simplices);
  EXPECT_EQ(e.verdict, Verdict::report);
  EXPECT_EQ(e.details["decision"], "REFUTED");
  EXPECT_EQ(c.overall(), Verdict::certified);  // the rest of the certificate is unaffected

  SecureRun claimed(P, true);
  claimed.o.skip_restricted = true;  // no check 11: eps is only a star-radius bound
  const Certificate d = run_certify(claimed.o);
  const CheckEntry& f = check(d, CheckId::secure_simplices);
  EXPECT_EQ(f.verdict, Verdict::undecided) << f.summary;
  EXPECT_FALSE(f.details["parameters"]["eps_is_a_sampling_radius"].get<bool>());
  EXPECT_NE(f.details["reason"].get<std::string>().find("check 11"), std::string::npos);

  // The claim is about the complex under test; check 7 evaluates the stars of Del_TM(P), so a
  // complex given as restricted is not decided by it.
  SecureRun restricted(P, true);
  write_text(restricted.dir.file("complex.txt"), io::format_complex(audit("builtin:sphere-2", P).complex));
  restricted.o.complex = restricted.dir.file("complex.txt");
  restricted.o.kind = ComplexKind::restricted;
  const Certificate g = run_certify(restricted.o);
  EXPECT_EQ(check(g, CheckId::secure_simplices).verdict, Verdict::undecided);
  EXPECT_EQ(check(g, CheckId::restricted_delaunay).verdict, Verdict::certified);
}

}  // namespace
}  // namespace delcert::certify::test
