// Certified enclosures of real numbers in arbitrary precision (MPFI, MPFR-based intervals), for
// reporting margins and for the intrinsic-metric checks (sqrt, acos, asin, atan2).
//
// An Enclosure is a closed interval [lo, hi] of MPFR numbers that contains the exact value of
// the expression it was computed from: every operation rounds outward. The precision (bits of
// the endpoints) is chosen at construction and propagates (binary operations use the larger).
//
// A reported margin is a certified LOWER BOUND: report `lower()` (a double <= the true value,
// exactly representable and printed with round-trip precision by `lower_string()`), never a
// midpoint. Typical use: the exact rational margin from a predicate's *_exact() function,
//   Enclosure margin(cell.power_exact(q) - delta2);   // |c - q|^2 - R^2 - delta^2
//   report(margin.lower_string());
// and for geodesic quantities, e.g. on a sphere of radius r:
//   Enclosure angle = acos(Enclosure(dot) / Enclosure(r2));
//
// Domain errors: sqrt, acos and asin use only the part of the argument's enclosure inside their
// domain (an enclosure computed from an exact value that is in the domain may poke out of it
// only by rounding); when no part is inside they throw std::domain_error. Division by an
// enclosure that contains 0 throws std::domain_error.
#pragma once

#include <gmpxx.h>
#include <mpfr.h>

#include <memory>
#include <string>

namespace delcert::exact {

class Enclosure {
 public:
  static constexpr int kDefaultPrecision = 128;

  // Point enclosures of exact values (tight: the two neighbouring precision-p numbers, or the
  // value itself when representable).
  explicit Enclosure(const mpq_class& exact, int precision = kDefaultPrecision);
  explicit Enclosure(double exact, int precision = kDefaultPrecision);
  explicit Enclosure(long exact, int precision = kDefaultPrecision);
  // The interval [lo, hi] (lo <= hi required).
  static Enclosure between(const mpq_class& lo, const mpq_class& hi, int precision = kDefaultPrecision);
  static Enclosure pi(int precision = kDefaultPrecision);

  Enclosure(const Enclosure& other);
  Enclosure& operator=(const Enclosure& other);
  Enclosure(Enclosure&& other) noexcept;
  Enclosure& operator=(Enclosure&& other) noexcept;
  ~Enclosure();

  int precision() const;

  // Largest double <= lo and smallest double >= hi.
  double lower() const;
  double upper() const;
  // Exact endpoints as rationals.
  mpq_class lower_exact() const;
  mpq_class upper_exact() const;
  // lower() / upper() printed with round-trip precision ("%.17g"), so the printed decimal is
  // the double itself, a certified bound.
  std::string lower_string() const;
  std::string upper_string() const;
  // "[lo, hi]" with both endpoints printed outward at about `digits` significant digits.
  std::string to_string(int digits = 20) const;

  bool contains(const mpq_class& x) const;
  bool contains(mpfr_srcptr x) const;
  bool is_positive() const;  // lo > 0: certainly positive
  bool is_negative() const;  // hi < 0
  bool contains_zero() const;
  // hi - lo rounded up, as a double (0 for an exact point).
  double width() const;

  friend Enclosure operator+(const Enclosure& a, const Enclosure& b);
  friend Enclosure operator-(const Enclosure& a, const Enclosure& b);
  friend Enclosure operator*(const Enclosure& a, const Enclosure& b);
  friend Enclosure operator/(const Enclosure& a, const Enclosure& b);
  friend Enclosure operator-(const Enclosure& a);
  friend Enclosure sqrt(const Enclosure& a);
  friend Enclosure acos(const Enclosure& a);
  friend Enclosure asin(const Enclosure& a);
  friend Enclosure atan(const Enclosure& a);
  // atan2(y, x), the angle of (x, y) in [-pi, pi]. Throws std::domain_error when the box
  // x * y contains the origin (the angle is undefined there).
  friend Enclosure atan2(const Enclosure& y, const Enclosure& x);
  friend Enclosure cos(const Enclosure& a);
  friend Enclosure sin(const Enclosure& a);
  friend Enclosure square(const Enclosure& a);
  // The convex hull of a and b.
  friend Enclosure hull(const Enclosure& a, const Enclosure& b);

  struct Impl;

 private:
  Enclosure();
  static Enclosure with_precision(long precision);
  std::unique_ptr<Impl> impl_;
};

}  // namespace delcert::exact
