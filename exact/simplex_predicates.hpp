// Filtered exact predicates on ambient simplices and distances (issue 3 predicates 4-6).
//
// Points are pointers to N doubles (the exact rationals they represent). Every answer is the
// exact sign; degenerate input (repeated or affinely dependent points) is allowed everywhere and
// never divides by zero. Evaluation: interval arithmetic (squared distances enclosed from a
// floating-point sum of squares with a rigorous relative error bound), then exact (CGAL::Mpzf)
// when the interval contains 0; each call is counted in FilterContext::stats.
#pragma once

#include <gmpxx.h>

#include <span>
#include <vector>

#include "exact/filter_stats.hpp"
#include "exact/interval.hpp"
#include "exact/number_types.hpp"

namespace delcert::exact {

inline constexpr int kMaxThicknessSimplexDimension = 7;  // largest j accepted by the thickness test

// ---- Thickness (docs/design.md §3.1: Upsilon(t) = min_p D(p, t) / (j Delta(t)), Upsilon = 1 for j = 0) ----
//
// sign(Upsilon(t) - Gamma) with Gamma = sqrt(gamma_squared) >= 0, for the j-simplex t given by
// its j + 1 vertices. Decided through squares and Gram determinants (see detail/kernels.hpp):
//   Upsilon(t) >= Gamma  <=>  for every vertex v: det G(t) >= Gamma^2 j^2 Delta^2 det G(t_v).
// Conventions for degenerate t (affinely dependent, including repeated vertices): Upsilon = 0,
// so the answer is -1 for Gamma > 0 and 0 for Gamma = 0. For Gamma0-goodness of a j-face pass
// gamma_squared = Gamma0^(2j). Throws std::invalid_argument for gamma_squared < 0 or j too large.
int thickness_sign(std::span<const double* const> vertices, int N, const RationalConstant& gamma_squared,
                   FilterContext& ctx);
// Upsilon(t)^2 exactly (rational; 0 for degenerate t, 1 for j = 0). For reports.
mpq_class thickness_squared_exact(std::span<const double* const> vertices, int N);

// ---- Squared distances ----
// sign(|a - b|^2 - |c - d|^2).
int compare_squared_distances(const double* a, const double* b, const double* c, const double* d, int N,
                              FilterContext& ctx);
// sign(|a - b|^2 - r2) for a rational r2 (e.g. a sparsity bound (mu eps)^2).
int compare_squared_distance(const double* a, const double* b, const RationalConstant& r2, int N, FilterContext& ctx);
// |a - b|^2 exactly (a dyadic rational).
mpq_class squared_distance_exact(const double* a, const double* b, int N);

// ---- Ambient power of an exactly given centre ----

// A point with exact rational coordinates (e.g. a cell centre from TangentCell::centre_exact),
// prepared for filtered predicates: a common denominator, integer numerators and enclosures.
class RationalPoint {
 public:
  explicit RationalPoint(std::vector<mpq_class> coordinates);
  int dimension() const { return static_cast<int>(coords_.size()); }
  const std::vector<mpq_class>& coordinates() const { return coords_; }
  const Box& enclosure() const { return enclosure_; }
  const mpz_class& denominator() const { return denominator_; }   // D > 0
  const std::vector<mpz_class>& numerators() const { return numerators_; }  // x_i = X_i / D

 private:
  std::vector<mpq_class> coords_;
  Box enclosure_;
  mpz_class denominator_;
  std::vector<mpz_class> numerators_;
};

// sign(|x - q|^2 - |x - p|^2): +1 when q is strictly farther from x than p.
int ambient_power_sign(const RationalPoint& x, const double* p, const double* q, FilterContext& ctx);

// The same for x anywhere in a box (e.g. a Krawczyk enclosure of a point of M on a Voronoi
// face): +1 or -1 when that sign holds for every x in the box, 0 when the box does not decide
// (interval evaluation of the affine function |q|^2 - |p|^2 - 2 x.(q - p); no exact fallback).
int ambient_power_sign_on_box(const Box& x, const double* p, const double* q);

}  // namespace delcert::exact
