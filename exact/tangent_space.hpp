// Exact tangent spaces of an implicit manifold (docs/design.md §2).
//
// M = { x in R^N : F(x) = 0 } with F = (F_1..F_k), k = N - m, polynomials with rational
// coefficients. At a sample point p (doubles, taken as exact rationals) the tangent flat is
// defined as T_p = p + ker J_F(p), evaluated at p itself.
//
// TangentSpace computes an exact basis U (N x m) of ker J_F(p) by cofactors (Cramer's rule
// without the division): with k pivot columns P of J and a free column f,
//   u_f = det(J_P) e_f - sum_l det(J_P with column l replaced by J_f) e_{P_l}
// satisfies J u_f = 0 (expand J u_f with Cramer's rule), and the m vectors u_f are linearly
// independent because their restriction to the free coordinates is det(J_P) * identity.
// Every entry of U is a k x k minor of J, i.e. a polynomial in the entries of J. We scale each
// F_i by the common denominator of its coefficients first (which does not change ker J), so J
// has integer-coefficient polynomial entries and, p being dyadic, U is dyadic: it is computed
// exactly in CGAL::Mpzf and offered here as exact rationals.
//
// U is not orthonormal; everything tangential is expressed through U and its Gram matrix
// G = U^T U, e.g. the orthogonal projection pi_p(q) = p + U G^{-1} U^T (q - p).
// The pivot columns are chosen by a column-pivoted QR of the double Jacobian (rows normalised),
// which is deterministic and keeps U well conditioned; if the chosen minor is exactly zero the
// other column sets are tried, and only when every k x k minor vanishes is J_F(p) declared
// rank deficient.
#pragma once

#include <gmpxx.h>

#include <Eigen/Core>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "exact/interval.hpp"
#include "exact/polynomial.hpp"

namespace delcert::exact {

// The polynomial system F : R^N -> R^k with its exact symbolic Jacobian, prepared once for
// exact and double evaluation. Immutable; cheap to copy (shared); thread-safe to share.
class ImplicitSystem {
 public:
  // `equations` are k polynomials in `ambient_dimension` variables, 0 <= k < N. Throws
  // std::invalid_argument when a polynomial has a different number of variables or k >= N.
  ImplicitSystem(std::vector<Polynomial> equations, int ambient_dimension);
  // Parses each equation with Polynomial::parse (e.g. the "equations" of a manifold spec).
  static ImplicitSystem parse(const std::vector<std::string>& equations, int ambient_dimension);

  int ambient_dimension() const;    // N
  int codimension() const;          // k = N - m
  int intrinsic_dimension() const;  // m
  const std::vector<Polynomial>& equations() const;

  // Exact F(x) and J_F(x) at a double point (k values; k x N row-major).
  std::vector<mpq_class> evaluate_exact(std::span<const double> x) const;
  // Enclosures of |F_i(x)| (k intervals, a few ulps wide): S_i(x) = D_i F_i(x) (D_i > 0 the
  // common denominator of F_i's coefficients, S_i with integer coefficients) evaluated exactly in
  // dyadic arithmetic, then enclosed and divided by D_i with outward rounding. Several times
  // faster than evaluate_exact (no rational arithmetic).
  std::vector<Interval> residual_enclosures(std::span<const double> x) const;
  std::vector<mpq_class> jacobian_exact(std::span<const double> x) const;
  // Double Jacobian J_F(x), k x N.
  Eigen::MatrixXd jacobian(std::span<const double> x) const;

  struct Impl;
  const Impl& impl() const { return *impl_; }

 private:
  std::shared_ptr<const Impl> impl_;
};

// Exact basis of ker J_F(p) at a double point p, and its Gram matrix. Immutable; cheap to copy;
// thread-safe to share.
class TangentSpace {
 public:
  // Throws std::domain_error when J_F(p) is exactly rank deficient (p is a singular point of F),
  // std::invalid_argument on a non-finite coordinate or a dimension mismatch.
  TangentSpace(const ImplicitSystem& system, std::span<const double> p);

  int ambient_dimension() const;    // N
  int intrinsic_dimension() const;  // m
  std::span<const double> point() const;  // p, N doubles

  // U, N x m: exact dyadic rationals. Column a is the kernel vector of free column
  // free_columns()[a]; its entry there is det(J_P) > 0.
  const mpq_class& basis(int row, int col) const;
  // G = U^T U, m x m, exact.
  const mpq_class& gram(int a, int b) const;
  // The tightest double intervals holding basis(row, col) and gram(a, b): equal to
  // enclose(basis(row, col)) and enclose(gram(a, b)) (number_types.hpp), without the rationals
  // (those are converted on first use).
  Interval basis_enclosure(int row, int col) const;
  Interval gram_enclosure(int a, int b) const;
  // U rounded to the nearest doubles (for approximate work and diagnostics only).
  Eigen::MatrixXd basis_approx() const;
  const std::vector<int>& pivot_columns() const;  // the k columns P of J used as pivots
  const std::vector<int>& free_columns() const;   // the other m columns, increasing

  // Exact orthogonal projection of x onto T_p: p + U G^{-1} U^T (x - p) (N rationals), and the
  // exact weight w(x) = -|x - pi_p(x)|^2 of the tangential star (docs/design.md §3.2). Slow (rational
  // linear algebra); meant for reports, tests and witnesses.
  std::vector<mpq_class> project_exact(std::span<const double> x) const;
  mpq_class weight_exact(std::span<const double> x) const;

  struct Impl;
  const Impl& impl() const { return *impl_; }
  std::shared_ptr<const Impl> shared_impl() const { return impl_; }

 private:
  std::shared_ptr<const Impl> impl_;
};

}  // namespace delcert::exact
