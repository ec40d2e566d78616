// Check 1 (input sanity) and check 2 (sparsity).
//
// Input sanity is mostly enforced as bad input (exit status 2, "file:line: problem"): the
// readers refuse malformed files and bit-identical points; here every point must also satisfy
// |F_i(p)| <= residual_tolerance exactly, lie where the selector is > 0, have a full-rank
// Jacobian (so that T_p = p + ker J_F(p) is an m-flat), and be certifiably near M: an interval
// Krawczyk test (exact/manifold_distance.hpp) must prove a point x* of M within a certified
// distance of p and a full-rank J_F on a box around x*. The residual alone proves neither (a
// spec with a rank-deficient Jacobian on M, such as (|x|^2 - 1)^2 = 0, has tiny residuals at
// points up to sqrt(tolerance) away, and no tangent space). The certificate entry records the
// certified maximum residual and the certified maximum distance to M.
#pragma once

#include <string>
#include <vector>

#include "certify/certificate.hpp"
#include "io/complex.hpp"
#include "io/points.hpp"
#include "io/spec.hpp"

namespace delcert::certify {

namespace detail {
class PointGrid;
}  // namespace detail

// Points off M. A point with |F_i(p)| > residual_tolerance is refused (io::InputError) unless
// `accept_off_manifold`: the complex is claimed to be restricted Delaunay (a surface mesher's
// vertices, found by bisection, lie only near M). Del_RM(P) and the covering radius are defined
// for any P and need no tangent space at p; Del_TM(P) needs T_p M, which a point off M does not
// have, so the caller leaves the tangential checks uncomputed (docs/certificate.md, "Points off
// M"). Such points are listed in `off_manifold` and the entry reports their largest residual and
// their certified distance to M; every other requirement below still holds for them.
//
// Throws io::InputError naming the points file and the point's line (lines[i], from
// io::parse_points_file; no line for i >= lines.size()) for a point off M (beyond the
// tolerance, unless accepted), on the wrong component, where the Jacobian is rank-deficient, or
// where no point of M can be certified nearby (never a verdict: bad input, exit status 2).
struct SanityResult {
  CheckEntry entry{CheckId::input_sanity};
  std::vector<int> off_manifold;  // sorted indices of the points with a residual above the tolerance
  std::vector<double> distance_to_M;  // per point, a certified upper bound of its distance to M
};
SanityResult check_input_sanity(const io::ManifoldSpec& spec, const io::PointSet& points, const std::vector<long>& lines,
                                const std::string& points_file, bool accept_off_manifold, int threads);

// Check 2: the exact minimum squared distance and the pair realising it (smallest indices among
// ties), compared with the claimed sparsity (distance > claim) when given.
struct SparsityResult {
  CheckEntry entry{CheckId::sparsity};
  mpq_class min_squared;  // exact
  int i = -1, j = -1;
};
SparsityResult check_sparsity(const io::PointSet& points, const detail::PointGrid& grid, const mpq_class* claim,
                              exact::FilterContext& ctx, int threads = 1);

}  // namespace delcert::certify
