#include "exact/manifold_distance.hpp"

#include <Eigen/Core>
#include <Eigen/LU>
#include <Eigen/QR>
#include <algorithm>
#include <climits>
#include <cmath>
#include <stdexcept>

#include "exact/detail/cgal_number_types.hpp"
#include "exact/detail/interval_polynomial.hpp"
#include "exact/number_types.hpp"

namespace delcert::exact {

using detail::IA;

struct ManifoldDistance::Impl {
  int N = 0, k = 0;
  int scale_exponent = 0;  // the equations below are in y = x / 2^scale_exponent
  std::vector<Polynomial> f, df;  // df: k x N row-major, d f_i / d x_v
  std::vector<std::vector<Interval>> f_coef, df_coef;
  std::vector<DoublePolynomial> f_d, df_d;
  std::optional<Polynomial> selector;
  std::vector<Interval> selector_coef;
};

namespace {

using detail::coefficient_enclosures;
using detail::evaluate;
using detail::finite;

bool strictly_inside(const Box& K, const Box& T) {
  for (std::size_t i = 0; i < K.size(); ++i)
    if (!(K[i].lo > T[i].lo && K[i].hi < T[i].hi)) return false;
  return true;
}

double total_width(const Box& b) {
  double s = 0;
  for (const auto& i : b) s += i.width();
  return s;
}

struct Slice {
  const ManifoldDistance::Impl& S;
  std::span<const double> p;
  std::vector<double> A;  // k x N row-major: the normal directions (exact doubles)

  // The interval hull of p + A^T t over t in T (outward rounding; caller holds upward rounding).
  std::vector<IA> image(const Box& T) const {
    std::vector<IA> x(S.N);
    for (int v = 0; v < S.N; ++v) {
      IA acc(p[v]);
      for (int j = 0; j < S.k; ++j) acc = acc + IA(A[j * S.N + v]) * IA(T[j].lo, T[j].hi);
      x[v] = acc;
    }
    return x;
  }

  // K(T) as in the header; X receives the box on which J_F was enclosed. False when something
  // overflowed or the midpoint matrix is singular (then nothing is known).
  bool krawczyk(const Box& T, Box& K, std::vector<IA>& X) const {
    const int k = S.k, N = S.N;
    Box Y0(k);
    for (int i = 0; i < k; ++i) {
      const double y = std::clamp(T[i].lo + 0.5 * (T[i].hi - T[i].lo), T[i].lo, T[i].hi);
      Y0[i] = Interval::point(y);
    }
    std::vector<IA> gy(k), jg(static_cast<std::size_t>(k) * k);
    bool ok = true;
    {
      detail::EnsureUpward up;
      X = image(T);
      const std::vector<IA> xy = image(Y0);
      for (int i = 0; i < k; ++i) {
        gy[i] = evaluate(S.f[i], S.f_coef[i], std::span<const IA>(xy));
        ok = ok && finite(gy[i]);
      }
      std::vector<IA> jf(static_cast<std::size_t>(k) * N);
      for (int i = 0; i < k * N; ++i) {
        jf[i] = evaluate(S.df[i], S.df_coef[i], std::span<const IA>(X));
        ok = ok && finite(jf[i]);
      }
      // J_G(T) enclosed by J_F(X) A^T.
      for (int i = 0; i < k; ++i)
        for (int j = 0; j < k; ++j) {
          IA acc(0);
          for (int v = 0; v < N; ++v) acc = acc + jf[i * N + v] * IA(A[j * N + v]);
          jg[i * k + j] = acc;
          ok = ok && finite(acc);
        }
    }
    if (!ok) return false;
    Eigen::MatrixXd Y(k, k);
    {
      // Preconditioner: any matrix is correct; the inverse of the midpoint makes the test work.
      NearestRounding nearest;
      Eigen::MatrixXd mid(k, k);
      for (int i = 0; i < k; ++i)
        for (int j = 0; j < k; ++j) mid(i, j) = 0.5 * (jg[i * k + j].inf() + jg[i * k + j].sup());
      Eigen::FullPivLU<Eigen::MatrixXd> lu(mid);
      if (!lu.isInvertible()) return false;
      Y = lu.inverse();
      if (!Y.allFinite()) return false;
    }
    detail::EnsureUpward up;
    K.assign(k, Interval{});
    for (int i = 0; i < k; ++i) {
      const IA yi(Y0[i].lo);
      IA acc = yi;
      for (int j = 0; j < k; ++j) acc = acc - IA(Y(i, j)) * gy[j];
      for (int j = 0; j < k; ++j) {
        IA c(i == j ? 1.0 : 0.0);
        for (int l = 0; l < k; ++l) c = c - IA(Y(i, l)) * jg[l * k + j];
        acc = acc + c * (IA(T[j].lo, T[j].hi) - IA(Y0[j].lo));
      }
      if (!finite(acc)) return false;
      K[i] = detail::from_ia(acc);
    }
    return true;
  }
};

Box to_box(const std::vector<IA>& x) {
  Box b;
  for (const auto& i : x) b.push_back(detail::from_ia(i));
  return b;
}

// q(y) = p(2^e y) / 2^s, exactly: a term c x^a becomes c 2^(e|a|) / 2^s y^a, with 2^s within a
// factor 2 of the largest coefficient after the substitution (so q's coefficients are near 1).
Polynomial rescaled(const Polynomial& p, int e, int N) {
  if (e == 0 || p.is_zero() || p.num_variables() != N) return p;  // (a wrong size is refused by the caller)
  std::vector<mpq_class> c;
  long s = LONG_MIN;
  for (const auto& t : p.terms()) {
    long deg = 0;
    for (auto x : t.monomial.exponents) deg += static_cast<long>(x);
    mpq_class v;
    const long shift = static_cast<long>(e) * deg;
    if (shift >= 0) mpq_mul_2exp(v.get_mpq_t(), t.coefficient.get_mpq_t(), static_cast<mp_bitcnt_t>(shift));
    else mpq_div_2exp(v.get_mpq_t(), t.coefficient.get_mpq_t(), static_cast<mp_bitcnt_t>(-shift));
    s = std::max(s, static_cast<long>(mpz_sizeinbase(v.get_num_mpz_t(), 2)) -
                        static_cast<long>(mpz_sizeinbase(v.get_den_mpz_t(), 2)));
    c.push_back(std::move(v));
  }
  Polynomial out(N);
  for (std::size_t i = 0; i < c.size(); ++i) {
    if (s >= 0) mpq_div_2exp(c[i].get_mpq_t(), c[i].get_mpq_t(), static_cast<mp_bitcnt_t>(s));
    else mpq_mul_2exp(c[i].get_mpq_t(), c[i].get_mpq_t(), static_cast<mp_bitcnt_t>(-s));
    Polynomial term = Polynomial::constant(c[i], N);
    const auto& a = p.terms()[i].monomial.exponents;
    for (std::size_t v = 0; v < a.size(); ++v)
      for (std::uint32_t j = 0; j < a[v]; ++j) term = term * Polynomial::variable(static_cast<int>(v), N);
    out = out + term;
  }
  return out;
}

// Multiplies every bound by the exact 2^e, rounding outward (the caller holds upward rounding).
Interval scale_out(const Interval& x, double two_e) { return detail::from_ia(IA(x.lo, x.hi) * IA(two_e)); }

}  // namespace

ManifoldDistance::ManifoldDistance(const std::vector<Polynomial>& given, int N, const Polynomial* given_selector,
                                   int scale_exponent) {
  if (scale_exponent < -1074 || scale_exponent > 1023)
    throw std::invalid_argument("manifold distance: scale exponent outside the double range");
  std::vector<Polynomial> equations;
  for (const auto& e : given) equations.push_back(rescaled(e, scale_exponent, N));
  std::optional<Polynomial> scaled_selector;
  if (given_selector) scaled_selector = rescaled(*given_selector, scale_exponent, N);
  const Polynomial* selector = scaled_selector ? &*scaled_selector : nullptr;
  auto impl = std::make_shared<Impl>();
  impl->scale_exponent = scale_exponent;
  const int k = static_cast<int>(equations.size());
  if (N < 1 || k < 1 || k > N) throw std::invalid_argument("manifold distance: need 1 <= #equations <= N");
  impl->N = N;
  impl->k = k;
  for (const auto& e : equations) {
    Polynomial p = e;
    if (p.is_zero()) p = Polynomial(N);
    if (p.num_variables() != N) throw std::invalid_argument("manifold distance: an equation has the wrong number of variables");
    impl->f.push_back(p);
    impl->f_coef.push_back(coefficient_enclosures(p));
    impl->f_d.emplace_back(p);
  }
  for (int i = 0; i < k; ++i)
    for (int v = 0; v < N; ++v) {
      Polynomial d = impl->f[i].derivative(v);
      if (d.num_variables() != N) d = Polynomial(N);
      impl->df_coef.push_back(coefficient_enclosures(d));
      impl->df_d.emplace_back(d);
      impl->df.push_back(std::move(d));
    }
  if (selector) {
    if (selector->num_variables() != N && !selector->is_zero())
      throw std::invalid_argument("manifold distance: the selector has the wrong number of variables");
    impl->selector = selector->is_zero() ? Polynomial(N) : *selector;
    impl->selector_coef = coefficient_enclosures(*impl->selector);
  }
  impl_ = std::move(impl);
}

DistanceCertificate ManifoldDistance::certify(std::span<const double> x) const {
  const int e = impl_->scale_exponent;
  if (e == 0) return certify_scaled(x);
  if (static_cast<int>(x.size()) != impl_->N) throw std::invalid_argument("manifold distance: point of the wrong dimension");
  std::vector<double> y(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) {
    y[i] = std::ldexp(x[i], -e);  // exact unless it underflows: checked by the round trip
    if (std::isfinite(x[i]) && std::ldexp(y[i], e) != x[i]) {
      DistanceCertificate out;
      out.failure = "coordinate " + std::to_string(i) + " loses bits when scaled by 2^" + std::to_string(-e) +
                    " (the points' coordinates span more than the double exponent range)";
      return out;
    }
  }
  DistanceCertificate d = certify_scaled(y);
  detail::EnsureUpward up;
  const double two_e = std::ldexp(1.0, e);  // exact: -1074 <= e <= 1023
  d.searched_radius = (IA(d.searched_radius) * IA(two_e)).sup();
  if (!d.certified) return d;
  d.distance_upper = (IA(d.distance_upper) * IA(two_e)).sup();
  for (auto& b : d.zero_box) b = scale_out(b, two_e);
  for (auto& b : d.region) b = scale_out(b, two_e);
  if (!std::isfinite(d.distance_upper)) {
    d.certified = false;
    d.failure = "the distance bound overflows";
  }
  return d;
}

DistanceCertificate ManifoldDistance::certify_scaled(std::span<const double> p) const {
  const Impl& S = *impl_;
  const int N = S.N, k = S.k;
  DistanceCertificate out;
  if (static_cast<int>(p.size()) != N) throw std::invalid_argument("manifold distance: point of the wrong dimension");
  for (double c : p)
    if (!std::isfinite(c)) {
      out.failure = "the point has a non-finite coordinate";
      return out;
    }
  Slice slice{S, p, std::vector<double>(static_cast<std::size_t>(k) * N)};

  // ---- 1. Floating point (round to nearest): normal directions A and a Newton guess t~. -----
  Eigen::VectorXd t = Eigen::VectorXd::Zero(k);
  // The size of the point's coordinates sets the initial box and the stopping tests (relative, so
  // that the test works at every magnitude: inputs scaled by 2^-600 or 2^450 behave alike); 1 for
  // the origin. These only steer the search; correctness never depends on them.
  double scale = 0;
  {
    NearestRounding nearest;
    for (double c : p) scale = std::max(scale, std::abs(c));
    if (!(scale > 0)) scale = 1;
    auto jacobian_at = [&](const std::vector<double>& x, Eigen::MatrixXd& J, Eigen::VectorXd& g) {
      for (int i = 0; i < k; ++i) {
        g(i) = S.f_d[i](x);
        for (int v = 0; v < N; ++v) J(i, v) = S.df_d[i * N + v](x);
      }
      return J.allFinite() && g.allFinite();
    };
    std::vector<double> x(p.begin(), p.end());
    Eigen::MatrixXd J(k, N);
    Eigen::VectorXd g(k);
    if (!jacobian_at(x, J, g)) {
      out.failure = "F or its Jacobian overflows at the point";
      return out;
    }
    Eigen::HouseholderQR<Eigen::MatrixXd> qr(J.transpose());
    Eigen::MatrixXd Q = qr.householderQ() * Eigen::MatrixXd::Identity(N, k);
    if (!Q.allFinite()) {
      out.failure = "no normal directions at the point (floating-point failure)";
      return out;
    }
    for (int j = 0; j < k; ++j)
      for (int v = 0; v < N; ++v) slice.A[j * N + v] = Q(v, j);
    for (int it = 0; it < 4; ++it) {
      for (int v = 0; v < N; ++v) {
        x[v] = p[v];
        for (int j = 0; j < k; ++j) x[v] += Q(v, j) * t(j);
      }
      if (it > 0 && !jacobian_at(x, J, g)) break;
      Eigen::FullPivLU<Eigen::MatrixXd> lu(J * Q);
      if (!lu.isInvertible()) break;
      Eigen::VectorXd dt = lu.solve(-g);
      if (!dt.allFinite()) break;
      t += dt;
      if (dt.lpNorm<Eigen::Infinity>() <= 0x1p-50 * scale) break;  // at rounding level
    }
    if (!t.allFinite()) t.setZero();
  }

  // ---- 2. Krawczyk with epsilon-inflation until K(T) lies inside T. ----------------------------
  Box T(k), K;
  std::vector<IA> X;
  {
    NearestRounding nearest;
    const double r = 0x1p-20 * t.lpNorm<Eigen::Infinity>() + 0x1p-40 * scale;
    for (int i = 0; i < k; ++i) T[i] = {t(i) - r, t(i) + r};
  }
  bool proven = false;
  Box region;
  constexpr int kInflations = 8;
  for (int attempt = 0; attempt < kInflations; ++attempt) {
    ++out.krawczyk_steps;
    if (!slice.krawczyk(T, K, X)) {
      out.failure = "the interval Jacobian J_F A^T on the normal slice is singular at its midpoint or overflows";
      break;
    }
    if (strictly_inside(K, T)) {
      proven = true;
      region = to_box(X);
      break;
    }
    out.failure = "the Krawczyk operator never mapped the normal slice box into itself";
    // Next candidate: the hull of T and K, widened (any box is fine), unless it would be wider
    // than the guess itself plus 2^-10 of the scale (then K is wild: J_G is nearly singular).
    NearestRounding nearest;
    const double cap = 2 * t.lpNorm<Eigen::Infinity>() + 0x1p-10 * scale;
    Box next(k);
    bool too_wide = false;
    for (int i = 0; i < k; ++i) {
      const double lo = std::min(T[i].lo, K[i].lo), hi = std::max(T[i].hi, K[i].hi);
      const double c = lo + 0.5 * (hi - lo), rr = (hi - lo) * 1.5 + 0x1p-44 * scale;
      next[i] = {c - rr, c + rr};
      too_wide = too_wide || !(std::max(std::abs(c - rr), std::abs(c + rr)) <= cap);
    }
    if (too_wide) break;
    T = std::move(next);
  }
  {
    NearestRounding nearest;
    double s = 0;
    for (const auto& i : T) s += std::max(std::abs(i.lo), std::abs(i.hi)) * std::max(std::abs(i.lo), std::abs(i.hi));
    out.searched_radius = std::sqrt(s);
  }
  if (!proven) return out;
  out.failure.clear();

  // ---- 3. Contraction R <- K(R) n R (t* stays in R), then the zero box and the distance. ----
  // Stops when a step shrinks R by less than 1/8 or R is already at rounding level (2^-50 of the
  // coordinates' scale: the bound is then within a few ulps of |A^T t*|).
  Box R = K;
  for (int it = 0; it < 8 && total_width(R) > 0x1p-50 * scale; ++it) {
    Box K2;
    std::vector<IA> X2;
    if (!slice.krawczyk(R, K2, X2)) break;
    ++out.krawczyk_steps;
    Box next(k);
    bool empty = false;
    for (int i = 0; i < k; ++i) {
      next[i] = {std::max(K2[i].lo, R[i].lo), std::min(K2[i].hi, R[i].hi)};
      empty = empty || !(next[i].lo <= next[i].hi);
    }
    if (empty) break;  // impossible (t* is in both); keep R
    const double before = total_width(R), after = total_width(next);
    R = next;
    if (!(after < 0.875 * before)) break;
  }
  double bound = 0;
  {
    detail::EnsureUpward up;
    std::vector<IA> x = slice.image(R);
    out.zero_box = to_box(x);
    if (S.selector) {
      IA s = evaluate(*S.selector, S.selector_coef, std::span<const IA>(x));
      if (!(s.inf() > 0)) {
        out.failure = "the component selector is not certainly > 0 at the zero of F near the point";
        return out;
      }
    }
    // |A^T t|^2 <= sum_v mag(sum_j A_jv R_j)^2, every operation rounded upward (all terms are
    // >= 0, so no cancellation; an overflow gives +inf, refused below).
    double s = 0;
    for (int v = 0; v < N; ++v) {
      IA d(0);
      for (int j = 0; j < k; ++j) d = d + IA(slice.A[j * N + v]) * IA(R[j].lo, R[j].hi);
      const double mag = std::max(-d.inf(), d.sup());
      s = s + mag * mag;
    }
    // sqrt is correctly rounded in the current (upward) mode on IEEE hardware. Belt and braces
    // in case it were rounded to nearest instead: for r = fl(sqrt(s)) normal, sqrt(s) <= r +
    // ulp(r)/2 <= r (1 + 2^-52); for r subnormal, sqrt(s) <= r + 2^-1075. Both added terms are
    // rounded upward, so `bound` >= sqrt(s) in either case.
    bound = std::sqrt(s) * (1 + 0x1p-52) + 0x1p-1074;
  }
  if (!std::isfinite(bound)) {
    out.failure = "the distance bound overflows";
    return out;
  }
  out.certified = true;
  out.distance_upper = bound;
  out.region = std::move(region);
  return out;
}

}  // namespace delcert::exact
