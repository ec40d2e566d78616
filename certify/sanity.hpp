// Check 1 (input sanity) and check 2 (sparsity).
//
// Input sanity is mostly enforced as bad input (exit status 2, "file:line: problem"): the
// readers refuse malformed files and bit-identical points; here every point must also satisfy
// |F_i(p)| <= residual_tolerance exactly, lie where the selector is > 0, and have a full-rank
// Jacobian (so that T_p = p + ker J_F(p) is an m-flat). The certificate entry records the
// certified maximum residual.
#pragma once

#include <string>
#include <vector>

#include "certify/certificate.hpp"
#include "core/io/complex.hpp"
#include "core/io/points.hpp"
#include "core/io/spec.hpp"

namespace delcert::certify {

class PointGrid;

// Line number (1-based) of every point in the text of a points file, for error messages.
std::vector<long> point_line_numbers(const std::string& points_text);

// Throws io::InputError naming the points file and the point's line for a point off M (beyond
// the tolerance), on the wrong component, or where the Jacobian is rank-deficient.
CheckEntry check_input_sanity(const io::ManifoldSpec& spec, const io::PointSet& points, const std::vector<long>& lines,
                              const std::string& points_file, int threads);

// Check 2: the exact minimum squared distance and the pair realising it (smallest indices among
// ties), compared with the claimed sparsity (distance > claim) when given.
struct SparsityResult {
  CheckEntry entry;
  mpq_class min_squared;  // exact
  int i = -1, j = -1;
};
SparsityResult check_sparsity(const io::PointSet& points, const PointGrid& grid, const mpq_class* claim,
                              exact::FilterContext& ctx);

}  // namespace delcert::certify
