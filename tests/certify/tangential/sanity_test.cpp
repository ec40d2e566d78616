// Check 1 (input sanity): points must be certifiably near M, with a full-rank Jacobian there;
// a small residual alone is not accepted.
#include "certify/tangential/sanity.hpp"

#include "certify/detail/grid.hpp"

#include "exact/enclosure.hpp"
#include "exact/number_types.hpp"
#include "tests/certify/support.hpp"

namespace delcert::certify::test {
namespace {

double upper_bound(const CheckEntry& e) {
  return std::stod(e.margin["max_distance_to_M"]["certified_upper_bound"].get<std::string>());
}

CheckEntry sanity(const std::string& spec, const io::PointSet& P, int threads = 1) {
  return check_input_sanity(io::read_spec(spec), P, {}, "points.txt", false, threads).entry;
}

// The sphere written as (|x|^2 - 1)^2 = 0 has residuals ~1e-32 at the rotated octahedron's
// vertices (none exactly on S^2, so J_F(p) != 0 and the exact rank test at p passes), but its
// Jacobian vanishes on M: before the distance certificate this input was CERTIFIED.
TEST(Sanity, SquaredSphereIsNeverCertified) {
  CertifyOptions o;
  o.manifold = fixture("certify/spec-squared-sphere.json");
  o.points = fixture("certify/squared-sphere-points.txt");
  for (std::string complex : {fixture("certify/octahedron.complex"), std::string()}) {
    SCOPED_TRACE(complex);
    o.complex = complex;
    try {
      Certificate c = run_certify(o);
      ADD_FAILURE() << "a certificate was produced, verdict " << c.to_text(false).substr(0, 400);
    } catch (const io::InputError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find(o.points + ":5:"), std::string::npos) << what;  // point 0, line 5
      EXPECT_NE(what.find("point 0: no point of M could be certified"), std::string::npos) << what;
      EXPECT_NE(what.find("rank-deficient"), std::string::npos) << what;
    }
  }
  // The same points on the sphere written properly are fine, and within rounding of it.
  o.manifold = "builtin:sphere-2";
  o.complex = fixture("certify/octahedron.complex");
  Certificate c = run_certify(o);
  EXPECT_EQ(c.overall(), Verdict::certified) << c.to_text(false);
  EXPECT_LE(upper_bound(check(c, CheckId::input_sanity)), 1e-15);
}

TEST(Sanity, SquaredSphereExitsWithStatus2AndNoCertificate) {
  TempDir dir("squared");
  const std::string out = dir.file("never.json"), points = fixture("certify/squared-sphere-points.txt");
  RunResult r = run(binary() + " --manifold '" + fixture("certify/spec-squared-sphere.json") + "' --points '" + points +
                        "' --complex '" + fixture("certify/octahedron.complex") + "' --out '" + out + "'",
                    dir);
  EXPECT_EQ(r.exit_code, 2) << r.out << r.err;
  EXPECT_NE(r.err.find(points + ":5: point 0: no point of M could be certified"), std::string::npos) << r.err;
  EXPECT_EQ(r.out.find("verdict:"), std::string::npos) << r.out;
  EXPECT_FALSE(std::filesystem::exists(out));
}

// On the squared sphere, (1, 0, 0) lies on M with J_F(p) = 0 exactly: the Krawczyk test fails
// (so it cannot vouch for the rank at p) and the exact rank refuses the point by name.
TEST(Sanity, ExactlyRankDeficientJacobianAtThePointIsRefused) {
  const io::PointSet P = make_points(3, {{1, 0, 0}, {0, 1, 0}});
  try {
    sanity(fixture("certify/spec-squared-sphere.json"), P);
    ADD_FAILURE() << "accepted a point where J_F vanishes";
  } catch (const io::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("the Jacobian of F is rank-deficient at point 0"), std::string::npos) << e.what();
  }
}

TEST(Sanity, OctahedronVerticesAreExactlyOnTheSphere) {
  io::PointSet P = make_points(3, {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}});
  CheckEntry e = sanity("builtin:sphere-2", P);
  EXPECT_LE(upper_bound(e), 1e-15);
  EXPECT_GE(upper_bound(e), 0.0);
  EXPECT_EQ(e.verdict, Verdict::certified);
}

TEST(Sanity, PointMovedAlongTheNormalHasACertifiedDistance) {
  // Point 3 is (0.6, 0.8, 0) moved outward by about 1e-6 (exactly |p| - 1, enclosed below).
  const double s = 1 + 1e-6;
  io::PointSet P = make_points(3, {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0.6 * s, 0.8 * s, 0}, {0, 0, 1}, {0, 0, -1}});
  // |F(p)| = |p|^2 - 1 ~ 2e-6 exceeds the default tolerance 1e-9: raise it in a spec copy.
  io::ManifoldSpec spec = io::read_spec("builtin:sphere-2");
  spec.residual_tolerance = mpq_class(1, 1000);
  CheckEntry e = check_input_sanity(spec, P, {}, "points.txt", false, 2).entry;
  const double bound = upper_bound(e);
  mpq_class n2 = 0;
  for (double c : P.point(3)) n2 += exact::to_rational(c) * exact::to_rational(c);
  const exact::Enclosure truth = sqrt(exact::Enclosure(n2)) - exact::Enclosure(1L);
  EXPECT_GE(bound, truth.lower());  // contains the true distance (about 1e-6)
  EXPECT_GE(bound, 0.999999e-6);
  EXPECT_LE(bound, truth.upper() + 1e-15);  // and not much more
  EXPECT_EQ(e.margin["max_distance_to_M"]["at_point"], 3);
  // The same point with the squared equation is refused, whatever the tolerance.
  io::ManifoldSpec squared = io::read_spec(fixture("certify/spec-squared-sphere.json"));
  squared.residual_tolerance = mpq_class(1, 1000);
  EXPECT_THROW(check_input_sanity(squared, P, {}, "points.txt", false, 1), io::InputError);
  // Accepting points off M (a restricted claim) does not relax the distance certificate.
  EXPECT_THROW(check_input_sanity(squared, P, {}, "points.txt", true, 1), io::InputError);
}

// Points beyond the residual tolerance: refused unless accepted (a complex claimed restricted,
// issue 11 item 5); accepted, they are listed and their distance to M is still certified.
TEST(Sanity, PointsOffMAreListedWhenAccepted) {
  const double s = 1 + 1e-4;  // |F| ~ 2e-4 > 1e-9 at points 0 and 4
  io::PointSet P = make_points(3, {{s, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1 / s}, {0, 0, -1}});
  const io::ManifoldSpec spec = io::read_spec("builtin:sphere-2");
  try {
    check_input_sanity(spec, P, {3, 4, 5, 6, 7, 8}, "points.txt", false, 1);
    ADD_FAILURE() << "a point off M was accepted";
  } catch (const io::InputError& e) {
    // Said at once, with how many, how far (the largest certified distance bound and its point) and what to do.
    const std::string what = e.what();
    EXPECT_EQ(what.find("points.txt:3: the points are not on M: 2 of 6 point(s) off M beyond the residual tolerance"), 0u) << what;
    EXPECT_NE(what.find("of M (certified upper bound; the largest: point 0)"), std::string::npos) << what;
    EXPECT_NE(what.find("--kind restricted"), std::string::npos) << what;
  }
  const SanityResult r = check_input_sanity(spec, P, {}, "points.txt", true, 2);
  EXPECT_EQ(r.off_manifold, (std::vector<int>{0, 4}));
  EXPECT_EQ(r.entry.details["off_manifold_points"], 2);
  EXPECT_EQ(r.entry.details["first_off_manifold_point"], 0);
  EXPECT_GE(upper_bound(r.entry), 1e-4);  // |p| - 1 at point 0
  EXPECT_LE(upper_bound(r.entry), 1e-4 + 1e-12);
  EXPECT_EQ(r.entry.summary.find("the points are not on M: 2 of 6 point(s) off M"), 0u) << r.entry.summary;
  EXPECT_NE(r.entry.summary.find("(certified upper bound; the largest: point 0)"), std::string::npos) << r.entry.summary;
  // Within the tolerance nothing is listed.
  EXPECT_TRUE(check_input_sanity(spec, make_points(3, {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}), {}, "p", true, 1).off_manifold.empty());
}

TEST(Sanity, So3PointsNearTheGroupAndTheWrongComponent) {
  const double e = 1e-7;
  io::ManifoldSpec spec = io::read_spec("builtin:so3");
  spec.residual_tolerance = mpq_class(1, 1000);
  // diag(1 + e, 1, 1) is at distance (1 + e) - 1 from SO(3) (its polar factor is I).
  io::PointSet P = make_points(9, {{1, 0, 0, 0, 1, 0, 0, 0, 1}, {0, 1, 0, -1, 0, 0, 0, 0, 1}, {1 + e, 0, 0, 0, 1, 0, 0, 0, 1}});
  CheckEntry c = check_input_sanity(spec, P, {}, "points.txt", false, 1).entry;
  EXPECT_GE(upper_bound(c), P.point(2)[0] - 1);
  EXPECT_LE(upper_bound(c), P.point(2)[0] - 1 + 1e-14);
  EXPECT_EQ(c.margin["max_distance_to_M"]["at_point"], 2);
  io::PointSet W = make_points(9, {{1, 0, 0, 0, 1, 0, 0, 0, 1}, {-1, 0, 0, 0, 1, 0, 0, 0, 1}});
  EXPECT_THROW(check_input_sanity(spec, W, {}, "points.txt", false, 1), io::InputError);
  EXPECT_THROW(check_input_sanity(spec, W, {}, "points.txt", true, 1), io::InputError);  // wrong component, still
}

TEST(Sanity, BuiltinSamplesPassWithTinyDistances) {
  struct C {
    std::string spec;
    io::PointSet P;
  };
  for (const C& c : {C{"builtin:sphere-2", fibonacci_sphere(200)}, C{"builtin:sphere-3", spread_sphere(4, 60, 0.45, 11)},
                     C{"builtin:clifford-torus-2", torus2_lattice(6, 7)}, C{"builtin:clifford-torus-3", torus3_bcc(3)},
                     C{"builtin:torus-of-revolution", torus_of_revolution(12, 6)}}) {
    SCOPED_TRACE(c.spec);
    CheckEntry e = sanity(c.spec, c.P, 2);
    EXPECT_LE(upper_bound(e), 1e-14);
  }
}


// Check 2 on 5000 points of a jittered grid (three blocks of the parallel passes), with the
// closest distance planted twice, at pairs (4100, 4101) and (2500, 4999), and a pair barely
// farther at (7, 8): the exact minimum, the smallest pair among ties, and the same answer and
// filter counts for any thread count.
TEST(Sanity, SparsityFindsTheSmallestTiedPairOnAnyThreadCount) {
  std::vector<std::vector<double>> pts;
  std::uint64_t state = 99;
  auto jitter = [&] { return double((state = state * 6364136223846793005ull + 1442695040888963407ull) >> 40) / double(1ull << 24) * 0.2; };
  for (int a = 0; a < 50; ++a)
    for (int b = 0; b < 100; ++b) pts.push_back({a + jitter(), b + jitter(), jitter()});
  const double h = 0x1p-10;
  pts[4101] = {pts[4100][0] + h, pts[4100][1], pts[4100][2]};
  pts[4999] = {pts[2500][0], pts[2500][1] + h, pts[2500][2]};
  pts[7] = {0.5, 7.5, 0.5};  // every sum below is exact (the coordinates' ulps divide 2^-40)
  pts[8] = {0.5, 7.5, 0.5 + h + 0x1p-40};
  const io::PointSet P = make_points(3, pts);
  const detail::PointGrid grid(P, 2);
  std::optional<exact::FilterStats> first;
  for (int threads : {1, 2, 3}) {
    exact::FilterContext ctx;
    const SparsityResult R = check_sparsity(P, grid, nullptr, ctx, threads);
    EXPECT_EQ(R.min_squared, mpq_class(h) * mpq_class(h)) << threads;
    EXPECT_EQ(R.i, 2500) << threads;
    EXPECT_EQ(R.j, 4999) << threads;
    if (!first) first = ctx.stats;
    EXPECT_EQ(ctx.stats.total_calls(), first->total_calls()) << threads;
    EXPECT_EQ(ctx.stats.total_failures(), first->total_failures()) << threads;
  }
}

}  // namespace
}  // namespace delcert::certify::test
