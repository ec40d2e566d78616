#include "exact/tangent_space.hpp"

#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>

#include "exact/detail/kernels.hpp"
#include "exact/detail/tangent_impl.hpp"
#include "exact/equations.hpp"
#include "exact/interval.hpp"
#include "exact/linear_algebra.hpp"
#include "exact/number_types.hpp"

namespace delcert::exact {

static_assert(detail::kMaxCodim == kMaxCodimension);  // (exact/equations.hpp)

using detail::EX;
using detail::IA;

namespace {

// The tightest double interval holding x: enclose(to_mpq(x)) (number_types.hpp), without the
// rational when CGAL's enclosure [lo, hi] of the dyadic x already is it: x equal to an end (an
// exact comparison of dyadics), or lo and hi adjacent doubles with x strictly between them, so
// lo = RD(x) and hi = RU(x), which is what enclose returns (for x > 0 its truncation RD(x) and
// the next double up, for x < 0 the next double down and RU(x)). Otherwise (wider, infinite)
// through the rational.
Interval tight_enclosure(const EX& x) {
  const auto [lo, hi] = detail::to_interval_nearest(x);
  if (std::isfinite(lo) && std::isfinite(hi)) {
    if (EX(lo) == x) return Interval::point(lo);
    if (EX(hi) == x) return Interval::point(hi);
    if (lo < hi && std::nextafter(lo, std::numeric_limits<double>::infinity()) == hi) return {lo, hi};
  }
  return enclose(detail::to_mpq(x));
}

std::vector<EX> to_ex(std::span<const double> x) {
  std::vector<EX> out;
  out.reserve(x.size());
  for (double v : x) {
    if (!std::isfinite(v))
      throw std::invalid_argument("non-finite coordinate: exact predicates need finite doubles");
    out.emplace_back(v);  // exact: Mpzf represents every double
  }
  return out;
}

// k x k determinant of the columns `cols` of the k x N matrix J (row-major), exactly.
EX minor_of(const std::vector<EX>& J, int k, int N, const std::vector<int>& cols) {
  std::vector<EX> a(static_cast<std::size_t>(k) * k);
  for (int i = 0; i < k; ++i)
    for (int c = 0; c < k; ++c) a[i * k + c] = J[i * N + cols[c]];
  return detail::dispatch<1, detail::kMaxCodim>(k, [&](auto K) { return determinant<K()>(a.data()); });
}

// Maximal minors of the k x (k+1) matrix [J_P | J_f]: out[j] = det(columns without j).
void maximal_minors(const std::vector<EX>& J, int k, int N, const std::vector<int>& P, int f, std::vector<EX>& out) {
  detail::dispatch<1, detail::kMaxCodim>(k, [&](auto K) {
    constexpr int R = K();
    constexpr int C = R + 1;
    std::vector<EX> a(static_cast<std::size_t>(R) * C);
    for (int i = 0; i < R; ++i) {
      for (int c = 0; c < R; ++c) a[i * C + c] = J[i * N + P[c]];
      a[i * C + R] = J[i * N + f];
    }
    std::vector<EX> table(1u << C);
    minor_table<R, C>(a.data(), table.data());
    out.resize(C);
    for (int j = 0; j < C; ++j) out[j] = table[((1u << C) - 1) ^ (1u << j)];
  });
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// ImplicitSystem
// ---------------------------------------------------------------------------------------------

ImplicitSystem::ImplicitSystem(std::vector<Polynomial> equations, int N) {
  auto impl = std::make_shared<Impl>();
  const int k = static_cast<int>(equations.size());
  if (N < 1) throw std::invalid_argument("ambient dimension must be positive");
  if (k >= N)
    throw std::invalid_argument("a manifold of R^" + std::to_string(N) + " needs fewer than " + std::to_string(N) +
                                " equations (got " + std::to_string(k) + ")");
  if (k > detail::kMaxCodim)
    throw std::invalid_argument("codimension " + std::to_string(k) + " exceeds the supported maximum " +
                                std::to_string(detail::kMaxCodim));
  for (int i = 0; i < k; ++i)
    if (equations[i].num_variables() != N && !equations[i].is_zero())
      throw std::invalid_argument("equation " + std::to_string(i + 1) + " has " +
                                  std::to_string(equations[i].num_variables()) + " variables, expected " +
                                  std::to_string(N));
  impl->N = N;
  impl->k = k;
  impl->equations = std::move(equations);
  for (int i = 0; i < k; ++i) {
    // D_i F_i has integer coefficients (integer_form), and so do its derivatives.
    const Polynomial& f = impl->equations[i];
    const auto form = f.integer_form();
    Polynomial scaled = f.scaled(mpq_class(form.denominator));
    impl->scaled.push_back(scaled);
    impl->scaled_coefficients.emplace_back();
    for (const auto& t : scaled.terms()) impl->scaled_coefficients.back().push_back(detail::to_ex(t.coefficient.get_num()));
    impl->denominators.push_back(enclose(mpq_class(form.denominator)));
    for (int j = 0; j < N; ++j) {
      Polynomial d = scaled.is_zero() ? Polynomial(N) : scaled.derivative(j);
      std::vector<EX> coefs;
      for (const auto& t : d.terms()) {
        // Integer by construction: derivative of an integer-coefficient polynomial.
        coefs.push_back(detail::to_ex(t.coefficient.get_num()));
      }
      impl->derivatives.push_back(f.is_zero() ? Polynomial(N) : f.derivative(j));
      impl->jacobian_double.emplace_back(impl->derivatives.back());
      impl->jacobian_coefficients.push_back(std::move(coefs));
      impl->jacobian.push_back(std::move(d));
    }
  }
  impl_ = std::move(impl);
}

ImplicitSystem ImplicitSystem::parse(const std::vector<std::string>& equations, int N) {
  std::vector<Polynomial> polys;
  for (const auto& e : equations) polys.push_back(Polynomial::parse(e, N));
  return ImplicitSystem(std::move(polys), N);
}

int ImplicitSystem::ambient_dimension() const { return impl_->N; }
int ImplicitSystem::codimension() const { return impl_->k; }
int ImplicitSystem::intrinsic_dimension() const { return impl_->N - impl_->k; }
const std::vector<Polynomial>& ImplicitSystem::equations() const { return impl_->equations; }

std::vector<Interval> ImplicitSystem::residual_enclosures(std::span<const double> x) const {
  const Impl& S = *impl_;
  if (static_cast<int>(x.size()) != S.N) throw std::invalid_argument("point has the wrong dimension");
  const std::vector<EX> xe = to_ex(x);
  detail::EnsureUpward up;  // the interval division below
  std::vector<Interval> out;
  for (int i = 0; i < S.k; ++i) {
    const auto& coefs = S.scaled_coefficients[i];
    EX s = S.scaled[i].is_zero() ? EX(0)
                                 : S.scaled[i].evaluate_with<EX>(std::span<const EX>(xe), [&](std::size_t t) { return coefs[t]; });
    if (s.sign() < 0) s = EX(0) - s;
    const IA v = detail::enclose_ex(s) / IA(S.denominators[i].lo, S.denominators[i].hi);
    out.push_back({std::max(0.0, v.inf()), v.sup()});
  }
  return out;
}

std::vector<EX> ImplicitSystem::Impl::jacobian_at(const std::vector<EX>& x) const {
  std::vector<EX> J(static_cast<std::size_t>(k) * N);
  std::span<const EX> xs(x);
  for (int i = 0; i < k * N; ++i) {
    const auto& coefs = jacobian_coefficients[i];
    J[i] = jacobian[i].evaluate_with<EX>(xs, [&](std::size_t t) { return coefs[t]; });
  }
  return J;
}

std::vector<mpq_class> ImplicitSystem::evaluate_exact(std::span<const double> x) const {
  if (static_cast<int>(x.size()) != impl_->N) throw std::invalid_argument("point has the wrong dimension");
  auto xq = to_rational(x);
  std::vector<mpq_class> out;
  for (const auto& f : impl_->equations) out.push_back(f.is_zero() ? mpq_class(0) : f.evaluate(std::span<const mpq_class>(xq)));
  return out;
}

std::vector<mpq_class> ImplicitSystem::jacobian_exact(std::span<const double> x) const {
  if (static_cast<int>(x.size()) != impl_->N) throw std::invalid_argument("point has the wrong dimension");
  auto xq = to_rational(x);
  std::vector<mpq_class> out;
  out.reserve(impl_->derivatives.size());
  for (const auto& d : impl_->derivatives) out.push_back(d.evaluate(std::span<const mpq_class>(xq)));
  return out;
}

Eigen::MatrixXd ImplicitSystem::jacobian(std::span<const double> x) const {
  Eigen::MatrixXd J(impl_->k, impl_->N);
  for (int i = 0; i < impl_->k; ++i)
    for (int j = 0; j < impl_->N; ++j) J(i, j) = impl_->jacobian_double[i * impl_->N + j](x);
  return J;
}

// ---------------------------------------------------------------------------------------------
// TangentSpace
// ---------------------------------------------------------------------------------------------

TangentSpace::TangentSpace(const ImplicitSystem& system, std::span<const double> p) {
  const auto& sys = system.impl();
  const int N = sys.N, k = sys.k, m = N - k;
  if (static_cast<int>(p.size()) != N)
    throw std::invalid_argument("point has dimension " + std::to_string(p.size()) + ", the manifold's ambient dimension is " +
                                std::to_string(N));
  auto impl = std::make_shared<Impl>();
  impl->N = N;
  impl->m = m;
  impl->k = k;
  impl->p.assign(p.begin(), p.end());
  impl->p_exact = to_ex(p);
  impl->U_exact.assign(static_cast<std::size_t>(N) * m, EX(0));

  if (k == 0) {
    // No equations: T_p = R^N, U = identity.
    for (int i = 0; i < N; ++i) impl->U_exact[i * m + i] = EX(1);
    impl->frees.resize(N);
    std::iota(impl->frees.begin(), impl->frees.end(), 0);
  } else {
    const std::vector<EX> J = sys.jacobian_at(impl->p_exact);

    // Pivot order from a column-pivoted QR of the double Jacobian with normalised rows. This only
    // chooses which exact minor to use; correctness does not depend on it.
    std::vector<int> order(N);
    {
      NearestRounding nearest;  // ordinary floating point, even inside a caller's UpwardRounding
      Eigen::MatrixXd Jd(k, N);
      for (int i = 0; i < k; ++i)
        for (int j = 0; j < N; ++j) Jd(i, j) = sys.jacobian_double[i * N + j](p);
      bool finite = Jd.allFinite();
      if (finite) {
        for (int i = 0; i < k; ++i) {
          double nrm = Jd.row(i).norm();
          if (nrm > 0 && std::isfinite(nrm)) Jd.row(i) /= nrm;
        }
        Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(Jd);
        const auto& perm = qr.colsPermutation().indices();
        for (int j = 0; j < N; ++j) order[j] = perm[j];
      } else {
        std::iota(order.begin(), order.end(), 0);
      }
    }
    std::vector<int> P(order.begin(), order.begin() + k);
    std::sort(P.begin(), P.end());
    EX det = minor_of(J, k, N, P);
    if (det.is_zero()) {
      // Exhaustive search over column sets, in the preference order of the QR permutation.
      std::vector<int> byrank = order;  // column ids sorted by preference
      std::vector<int> comb(k);
      std::iota(comb.begin(), comb.end(), 0);
      bool found = false;
      for (;;) {
        std::vector<int> cols(k);
        for (int c = 0; c < k; ++c) cols[c] = byrank[comb[c]];
        std::sort(cols.begin(), cols.end());
        EX d = minor_of(J, k, N, cols);
        if (!d.is_zero()) {
          P = cols;
          det = d;
          found = true;
          break;
        }
        int c = k - 1;
        while (c >= 0 && comb[c] == N - k + c) --c;
        if (c < 0) break;
        ++comb[c];
        for (int e = c + 1; e < k; ++e) comb[e] = comb[e - 1] + 1;
      }
      if (!found) {
        std::string where;
        for (int i = 0; i < N; ++i) where += (i ? ", " : "") + std::to_string(p[i]);
        throw std::domain_error("the Jacobian of the manifold's equations is rank deficient at the point (" + where +
                                "): it is a singular point of F, so T_p = p + ker J_F(p) is not an m-flat; move "
                                "the point or fix the equations");
      }
    }
    impl->pivots = P;
    for (int j = 0, pi = 0; j < N; ++j) {
      if (pi < k && P[pi] == j) {
        ++pi;
        continue;
      }
      impl->frees.push_back(j);
    }
    // Kernel vectors by Cramer's rule without division (see the header):
    //   u_f[f] = det J_P,  u_f[P_l] = -det(J_P with column l replaced by J_f).
    // With minors_j = det([J_P | J_f] without column j): det J_P = minors_k and moving J_f from
    // the last position to position l takes k - 1 - l transpositions, so
    // det(J_P with column l replaced by J_f) = (-1)^(k-1-l) minors_l and u_f[P_l] = (-1)^(k-l) minors_l.
    // Finally U is multiplied by sign(det J_P) so that u_f[f] > 0 (a normalisation only).
    const bool flip = det.sign() < 0;
    std::vector<EX> minors;
    for (int a = 0; a < m; ++a) {
      const int f = impl->frees[a];
      maximal_minors(J, k, N, P, f, minors);
      EX uf = minors[k];
      impl->U_exact[f * m + a] = flip ? EX(0) - uf : uf;
      for (int l = 0; l < k; ++l) {
        EX v = ((k - l) % 2 == 0) ? minors[l] : EX(0) - minors[l];
        impl->U_exact[P[l] * m + a] = flip ? EX(0) - v : v;
      }
    }
  }

  // Enclosures and the exact Gram matrix (the rationals wait for their first use).
  impl->U_interval.reserve(impl->U_exact.size());
  impl->U_tight.reserve(impl->U_exact.size());
  for (const auto& u : impl->U_exact) {
    impl->U_interval.push_back(detail::enclose_ex(u));
    impl->U_tight.push_back(tight_enclosure(u));
  }
  {
    detail::EnsureUpward guard;
    for (const IA& u : impl->U_interval) {
      if (!std::isfinite(u.inf()) || !std::isfinite(u.sup())) {
        // Beyond the double range: the fast chart rows become non-finite and fall back to
        // interval arithmetic (then to exact arithmetic).
        const double inf = std::numeric_limits<double>::infinity();
        impl->U_mid.push_back(0.0);
        impl->U_rad.push_back(inf);
        impl->U_err.push_back(inf);
        continue;
      }
      // Any double in [lo, hi] will do as the midpoint; the radius is rounded up.
      const double mid = std::clamp(u.inf() + 0.5 * (u.sup() - u.inf()), u.inf(), u.sup());
      impl->U_mid.push_back(mid);
      const double rad = std::max((IA(u.sup()) - IA(mid)).sup(), (IA(mid) - IA(u.inf())).sup());
      impl->U_rad.push_back(rad);
      // (N + 3) eps |mid| + (1 + 2 eps) rad, rounded up (eps = 2^-52; see interval_row).
      const double eps = 0x1.0p-52;
      impl->U_err.push_back((IA((N + 3) * eps) * IA(std::abs(mid)) + IA(1 + 2 * eps) * IA(rad)).sup());
    }
  }
  impl->G_exact.assign(static_cast<std::size_t>(m) * m, EX(0));
  for (int a = 0; a < m; ++a)
    for (int b = a; b < m; ++b) {
      EX g(0);
      for (int i = 0; i < N; ++i) g = g + impl->U_exact[i * m + a] * impl->U_exact[i * m + b];
      impl->G_exact[a * m + b] = impl->G_exact[b * m + a] = g;
    }
  for (const auto& g : impl->G_exact) impl->G_tight.push_back(tight_enclosure(g));
  // adj(G) (symmetric): cofactors by exact determinants. Used by faces of dimension < m, which
  // (like all tangential predicates) are supported for m <= kMaxIntrinsicDim.
  if (m <= detail::kMaxIntrinsicDim) {
    impl->adj_gram_exact.assign(static_cast<std::size_t>(m) * m, EX(0));
    adjugate(impl->G_exact.data(), m, impl->adj_gram_exact.data());
    for (const auto& a : impl->adj_gram_exact) impl->adj_gram_interval.push_back(detail::enclose_ex(a));
  }
  impl_ = std::move(impl);
}

int TangentSpace::ambient_dimension() const { return impl_->N; }
int TangentSpace::intrinsic_dimension() const { return impl_->m; }
std::span<const double> TangentSpace::point() const { return impl_->p; }
const std::vector<mpq_class>& TangentSpace::Impl::U_rational() const {
  std::call_once(rational_once, [this] {
    for (const auto& u : U_exact) U_rational_.push_back(detail::to_mpq(u));
    for (const auto& g : G_exact) gram_.push_back(detail::to_mpq(g));
  });
  return U_rational_;
}
const std::vector<mpq_class>& TangentSpace::Impl::gram() const {
  U_rational();
  return gram_;
}

const mpq_class& TangentSpace::basis(int row, int col) const { return impl_->U_rational().at(row * impl_->m + col); }
const mpq_class& TangentSpace::gram(int a, int b) const { return impl_->gram().at(a * impl_->m + b); }
Interval TangentSpace::basis_enclosure(int row, int col) const { return impl_->U_tight.at(row * impl_->m + col); }
Interval TangentSpace::gram_enclosure(int a, int b) const { return impl_->G_tight.at(a * impl_->m + b); }
const std::vector<int>& TangentSpace::pivot_columns() const { return impl_->pivots; }
const std::vector<int>& TangentSpace::free_columns() const { return impl_->frees; }

Eigen::MatrixXd TangentSpace::basis_approx() const {
  Eigen::MatrixXd U(impl_->N, impl_->m);
  for (int i = 0; i < impl_->N; ++i)
    for (int a = 0; a < impl_->m; ++a) U(i, a) = impl_->U_rational()[i * impl_->m + a].get_d();
  return U;
}

std::vector<mpq_class> TangentSpace::project_exact(std::span<const double> x) const {
  const int N = impl_->N, m = impl_->m;
  if (static_cast<int>(x.size()) != N) throw std::invalid_argument("point has the wrong dimension");
  std::vector<mpq_class> d(N), r(m, mpq_class(0));
  for (int i = 0; i < N; ++i) d[i] = to_rational(x[i]) - to_rational(impl_->p[i]);
  for (int a = 0; a < m; ++a)
    for (int i = 0; i < N; ++i) r[a] += impl_->U_rational()[i * m + a] * d[i];
  // G z = r, G = U^T U symmetric positive definite.
  const auto z = solve(impl_->gram(), r, m);
  if (!z) throw std::domain_error("singular Gram matrix (internal error: U must have full rank)");
  std::vector<mpq_class> out(N);
  for (int i = 0; i < N; ++i) {
    out[i] = to_rational(impl_->p[i]);
    for (int a = 0; a < m; ++a) out[i] += impl_->U_rational()[i * m + a] * (*z)[a];
  }
  return out;
}

mpq_class TangentSpace::weight_exact(std::span<const double> x) const {
  auto q = project_exact(x);
  mpq_class s = 0;
  for (int i = 0; i < impl_->N; ++i) {
    mpq_class d = to_rational(x[i]) - q[i];
    s += d * d;
  }
  return -s;
}

}  // namespace delcert::exact
