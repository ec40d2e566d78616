// Double-precision intervals as plain data, and the rounding-mode guard for batches of
// filtered predicates.
//
// The filtered predicates of exact/ evaluate interval arithmetic (CGAL's Interval_nt_advanced,
// kept inside exact/*.cpp) which needs the FPU rounding mode set to "upward". Every predicate
// sets that mode itself when it is not already set, so callers need nothing. A caller that makes
// many predicate calls in a row can hold one `UpwardRounding` for the whole batch and save the
// two mode switches per call:
//
//   {
//     delcert::exact::UpwardRounding batch;   // one switch for the batch
//     for (...) chart.power_sign(...);        // no switch inside
//   }                                         // previous mode restored
//
// Inside such a scope ordinary double arithmetic rounds upward too, and libm functions (sqrt
// aside) are not guaranteed to be accurate: keep plain floating-point geometry, Eigen
// decompositions and libm calls outside it.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "exact/small_vector.hpp"

namespace delcert::exact {

// A closed interval [lo, hi] of reals, lo <= hi. Used for boxes (Krawczyk) and for reporting
// double enclosures. Plain data: no arithmetic here (that lives in the filtered kernels).
struct Interval {
  double lo = 0.0;
  double hi = 0.0;

  static Interval point(double x) { return {x, x}; }
  bool contains(double x) const { return lo <= x && x <= hi; }
  bool contains(const Interval& o) const { return lo <= o.lo && o.hi <= hi; }
  double width() const { return hi - lo; }
  double midpoint() const { return lo + 0.5 * (hi - lo); }
  bool is_finite() const { return std::isfinite(lo) && std::isfinite(hi); }
};

// An axis-aligned box, one interval per coordinate (inline up to 8 of them: no allocation per box
// in the subdivisions of the usual dimensions).
using Box = SmallVector<Interval, 8>;

// RAII: switches the rounding mode of the calling thread to upward and restores the previous
// mode on destruction. Nesting is allowed. Not copyable.
class UpwardRounding {
 public:
  UpwardRounding();
  ~UpwardRounding();
  UpwardRounding(const UpwardRounding&) = delete;
  UpwardRounding& operator=(const UpwardRounding&) = delete;

 private:
  unsigned saved_;
  bool changed_;
};

// RAII: the opposite guard, round-to-nearest for a stretch of ordinary floating-point code
// (Eigen, libm, Newton steps) inside an UpwardRounding batch. Restores on destruction.
class NearestRounding {
 public:
  NearestRounding();
  ~NearestRounding();
  NearestRounding(const NearestRounding&) = delete;
  NearestRounding& operator=(const NearestRounding&) = delete;

 private:
  unsigned saved_;
  bool changed_;
};

// True when the calling thread's rounding mode is upward (for assertions in tests).
bool rounding_is_upward();
// True when the calling thread's rounding mode is round-to-nearest.
bool rounding_is_nearest();

// Start-up self-test of directed rounding: under UpwardRounding, 1 + 2^-60 must exceed 1 and
// -1 - 2^-60 must equal -1, a product that overflows negatively must round to -DBL_MAX, and
// CGAL's interval sum [1, 1] + [2^-60, 2^-60] must not be a point. The operands pass through
// volatile memory so that no compiler can fold them at translation time. Returns an empty string
// when all hold, else what failed: every enclosure in exact/ depends on this, so a program that
// certifies must refuse to run when it fails (delcert-certify: internal error, exit 3).
std::string directed_rounding_failure();

}  // namespace delcert::exact
