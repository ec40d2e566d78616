#include "exact/enclosed_polynomial.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>
#include <utility>

#include "exact/detail/cgal_number_types.hpp"
#include "exact/number_types.hpp"
#include "exact/small_buffer.hpp"

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
  r.exps_.reserve(static_cast<std::size_t>(r.vars_) * (r.vars_ + 1));
  r.coef_.reserve(static_cast<std::size_t>(r.vars_) + 1);
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
  // The terms in lexicographic order of their exponents, ties in their current order (so equal
  // monomials are summed in the order they came: the same sums as a stable sort), merged into the
  // front of exps_ and coef_ (the result is never longer). Scratch on the stack for the usual
  // sizes (a chart's polynomials: a few dozen terms): the charts are built once per point.
  const std::size_t n = coef_.size(), w = static_cast<std::size_t>(vars_);
  SmallBuffer<std::size_t, 64> order(n);
  std::iota(order.begin(), order.end(), std::size_t{0});
  auto cmp = [&](std::size_t a, std::size_t b) {
    return std::lexicographical_compare(exps_.begin() + a * w, exps_.begin() + (a + 1) * w, exps_.begin() + b * w,
                                        exps_.begin() + (b + 1) * w);
  };
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return cmp(a, b) || (!cmp(b, a) && a < b); });
  auto equal = [&](std::size_t a, std::size_t b) { return std::equal(exps_.begin() + a * w, exps_.begin() + (a + 1) * w, exps_.begin() + b * w); };
  SmallBuffer<std::uint32_t, 512> exps(n * w);
  SmallBuffer<Interval, 64> coef(n);
  std::size_t out = 0;
  detail::EnsureUpward guard;
  for (std::size_t i = 0; i < n;) {
    IA c = detail::to_ia(coef_[order[i]]);
    std::size_t j = i + 1;
    for (; j < n && equal(order[i], order[j]); ++j) c += detail::to_ia(coef_[order[j]]);
    // A coefficient enclosed by [0, 0] is exactly 0 for every polynomial the result stands for:
    // the term is dropped (the exact zeros of a sparse chart, e.g. T or Nn entries that are 0).
    if (!(c.inf() == 0 && c.sup() == 0)) {
      std::copy(exps_.begin() + order[i] * w, exps_.begin() + (order[i] + 1) * w, exps.begin() + out * w);
      coef[out++] = detail::from_ia(c);
    }
    i = j;
  }
  exps_.assign(exps.begin(), exps.begin() + out * w);
  coef_.assign(coef.begin(), coef.begin() + out);
}

EnclosedPolynomial EnclosedPolynomial::operator+(const EnclosedPolynomial& o) const {
  if (o.vars_ != vars_) throw std::invalid_argument("enclosed polynomial: sum of polynomials in different variables");
  const EnclosedPolynomial both[] = {*this, o};
  return sum(both, vars_);
}

EnclosedPolynomial EnclosedPolynomial::sum(std::span<const EnclosedPolynomial> terms, int num_variables) {
  EnclosedPolynomial r(num_variables);
  std::size_t total = 0;
  for (const auto& t : terms) total += t.size();
  r.exps_.reserve(total * static_cast<std::size_t>(num_variables));
  r.coef_.reserve(total);
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

EnclosedPolynomial EnclosedPolynomial::scaled(const Interval& c) const& { return EnclosedPolynomial(*this).scaled(c); }

EnclosedPolynomial EnclosedPolynomial::scaled(const Interval& c) && {
  detail::EnsureUpward guard;
  for (auto& x : coef_) x = detail::from_ia(detail::to_ia(x) * detail::to_ia(c));
  return std::move(*this);
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
  mid.reserve(coef_.size());
  for (const auto& c : coef_) mid.push_back(c.midpoint());
  return DoublePolynomial(vars_, mid, exps_);
}

}  // namespace delcert::exact
