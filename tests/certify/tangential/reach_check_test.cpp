// Refuting a declared reach by Federer's inequality (certify/reach_check.hpp), on the flat torus
// S^1 x S^1 x {0} in R^6 (codimension 4, reach exactly 1). For two points x, y of it at angles
// differing by (α, β), y - x has normal part (cos α - 1, ., cos β - 1, ., 0, 0) in the circles' radial
// directions: dist(y - x, T_x M)^2 = (1 - cos α)^2 + (1 - cos β)^2 and |y - x|^2 = 2 (1 - cos α) +
// 2 (1 - cos β). With u = 1 - cos α, v = 1 - cos β, Federer's bound for reach τ reads
// sqrt(u^2 + v^2) <= (u + v) / τ: true for τ = 1 (with equality along one circle, v = 0: the
// sharpest possible test of soundness), false for τ = 100 for every pair, and for τ = 3/2 along one
// circle (u <= 2u/3 fails).
#include "certify/tangential/reach_check.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "certify/certify.hpp"
#include "certify/detail/grid.hpp"
#include "io/spec.hpp"
#include "tests/certify/support.hpp"

namespace delcert::certify {
namespace {

using namespace test;

// n x n points at angles 2π a / n, 2π b / n, index a n + b.
io::PointSet torus_points(int n) {
  io::PointSet P;
  P.dimension = 6;
  for (int a = 0; a < n; ++a)
    for (int b = 0; b < n; ++b) {
      const double s = 2 * M_PI * a / n, t = 2 * M_PI * b / n;
      const double x[6] = {std::cos(s), std::sin(s), std::cos(t), std::sin(t), 0, 0};
      P.push_back(x);
    }
  return P;
}

std::optional<ReachWitness> refute(const std::string& spec_file, const io::PointSet& P, double radius, int threads = 1) {
  const io::ManifoldSpec spec = io::read_spec(fixture("certify/" + spec_file));
  const exact::ImplicitSystem system(spec.equations, spec.ambient_dimension);
  const detail::PointGrid grid(P, spec.intrinsic_dimension);
  return refute_declared_reach(system, nullptr, P, grid, *spec.reach, radius, threads);
}

TEST(ReachCheck, FalseReachIsRefutedByTheFirstPair) {
  const io::PointSet P = torus_points(12);
  for (int threads : {1, 2}) {
    const auto w = refute("torus-2-in-r6-false-reach.json", P, 0.6, threads);
    ASSERT_TRUE(w);
    // Point 0's nearest neighbour of lowest index is point 1 (β = π/6), at distance 2 sin(π/12) < 0.6.
    EXPECT_EQ(w->i, 0);
    EXPECT_EQ(w->j, 1);
    EXPECT_EQ(w->tangent_at, 0);
    const double v = 1 - std::cos(M_PI / 6);  // the exact normal distance (about 0.134)
    EXPECT_LE(w->normal_distance_lower, v * (1 + 1e-9));
    EXPECT_GE(w->normal_distance_lower, v * (1 - 1e-9));
    EXPECT_GE(w->squared_distance_upper, 2 * v * (1 - 1e-9));
    EXPECT_GE(w->federer_bound_upper, 2 * v / 200 * (1 - 1e-9));
    EXPECT_GT(w->normal_distance_lower, w->federer_bound_upper);
  }
}

// The true reach: never refuted, whatever the radius (all pairs, including those along one circle
// where Federer's inequality is an equality).
TEST(ReachCheck, TrueReachIsNotRefuted) {
  for (int n : {6, 12, 25}) {
    const io::PointSet P = torus_points(n);
    EXPECT_FALSE(refute("torus-2-in-r6.json", P, 10.0)) << n;
    EXPECT_FALSE(refute("torus-2-in-r6.json", P, 10.0, 2)) << n;
  }
}

// Declared 3/2 (true 1): refuted along one circle; a radius too small to see any pair refutes nothing.
TEST(ReachCheck, SlightlyFalseReachAndRadius) {
  const io::PointSet P = torus_points(12);
  const io::ManifoldSpec spec = io::read_spec(fixture("certify/torus-2-in-r6.json"));
  const exact::ImplicitSystem system(spec.equations, 6);
  const detail::PointGrid grid(P, 2);
  io::ReachSpec reach = *spec.reach;
  reach.text = "3/2", reach.squared = mpq_class(9, 4), reach.exact = false;
  const auto w = refute_declared_reach(system, nullptr, P, grid, reach, 0.6, 1);
  ASSERT_TRUE(w);
  EXPECT_EQ(w->i, 0);
  EXPECT_EQ(w->j, 1);
  EXPECT_FALSE(refute_declared_reach(system, nullptr, P, grid, reach, 0.1, 1));
}

// The driver: check 1 REFUTED with the witness, and a line in the text output.
TEST(ReachCheck, DriverRefutesCheckOne) {
  TempDir dir("reach");
  const io::PointSet P = torus_points(12);
  std::ostringstream text;
  text.precision(17);
  text << "delcert-points v1\n6 " << P.size() << "\n";
  for (std::size_t i = 0; i < P.size(); ++i)
    for (int v = 0; v < 6; ++v) text << P.point(i)[v] << (v == 5 ? "\n" : " ");
  write_text(dir.file("points.txt"), text.str());
  CertifyOptions o;
  o.points = dir.file("points.txt");
  o.skip_restricted = true;
  o.manifold = fixture("certify/torus-2-in-r6-false-reach.json");
  const Certificate c = run_certify(o);
  const CheckEntry& e = check(c, CheckId::input_sanity);
  EXPECT_EQ(e.verdict, Verdict::refuted);
  ASSERT_FALSE(e.witnesses.empty());
  EXPECT_EQ(e.witnesses[0]["kind"], "declared_reach_is_false");
  EXPECT_EQ(e.witnesses[0]["points"], nlohmann::json::array({0, 1}));
  EXPECT_EQ(e.witnesses[0]["declared_reach"], "100");
  EXPECT_NE(c.to_text(false).find("DECLARED REACH 100 IS FALSE"), std::string::npos);
  EXPECT_EQ(c.overall(), Verdict::refuted);
  o.manifold = fixture("certify/torus-2-in-r6.json");
  EXPECT_NE(check(run_certify(o), CheckId::input_sanity).verdict, Verdict::refuted);
}

}  // namespace
}  // namespace delcert::certify
