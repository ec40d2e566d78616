#include "core/refine/cospherical.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "core/spatial/neighbour_index.hpp"
#include "core/sampling/random.hpp"

namespace delcert::refine {
namespace {

// σ = three points on the unit circle in the plane z = 0 of R^3; its "power centre" c = origin,
// R = 1 (as if T_p were the plane). L(σ) = √3 (an equilateral triangle).
io::PointSet base() {
  io::PointSet ps;
  ps.dimension = 3;
  for (int i = 0; i < 3; ++i) {
    double a = 2 * std::numbers::pi * i / 3;
    ps.push_back(std::vector<double>{std::cos(a), std::sin(a), 0});
  }
  return ps;
}

const std::vector<int> kCell{0, 1, 2};
const std::vector<double> kCentre{0, 0, 0};

TEST(Cosph, PowerWindowDecidesMembership) {
  auto ps = base();
  const double delta0 = 0.2;
  // q far from the vertices (L(q*σ) = √3 stays the shortest edge): bound δ0^2 * 3 = 0.12.
  auto at_power = [&](double power) {
    const double r = std::sqrt(1 + power);
    auto p = ps;
    p.push_back(std::vector<double>{0, 0, r});  // on the axis: equidistant from the vertices
    return p;
  };
  CosphOptions o;
  o.delta0 = delta0;
  CosphMember m;
  // On the axis at height r, distance to each vertex is sqrt(1 + r^2) >= √3 only for r >= √2;
  // below that L(q*σ) shrinks: compute the bound with the true L.
  for (double power : {0.0, 0.05, 0.11, 0.13, 0.5}) {
    auto p = at_power(power);
    const double l = std::min(std::sqrt(3.0), std::sqrt(1 + 1 + power));
    const double bound = delta0 * delta0 * l * l;
    const bool expect = power <= bound;
    EXPECT_EQ(cosph_member(p, kCell, kCentre, 1.0, 3, o, &m), expect) << power;
    if (expect) {
      EXPECT_NEAR(m.power, power, 1e-12);
      EXPECT_NEAR(m.bound, bound, 1e-12);
    }
  }
  // A point inside the ball (negative power) is not in the paper's cosph; in the practical
  // variant (lower = -inf) it is.
  auto inside = at_power(-0.1);
  EXPECT_FALSE(cosph_member(inside, kCell, kCentre, 1.0, 3, o));
  CosphOptions practical = o;
  practical.lower = -std::numeric_limits<double>::infinity();
  EXPECT_TRUE(cosph_member(inside, kCell, kCentre, 1.0, 3, practical));
  // A vertex of σ is never an apex.
  EXPECT_FALSE(cosph_member(ps, kCell, kCentre, 1.0, 1, practical));
}

TEST(Cosph, ShortEdgeToTheApexShrinksTheBoundAndTheFloorRestoresIt) {
  auto ps = base();
  // q just outside the circle next to vertex 0: power = (1.01)^2 - 1 ≈ 0.0201, L(q*σ) = 0.01.
  ps.push_back(std::vector<double>{1.01, 0, 0});
  CosphOptions o;
  o.delta0 = 0.2;
  EXPECT_FALSE(cosph_member(ps, kCell, kCentre, 1.0, 3, o));  // bound 0.04 * 1e-4
  o.length_floor = 1.0;                                        // bound 0.04 > 0.0201
  EXPECT_TRUE(cosph_member(ps, kCell, kCentre, 1.0, 3, o));
}

TEST(Cosph, PreconditionsOfTheFullDefinition) {
  auto ps = base();
  ps.push_back(std::vector<double>{0, 0, std::sqrt(1.05)});  // power 0.05
  CosphOptions o;
  o.delta0 = 0.2;
  EXPECT_TRUE(cosph_test(ps, kCell, kCentre, 1.0, 3, /*eps=*/1.5, /*gamma0=*/0.3, o));
  EXPECT_FALSE(cosph_test(ps, kCell, kCentre, 1.0, 3, /*eps=*/1.0, 0.3, o));   // R_p < ε fails
  EXPECT_FALSE(cosph_test(ps, kCell, kCentre, 1.0, 3, 1.5, /*gamma0=*/0.7, o));  // σ Γ0-bad (Υ = 0.433 < 0.49)
}

TEST(Cosph, MembersAgreeWithBruteForce) {
  sampling::Random rng(3);
  io::PointSet ps = base();
  for (int i = 0; i < 400; ++i) {
    // Points near the unit sphere, so that many powers are small.
    std::vector<double> v{rng.normal(), rng.normal(), rng.normal()};
    double n = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    double r = 1 + rng.uniform(-0.05, 0.2);
    for (auto& c : v) c *= r / n;
    ps.push_back(v);
  }
  spatial::NeighbourIndex index(ps);
  for (double floor : {0.0, 0.5}) {
    CosphOptions o;
    o.delta0 = 0.3;
    o.length_floor = floor;
    auto members = cosph_members(ps, index, kCell, kCentre, 1.0, o);
    std::vector<std::size_t> brute;
    for (std::size_t q = 0; q < ps.size(); ++q)
      if (cosph_member(ps, kCell, kCentre, 1.0, q, o)) brute.push_back(q);
    ASSERT_EQ(members.size(), brute.size());
    for (std::size_t i = 0; i < brute.size(); ++i) EXPECT_EQ(members[i].q, brute[i]);
    EXPECT_GT(brute.size(), 3u);  // the window is not empty: the test can fail
  }
}

}  // namespace
}  // namespace delcert::refine
