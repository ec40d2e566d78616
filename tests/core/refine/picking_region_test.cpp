#include "core/refine/picking_region.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "core/sampling/sampling.hpp"
#include "io/spec.hpp"

namespace delcert::refine {
namespace {

TEST(PickingRegion, UniformInTheTangentBall) {
  for (const char* name : {"sphere-2", "sphere-3"}) {
    manifold::Manifold M(io::read_spec(std::string("builtin:") + name));
    const int m = M.intrinsic_dimension(), N = M.ambient_dimension();
    Eigen::VectorXd p = Eigen::VectorXd::Zero(N);
    p[0] = 1;
    auto frame = M.frame(manifold::as_span(p));
    ASSERT_TRUE(frame);
    PickingRegion region;
    region.centre = p + frame->tangent * Eigen::VectorXd::Constant(m, 0.05);
    region.radius = 0.04;
    region.tangent = frame->tangent;
    sampling::Random rng(8);
    const int n = 4000;
    int inner = 0;
    Eigen::VectorXd mean = Eigen::VectorXd::Zero(N);
    for (int i = 0; i < n; ++i) {
      Eigen::VectorXd y = sample_picking_region(region, rng);
      Eigen::VectorXd d = y - region.centre;
      // In T_p: no normal component; inside the ball.
      EXPECT_LT((frame->normal.transpose() * d).norm(), 1e-14);
      ASSERT_LE(d.norm(), region.radius * (1 + 1e-12));
      if (d.norm() < region.radius / 2) ++inner;
      mean += y;
    }
    mean /= n;
    // P(|y - c| < r/2) = 2^-m; the binomial standard deviation is below 0.008 here.
    EXPECT_NEAR(static_cast<double>(inner) / n, std::pow(0.5, m), 0.03) << name;
    EXPECT_LT((mean - region.centre).norm(), 0.1 * region.radius) << name;
  }
}

TEST(PickingRegion, PsiLandsOnTheManifoldAboveTheSample) {
  manifold::Manifold M(io::read_spec("builtin:so3"));
  sampling::Random rng(2);
  io::PointSet ps;
  sampling::sample_manifold(M, 3, rng, ps);
  for (std::size_t i = 0; i < ps.size(); ++i) {
    auto frame = M.frame(ps.point(i));
    ASSERT_TRUE(frame);
    PickingRegion region;
    Eigen::Map<const Eigen::VectorXd> p(ps.point(i).data(), M.ambient_dimension());
    region.centre = p + frame->tangent * Eigen::VectorXd::Constant(3, 0.02);
    region.radius = 0.03;
    region.tangent = frame->tangent;
    for (int k = 0; k < 20; ++k) {
      Eigen::VectorXd y;
      auto x = pick_in_region(M, ps.point(i), *frame, region, rng, 0.1, &y);
      ASSERT_TRUE(x);
      EXPECT_LT(M.residual(manifold::as_span(*x)), 1e-12);
      EXPECT_TRUE(M.on_selected_component(manifold::as_span(*x)));
      // x - y is normal to T_p: the projection of x onto T_p is y.
      EXPECT_LT((frame->tangent.transpose() * (*x - y)).norm(), 1e-12);
    }
  }
}

TEST(PickingRegion, SameSeedSameSamples) {
  PickingRegion region;
  region.centre = Eigen::VectorXd::Zero(4);
  region.radius = 1;
  region.tangent = Eigen::MatrixXd::Identity(4, 3);
  sampling::Random a(99), b(99);
  for (int i = 0; i < 10; ++i) EXPECT_EQ(sample_picking_region(region, a), sample_picking_region(region, b));
}

}  // namespace
}  // namespace delcert::refine
