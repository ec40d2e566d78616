// Filter-then-exact, written once (in the spirit of CGAL's Filtered_predicate). Private to
// exact/*.cpp.
//
// A filtered predicate evaluates a kernel formula (detail/kernels.hpp, templated on the number
// type) first in interval arithmetic under upward rounding: the result encloses the exact value,
// so a sign read from an interval that excludes 0 (or from the point interval [0, 0]) is the exact
// sign. When the interval cannot decide, the same formula is evaluated exactly (CGAL::Mpzf, ring
// operations on dyadic inputs) and its sign is the answer. Either way the call counts itself in
// the FilterContext under its PredicateKind: one call, one filter failure when the exact path
// decided, one zero result when the sign is 0. Certificates report these counts.
#pragma once

#include "exact/detail/cgal_number_types.hpp"

namespace delcert::exact::detail {

// The sign an evaluation decided: from an interval value (certain_sign: kUndecided when it
// contains 0 and another value), from an exact value, or a sign the evaluation decided itself
// (-1, 0, 1, or kUndecided from an interval evaluation; for predicates that test several
// quantities). Any other result type is an error (no silent conversion to int).
inline int sign_of(const IA& x) { return certain_sign(x); }
inline int sign_of(const EX& x) { return exact_sign(x); }
inline int sign_of(int s) { return s; }
template <class T>
int sign_of(const T&) = delete;

// Sign of one predicate call of kind `kind`: `interval()` first, unless ctx.force_exact or
// !use_filter (the caller knows the interval inputs are unusable, e.g. not finite); then
// `exact()` when the interval did not decide. Holds upward rounding for both evaluations (one
// read of the control register when the caller already holds it).
template <class IntervalEval, class ExactEval>
int filtered_sign(FilterContext& ctx, PredicateKind kind, bool use_filter, IntervalEval&& interval, ExactEval&& exact) {
  EnsureUpward guard;
  if (use_filter && !ctx.force_exact) {
    const int s = sign_of(interval());
    if (s != kUndecided) {
      count_result(ctx, kind, false, s);
      return s;
    }
  }
  const int s = sign_of(exact());
  count_result(ctx, kind, true, s);
  return s;
}

template <class IntervalEval, class ExactEval>
int filtered_sign(FilterContext& ctx, PredicateKind kind, IntervalEval&& interval, ExactEval&& exact) {
  return filtered_sign(ctx, kind, true, static_cast<IntervalEval&&>(interval), static_cast<ExactEval&&>(exact));
}

}  // namespace delcert::exact::detail
