#include "exact/enclosed_polynomial.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>

#include "exact/detail/cgal_number_types.hpp"
#include "exact/number_types.hpp"

namespace delcert::exact {

using detail::IA;

EnclosedPolynomial EnclosedPolynomial::from_exact(const Polynomial& p) {
  EnclosedPolynomial r(p.num_variables());
  for (const auto& t : p.terms()) {
    for (int v = 0; v < r.vars_; ++v)
      r.exps_.push_back(v < static_cast<int>(t.monomial.exponents.size()) ? t.monomial.exponents[v] : 0);
    r.coef_.push_back(enclose(t.coefficient));
  }
  return r;  // p's order (Polynomial's own, distinct monomials): the evaluations repeat Krawczyk's
}

EnclosedPolynomial EnclosedPolynomial::constant(Interval c, int num_variables) {
  EnclosedPolynomial r(num_variables);
  r.exps_.assign(num_variables, 0u);
  r.coef_.push_back(c);
  return r;
}

EnclosedPolynomial EnclosedPolynomial::affine(Interval constant, std::span<const Interval> linear) {
  EnclosedPolynomial r(static_cast<int>(linear.size()));
  r.exps_.assign(r.vars_, 0u);
  r.coef_.push_back(constant);
  for (int j = 0; j < r.vars_; ++j) {
    for (int v = 0; v < r.vars_; ++v) r.exps_.push_back(v == j ? 1u : 0u);
    r.coef_.push_back(linear[j]);
  }
  r.normalize();
  return r;
}

void EnclosedPolynomial::normalize() {
  const std::size_t n = coef_.size();
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), std::size_t{0});
  auto less = [&](std::size_t a, std::size_t b) {
    return std::lexicographical_compare(exps_.begin() + a * vars_, exps_.begin() + (a + 1) * vars_,
                                        exps_.begin() + b * vars_, exps_.begin() + (b + 1) * vars_);
  };
  auto equal = [&](std::size_t a, std::size_t b) {
    return std::equal(exps_.begin() + a * vars_, exps_.begin() + (a + 1) * vars_, exps_.begin() + b * vars_);
  };
  std::stable_sort(order.begin(), order.end(), less);
  std::vector<std::uint32_t> exps;
  std::vector<Interval> coef;
  detail::EnsureUpward guard;
  for (std::size_t i = 0; i < n;) {
    IA c = detail::to_ia(coef_[order[i]]);
    std::size_t j = i + 1;
    for (; j < n && equal(order[i], order[j]); ++j) c += detail::to_ia(coef_[order[j]]);
    // A coefficient enclosed by [0, 0] is exactly 0 for every polynomial the result stands for:
    // the term is dropped (the exact zeros of a sparse chart, e.g. T or Nn entries that are 0).
    if (!(c.inf() == 0 && c.sup() == 0)) {
      exps.insert(exps.end(), exps_.begin() + order[i] * vars_, exps_.begin() + (order[i] + 1) * vars_);
      coef.push_back(detail::from_ia(c));
    }
    i = j;
  }
  exps_ = std::move(exps);
  coef_ = std::move(coef);
}

EnclosedPolynomial EnclosedPolynomial::operator+(const EnclosedPolynomial& o) const {
  if (o.vars_ != vars_) throw std::invalid_argument("enclosed polynomial: sum of polynomials in different variables");
  const EnclosedPolynomial both[] = {*this, o};
  return sum(both, vars_);
}

EnclosedPolynomial EnclosedPolynomial::sum(std::span<const EnclosedPolynomial> terms, int num_variables) {
  EnclosedPolynomial r(num_variables);
  for (const auto& t : terms) {
    if (t.vars_ != num_variables) throw std::invalid_argument("enclosed polynomial: sum of polynomials in different variables");
    r.exps_.insert(r.exps_.end(), t.exps_.begin(), t.exps_.end());
    r.coef_.insert(r.coef_.end(), t.coef_.begin(), t.coef_.end());
  }
  r.normalize();
  return r;
}

EnclosedPolynomial EnclosedPolynomial::operator*(const EnclosedPolynomial& o) const {
  if (o.vars_ != vars_) throw std::invalid_argument("enclosed polynomial: product of polynomials in different variables");
  EnclosedPolynomial r(vars_);
  r.exps_.reserve(size() * o.size() * vars_);
  r.coef_.reserve(size() * o.size());
  {
    detail::EnsureUpward guard;
    for (std::size_t i = 0; i < size(); ++i)
      for (std::size_t j = 0; j < o.size(); ++j) {
        for (int v = 0; v < vars_; ++v) {
          const std::uint32_t a = exps_[i * vars_ + v], b = o.exps_[j * vars_ + v];
          if (a > UINT32_MAX - b) throw std::overflow_error("enclosed polynomial: exponent above 2^32 - 1");
          r.exps_.push_back(a + b);
        }
        r.coef_.push_back(detail::from_ia(detail::to_ia(coef_[i]) * detail::to_ia(o.coef_[j])));
      }
  }
  r.normalize();
  return r;
}

EnclosedPolynomial EnclosedPolynomial::scaled(const Interval& c) const {
  EnclosedPolynomial r = *this;
  detail::EnsureUpward guard;
  for (auto& x : r.coef_) x = detail::from_ia(detail::to_ia(x) * detail::to_ia(c));
  return r;
}

EnclosedPolynomial EnclosedPolynomial::derivative(int var) const {
  if (var < 0 || var >= vars_)
    throw std::invalid_argument("enclosed polynomial: no variable " + std::to_string(var + 1) + " to differentiate in");
  EnclosedPolynomial r(vars_);
  detail::EnsureUpward guard;
  for (std::size_t i = 0; i < size(); ++i) {
    const std::uint32_t e = exps_[i * vars_ + var];
    if (e == 0) continue;
    r.exps_.insert(r.exps_.end(), exps_.begin() + i * vars_, exps_.begin() + (i + 1) * vars_);
    r.exps_[r.coef_.size() * vars_ + var] = e - 1;
    // e < 2^32 is exact in a double.
    r.coef_.push_back(detail::from_ia(detail::to_ia(coef_[i]) * IA(static_cast<double>(e))));
  }
  // Distinct monomials stay distinct (a -> a - e_var is injective), and lowering one exponent of
  // every term keeps their order: no merging, no re-sorting needed.
  return r;
}

DoublePolynomial EnclosedPolynomial::midpoints() const {
  std::vector<double> mid;
  for (const auto& c : coef_) mid.push_back(c.midpoint());
  return DoublePolynomial(vars_, mid, exps_);
}

}  // namespace delcert::exact
