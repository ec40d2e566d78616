#include "core/sampling/sampling.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <regex>

#include "core/spatial/neighbour_index.hpp"
#include "core/refine/parameters.hpp"
#include "io/input_error.hpp"
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

namespace delcert::sampling {
namespace {

// The eps that `delcert sample` and `refine` suggest when they refuse one as too small, read back
// as --eps is (refine::parse_eps_option, then the double below or at the decimal), is accepted:
// it was rounded to 0.0066 and refused at 0.0066 (issue 41). Two significant digits, never below
// the cap's extrapolated eps.
TEST(EpsNetSize, TheSuggestedEpsIsAccepted) {
  const std::regex suggestion("give eps >= ([0-9.e+-]+)$");
  for (const char* name : {"sphere-2", "clifford-torus-2", "sphere-3", "so3", "torus-of-revolution"})
    for (double eps : {1e-300, 1e-4, 1e-3, 0.005, 0.0066}) {
      manifold::Manifold manifold(io::read_spec(std::string("builtin:") + name));
      EpsNetOptions o;
      o.eps = eps;
      std::string text;
      try {
        check_eps_net_size(manifold, o);
        continue;  // accepted as it is (e.g. 0.005 on a small manifold)
      } catch (const io::InputError& e) {
        std::smatch m;
        const std::string message = e.what();
        ASSERT_TRUE(std::regex_search(message, m, suggestion)) << message;
        text = m[1].str();
        EXPECT_NE(message.find("more than the cap of 4e+06"), std::string::npos) << message;
      }
      EXPECT_EQ(text, smallest_eps_within_cap(manifold, o));
      // Two significant digits: the mantissa, without its point, leading and trailing zeros.
      std::string digits = text.substr(0, text.find('e'));
      digits.erase(std::remove(digits.begin(), digits.end(), '.'), digits.end());
      digits.erase(0, digits.find_first_not_of('0'));
      digits.erase(digits.find_last_not_of('0') + 1);
      EXPECT_LE(digits.size(), 2u) << text;
      EpsNetOptions back = o;
      back.eps = refine::parse_eps_option(text).value.get_d();
      EXPECT_GE(back.eps, estimate_eps_net(manifold, o).eps_at_cap * (1 - 1e-12)) << name << " " << text;
      EXPECT_NO_THROW(check_eps_net_size(manifold, back)) << name << " eps " << eps << " -> " << text;
    }
}

// When the dense sample reaches max_dense before it is `oversampling` times the net, the result
// says so (delcert sample then warns); when it does not, it does not.
TEST(EpsNetSize, TheResultSaysWhenTheDenseSampleHitTheCap) {
  manifold::Manifold sphere(io::read_spec("builtin:sphere-2"));
  EpsNetOptions o;
  o.eps = 0.1;
  o.min_dense = 4000;
  o.max_dense = 5000;
  const EpsNetResult capped = eps_net(sphere, o);
  EXPECT_TRUE(capped.dense_capped);
  EXPECT_EQ(capped.dense_size, 5000u);
  EXPECT_LT(static_cast<double>(capped.dense_size), o.oversampling * static_cast<double>(capped.points.size()));
  o.eps = 0.5;
  o.max_dense = 4'000'000;
  EXPECT_FALSE(eps_net(sphere, o).dense_capped);
}

}  // namespace
}  // namespace delcert::sampling
