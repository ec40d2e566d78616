// Tangential stars: brute force, the CGAL reference path, degenerate input, centres, updates.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>
#include <stdexcept>
#include <vector>

#include "core/tangential/star.hpp"
#include "core/tangential/tangential_complex.hpp"
#include "tests/core/tangential/test_support.hpp"

namespace delcert::tangential {
namespace {

using testing::Sample;

std::vector<std::vector<int>> cells_of(const Star& star) {
  std::vector<std::vector<int>> out;
  for (std::size_t c = 0; c < star.size(); ++c) out.emplace_back(star.cell(c).begin(), star.cell(c).end());
  return out;
}

std::vector<std::size_t> all_indices(std::size_t n) {
  std::vector<std::size_t> v(n);
  std::iota(v.begin(), v.end(), std::size_t{0});
  return v;
}

std::vector<Star> stars_of(const Sample& s, StarPath path, int threads = 1) {
  spatial::NeighbourIndex index(s.points);
  std::vector<Star> stars;
  StarOptions options;
  options.path = path;
  options.threads = threads;
  compute_stars(s.points, s.planes, index, all_indices(s.points.size()), stars, options);
  return stars;
}

// Each star equals the brute-force star over all (m+1)-subsets containing p.
void expect_brute_force(const Sample& s) {
  auto stars = stars_of(s, StarPath::automatic);
  std::size_t checked = 0;
  for (std::size_t p = 0; p < s.points.size(); ++p) {
    bool degenerate = false;
    auto expected = testing::brute_force_star(s.points, s.planes, p, &degenerate);
    if (degenerate) continue;  // a random sample is never this close to a tie; skip rather than guess
    ++checked;
    EXPECT_EQ(cells_of(stars[p]), expected) << "star of point " << p;
    EXPECT_TRUE(stars[p].closed);
  }
  EXPECT_GE(checked, s.points.size() * 9 / 10);
}

TEST(TangentialStars, BruteForceSphere2) { expect_brute_force(testing::builtin_sample("sphere-2", 60, 11)); }
TEST(TangentialStars, BruteForceCliffordTorus2) {
  expect_brute_force(testing::builtin_sample("clifford-torus-2", 70, 12));
}
TEST(TangentialStars, BruteForceSphere3) { expect_brute_force(testing::builtin_sample("sphere-3", 40, 13)); }
TEST(TangentialStars, BruteForceSO3) { expect_brute_force(testing::builtin_sample("so3", 40, 14)); }
TEST(TangentialStars, BruteForceSphere4) { expect_brute_force(testing::sphere_sample(4, 32, 15)); }

// The certified power-cell clipping computes exactly CGAL's regular-triangulation stars,
// centres included (bit for bit: the centres come from one canonical function).
void expect_same_as_reference(const Sample& s) {
  auto fast = stars_of(s, StarPath::automatic, 2);
  auto reference = stars_of(s, StarPath::regular_triangulation, 2);
  for (std::size_t p = 0; p < s.points.size(); ++p) {
    ASSERT_EQ(fast[p].cells, reference[p].cells) << "star of point " << p;
    ASSERT_EQ(fast[p].centres, reference[p].centres) << "star of point " << p;
    ASSERT_EQ(fast[p].radii2, reference[p].radii2) << "star of point " << p;
    EXPECT_EQ(reference[p].method, StarMethod::regular_triangulation);
  }
}

// The look-ahead star: tentative_star(points without x, x) is bit for bit the star compute_stars
// gives x once appended, on every m (cells, centres, radii, closedness), and leaves nothing behind.
void expect_tentative_equals_appended(const Sample& s) {
  const std::size_t n = s.points.size() - 8;  // the last 8 points are the tentative ones, one at a time
  io::PointSet head;
  head.dimension = s.points.dimension;
  head.coordinates.assign(s.points.coordinates.begin(), s.points.coordinates.begin() + n * s.points.dimension);
  const spatial::NeighbourIndex head_index(head);
  for (std::size_t x = n; x < s.points.size(); ++x) {
    const Star tentative = tentative_star(head, s.planes, head_index, s.points.point(x), s.planes.basis(x));
    io::PointSet with = head;
    with.push_back(s.points.point(x));
    TangentPlanes planes(s.planes.ambient_dimension(), s.planes.intrinsic_dimension());
    for (std::size_t i = 0; i < n; ++i) planes.push_back(s.planes.basis(i));
    planes.push_back(s.planes.basis(x));  // x's plane at its appended index n
    const spatial::NeighbourIndex index(with);
    std::vector<Star> stars;
    const std::vector<std::size_t> which{n};
    compute_stars(with, planes, index, which, stars);
    const Star& appended = stars[n];
    EXPECT_GT(tentative.size(), 0u);
    EXPECT_EQ(tentative.cells, appended.cells) << "point " << x;
    EXPECT_EQ(tentative.centres, appended.centres) << "point " << x;
    EXPECT_EQ(tentative.radii2, appended.radii2) << "point " << x;
    EXPECT_EQ(tentative.closed, appended.closed);
    EXPECT_EQ(head_index.size(), n);
  }
  // x on one of the points is refused; so is a basis of the wrong size.
  EXPECT_THROW(tentative_star(head, s.planes, head_index, head.point(0), s.planes.basis(0)), std::invalid_argument);
  EXPECT_THROW(tentative_star(head, s.planes, head_index, s.points.point(n), s.planes.basis(n).subspan(1)),
               std::invalid_argument);
}

TEST(TangentialStars, TentativeStarIsTheStarOnceAppended) {
  expect_tentative_equals_appended(testing::builtin_sample("sphere-2", 300, 31));
  expect_tentative_equals_appended(testing::builtin_sample("clifford-torus-3", 600, 32));
  expect_tentative_equals_appended(testing::sphere_sample(4, 400, 33));
}

TEST(TangentialStars, SameAsRegularTriangulationSphere2) {
  expect_same_as_reference(testing::builtin_sample("sphere-2", 3000, 21));
}
TEST(TangentialStars, SameAsRegularTriangulationTorusOfRevolution) {
  expect_same_as_reference(testing::builtin_sample("torus-of-revolution", 2000, 22));
}
TEST(TangentialStars, SameAsRegularTriangulationCliffordTorus3) {
  expect_same_as_reference(testing::builtin_sample("clifford-torus-3", 1500, 23));
}
TEST(TangentialStars, SameAsRegularTriangulationSO3) { expect_same_as_reference(testing::builtin_sample("so3", 800, 24)); }
TEST(TangentialStars, SameAsRegularTriangulationSphere4) { expect_same_as_reference(testing::sphere_sample(4, 400, 25)); }

// Every star is a closed fan around p: each (m-1)-face through p lies in exactly two cells.
void expect_closed_fans(const std::vector<Star>& stars) {
  for (std::size_t p = 0; p < stars.size(); ++p) {
    const Star& star = stars[p];
    ASSERT_TRUE(star.closed) << p;
    std::vector<std::vector<int>> ridges;
    for (std::size_t c = 0; c < star.size(); ++c) {
      auto cell = star.cell(c);
      ASSERT_TRUE(std::find(cell.begin(), cell.end(), static_cast<int>(p)) != cell.end());
      for (int drop : cell) {
        if (drop == static_cast<int>(p)) continue;
        std::vector<int> r;
        for (int v : cell)
          if (v != drop) r.push_back(v);
        ridges.push_back(r);
      }
    }
    std::sort(ridges.begin(), ridges.end());
    for (std::size_t i = 0; i < ridges.size(); i += 2) {
      ASSERT_LT(i + 1, ridges.size()) << p;
      ASSERT_EQ(ridges[i], ridges[i + 1]) << p;
      if (i + 2 < ridges.size()) {
        ASSERT_NE(ridges[i], ridges[i + 2]) << p;
      }
    }
  }
}

// An exact grid is cospherical everywhere (squares of a grid on the Clifford torus): the fast
// path must notice that it cannot decide and hand those stars to the exact regular triangulation.
TEST(TangentialStars, CosphericalGridFallsBackAndStaysValid) {
  Sample s = testing::clifford_grid(2, 24, 0.0, 1);
  spatial::NeighbourIndex index(s.points);
  std::vector<Star> stars;
  StarStats stats = compute_stars(s.points, s.planes, index, all_indices(s.points.size()), stars, {});
  EXPECT_GT(stats.fallbacks, 0u);
  expect_closed_fans(stars);
  auto reference = stars_of(s, StarPath::regular_triangulation);
  for (std::size_t p = 0; p < stars.size(); ++p) EXPECT_EQ(stars[p].cells, reference[p].cells) << p;
}

// Grids moved by 1e-15 .. 1e-9 radians: signs within a few ulps of zero everywhere. Every sign the
// fast path decides must be the exact one (same stars as the exact reference), and it must
// decide most of them once the perturbation is well above rounding.
TEST(TangentialStars, NearlyCosphericalInputMatchesExactReference) {
  for (int k : {2, 3})
    for (double jitter : {1e-15, 1e-14, 1e-13, 1e-12, 1e-11, 1e-9}) {
      Sample s = testing::clifford_grid(k, k == 2 ? 24 : 7, jitter, 2);
      spatial::NeighbourIndex index(s.points);
      std::vector<Star> stars;
      StarStats stats = compute_stars(s.points, s.planes, index, all_indices(s.points.size()), stars, {});
      auto reference = stars_of(s, StarPath::regular_triangulation);
      for (std::size_t p = 0; p < stars.size(); ++p)
        ASSERT_EQ(stars[p].cells, reference[p].cells) << "k " << k << " jitter " << jitter << " star " << p;
      expect_closed_fans(stars);
      if (jitter >= 1e-9) {
        EXPECT_LT(stats.fallbacks, s.points.size() / 20) << "k " << k;
      }
    }
}

// The Delaunay balls of the output are empty: no point is closer to c_p(s) than R_p(s).
TEST(TangentialStars, BallsAreEmptyAndCentresCanonical) {
  Sample s = testing::builtin_sample("clifford-torus-2", 1500, 31);
  auto stars = stars_of(s, StarPath::automatic);
  const int N = s.points.dimension;
  for (std::size_t p = 0; p < stars.size(); p += 7) {
    const Star& star = stars[p];
    for (std::size_t c = 0; c < star.size(); ++c) {
      auto centre = star.centre(c);
      double r2p = 0;
      for (int k = 0; k < N; ++k) r2p += (centre[k] - s.points.point(p)[k]) * (centre[k] - s.points.point(p)[k]);
      EXPECT_NEAR(r2p, star.radii2[c], 1e-12 * (1 + star.radii2[c]));
      auto cell = star.cell(c);
      for (std::size_t q = 0; q < s.points.size(); ++q) {
        double e2 = 0;
        for (int k = 0; k < N; ++k) e2 += (centre[k] - s.points.point(q)[k]) * (centre[k] - s.points.point(q)[k]);
        const bool vertex = std::find(cell.begin(), cell.end(), static_cast<int>(q)) != cell.end();
        if (vertex) {
          EXPECT_NEAR(e2, star.radii2[c], 1e-9 * star.radii2[c]);
        } else {
          EXPECT_GT(e2, star.radii2[c] * (1 - 1e-9)) << "point " << q << " in a ball of star " << p;
        }
      }
      // power_centre recomputes the same centre bit for bit.
      std::vector<double> again(N);
      double r2 = 0;
      ASSERT_TRUE(power_centre(s.points, s.planes, p, cell, again, &r2));
      EXPECT_EQ(std::vector<double>(centre.begin(), centre.end()), again);
      EXPECT_EQ(r2, star.radii2[c]);
    }
  }
}

// Inserting points and recomputing only stars_to_update gives the stars of a full rebuild.
TEST(TangentialStars, InsertRecomputesExactlyWhatChanges) {
  Sample all = testing::builtin_sample("sphere-3", 1800, 41);
  Sample s;
  s.points.dimension = all.points.dimension;
  s.planes = TangentPlanes(all.planes.ambient_dimension(), all.planes.intrinsic_dimension());
  const std::size_t first = 1500;
  for (std::size_t i = 0; i < first; ++i) {
    s.points.push_back(all.points.point(i));
    s.planes.push_back(all.planes.basis(i));
  }
  TangentialComplex tc(s.points, s.planes);
  std::size_t recomputed = 0;
  for (std::size_t i = first; i < all.points.size(); i += 60) {  // five batches of 60 points
    for (std::size_t j = i; j < i + 60; ++j) {
      s.points.push_back(all.points.point(j));
      s.planes.push_back(all.planes.basis(j));
    }
    recomputed += tc.insert(s.points, s.planes).size();
  }
  EXPECT_LT(recomputed, 5 * 1500u);  // local updates, not rebuilds
  TangentialComplex full(all.points, all.planes);
  ASSERT_EQ(tc.size(), full.size());
  for (std::size_t p = 0; p < full.size(); ++p) {
    EXPECT_EQ(tc.star(p).cells, full.star(p).cells) << p;
    EXPECT_EQ(tc.star(p).centres, full.star(p).centres) << p;
  }
}

TEST(TangentialStars, RejectsBadInput) {
  Sample s = testing::builtin_sample("sphere-2", 50, 51);
  spatial::NeighbourIndex index(s.points);
  std::vector<Star> stars;
  std::vector<std::size_t> which{0, 1};
  // Planes for fewer points than there are.
  TangentPlanes few(3, 2);
  few.push_back(s.planes.basis(0));
  EXPECT_THROW(compute_stars(s.points, few, index, which, stars), std::invalid_argument);
  // An index over another point set.
  io::PointSet other = s.points;
  other.push_back(s.points.point(3));
  EXPECT_THROW(compute_stars(other, s.planes, index, which, stars), std::invalid_argument);
  // Two identical points.
  Sample dup = s;
  dup.points.push_back(s.points.point(7));
  dup.planes.push_back(s.planes.basis(7));
  spatial::NeighbourIndex dup_index(dup.points);
  std::vector<std::size_t> seven{7};
  EXPECT_THROW(compute_stars(dup.points, dup.planes, dup_index, seven, stars), std::invalid_argument);
  // Unsupported intrinsic dimension (a curve).
  TangentPlanes curve(3, 1);
  EXPECT_THROW(compute_stars(s.points, curve, index, which, stars), std::invalid_argument);
  // A basis that is not orthonormal.
  TangentPlanes planes(3, 2);
  const double skew[6] = {1, 0, 0, 1, 1, 0};
  EXPECT_THROW(planes.push_back(skew), std::invalid_argument);
}

// Too few points for a closed fan: the finite cells are reported and the star is marked open.
TEST(TangentialStars, TooFewPointsGivesOpenStars) {
  Sample s = testing::sphere_sample(2, 3, 61);
  auto stars = stars_of(s, StarPath::automatic);
  for (const Star& star : stars) {
    EXPECT_FALSE(star.closed);
    EXPECT_EQ(cells_of(star), (std::vector<std::vector<int>>{{0, 1, 2}}));
  }
}

}  // namespace
}  // namespace delcert::tangential
