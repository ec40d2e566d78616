// The Del_M engines behind certify/intrinsic.hpp, one per closed-form metric. Each fills the
// whole IntrinsicDelaunay (computed = true, metric, convention, completeness, the decided
// candidates, complete/reason); compute_intrinsic_delaunay validates the candidates and dispatches.
#pragma once

#include <gmpxx.h>

#include <array>
#include <vector>

#include "certify/intrinsic/intrinsic.hpp"

namespace delcert::certify::detail {

// M a round sphere of the spec's centre and radius, m = N - 1 (certify/intrinsic_sphere.cpp).
IntrinsicDelaunay intrinsic_delaunay_sphere(const io::ShapeSpec& metric, const io::PointSet& points,
                                            const PointGrid& grid, const std::vector<std::vector<int>>& candidates,
                                            int threads);

// M the product of circles of the spec's radii in the coordinate planes (x1, x2), (x3, x4), ...,
// N = 2m (a flat torus; certify/intrinsic_torus.cpp).
IntrinsicDelaunay intrinsic_delaunay_flat_torus(const io::ShapeSpec& metric, const io::PointSet& points,
                                                const PointGrid& grid, const std::vector<std::vector<int>>& candidates,
                                                int threads);

// M a product of round spheres (factors on disjoint coordinate blocks, centred at 0, m <= 3): the
// geodesic Voronoi cells (certify/intrinsic_product.cpp).
IntrinsicDelaunay intrinsic_delaunay_product(const io::ManifoldSpec& spec, const io::ShapeSpec& metric,
                                             const io::PointSet& points, const PointGrid& grid,
                                             const std::vector<std::vector<int>>& candidates, int threads);

// M = SO(3) in R^9 (x1..x9 row-major), the Frobenius metric (certify/intrinsic_so3.cpp).
// Davenport's symmetric 4 x 4 matrix B(p), linear in p (3 x 3, row-major): <R(x), p> = x^T B(p) x
// for every quaternion x, R(x) the rotation matrix of x times |x|^2 (quadratic in x). So
// R(x)_ij = x^T B(E_ij) x, E_ij the matrix unit (certify/rvd_param.cpp builds its charts so).
using Mat4 = std::array<std::array<mpq_class, 4>, 4>;
Mat4 davenport(const std::array<mpq_class, 9>& p);
// A floating-point unit eigenvector of B's largest eigenvalue (a guess: callers certify it).
std::array<double, 4> top_eigenvector(const Mat4& B);

IntrinsicDelaunay intrinsic_delaunay_so3(const io::PointSet& points, const PointGrid& grid,
                                         const std::vector<std::vector<int>>& candidates, int threads);

}  // namespace delcert::certify::detail
