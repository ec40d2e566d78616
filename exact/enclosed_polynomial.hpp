// A polynomial known by ENCLOSURES of its coefficients (docs/design.md §4.1).
//
// An EnclosedPolynomial with monomials x^a_i and coefficient intervals C_i stands for every
// polynomial sum c_i x^a_i with c_i in C_i. Its operations keep that meaning: for every choice of
// the operands within their enclosures, the exact result lies within the result's enclosures.
// Each coefficient of a sum, product, scaling or derivative is a sum of products of operand
// coefficients (and of integer exponents), evaluated in interval arithmetic under upward
// rounding (CGAL's Interval_nt_advanced: lower bounds computed as -(upward(-x))), so by
// inclusion isotonicity it encloses the exact value for every such choice; an overflow gives an
// infinite bound, which later evaluations report as non-finite (they decide nothing then). This
// is how exact/chart.cpp builds G(u, h) = F(p + T u + Nn h) without rational arithmetic: the
// exact G (the chart's true equations) is one of the polynomials the result stands for, and
// Krawczyk answers for every one of them (exact/krawczyk.hpp).
//
// #terms by num_variables exponents, row-major; terms sorted by exponent vector, distinct, and
// none with the coefficient enclosure [0, 0] (exactly zero: dropped) except in from_exact's
// copies, which keep the exact polynomial's terms (all non-zero) and order.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "exact/interval.hpp"
#include "exact/polynomial.hpp"

namespace delcert::exact {

class EnclosedPolynomial {
 public:
  explicit EnclosedPolynomial(int num_variables = 0) : vars_(num_variables) {}
  // The coefficients of p enclosed (round-to-nearest bounds widened outward), terms in p's order.
  static EnclosedPolynomial from_exact(const Polynomial& p);
  // The constant c over num_variables variables.
  static EnclosedPolynomial constant(Interval c, int num_variables);
  // c + sum_j l_j x_j over linear.size() variables.
  static EnclosedPolynomial affine(Interval constant, std::span<const Interval> linear);

  int num_variables() const { return vars_; }
  std::size_t size() const { return coef_.size(); }
  const Interval& coefficient(std::size_t term) const { return coef_[term]; }
  std::span<const std::uint32_t> exponents(std::size_t term) const {
    return {exps_.data() + term * vars_, static_cast<std::size_t>(vars_)};
  }

  // Throw std::invalid_argument when the numbers of variables differ (operator+, operator*),
  // or var is out of range (derivative); std::overflow_error on an exponent above 2^32 - 1.
  EnclosedPolynomial operator+(const EnclosedPolynomial& o) const;
  // The sum of all of them (one normalisation), the zero polynomial in num_variables when empty.
  static EnclosedPolynomial sum(std::span<const EnclosedPolynomial> terms, int num_variables);
  EnclosedPolynomial operator*(const EnclosedPolynomial& o) const;
  EnclosedPolynomial scaled(const Interval& c) const&;
  EnclosedPolynomial scaled(const Interval& c) &&;  // the same, reusing this one's storage
  EnclosedPolynomial derivative(int var) const;

  // The polynomial without the terms whose exponents satisfy `known_zero`: for a caller that
  // knows those coefficients to be exactly 0 in the polynomial it stands for (it then stands for
  // it still).
  template <class Pred>
  EnclosedPolynomial without(Pred known_zero) const {
    EnclosedPolynomial r(vars_);
    for (std::size_t i = 0; i < size(); ++i)
      if (!known_zero(exponents(i))) {
        r.exps_.insert(r.exps_.end(), exponents(i).begin(), exponents(i).end());
        r.coef_.push_back(coef_[i]);
      }
    return r;
  }

  // The polynomial of the coefficients' midpoints, for approximate values (Newton guesses only).
  DoublePolynomial midpoints() const;

 private:
  // Sorts the terms by exponents and adds the coefficients of equal monomials (upward rounding).
  void normalize();
  int vars_ = 0;
  std::vector<std::uint32_t> exps_;
  std::vector<Interval> coef_;
};

}  // namespace delcert::exact
