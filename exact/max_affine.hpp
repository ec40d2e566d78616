// An upper bound of a maximum of affine functions, minimised over nonnegative weights
// (the Lagrangian bound of certify/rvd.cpp's covering refinement).
//
// Given F (#C values) and S (#C by #Q, row-major), returns
//     B = max_c ( F_c + sum_q lambda_q S_cq )
// for one vector lambda >= 0 chosen here, evaluated UNDER UPWARD ROUNDING (set here): every
// product lambda_q S_cq and every sum rounds up, so B is not below the exact value of the
// expression for that lambda, whatever the inputs. lambda is chosen in floating point by
// coordinate descent (two sweeps; for one q the function t -> max_c (A_c + t S_cq) is convex
// and piecewise linear, minimal at t = 0 or where a rising and a falling line cross); the choice
// only affects how small B is, never its meaning. Terms with lambda_q = 0 are skipped (so an
// infinite S_cq with lambda_q = 0 adds nothing); a NaN anywhere in the evaluation gives +inf.
// Hence, for any caller with g(x) <= F_c + sum_q lambda_q S_cq at the points x it covers by c and
// f(x) <= g(x) whenever every s_q(x) >= 0 (S_cq >= s_q on those points), B bounds f there.
#pragma once

#include <span>

namespace delcert::exact {

double max_affine_upper_bound(std::span<const double> F, std::span<const double> S, int num_q);

}  // namespace delcert::exact
