#include "core/sampling/sampling.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "core/spatial/neighbour_index.hpp"
#include "io/spec.hpp"

namespace delcert::sampling {
namespace {

double min_pairwise_distance_brute_force(const io::PointSet& ps) {
  double best = INFINITY;
  for (std::size_t i = 0; i < ps.size(); ++i)
    for (std::size_t j = i + 1; j < ps.size(); ++j) {
      double s = 0;
      for (int k = 0; k < ps.dimension; ++k) s += std::pow(ps.point(i)[k] - ps.point(j)[k], 2);
      best = std::min(best, std::sqrt(s));
    }
  return best;
}

struct NetCase {
  const char* manifold;
  double eps;
};

class EpsNet : public ::testing::TestWithParam<NetCase> {};

TEST_P(EpsNet, IsSparseCoveringAndDeterministic) {
  manifold::Manifold manifold(io::read_spec(std::string("builtin:") + GetParam().manifold));
  EpsNetOptions o;
  o.eps = GetParam().eps;
  o.seed = 42;
  EpsNetResult a = eps_net(manifold, o);
  ASSERT_GT(a.points.size(), 10u);
  double dmin = min_pairwise_distance_brute_force(a.points);
  EXPECT_GE(dmin, o.eps);
  EXPECT_EQ(dmin, a.min_distance);
  EXPECT_LT(a.covering_radius, o.eps);
  EXPECT_LT(a.max_residual, 1e-12);
  // An independent dense sample (other seed) is covered at about eps too.
  Random rng(99);
  io::PointSet probe;
  sample_manifold(manifold, 2000, rng, probe);
  const spatial::NeighbourIndex tree(a.points);
  double worst = 0;
  for (std::size_t i = 0; i < probe.size(); ++i) {
    std::size_t nn = 0;
    tree.nearest_distance2(probe.point(i), &nn);
    double s = 0;
    for (int k = 0; k < probe.dimension; ++k) s += std::pow(probe.point(i)[k] - a.points.point(nn)[k], 2);
    worst = std::max(worst, std::sqrt(s));
  }
  EXPECT_LT(worst, 1.5 * o.eps);
  // Same seed, same bytes; another seed, another net.
  EpsNetResult b = eps_net(manifold, o);
  EXPECT_EQ(io::format_points(a.points), io::format_points(b.points));
  o.seed = 43;
  EXPECT_NE(io::format_points(eps_net(manifold, o).points), io::format_points(a.points));
}

INSTANTIATE_TEST_SUITE_P(Builtins, EpsNet,
                         ::testing::Values(NetCase{"sphere-2", 0.2}, NetCase{"clifford-torus-2", 0.3},
                                           NetCase{"torus-of-revolution", 0.4}, NetCase{"sphere-3", 0.45},
                                           NetCase{"so3", 0.8}));

// A product parametrization (S^2 x S^1 of radii 1 and 2, the circle on x1, x5): every sample
// on both factors, both factors' coordinates spread (each factor sampled uniformly on its own).
TEST(SampleShape, ProductOfASphereAndACircle) {
  const io::ManifoldSpec spec = io::parse_spec(R"({"format": "delcert-manifold v1", "intrinsic_dimension": 3,
    "ambient_dimension": 5, "equations": ["x2^2 + x3^2 + x4^2 - 1", "x1^2 + x5^2 - 4"],
    "parametrization": {"name": "product", "factors": [{"type": "sphere", "coordinates": [2, 3, 4], "radius": "1"},
                                                       {"type": "sphere", "coordinates": [1, 5], "radius": "2"}]}})",
                                               "s2xs1.json");
  manifold::Manifold manifold(spec);
  Random random(7);
  io::PointSet P;
  sample_manifold(manifold, 2000, random, P);
  ASSERT_EQ(P.size(), 2000u);
  double mean[5] = {0, 0, 0, 0, 0};
  for (std::size_t i = 0; i < P.size(); ++i) {
    const auto p = P.point(i);
    EXPECT_NEAR(p[1] * p[1] + p[2] * p[2] + p[3] * p[3], 1, 1e-12);
    EXPECT_NEAR(p[0] * p[0] + p[4] * p[4], 4, 1e-12);
    for (int k = 0; k < 5; ++k) mean[k] += p[k] / 2000;
  }
  for (int k = 0; k < 5; ++k) EXPECT_LT(std::abs(mean[k]), 0.15) << k;  // uniform: centred (4 sigma)
}

TEST(FarthestPoint, KnownAnswerOnALine) {
  io::PointSet ps;
  ps.dimension = 1;
  for (double x : {0.0, 1.0, 2.0, 3.0, 4.0, 10.0}) ps.coordinates.push_back(x);
  double cover = 0;
  auto sel = farthest_point_selection(ps, 2.5, &cover);
  // 0 first; farthest is 10; then 4 (distance 4 to {0, 10}); then 2 is at distance 2 < 2.5: stop.
  EXPECT_EQ(sel, (std::vector<std::size_t>{0, 5, 4}));
  EXPECT_DOUBLE_EQ(cover, 2.0);
}

}  // namespace
}  // namespace delcert::sampling

namespace delcert::sampling {
namespace {

// The pilot estimate of an eps-net's size (used to refuse an eps that cannot end) is within a
// factor 2 of the net eps_net makes, where the pilot resolves eps and where it must extrapolate;
// and it grows like eps^-m.
TEST(EpsNetEstimate, WithinAFactorTwoOfTheNet) {
  for (const char* name : {"sphere-2", "clifford-torus-2", "sphere-3"})
    for (double eps : {0.3, 0.1}) {
      manifold::Manifold manifold(io::read_spec(std::string("builtin:") + name));
      EpsNetOptions o;
      o.eps = eps;
      const EpsNetEstimate e = estimate_eps_net(manifold, o);
      const double actual = static_cast<double>(eps_net(manifold, o).points.size());
      EXPECT_GT(e.net_points, actual / 2) << name << " eps " << eps;
      EXPECT_LT(e.net_points, actual * 2) << name << " eps " << eps;
      EXPECT_DOUBLE_EQ(e.dense_points, std::max(o.oversampling * e.net_points, static_cast<double>(o.min_dense)));
    }
  manifold::Manifold sphere(io::read_spec("builtin:sphere-2"));
  EpsNetOptions tiny;
  tiny.eps = 1e-300;
  EXPECT_GT(estimate_eps_net(sphere, tiny).dense_points, 1e300);
}

}  // namespace
}  // namespace delcert::sampling
