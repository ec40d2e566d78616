// Interval arithmetic for consumers of exact/ that compute their own enclosures (the certifier's
// reported radii and margins, its search radii), so that they include no CGAL header themselves.
//
// IntervalNumber is CGAL's Interval_nt_advanced, the type the filtered predicates of exact/ use:
// every operation rounds its bounds outward PROVIDED the rounding mode is upward, so hold an
// exact::UpwardRounding (interval.hpp) around every computation with it. An enclosure computed
// here is never a decision by itself: the signs that matter come from exact/'s filtered
// predicates. This is the one public header of exact/ that includes a CGAL header (Interval_nt
// only, header-only); everything else of CGAL stays inside exact/*.cpp.
#pragma once

#include <CGAL/Interval_nt.h>

#include <algorithm>

#include "exact/interval.hpp"

namespace delcert::exact {

using IntervalNumber = CGAL::Interval_nt_advanced;

// Between the plain-data Interval and the arithmetic type (exact: the bounds are copied).
inline IntervalNumber to_interval_number(const Interval& x) { return IntervalNumber(x.lo, x.hi); }
inline Interval to_interval(const IntervalNumber& x) { return {x.inf(), x.sup()}; }

// Enclosures of sqrt(x) and x^2 (CGAL's, tighter than x * x for an interval containing 0).
inline IntervalNumber sqrt(const IntervalNumber& x) { return CGAL::sqrt(x); }
inline IntervalNumber square(const IntervalNumber& x) { return CGAL::square(x); }

// [max lo, max hi]: encloses max(x, y) for x, y in the operands.
inline IntervalNumber interval_max(const IntervalNumber& a, const IntervalNumber& b) {
  return IntervalNumber(std::max(a.inf(), b.inf()), std::max(a.sup(), b.sup()));
}

}  // namespace delcert::exact
