// The tangential complex as a whole: known answers (S^2 = convex hull, a lattice torus),
// assembly, topology, and independence from the thread count.
#include <gtest/gtest.h>

#include <gmpxx.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/tangential/complex_topology.hpp"
#include "core/tangential/tangential_complex.hpp"
#include "tests/core/tangential/test_support.hpp"

namespace delcert::tangential {
namespace {

// Sign of det[b - a, c - a, d - a], exact: a floating-point value with a forward error bound,
// and exact rationals (the doubles' own values) when the bound does not decide.
int orientation(const double* a, const double* b, const double* c, const double* d) {
  double m[3][3], bound_terms[3][3];
  for (int j = 0; j < 3; ++j) {
    m[0][j] = b[j] - a[j], m[1][j] = c[j] - a[j], m[2][j] = d[j] - a[j];
    for (int i = 0; i < 3; ++i) bound_terms[i][j] = std::abs(m[i][j]);
  }
  const double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                     m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                     m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  const double perm = bound_terms[0][0] * (bound_terms[1][1] * bound_terms[2][2] + bound_terms[1][2] * bound_terms[2][1]) +
                      bound_terms[0][1] * (bound_terms[1][0] * bound_terms[2][2] + bound_terms[1][2] * bound_terms[2][0]) +
                      bound_terms[0][2] * (bound_terms[1][0] * bound_terms[2][1] + bound_terms[1][1] * bound_terms[2][0]);
  // Differences (1 rounding each) and a 3x3 expansion (5 roundings): 16 eps is ample.
  if (std::abs(det) > 16 * 0x1p-53 * perm) return det > 0 ? 1 : -1;
  mpq_class e[3][3];
  for (int j = 0; j < 3; ++j) {
    e[0][j] = mpq_class(b[j]) - mpq_class(a[j]);
    e[1][j] = mpq_class(c[j]) - mpq_class(a[j]);
    e[2][j] = mpq_class(d[j]) - mpq_class(a[j]);
  }
  mpq_class x = e[0][0] * (e[1][1] * e[2][2] - e[1][2] * e[2][1]) - e[0][1] * (e[1][0] * e[2][2] - e[1][2] * e[2][0]) +
                e[0][2] * (e[1][0] * e[2][1] - e[1][1] * e[2][0]);
  return sgn(x);
}

// S^2: for points on a sphere the tangential complex is the boundary of their convex hull.
TEST(TangentialComplex, Sphere2IsTheConvexHull) {
  auto s = testing::builtin_sample("sphere-2", 2000, 101);
  const std::size_t n = s.points.size();
  StarStats stats;
  TangentialComplex tc(s.points, s.planes, {}, &stats);
  Assembly a = tc.assemble();
  EXPECT_TRUE(a.inconsistent.empty());
  EXPECT_EQ(a.isolated_vertices, 0u);
  EXPECT_EQ(a.star_cells, 3 * a.complex.simplices.size());  // each triangle in the stars of its 3 vertices
  ComplexTopology t = analyze_complex(a.complex);
  EXPECT_EQ(t.dimension, 2);
  EXPECT_TRUE(t.pure);
  EXPECT_EQ(t.boundary_ridges, 0u);
  EXPECT_EQ(t.singular_ridges, 0u);  // every edge in exactly two triangles
  EXPECT_TRUE(t.pseudomanifold);
  EXPECT_EQ(t.euler_characteristic, 2);
  // Independent check: every triangle is a facet of the hull (all other points strictly on the
  // side of the origin), and there are 2n - 4 of them, as many as the hull of n points in
  // convex general position has: so the complex is the whole hull.
  ASSERT_EQ(a.complex.simplices.size(), 2 * n - 4);
  const double origin[3] = {0, 0, 0};
  for (const auto& tri : a.complex.simplices) {
    ASSERT_EQ(tri.size(), 3u);
    const double *A = s.points.point(tri[0]).data(), *B = s.points.point(tri[1]).data(),
                 *C = s.points.point(tri[2]).data();
    const int inside = orientation(A, B, C, origin);
    ASSERT_NE(inside, 0);
    for (std::size_t q = 0; q < n; ++q) {
      if (static_cast<int>(q) == tri[0] || static_cast<int>(q) == tri[1] || static_cast<int>(q) == tri[2]) continue;
      ASSERT_EQ(orientation(A, B, C, s.points.point(q).data()), inside)
          << "point " << q << " is beyond triangle " << tri[0] << " " << tri[1] << " " << tri[2];
    }
  }
}

// A dense, well-protected sample of the Clifford torus (a jittered triangular lattice): the
// complex is consistent, a pure 2-pseudomanifold, with Euler characteristic 0.
TEST(TangentialComplex, CliffordTorusLattice) {
  auto s = testing::clifford_lattice(52, 60, 0.05, 102);
  TangentialComplex tc(s.points, s.planes, testing::with_threads(2));
  Assembly a = tc.assemble(2);
  EXPECT_TRUE(a.inconsistent.empty()) << a.inconsistent.size() << " inconsistent simplices";
  ComplexTopology t = analyze_complex(a.complex);
  EXPECT_TRUE(t.pure);
  EXPECT_TRUE(t.pseudomanifold);
  EXPECT_EQ(t.euler_characteristic, 0);
  EXPECT_EQ(a.complex.simplices.size(), 2 * s.points.size());  // a triangulated torus: F = 2V
}

// Stars, complex and inconsistent simplices do not depend on the number of threads.
TEST(TangentialComplex, SameOutputForOneTwoFourThreads) {
  auto s = testing::builtin_sample("clifford-torus-2", 4000, 103);  // random: has inconsistencies
  TangentialComplex one(s.points, s.planes, testing::with_threads(1));
  Assembly a1 = one.assemble(1);
  EXPECT_FALSE(a1.inconsistent.empty());
  for (int threads : {2, 4}) {
    TangentialComplex tc(s.points, s.planes, testing::with_threads(threads));
    for (std::size_t p = 0; p < s.points.size(); ++p) {
      ASSERT_EQ(tc.star(p).cells, one.star(p).cells) << p;
      ASSERT_EQ(tc.star(p).centres, one.star(p).centres) << p;
      ASSERT_EQ(tc.star(p).radii2, one.star(p).radii2) << p;
    }
    Assembly a = tc.assemble(threads);
    EXPECT_EQ(a.complex.simplices, a1.complex.simplices);
    EXPECT_EQ(a.inconsistent, a1.inconsistent);
  }
}

// Inconsistency is found from the stars alone: a simplex missing from one vertex's star.
TEST(TangentialComplex, AssembleFindsInconsistentSimplices) {
  std::vector<Star> stars(4);
  auto set = [&](int p, std::vector<int> cells) {
    stars[p].m = 2;
    stars[p].N = 3;
    stars[p].cells = cells;
    stars[p].radii2.assign(cells.size() / 3, 1.0);
    stars[p].centres.assign(cells.size(), 0.0);
  };
  set(0, {0, 1, 2, 0, 1, 3});
  set(1, {0, 1, 2, 0, 1, 3});
  set(2, {0, 1, 2});
  set(3, {1, 2, 3});  // {0,1,3} is missing here, {1,2,3} is only here
  Assembly a = assemble(stars, 4);
  EXPECT_EQ(a.complex.simplices, (std::vector<std::vector<int>>{{0, 1, 2}, {0, 1, 3}, {1, 2, 3}}));
  EXPECT_EQ(a.inconsistent, (std::vector<std::vector<int>>{{0, 1, 3}, {1, 2, 3}}));
  EXPECT_EQ(a.star_cells, 6u);
}

TEST(ComplexTopology, KnownComplexes) {
  io::Complex tetra{4, {{0, 1, 2}, {0, 1, 3}, {0, 2, 3}, {1, 2, 3}}};  // boundary of a tetrahedron
  ComplexTopology t = analyze_complex(tetra);
  EXPECT_EQ(t.euler_characteristic, 2);
  EXPECT_TRUE(t.pseudomanifold);
  EXPECT_EQ(t.faces_by_dimension, (std::vector<std::size_t>{4, 6, 4}));

  io::Complex disk{3, {{0, 1, 2}}};
  t = analyze_complex(disk);
  EXPECT_EQ(t.euler_characteristic, 1);
  EXPECT_EQ(t.boundary_ridges, 3u);
  EXPECT_FALSE(t.pseudomanifold);

  io::Complex two_spheres{8, {{0, 1, 2}, {0, 1, 3}, {0, 2, 3}, {1, 2, 3}, {4, 5, 6}, {4, 5, 7}, {4, 6, 7}, {5, 6, 7}}};
  t = analyze_complex(two_spheres);
  EXPECT_EQ(t.euler_characteristic, 4);
  EXPECT_EQ(t.components, 2u);
  EXPECT_FALSE(t.pseudomanifold);  // not strongly connected

  io::Complex mixed{5, {{0, 1, 2}, {2, 3}, {4}}};
  t = analyze_complex(mixed);
  EXPECT_FALSE(t.pure);
  EXPECT_EQ(t.maximal_by_dimension, (std::vector<std::size_t>{1, 1, 1}));
  EXPECT_EQ(t.euler_characteristic, 5 - 4 + 1);

  io::Complex fin{5, {{0, 1, 2}, {0, 1, 3}, {0, 1, 4}}};  // an edge in three triangles
  t = analyze_complex(fin);
  EXPECT_EQ(t.singular_ridges, 1u);
}

}  // namespace
}  // namespace delcert::tangential
