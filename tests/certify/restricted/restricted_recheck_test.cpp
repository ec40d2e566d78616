// Issue 39: points off M beyond the first balls' reach, and the independent re-check of check 12's
// refuting witnesses (certify/restricted_recheck.hpp).
#include <gtest/gtest.h>

#include <set>

#include "certify/restricted/restricted.hpp"
#include "certify/restricted/restricted_recheck.hpp"
#include "certify/tangential/sanity.hpp"
#include "io/complex.hpp"
#include "io/points.hpp"
#include "io/spec.hpp"
#include "tests/certify/support.hpp"

namespace delcert::certify::test {
namespace {

io::PointSet mesh_points(const char* scale) {
  return io::read_points(fixture(std::string("soundness/off-manifold/sphere-mesh-scaled-") + scale + ".off"));
}

// The root cause: every first ball (radius about twice the spacing, 0.23) is farther than 0.3 from
// M, so every cell is complete and EMPTY, c = 0 < min r, and the covering argument "held" with no
// point of M known near P. Without an anchor it proves nothing: not complete, with the reason.
// With check 1's distances the balls reach M and the whole of Del_RM is found.
TEST(OffManifold, TheCoveringArgumentNeedsAnAnchor) {
  const io::PointSet P = mesh_points("1.3");
  const io::ManifoldSpec spec = io::read_spec("builtin:sphere-2");
  const exact::ImplicitSystem F(spec.equations, 3);
  const detail::PointGrid grid(P, 2);
  const io::ComplexFile mesh = io::read_complex(fixture("soundness/off-manifold/sphere-mesh-scaled-1.3.off"));
  RestrictedDelaunayOptions o;
  o.expected = &mesh.complex.simplices;  // as delcert-certify does: first radii from the mesh's triangles
  const RestrictedDelaunay blind = compute_restricted_delaunay(F, P, grid, o);
  EXPECT_TRUE(blind.simplices.empty());
  EXPECT_FALSE(blind.covering_certified);
  EXPECT_NE(blind.reason.find("no anchor"), std::string::npos) << blind.reason;
  // Distances too small to reach M (work only: they cannot make it wrong, only slow or undecided):
  // still no anchor, and the reason names the farthest point and its distance to M.
  const std::vector<double> small(P.size(), 0.01);
  o.distance_to_M = &small;
  const RestrictedDelaunay short_balls = compute_restricted_delaunay(F, P, grid, o);
  EXPECT_FALSE(short_balls.covering_certified);
  EXPECT_NE(short_balls.reason.find("no anchor"), std::string::npos) << short_balls.reason;
  EXPECT_NE(short_balls.reason.find("point 0 is up to 0.01 from M"), std::string::npos) << short_balls.reason;

  const std::vector<double> distance(P.size(), 0.30000000000000009);  // check 1's bound (about)
  o.distance_to_M = &distance;
  const RestrictedDelaunay R = compute_restricted_delaunay(F, P, grid, o);
  EXPECT_TRUE(R.covering_certified) << R.reason;
  EXPECT_EQ(R.simplices.size(), 820u);
}

struct Fixture {
  io::PointSet P = fibonacci_sphere(60);
  io::ManifoldSpec spec = io::read_spec("builtin:sphere-2");
  RecheckInput in{&spec.equations, nullptr, &P};
  RestrictedDelaunay R;
  Fixture() {
    const exact::ImplicitSystem F(spec.equations, 3);
    const detail::PointGrid grid(P, 2);
    R = compute_restricted_delaunay(F, P, grid, RestrictedDelaunayOptions{});
  }
};

// Every restricted Voronoi vertex the engine certifies passes the independent re-check, in a box
// that meets the engine's, and the covering argument's premise re-checks.
TEST(RestrictedRecheck, GenuineWitnessesPass) {
  const Fixture f;
  ASSERT_TRUE(f.R.covering_certified) << f.R.reason;
  ASSERT_FALSE(f.R.simplices.empty());
  for (const auto& s : f.R.simplices) {
    const auto B = recheck_nearest_set(f.in, s.simplex, s.vertex.x);
    ASSERT_TRUE(B.has_value()) << s.simplex[0] << " " << s.simplex[1] << " " << s.simplex[2];
    for (int v = 0; v < 3; ++v) EXPECT_TRUE((*B)[v].lo <= s.vertex.x[v].hi && s.vertex.x[v].lo <= (*B)[v].hi);
  }
  EXPECT_NO_THROW(require_completeness(f.in, f.R, "test"));
}

// Forged witnesses: a simplex with a vertex replaced, a vertex box moved to another simplex's
// vertex, an edge presented as a face point at a vertex (its third point is as near there), and a
// simplex of another dimension. Each fails, and require_nearest_set throws.
TEST(RestrictedRecheck, ForgedWitnessesTripIt) {
  const Fixture f;
  ASSERT_GE(f.R.simplices.size(), 2u);
  const RestrictedSimplex& a = f.R.simplices[0];
  const RestrictedSimplex& b = f.R.simplices.back();
  std::vector<int> wrong = a.simplex;
  for (int v = 0; v < static_cast<int>(f.P.size()); ++v)
    if (std::find(b.simplex.begin(), b.simplex.end(), v) == b.simplex.end() &&
        std::find(wrong.begin(), wrong.end(), v) == wrong.end()) {
      wrong.back() = v;
      break;
    }
  std::sort(wrong.begin(), wrong.end());
  int other = 0;  // a point not in a's simplex
  while (std::find(a.simplex.begin(), a.simplex.end(), other) != a.simplex.end()) ++other;
  const std::vector<std::pair<std::vector<int>, exact::Box>> forged = {
      {wrong, a.vertex.x},                                     // another simplex, the same vertex
      {a.simplex, b.vertex.x},                                 // the simplex, another simplex's vertex
      {{a.simplex[0], a.simplex[1]}, a.vertex.x},              // an edge as a face point at a vertex
      {{a.simplex[0]}, a.vertex.x},                            // a point alone, at a vertex
      {{a.simplex[0], a.simplex[1], a.simplex[2], other}, a.vertex.x},  // too many points
  };
  for (const auto& [simplex, box] : forged) {
    std::vector<int> s = simplex;
    std::sort(s.begin(), s.end());
    EXPECT_FALSE(recheck_nearest_set(f.in, s, box).has_value()) << s.size();
    EXPECT_THROW(require_nearest_set(f.in, s, box, "test"), WitnessRecheckFailure);
  }
  // The genuine one, for contrast, passes through the throwing form.
  EXPECT_NO_THROW(require_nearest_set(f.in, a.simplex, a.vertex.x, "test"));
}

// A forged completeness premise: a cell not complete, a covering bound not below the radii, no
// anchor, an anchor that is no witness. Each throws; the genuine premise does not (above).
TEST(RestrictedRecheck, ForgedCompletenessTripsIt) {
  const Fixture f;
  ASSERT_TRUE(f.R.covering_certified);
  {
    RestrictedDelaunay R = f.R;
    R.cells[7].complete = false;
    EXPECT_THROW(require_completeness(f.in, R, "test"), WitnessRecheckFailure);
  }
  {
    RestrictedDelaunay R = f.R;
    R.cells[3].covering_bound = R.cells[5].graph_radius;
    EXPECT_THROW(require_completeness(f.in, R, "test"), WitnessRecheckFailure);
  }
  {
    RestrictedDelaunay R = f.R;  // the 1.3 case: every cell complete and empty
    R.simplices.clear(), R.lower_faces.clear();
    for (auto& c : R.cells) c.vertices.clear(), c.covering_bound = 0;
    EXPECT_THROW(require_completeness(f.in, R, "test"), WitnessRecheckFailure);
  }
  {
    RestrictedDelaunay R = f.R;  // anchors whose boxes hold no such point
    const exact::Box elsewhere = R.simplices.back().vertex.x;
    const std::vector<int> first = R.simplices[0].simplex;
    for (auto& s : R.simplices) s.vertex.x = elsewhere, s.simplex = first;
    EXPECT_THROW(require_completeness(f.in, R, "test"), WitnessRecheckFailure);
  }
  {
    RestrictedDelaunay R = f.R;
    R.cross_check_failures.push_back({R.simplices[0].simplex, R.simplices[0].simplex[0], R.simplices[0].simplex[1]});
    EXPECT_THROW(require_completeness(f.in, R, "test"), WitnessRecheckFailure);
  }
}

}  // namespace
}  // namespace delcert::certify::test
