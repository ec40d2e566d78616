// Exact numbers at the interface of exact/: GMP rationals (mpq_class) and the helpers that move
// between them and doubles without losing anything.
//
// Conventions (docs/design.md §2): an input coordinate is a finite IEEE double and means the exact
// rational it represents, a dyadic number m * 2^e. Thresholds (delta^2, Gamma, epsilon^2) are
// arbitrary rationals, parsed exactly from decimal text with parse_rational().
#pragma once

#include <gmpxx.h>

#include <span>
#include <vector>

#include "exact/interval.hpp"

namespace delcert::exact {

// The exact rational value of a finite double (throws std::invalid_argument on NaN/inf).
mpq_class to_rational(double x);
std::vector<mpq_class> to_rational(std::span<const double> x);

// True when q = a / 2^k for integers a and k >= 0 (every finite double is dyadic).
bool is_dyadic(const mpq_class& q);

// The tightest double interval containing q: lo = hi = q when q is a double, otherwise two
// adjacent doubles (or +-DBL_MAX/inf beyond the double range). Independent of the rounding mode.
Interval enclose(const mpq_class& q);

// A rational constant prepared once for use in many filtered predicate calls: the exact value,
// its numerator and denominator, and a double interval enclosing it.
class RationalConstant {
 public:
  RationalConstant() : RationalConstant(mpq_class(0)) {}
  // Implicit on purpose: an mpq_class can be passed where a RationalConstant is expected (at
  // the cost of re-preparing it on every call).
  RationalConstant(const mpq_class& value);  // NOLINT(google-explicit-constructor)

  const mpq_class& value() const { return value_; }
  const Interval& enclosure() const { return enclosure_; }
  int sign() const { return sgn(value_); }

 private:
  mpq_class value_;
  Interval enclosure_;
};

}  // namespace delcert::exact
