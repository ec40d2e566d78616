#include "exact/chart.hpp"

#include <Eigen/Core>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>

#include "exact/detail/cgal_number_types.hpp"
#include "exact/detail/interval_polynomial.hpp"
#include "exact/enclosed_polynomial.hpp"
#include "exact/number_types.hpp"
#include "exact/small_buffer.hpp"

namespace delcert::exact {

using detail::IA;

std::string_view to_string(ChartStatus status) {
  switch (status) {
    case ChartStatus::unique: return "unique";
    case ChartStatus::none: return "none";
    case ChartStatus::undecided: return "undecided";
  }
  return "unknown";
}

struct ChartEnclosure::Impl {
  int N = 0, m = 0, k = 0;
  std::vector<double> p;
  std::vector<mpq_class> T, Nn;              // N x m, N x k, row-major
  std::vector<Interval> T_enc, Nn_enc;       // their enclosures
  ParametricSystem G;                        // k equations in (u, h)
  // G, d G_i / d h_j (k x k), d G_i / d u_a (k x m), for their approximate values (Newton).
  std::vector<DoublePolynomial> g, gh, gu;
  ChartOptions options;

  Impl(ParametricSystem system) : G(std::move(system)) {}
};

namespace {

// F(p + T u + Nn h) by enclosures: every variable x_v of F is replaced by the enclosed affine
// polynomial A_v in the m + k variables (u, h), and the products are expanded in interval
// arithmetic (exact/enclosed_polynomial.hpp).
EnclosedPolynomial substitute_affine(const Polynomial& f, const std::vector<EnclosedPolynomial>& A, int vars) {
  std::vector<EnclosedPolynomial> parts;
  parts.reserve(f.terms().size());
  std::vector<std::vector<EnclosedPolynomial>> powers(A.size());  // powers[v][e - 2] = A_v^e, filled lazily
  auto power = [&](std::size_t v, std::uint32_t e) -> const EnclosedPolynomial& {
    if (e == 1) return A[v];
    auto& pw = powers[v];
    while (pw.size() < e - 1) pw.push_back((pw.empty() ? A[v] : pw.back()) * A[v]);
    return pw[e - 2];
  };
  for (const auto& t : f.terms()) {
    // The product of the powers, then one scaling by the coefficient's enclosure.
    std::optional<EnclosedPolynomial> prod;
    for (std::size_t v = 0; v < t.monomial.exponents.size(); ++v)
      if (t.monomial.exponents[v] > 0) {
        const EnclosedPolynomial& pw = power(v, t.monomial.exponents[v]);
        prod = prod ? *prod * pw : pw;
      }
    const Interval c = enclose(t.coefficient);
    parts.push_back(prod ? std::move(*prod).scaled(c) : EnclosedPolynomial::constant(c, vars));
  }
  return EnclosedPolynomial::sum(parts, vars);
}

// A certified lower bound, rounded down, of the smallest eigenvalue of the Gram matrix A^T A of
// the exact A (rows x cols, row-major; `enc` its enclosures); 0 when none is found positive.
// First Gershgorin's bound min_a (G_aa - sum_{b != a} |G_ab|) in interval arithmetic from the
// enclosures (each computed G_ab encloses the exact entry, so the computed lower end is below the
// exact Gershgorin bound, itself below the eigenvalue): enough for the nearly orthogonal columns
// of a chart. Failing that, exactly: the larger of Gershgorin's bound and det / trace^(cols - 1)
// (the product of the other eigenvalues is at most trace^(cols - 1)).
double smallest_eigenvalue_bound(const std::vector<mpq_class>& A, std::span<const Interval> enc, int rows, int cols) {
  {
    detail::EnsureUpward guard;
    std::vector<IA> G(static_cast<std::size_t>(cols) * cols, IA(0));
    for (int a = 0; a < cols; ++a)
      for (int b = 0; b < cols; ++b)
        for (int v = 0; v < rows; ++v) G[a * cols + b] += detail::to_ia(enc[v * cols + a]) * detail::to_ia(enc[v * cols + b]);
    double gersh = 0;
    for (int a = 0; a < cols; ++a) {
      IA row = G[a * cols + a];
      for (int b = 0; b < cols; ++b)
        if (b != a) row -= CGAL::abs(G[a * cols + b]);
      if (a == 0 || row.inf() < gersh) gersh = row.inf();
    }
    if (gersh > 0 && std::isfinite(gersh)) return gersh;
  }
  std::vector<mpq_class> G(static_cast<std::size_t>(cols) * cols);
  for (int a = 0; a < cols; ++a)
    for (int b = 0; b < cols; ++b)
      for (int v = 0; v < rows; ++v) G[a * cols + b] += A[v * cols + a] * A[v * cols + b];
  mpq_class gersh = -1, trace = 0;
  for (int a = 0; a < cols; ++a) {
    mpq_class row = G[a * cols + a];
    for (int b = 0; b < cols; ++b)
      if (b != a) row -= abs(G[a * cols + b]);
    if (a == 0 || row < gersh) gersh = row;
    trace += G[a * cols + a];
  }
  // det G by exact Gaussian elimination (G is positive semidefinite: a zero pivot means det 0).
  std::vector<mpq_class> E = G;
  mpq_class det = 1;
  for (int c = 0; c < cols && det != 0; ++c) {
    det *= E[c * cols + c];
    if (det == 0) break;
    for (int r = c + 1; r < cols; ++r) {
      const mpq_class f = E[r * cols + c] / E[c * cols + c];
      for (int j = c; j < cols; ++j) E[r * cols + j] -= f * E[c * cols + j];
    }
  }
  mpq_class bound = det;
  for (int i = 1; i < cols; ++i) bound /= trace;
  bound = std::max(bound, gersh);
  return bound > 0 ? enclose(bound).lo : 0;
}

// The power of two 2^s with max |column entry| * 2^s in [1/2, 1) (1 for a zero column).
mpq_class column_scale(const std::vector<mpq_class>& M, int rows, int cols, int c) {
  mpq_class big = 0;
  for (int r = 0; r < rows; ++r)
    if (abs(M[r * cols + c]) > big) big = abs(M[r * cols + c]);
  if (big == 0) return 1;
  // Start from 2^(bits(den) - bits(num)): big times it lies in (1/2, 2), so at most one step is left.
  const long e = static_cast<long>(mpz_sizeinbase(big.get_den_mpz_t(), 2)) -
                 static_cast<long>(mpz_sizeinbase(big.get_num_mpz_t(), 2));
  mpq_class s = 1;
  if (e >= 0) mpq_mul_2exp(s.get_mpq_t(), s.get_mpq_t(), static_cast<mp_bitcnt_t>(e));
  else mpq_div_2exp(s.get_mpq_t(), s.get_mpq_t(), static_cast<mp_bitcnt_t>(-e));
  while (big * s >= 1) s /= 2;
  while (big * s < mpq_class(1, 2)) s *= 2;
  return s;
}

double max_abs(std::span<const double> v) {
  double r = 0;
  for (double x : v) r = std::max(r, std::abs(x));
  return r;
}

// guess_slab for codimension 1 (hypersurfaces: the common case), with scalars instead of a 1 x 1
// LU. It computes the same doubles as the general version: Eigen's FullPivLU of a 1 x 1 matrix
// J is invertible iff J != 0 (the rank threshold is |J| eps < |J|), solves a vector right-hand
// side by dividing by J (TriangularSolverVector.h) and a matrix right-hand side by multiplying
// with 1 / J (TriangularSolverMatrix.h); the permutations are the identity. Ordinary floating
// point, as in guess_slab: it only chooses H.
bool guess_slab_scalar(const ChartEnclosure::Impl& S, const Box& U, std::span<const double> h_hint,
                       std::vector<double>& h0, std::vector<double>& r) {
  const int m = S.m;
  double zbuf[16];
  std::vector<double> zvec;
  if (m + 1 > 16) zvec.resize(m + 1);
  const std::span<double> z(m + 1 > 16 ? zvec.data() : zbuf, m + 1);
  double rad_u = 0;
  NearestRounding nearest;
  for (int a = 0; a < m; ++a) rad_u = std::max(rad_u, 0.5 * U[a].width());
  double g = 0, jh = 0;
  auto linearise = [&](double h) {
    z[m] = h;
    const std::span<const double> zc(z.data(), z.size());
    g = S.g[0](zc);
    jh = S.gh[0](zc);
    return std::isfinite(g) && std::isfinite(jh);
  };
  // Newton for G(z_u, .) = 0 from h; false when it breaks down. On success g and jh hold the
  // values at the final iterate (J_u is evaluated by the caller where needed).
  auto newton = [&](double& h) {
    for (int it = 0; it < S.options.newton_steps; ++it) {
      if (!linearise(h)) return false;
      if (jh == 0) return false;
      const double step = g / jh;
      h -= step;
      const double size = std::abs(step), scale = std::abs(h);
      if (!std::isfinite(size)) return false;
      if (size <= 0x1.0p-50 * (scale + rad_u)) break;
    }
    return linearise(h);
  };
  auto ju_finite = [&] {
    const std::span<const double> zc(z.data(), z.size());
    for (int a = 0; a < m; ++a)
      if (!std::isfinite(S.gu[a](zc))) return false;
    return true;
  };
  for (int a = 0; a < m; ++a) z[a] = std::clamp(U[a].midpoint(), U[a].lo, U[a].hi);
  if (!h_hint.empty()) h0.assign(h_hint.begin(), h_hint.end());
  if (!newton(h0[0]) || !ju_finite()) return false;  // no approximate point of M over the centre
  if (jh == 0) return false;
  {
    const std::span<const double> zc(z.data(), z.size());
    const double inv = 1.0 / jh;
    for (int a = 0; a < m; ++a) r[0] += std::abs(S.gu[a](zc) * inv) * 0.5 * U[a].width();
  }
  for (int corner = 0; corner < (1 << m); ++corner) {
    for (int a = 0; a < m; ++a) z[a] = (corner >> a) & 1 ? U[a].hi : U[a].lo;
    double hc = h0[0];
    if (!newton(hc) || !ju_finite()) continue;
    r[0] = std::max(r[0], std::abs(hc - h0[0]));
  }
  double floor_scale = max_abs(h0) + rad_u;
  if (floor_scale == 0) floor_scale = max_abs(S.p);
  r[0] = S.options.safety * r[0] + 0x1.0p-30 * floor_scale + 0x1.0p-1000;
  return std::isfinite(r[0]);
}

// The approximate centre h0 and predicted spread r of enclose() (see chart.hpp), in ordinary
// floating point (it only chooses H). False when no approximate point of M over U's centre is
// found. MaxK, MaxM bound k and m for Eigen's storage (Eigen::Dynamic: unbounded, on the heap).
template <int MaxK, int MaxM>
bool guess_slab(const ChartEnclosure::Impl& S, const Box& U, std::span<const double> h_hint, std::vector<double>& h0,
                std::vector<double>& r) {
  using MatKK = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, MaxK, MaxK>;
  using MatKM = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, MaxK, MaxM>;
  using VecK = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, MaxK, 1>;
  const int m = S.m, k = S.k;
  double zbuf[16];
  std::vector<double> zvec;
  if (m + k > 16) zvec.resize(m + k);
  const std::span<double> z(m + k > 16 ? zvec.data() : zbuf, m + k);
  double rad_u = 0;
  NearestRounding nearest;
  for (int a = 0; a < m; ++a) rad_u = std::max(rad_u, 0.5 * U[a].width());
  MatKK Jh(k, k);
  MatKM Ju(k, m);
  VecK g(k);
  // G and J_h at (z_u, h) in double (with J_u too when `with_u`); false on overflow. The Newton
  // steps need J_u only at the final iterate (it only feeds the slope estimate).
  auto linearise = [&](const double* h, bool with_u) {
    for (int i = 0; i < k; ++i) z[m + i] = h[i];
    const std::span<const double> zc(z.data(), z.size());
    for (int i = 0; i < k; ++i) {
      g(i) = S.g[i](zc);
      for (int j = 0; j < k; ++j) Jh(i, j) = S.gh[i * k + j](zc);
      if (with_u)
        for (int a = 0; a < m; ++a) Ju(i, a) = S.gu[i * m + a](zc);
    }
    return g.allFinite() && Jh.allFinite() && (!with_u || Ju.allFinite());
  };
  // Newton for G(z_u, .) = 0 from h; false when it breaks down.
  Eigen::FullPivLU<MatKK> lu(k, k);
  auto newton = [&](double* h) {
    for (int it = 0; it < S.options.newton_steps; ++it) {
      if (!linearise(h, false)) return false;
      lu.compute(Jh);
      if (!lu.isInvertible()) return false;
      const VecK step = lu.solve(g);
      double size = 0, scale = 0;
      for (int i = 0; i < k; ++i) {
        h[i] -= step(i);
        size = std::max(size, std::abs(step(i)));
        scale = std::max(scale, std::abs(h[i]));
      }
      if (!std::isfinite(size)) return false;
      if (size <= 0x1.0p-50 * (scale + rad_u)) break;
    }
    return linearise(h, true);
  };
  // The centre u0 of U.
  for (int a = 0; a < m; ++a) z[a] = std::clamp(U[a].midpoint(), U[a].lo, U[a].hi);
  if (!h_hint.empty()) h0.assign(h_hint.begin(), h_hint.end());
  if (!newton(h0.data())) return false;  // no approximate point of M over the centre
  lu.compute(Jh);
  if (!lu.isInvertible()) return false;
  // Predicted spread of h over U: linear (|dh/du| rad U, dh/du = -J_h^{-1} J_u at (u0, h0)) ...
  const MatKM slope = lu.solve(Ju);
  for (int i = 0; i < k; ++i)
    for (int a = 0; a < m; ++a) r[i] += std::abs(slope(i, a)) * 0.5 * U[a].width();
  // ... and, for the curvature, the Newton solutions at the 2^m corners of U (from h0).
  std::vector<double> hc(k);
  for (int corner = 0; corner < (1 << m); ++corner) {
    for (int a = 0; a < m; ++a) z[a] = (corner >> a) & 1 ? U[a].hi : U[a].lo;
    std::copy(h0.begin(), h0.end(), hc.begin());
    if (!newton(hc.data())) continue;
    for (int i = 0; i < k; ++i) r[i] = std::max(r[i], std::abs(hc[i] - h0[i]));
  }
  double floor_scale = max_abs(h0) + rad_u;
  if (floor_scale == 0) floor_scale = max_abs(S.p);
  // A side far thinner than the others fails Krawczyk: the coupling of the wide sides (the
  // enclosure of I - Y J_h times their radii) alone exceeds its radius. No side below 1/8 of the widest.
  const double widest = *std::max_element(r.begin(), r.end());
  for (int i = 0; i < k; ++i) {
    r[i] = S.options.safety * std::max(r[i], 0.125 * widest) + 0x1.0p-30 * floor_scale + 0x1.0p-1000;
    if (!std::isfinite(r[i])) return false;
  }
  return true;
}

}  // namespace

ChartEnclosure::ChartEnclosure(const ImplicitSystem& F, std::span<const double> p, std::vector<mpq_class> T,
                               std::vector<mpq_class> Nn, ChartOptions options)
    : ChartEnclosure(F, p, std::move(T), std::move(Nn), options, {}) {}

ChartEnclosure::ChartEnclosure(const ImplicitSystem& F, std::span<const double> p, std::vector<mpq_class> T,
                               std::vector<mpq_class> Nn, ChartOptions options, const std::vector<mpq_class>& given_J) {
  const int N = F.ambient_dimension(), k = F.codimension(), m = N - k;
  if (static_cast<int>(p.size()) != N)
    throw std::invalid_argument("chart: base point has " + std::to_string(p.size()) + " coordinates, expected " +
                                std::to_string(N));
  for (double x : p)
    if (!std::isfinite(x)) throw std::invalid_argument("chart: base point has a non-finite coordinate");
  if (static_cast<int>(T.size()) != N * m || static_cast<int>(Nn.size()) != N * k)
    throw std::invalid_argument("chart: T must be N x m and Nn must be N x (N - m)");
  if (m < 1) throw std::invalid_argument("chart: the manifold has dimension 0");
  const int vars = m + k;
  std::vector<Interval> T_enc, Nn_enc;
  for (const auto& q : T) T_enc.push_back(exact::enclose(q));
  for (const auto& q : Nn) Nn_enc.push_back(exact::enclose(q));
  // A_v = p_v + sum_a T_va u_a + sum_l Nn_vl h_l, known by enclosures (p_v exactly), and
  // G = F(A) by enclosed products (exact/enclosed_polynomial.hpp): the exact G is one of the
  // polynomials it stands for, so every Krawczyk answer on it holds for the exact G.
  std::vector<EnclosedPolynomial> A;
  std::vector<Interval> linear(vars);
  for (int v = 0; v < N; ++v) {
    for (int a = 0; a < m; ++a) linear[a] = T_enc[v * m + a];
    for (int l = 0; l < k; ++l) linear[m + l] = Nn_enc[v * k + l];
    A.push_back(EnclosedPolynomial::affine(Interval::point(p[v]), linear));
  }
  std::vector<EnclosedPolynomial> G;
  for (const auto& f : F.equations()) G.push_back(substitute_affine(f, A, vars));
  // The terms of G of degree 1 in u and 0 in h have the exact coefficients J_F(p) T (G_i(u, 0) =
  // F_i(p + T u)): 0 when T spans ker J_F(p) (always for ChartEnclosure::at; checked here
  // exactly). The interval expansion leaves tiny enclosures of 0 there; dropping them keeps G
  // exact in those terms and its evaluations cheaper (a sparse chart keeps few terms).
  {
    std::vector<mpq_class> own;
    if (given_J.empty()) own = F.jacobian_exact(p);
    const std::vector<mpq_class>& J = given_J.empty() ? own : given_J;  // k x N
    bool kernel = true;
    for (int i = 0; i < k && kernel; ++i)
      for (int a = 0; a < m && kernel; ++a) {
        mpq_class s = 0;
        for (int v = 0; v < N; ++v) s += J[i * N + v] * T[v * m + a];
        kernel = s == 0;
      }
    if (kernel)
      for (auto& g : G)
        g = g.without([m](std::span<const std::uint32_t> e) {
          std::uint32_t du = 0, dh = 0;
          for (std::size_t v = 0; v < e.size(); ++v) (static_cast<int>(v) < m ? du : dh) += e[v];
          return du == 1 && dh == 0;
        });
  }
  auto impl = std::make_shared<Impl>(ParametricSystem::from_enclosures(G, m));
  impl->N = N;
  impl->m = m;
  impl->k = k;
  impl->p.assign(p.begin(), p.end());
  impl->T = std::move(T);
  impl->Nn = std::move(Nn);
  impl->T_enc = std::move(T_enc);
  impl->Nn_enc = std::move(Nn_enc);
  for (int i = 0; i < k; ++i) {
    impl->g.push_back(G[i].midpoints());
    for (int j = 0; j < k; ++j) impl->gh.push_back(G[i].derivative(m + j).midpoints());
  }
  for (int i = 0; i < k; ++i)
    for (int a = 0; a < m; ++a) impl->gu.push_back(G[i].derivative(a).midpoints());
  impl->options = options;
  impl_ = std::move(impl);
}

ChartEnclosure ChartEnclosure::at(const ImplicitSystem& F, std::span<const double> p, ChartOptions options) {
  const TangentSpace tangent(F, p);
  const int N = F.ambient_dimension(), k = F.codimension(), m = N - k;
  std::vector<mpq_class> T(static_cast<std::size_t>(N) * m), Nn(static_cast<std::size_t>(N) * k);
  for (int v = 0; v < N; ++v)
    for (int a = 0; a < m; ++a) T[v * m + a] = tangent.basis(v, a);
  const std::vector<mpq_class> J = F.jacobian_exact(p);  // k x N
  for (int v = 0; v < N; ++v)
    for (int l = 0; l < k; ++l) Nn[v * k + l] = J[l * N + v];
  for (int a = 0; a < m; ++a) {
    const mpq_class s = column_scale(T, N, m, a);
    for (int v = 0; v < N; ++v) T[v * m + a] *= s;
  }
  for (int l = 0; l < k; ++l) {
    const mpq_class s = column_scale(Nn, N, k, l);
    for (int v = 0; v < N; ++v) Nn[v * k + l] *= s;
  }
  return ChartEnclosure(F, p, std::move(T), std::move(Nn), options, J);
}

int ChartEnclosure::ambient_dimension() const { return impl_->N; }
int ChartEnclosure::intrinsic_dimension() const { return impl_->m; }
int ChartEnclosure::codimension() const { return impl_->k; }
std::span<const double> ChartEnclosure::base_point() const { return impl_->p; }
const mpq_class& ChartEnclosure::tangent(int row, int col) const { return impl_->T[row * impl_->m + col]; }
const mpq_class& ChartEnclosure::normal(int row, int col) const { return impl_->Nn[row * impl_->k + col]; }
const ParametricSystem& ChartEnclosure::chart_system() const { return impl_->G; }
std::span<const Interval> ChartEnclosure::tangent_enclosure() const { return impl_->T_enc; }
std::span<const Interval> ChartEnclosure::normal_enclosure() const { return impl_->Nn_enc; }

ChartEnclosure::GramBounds ChartEnclosure::gram_bounds() const {
  const Impl& S = *impl_;
  const GramBounds g{smallest_eigenvalue_bound(S.T, S.T_enc, S.N, S.m), smallest_eigenvalue_bound(S.Nn, S.Nn_enc, S.N, S.k)};
  if (!(g.tangent > 0 && g.normal > 0))
    throw std::domain_error("chart: cannot bound the Gram matrix of its tangent or normal basis away from 0");
  return g;
}

bool ChartEnclosure::image(const Box& U, const Box& H, Box& X) const {
  const Impl& S = *impl_;
  if (static_cast<int>(U.size()) != S.m || static_cast<int>(H.size()) != S.k)
    throw std::invalid_argument("chart image: box dimensions do not match the chart");
  X.assign(S.N, Interval{});
  // Interval arithmetic under upward rounding (CGAL's outward-rounded Interval_nt_advanced):
  // each bound encloses p_v + sum T_va u_a + sum Nn_vl h_l for all u in U, h in H, the entries
  // of T and Nn enclosed by enclose(). Overflow gives an infinite bound (never -DBL_MAX in a
  // lower bound: CGAL computes lower bounds as -(upward(-x))), refused below.
  detail::EnsureUpward guard;
  for (int v = 0; v < S.N; ++v) {
    IA acc(S.p[v]);
    for (int a = 0; a < S.m; ++a) acc = acc + detail::to_ia(S.T_enc[v * S.m + a]) * IA(U[a].lo, U[a].hi);
    for (int l = 0; l < S.k; ++l) acc = acc + detail::to_ia(S.Nn_enc[v * S.k + l]) * IA(H[l].lo, H[l].hi);
    if (!detail::finite(acc)) return false;
    X[v] = detail::from_ia(acc);
  }
  return true;
}

Interval ChartEnclosure::offset_norm2(const Box& U, const Box& H) const {
  const Impl& S = *impl_;
  detail::EnsureUpward guard;
  IA s(0);
  for (int v = 0; v < S.N; ++v) {
    IA t(0);
    for (int a = 0; a < S.m; ++a) t += detail::to_ia(S.T_enc[v * S.m + a]) * IA(U[a].lo, U[a].hi);
    for (int l = 0; l < S.k; ++l) t += detail::to_ia(S.Nn_enc[v * S.k + l]) * IA(H[l].lo, H[l].hi);
    s += square(t);
  }
  return detail::from_ia(s);
}

bool ChartEnclosure::free_of_M(const Box& U, const Box& H) const {
  const int m = impl_->m, k = impl_->k;
  SmallBuffer<Interval, 16> z(m + k), face(m + k);
  std::copy(U.begin(), U.end(), z.begin());
  std::copy(H.begin(), H.end(), z.begin() + m);
  const ParametricSystem& G = impl_->G;
  auto strict = [](const Interval& g) { return g.lo > 0 || g.hi < 0; };
  for (int e = 0; e < k; ++e) {
    if (strict(G.enclose(e, z.span()))) return true;
    for (int l = 0; l < k; ++l) {
      if (!strict(G.enclose_derivative(e, l, z.span()))) continue;
      std::copy(z.begin(), z.end(), face.begin());
      face[m + l] = Interval{H[l].lo, H[l].lo};
      const Interval a = G.enclose(e, face.span());
      face[m + l] = Interval{H[l].hi, H[l].hi};
      const Interval b = G.enclose(e, face.span());
      if ((a.lo > 0 && b.lo > 0) || (a.hi < 0 && b.hi < 0)) return true;
    }
  }
  return false;
}

// THE TILT. (p* := x(0), the chart's point over u = 0, in the box X0 = the image of U0 x H0.)
// A = Nn^T (k x N, exact, enclosed by Nn_enc) has rank k (its Gram matrix is bounded
// below by g_N > 0) and A T = 0, so ker A = span T (dimension m). For x in the box X0 and any k x k
// matrix W (doubles, used exactly), let B = W J_F(x) and E = B - A, with e >= |E|_F (interval
// arithmetic under upward rounding: J_F(X0) from F's exact partial derivatives, which enclose
// J_F(x)). By Weyl's inequality sigma_min(B) >= sigma_min(A) - |E|_2 >= sqrt(g_N) - e =: d; when
// d > 0, B has rank k, so J_F(x) does and ker B = ker J_F(x) (dimension m). For a unit t in span T,
// A t = 0, so |B t| = |E t| <= e, and its distance to ker B is |B^T (B B^T)^-1 B t| <= |B t| /
// sigma_min(B) <= e / d. Both spaces have dimension m, so the largest principal angle θ is the
// largest angle from a unit t of span T to ker J_F(x): sin θ <= e / d. W is chosen (doubles) so
// that B is close to A: W = A~ J~^T (J~ J~^T)^-1 with J~ = J_F(p) and A~ = Nn^T rounded; any W is
// sound (a poor one only gives a bound >= 1, which is refused).
ChartEnclosure::BasePoint ChartEnclosure::base_point(const ImplicitSystem& F, const Polynomial* selector) const {
  const Impl& S = *impl_;
  const int N = S.N, m = S.m, k = S.k;
  if (F.ambient_dimension() != N || F.codimension() != k) throw std::invalid_argument("chart base point: system mismatch");
  BasePoint out;
  // Over a tiny box U0 around u = 0 rather than u = 0 itself: a zero-width box with p on M leaves
  // enclose() a slab too thin for the enclosed chart's rounding. X0 holds x(0) all the same.
  double scale = 0;
  for (double x : S.p) scale = std::max(scale, std::abs(x));
  const double w = std::ldexp(scale > 0 ? scale : 1.0, -30);
  const Box U0(m, Interval{-w, w});
  const ChartResult at0 = enclose(U0);
  if (at0.status != ChartStatus::unique) return out;
  Eigen::MatrixXd Jd = F.jacobian(S.p), Ad(k, N);
  for (int v = 0; v < N; ++v)
    for (int l = 0; l < k; ++l) Ad(l, v) = S.Nn_enc[v * k + l].midpoint();
  const Eigen::MatrixXd W = Ad * Jd.transpose() * (Jd * Jd.transpose()).inverse();
  if (!W.allFinite()) return out;
  const double gN = gram_bounds().normal;
  detail::EnsureUpward guard;
  std::vector<IA> X;
  for (const auto& i : at0.X) X.push_back(detail::to_ia(i));
  if (selector && !(detail::evaluate(*selector, detail::coefficient_enclosures(*selector), X).inf() > 0)) return out;
  std::vector<IA> J(static_cast<std::size_t>(k) * N);  // J_F(X0), k x N
  for (int i = 0; i < k; ++i)
    for (int v = 0; v < N; ++v) {
      const Polynomial d = F.equations()[i].derivative(v);
      J[i * N + v] = detail::evaluate(d, detail::coefficient_enclosures(d), X);
    }
  IA e2(0);
  for (int l = 0; l < k; ++l)
    for (int v = 0; v < N; ++v) {
      IA b = -detail::to_ia(S.Nn_enc[v * k + l]);
      for (int i = 0; i < k; ++i) b += IA(W(l, i)) * J[i * N + v];
      e2 += square(b);
    }
  const IA e = CGAL::sqrt(e2), d = CGAL::sqrt(IA(gN)) - e;
  if (!(d.inf() > 0) || !detail::finite(e)) return out;
  out.sin_tilt = (e / d).sup();
  out.distance = CGAL::sqrt(IA(offset_norm2(U0, at0.H).hi)).sup();
  out.x = at0.X;
  out.certified = out.sin_tilt < 1 && std::isfinite(out.distance);
  return out;
}

ChartResult ChartEnclosure::enclose_in(const Box& U, const Box& H) const {
  ChartResult out;
  const KrawczykResult r = krawczyk(impl_->G, U, H, impl_->options.krawczyk);
  out.krawczyk_calls = 1;
  out.H = r.box;
  if (r.status == RootStatus::no_root) {
    out.status = ChartStatus::none;
    out.H = H;
  } else if (r.status == RootStatus::unique_root) {
    // Krawczyk: for every u in U exactly one root in the input H, and it lies in r.box, a
    // subset of H; so it is also the only root in r.box.
    if (image(U, r.box, out.X)) out.status = ChartStatus::unique;
  }
  if (out.status != ChartStatus::unique) out.X.clear();
  return out;
}

ChartResult ChartEnclosure::enclose(const Box& U, std::span<const double> h_hint) const {
  const Impl& S = *impl_;
  const int m = S.m, k = S.k;
  if (static_cast<int>(U.size()) != m) throw std::invalid_argument("chart: parameter box has the wrong dimension");
  for (const auto& i : U)
    if (!i.is_finite() || !(i.lo <= i.hi)) throw std::invalid_argument("chart: parameter box must be finite, lo <= hi");
  if (!h_hint.empty() && static_cast<int>(h_hint.size()) != k)
    throw std::invalid_argument("chart: h hint has the wrong dimension");

  ChartResult out;
  std::vector<double> h0(k, 0.0), r(k, 0.0);
  // Small k and m (the usual case): matrices with fixed maximal storage (no heap); the same
  // Eigen algorithms, so the same doubles.
  const bool guessed = k == 1 ? guess_slab_scalar(S, U, h_hint, h0, r) : k <= 4 && m <= 4 ? guess_slab<4, 4>(S, U, h_hint, h0, r) : guess_slab<Eigen::Dynamic, Eigen::Dynamic>(S, U, h_hint, h0, r);
  if (!guessed) return out;
  for (int attempt = 0; attempt < S.options.attempts; ++attempt) {
    Box H(k);
    {
      NearestRounding nearest;
      for (int i = 0; i < k; ++i) H[i] = {h0[i] - r[i], h0[i] + r[i]};
    }
    bool finite_box = true;
    for (const auto& i : H) finite_box = finite_box && i.is_finite();
    if (!finite_box) break;
    ChartResult res = enclose_in(U, H);
    res.krawczyk_calls += out.krawczyk_calls;
    if (res.status == ChartStatus::unique) return res;
    out = std::move(res);
    out.status = ChartStatus::undecided;  // a root-free guessed H says nothing about M over U
    out.X.clear();
    for (double& x : r) x *= S.options.growth;
  }
  return out;
}

}  // namespace delcert::exact
