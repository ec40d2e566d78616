// Input checks that tie a point set to its manifold: the producer refuses points that are not on M
// before it computes anything from them (docs/design.md §9). Both throw io::InputError.
#pragma once

#include <string>

#include "core/manifold/manifold.hpp"
#include "io/points.hpp"

namespace delcert::manifold {

// Rejects input points that are not on M to the spec's residual tolerance, or are on a component
// the spec's selector excludes: their tangent flat would mean nothing. Throws io::InputError
// naming `path`.
void check_on_manifold(const Manifold& manifold, const io::PointSet& points, const std::string& path);

// The same check for points the producer sampled itself (delcert sample, refine without --points):
// a failure means the spec's parametrization (or projection) disagrees with its equations.
// Throws io::InputError naming the spec; the caller has written nothing yet.
void check_sample_on_manifold(const Manifold& manifold, const io::PointSet& points, const std::string& spec_path);

}  // namespace delcert::manifold
