// Re-checks of check 12's refuting witnesses (issue 39), in code of its own: nothing here uses the
// engine that found them (certify/rvd.cpp, certify/detail/param_cell.cpp, certify/restricted.cpp,
// their charts or the neighbour grid). A REFUTED rests on its witnesses; each is proven again here,
// from the manifold's equations and the points alone, before it is printed. A witness that fails
// its re-check means the program contradicts itself: WitnessRecheckFailure, which delcert-certify
// turns into an internal error (exit 3), never into a verdict.
//
// NEAREST SET. A restricted Voronoi vertex of an m-simplex C (|C| = m + 1), or a face point of a
// smaller C (|C| = j + 1 <= m), claims: some x of M = {F = 0} (with a selector s, also s(x) > 0) has
// exactly the points of C as its nearest points in P. Proof, in ambient coordinates: Krawczyk
// (exact/krawczyk.hpp, interval arithmetic with outward rounding on the EXACT rational polynomials)
// on the square system of N polynomials in x
//     F_i(x) = 0                                        (i = 1..k = N - m),
//     |x - c_0|^2 - |x - c_i|^2 = 2 x.(c_i - c_0) + |c_0|^2 - |c_i|^2 = 0   (i = 1..j),
//     x_a - t_a = 0                                      (a in A: m - j coordinate axes, t_a a double),
// whose coefficients are the exact rationals of the input doubles, in a box X around the witness's
// enclosure (the enclosure itself first, then widened; t_a its midpoint on axis a; the sets A in
// order until one works). A root proven (unique in X, or by inflation next to it) is such an x,
// equidistant from the points of C, in the root's box B. Then, on B: s > 0 in interval arithmetic,
// and for EVERY other point q of P (all of them, no grid) |x - q|^2 - |x - c_0|^2 =
// |q - c_0|^2 - 2 (x - c_0).(q - c_0) > 0 in interval arithmetic. So the points of C are exactly the
// nearest points of x in P: C is in Del_RM(P). B is the box printed as the witness.
//
// COMPLETENESS PREMISE. A rejection "by completeness" (a given simplex not in Del_RM(P), Del_RM(P)
// not pure) rests on the covering argument of certify/restricted.hpp. It is re-derived here from
// the cells' own reports, not from RestrictedDelaunay::covering_certified: every cell complete (no
// undecided box, covering bound below its radius), c = max covering bound < min radius, no
// cross-check failure, and an ANCHOR: a point of M with d(x, P) <= c, i.e. a certified vertex or
// face point whose NEAREST SET re-check above passes (its distance to its nearest points is at most
// the cell's bound, being in a kept box of that cell).
#pragma once

#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "certify/restricted/restricted.hpp"
#include "exact/interval.hpp"
#include "exact/polynomial.hpp"
#include "io/points.hpp"

namespace delcert::certify {

// A witness that does not hold, or a completeness premise that is false: the program is wrong.
class WitnessRecheckFailure : public std::logic_error {
 public:
  using std::logic_error::logic_error;
};

struct RecheckInput {
  const std::vector<exact::Polynomial>* equations = nullptr;  // F: k polynomials in N variables
  const exact::Polynomial* selector = nullptr;                // s, or nullptr
  const io::PointSet* points = nullptr;
};

// NEAREST SET (above) for `simplex` (sorted indices, 1 to m + 1 of them) near `hint` (N intervals):
// the box proven to hold a point of M whose nearest points in P are exactly the simplex's, or
// nullopt when the proof fails.
std::optional<exact::Box> recheck_nearest_set(const RecheckInput& in, const std::vector<int>& simplex,
                                              const exact::Box& hint);

// The same; throws WitnessRecheckFailure naming `what` (the check's claim) when it fails.
exact::Box require_nearest_set(const RecheckInput& in, const std::vector<int>& simplex, const exact::Box& hint,
                               const std::string& what);

// COMPLETENESS PREMISE (above) of R; throws WitnessRecheckFailure naming `what` and the failed
// condition when it does not hold.
void require_completeness(const RecheckInput& in, const RestrictedDelaunay& R, const std::string& what);

}  // namespace delcert::certify
