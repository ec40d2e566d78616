// The Del_M engines behind certify/intrinsic.hpp, one per closed-form metric. Each fills the
// whole IntrinsicDelaunay (computed = true, metric, convention, completeness, the decided
// candidates, complete/reason); compute_intrinsic_delaunay validates the candidates and dispatches.
#pragma once

#include <vector>

#include "certify/intrinsic.hpp"

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

// M = SO(3) in R^9 (x1..x9 row-major), the Frobenius metric (certify/intrinsic_so3.cpp).
IntrinsicDelaunay intrinsic_delaunay_so3(const io::PointSet& points, const PointGrid& grid,
                                         const std::vector<std::vector<int>>& candidates, int threads);

}  // namespace delcert::certify::detail
