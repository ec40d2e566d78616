// CGAL number types used inside exact/*.cpp. PRIVATE: include this only from exact/*.cpp,
// never from a public header (CGAL headers are expensive to compile and must not leak into
// consumers, see common build rules).
//
//  IA: CGAL::Interval_nt_advanced, interval arithmetic that assumes the rounding mode is upward.
//  EX: CGAL::Mpzf, exact multiprecision dyadic numbers (m * 2^e): every double converts exactly
//      and +, -, * are exact. No division: every formula of detail/kernels.hpp is division-free.
#pragma once

#include <CGAL/FPU.h>
#include <CGAL/Mpzf.h>
#include <gmpxx.h>

#include <utility>

#include "exact/filter_stats.hpp"
#include "exact/interval.hpp"
#include "exact/interval_arithmetic.hpp"

namespace delcert::exact::detail {

using IA = IntervalNumber;  // CGAL::Interval_nt_advanced (interval_arithmetic.hpp)
using EX = CGAL::Mpzf;

// Sign of an interval's contents: -1, 0 or +1 when certain, kUndecided when it contains 0 and
// another value. A point interval [0, 0] certifies an exact zero.
inline constexpr int kUndecided = 2;
inline int certain_sign(const IA& x) {
  if (x.inf() > 0) return 1;
  if (x.sup() < 0) return -1;
  if (x.inf() == 0 && x.sup() == 0) return 0;
  return kUndecided;  // also for NaN bounds
}

inline int exact_sign(const EX& x) { return static_cast<int>(x.sign()); }

inline IA to_ia(const Interval& x) { return to_interval_number(x); }
inline Interval from_ia(const IA& x) { return to_interval(x); }

// Exact conversion of an integer to Mpzf. Do NOT use Mpzf's own mpz constructor: in CGAL 5.5
// Mpzf(mpz_class) / Mpzf(Gmpz) drops the sign (init_from_mpz_t copies |z|) and mishandles 0
// (mpz_scan1 of 0 is ~0). Convert |z| and negate instead.
inline EX to_ex(const mpz_class& z) {
  const int s = sgn(z);
  if (s == 0) return EX(0);
  mpz_class a = abs(z);
  EX r(a);
  return s < 0 ? EX(-r) : r;
}

// Enclosure of an exact value as a double interval, in any rounding mode. Mpzf::to_interval is
// only right in round-to-nearest: it scales its (exact) 53-bit bounds by
// ldexp(Interval_nt, e), which takes std::ldexp(1.0, e) as the exact factor unless it is 0; for
// e < -1074 that is 0 under round-to-nearest (and the factor becomes [0, min double]) but
// 2^-1074 under upward rounding, a point factor far above 2^e: the enclosure of a value below
// about 2^-1022 would miss it (2^-2000 came out as [1.85 2^-1022, ...]). So the call runs in
// round-to-nearest (a read of the control word when it already is).
inline std::pair<double, double> to_interval_nearest(const EX& x) {
  const CGAL::FPU_CW_t saved = CGAL::FPU_get_cw();
  if (saved != CGAL_FE_TONEAREST) CGAL::FPU_set_cw(CGAL_FE_TONEAREST);
  const auto p = x.to_interval();
  if (saved != CGAL_FE_TONEAREST) CGAL::FPU_set_cw(saved);
  return p;
}
inline IA enclose_ex(const EX& x) {
  const auto p = to_interval_nearest(x);
  return IA(p.first, p.second);
}

inline mpq_class to_mpq(const EX& x) { return static_cast<mpq_class>(x); }

// Sets the rounding mode to upward for the scope unless it is already upward (then it costs
// one read of the control register).
class EnsureUpward {
 public:
  EnsureUpward() : saved_(CGAL::FPU_get_cw()), changed_(saved_ != CGAL_FE_UPWARD) {
    if (changed_) CGAL::FPU_set_cw(CGAL_FE_UPWARD);
  }
  ~EnsureUpward() {
    if (changed_) CGAL::FPU_set_cw(saved_);
  }
  EnsureUpward(const EnsureUpward&) = delete;
  EnsureUpward& operator=(const EnsureUpward&) = delete;

 private:
  CGAL::FPU_CW_t saved_;
  bool changed_;
};

// Bookkeeping helper: counts a call, and whether the exact path decided it.
inline void count_result(FilterContext& ctx, PredicateKind kind, bool exact_path, int sign) {
  auto& c = ctx.stats[kind];
  ++c.calls;
  if (exact_path) ++c.filter_failures;
  if (sign == 0) ++c.zero_results;
}

}  // namespace delcert::exact::detail
