#include "exact/geodesic_bounds.hpp"

#include <mpfr.h>

#include <algorithm>
#include <climits>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "exact/detail/cgal_number_types.hpp"
#include "exact/detail/interval_polynomial.hpp"
#include "exact/detail/mpfr_value.hpp"
#include "exact/detail/tangent_impl.hpp"

namespace delcert::exact {

using detail::IA;
using detail::Mpfr;

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

void check_box(const Box& X, int N, const char* who) {
  if (static_cast<int>(X.size()) != N) throw std::invalid_argument(std::string(who) + ": box of the wrong dimension");
  for (const auto& i : X)
    if (!(i.lo <= i.hi)) throw std::invalid_argument(std::string(who) + ": box with a NaN or empty interval");
}

// The largest magnitude in the interval (+infinity or NaN propagate as "not finite" to callers).
double magnitude(const IA& x) { return std::max(std::abs(x.inf()), std::abs(x.sup())); }

// x * 2^e as an outward-rounded interval product by exact powers of two (each factor 2^c with
// |c| <= 1000 is a normal double, exact), so an enclosure of the scaled set whatever overflows or
// underflows. Caller holds upward rounding.
IA times_power_of_two(IA x, int e) {
  while (e != 0) {
    const int c = std::clamp(e, -1000, 1000);
    x = x * IA(std::ldexp(1.0, c));
    e -= c;
  }
  return x;
}

// -ilogb(m), i.e. the s with 2^s m in [1, 2), for a finite m > 0.
int normalising_exponent(double m) { return -std::ilogb(m); }

// The first and second derivatives of F with their coefficient enclosures.
struct Derivative {
  Polynomial p;
  std::vector<Interval> coef;
  explicit Derivative(Polynomial q) : p(std::move(q)), coef(detail::coefficient_enclosures(p)) {}
  IA operator()(std::span<const IA> x) const { return detail::evaluate(p, coef, x); }
};

std::vector<Derivative> first_derivatives(const ImplicitSystem& F) {
  std::vector<Derivative> out;
  for (const auto& d : F.impl().derivatives) out.emplace_back(d);  // k x N row-major
  return out;
}

std::vector<IA> to_ia_box(const Box& X) {
  std::vector<IA> x;
  x.reserve(X.size());
  for (const auto& i : X) x.push_back(detail::to_ia(i));
  return x;
}

}  // namespace

// GERSHGORIN on the interval matrix. For every real J_r in J, G = J_r J_r^T has entries
// G_ii = sum_v J_iv^2 in S_ii (sum of interval squares) and G_ij in S_ij (sum of interval products):
// inclusion isotonicity. G is real symmetric, so each eigenvalue λ lies in a disc
// |λ - G_ii| <= sum_{j != i} |G_ij| (Gershgorin), hence
//   min_i (inf S_ii - sum_{j != i} sup|S_ij|) <= λ <= max_i (sup S_ii + sum_{j != i} sup|S_ij|).
// Scaled lower bound: with d_i = inf S_ii > 0 (doubles) and D = diag(d_i), G = D^{1/2} G' D^{1/2},
// G'_ij = G_ij / sqrt(d_i d_j). For unit v and w = D^{1/2} v, v^T G v = w^T G' w >= μ |w|^2 >= μ min_i d_i
// when λ_min(G') >= μ > 0, and Gershgorin on G' gives μ = min_i (inf S_ii / d_i - sum_{j != i}
// sup|S_ij| / sqrt(d_i d_j)). It succeeds where rows of very different lengths defeat the plain
// discs. Every operation is an outward-rounded interval operation (lower ends from .inf(), upper
// from .sup()), overflow giving infinite bounds (upper = +inf; a lower bound that is not finite is
// reported as 0) and underflow bounds rounded outward.
GramEigenvalueBounds gram_eigenvalue_bounds(std::span<const Interval> J, int k, int N) {
  if (k < 0 || N < 0 || J.size() != static_cast<std::size_t>(k) * N)
    throw std::invalid_argument("gram_eigenvalue_bounds: J must have k x N entries");
  detail::EnsureUpward guard;
  std::vector<IA> S(static_cast<std::size_t>(k) * k);
  for (int i = 0; i < k; ++i)
    for (int j = i; j < k; ++j) {
      IA s(0);
      for (int v = 0; v < N; ++v) {
        const IA a = detail::to_ia(J[i * N + v]);
        s += i == j ? square(a) : a * detail::to_ia(J[j * N + v]);
      }
      S[i * k + j] = S[j * k + i] = s;
    }
  GramEigenvalueBounds out{kInf, -kInf};
  for (int i = 0; i < k; ++i) {
    IA off(0);
    for (int j = 0; j < k; ++j)
      if (j != i) off += IA(magnitude(S[i * k + j]));
    out.lower = std::min(out.lower, (IA(S[i * k + i].inf()) - off).inf());
    out.upper = std::max(out.upper, (IA(S[i * k + i].sup()) + off).sup());
  }
  if (k == 0) out = {kInf, 0};  // G is the empty matrix: no eigenvalue (callers have k >= 1)
  bool scalable = k > 0;
  double min_d = kInf;
  for (int i = 0; i < k; ++i) {
    const double d = S[i * k + i].inf();
    scalable = scalable && d > 0 && d < kInf;
    min_d = std::min(min_d, d);
  }
  if (scalable) {
    double mu = kInf;
    for (int i = 0; i < k; ++i) {
      const IA di(S[i * k + i].inf());
      IA row = IA(S[i * k + i].inf()) / di;
      for (int j = 0; j < k; ++j)
        if (j != i) row -= IA(magnitude(S[i * k + j])) / sqrt(di * IA(S[j * k + j].inf()));
      mu = std::min(mu, row.inf());
    }
    if (mu > 0) out.lower = std::max(out.lower, (IA(mu) * IA(min_d)).inf());
  }
  if (!(out.lower > -kInf && out.lower < kInf)) out.lower = 0;  // NaN or infinite: nothing known
  if (!(out.upper < kInf)) out.upper = kInf;                      // NaN too
  return out;
}

bool jacobian_enclosure(const ImplicitSystem& F, const Box& X, std::vector<Interval>& J) {
  const int N = F.ambient_dimension(), k = F.codimension();
  check_box(X, N, "jacobian_enclosure");
  const std::vector<Derivative> d = first_derivatives(F);
  detail::EnsureUpward guard;
  const std::vector<IA> x = to_ia_box(X);
  J.assign(static_cast<std::size_t>(k) * N, Interval{});
  for (std::size_t i = 0; i < d.size(); ++i) {
    const IA v = d[i](x);
    if (!detail::finite(v)) return false;
    J[i] = detail::from_ia(v);
  }
  return true;
}

struct CurvatureBound::Impl {
  int N = 0, k = 0;
  std::vector<Derivative> first;   // k x N: dF_e/dx_v
  std::vector<Derivative> second;  // k x N x N: d2F_e/dx_v dx_w (both triangles, shared polynomials)
};

CurvatureBound::CurvatureBound(const ImplicitSystem& F) {
  auto S = std::make_shared<Impl>();
  S->N = F.ambient_dimension();
  S->k = F.codimension();
  S->first = first_derivatives(F);
  const int N = S->N;
  S->second.reserve(static_cast<std::size_t>(S->k) * N * N);
  for (int e = 0; e < S->k; ++e)
    for (int v = 0; v < N; ++v)
      for (int w = 0; w < N; ++w)
        S->second.emplace_back(w < v ? S->second[(e * N + w) * N + v].p : S->first[e * N + v].p.derivative(w));
  impl_ = std::move(S);
}

double CurvatureBound::operator()(const Box& X) const {
  const Impl& S = *impl_;
  const int N = S.N, k = S.k;
  check_box(X, N, "curvature_bound");
  detail::EnsureUpward guard;
  const std::vector<IA> x = to_ia_box(X);
  std::vector<IA> J(static_cast<std::size_t>(k) * N), H(static_cast<std::size_t>(k) * N * N);
  for (std::size_t i = 0; i < J.size(); ++i) J[i] = S.first[i](x);
  for (std::size_t i = 0; i < H.size(); ++i) H[i] = S.second[i](x);
  // Row scaling 2^{s_e} (header, SCALING): row e of J of magnitude in [1, 2). The Hessians get
  // 2^{s_e + σ} in one product, σ chosen so that the largest scaled Hessian entry is about 1: no
  // intermediate overflow where the result is finite.
  std::vector<int> s(k);
  int top = INT_MIN;  // max over e with H_e != 0 of s_e + ilogb(max |H_e|)
  for (int e = 0; e < k; ++e) {
    double m = 0, h = 0;
    for (int v = 0; v < N; ++v) m = std::max(m, magnitude(J[e * N + v]));
    for (int i = 0; i < N * N; ++i) h = std::max(h, magnitude(H[e * N * N + i]));
    if (!(m > 0 && m < kInf && h < kInf)) return kInf;  // a zero row (rank < k somewhere), overflow, NaN
    s[e] = normalising_exponent(m);
    if (h > 0) top = std::max(top, s[e] + std::ilogb(h));
    for (int v = 0; v < N; ++v) J[e * N + v] = times_power_of_two(J[e * N + v], s[e]);
  }
  // Then by c_e = 1 / (a double near the row's Euclidean length, in [1, 2 sqrt(N)]): rows of about
  // equal lengths, G near the identity where J's rows are orthogonal (|b|^2 / λ_min(G) then loses
  // nothing to the scaling: the Clifford tori). Any c_e > 0 is sound (header, SCALING); the interval
  // products by the double c_e <= 1 are outward rounded and cannot overflow.
  std::vector<double> c(k, 1.0);
  {
    NearestRounding nearest;
    for (int e = 0; e < k; ++e) {
      double n2 = 0;
      for (int v = 0; v < N; ++v) n2 += magnitude(J[e * N + v]) * magnitude(J[e * N + v]);
      c[e] = 1 / std::sqrt(n2);
    }
  }
  for (int e = 0; e < k; ++e)
    for (int v = 0; v < N; ++v) J[e * N + v] = J[e * N + v] * IA(c[e]);
  std::vector<Interval> Jb(J.size());
  for (std::size_t i = 0; i < J.size(); ++i) Jb[i] = detail::from_ia(J[i]);
  const double lambda = gram_eigenvalue_bounds(Jb, k, N).lower;
  if (!(lambda > 0)) return kInf;  // rank k not proven on X
  if (top == INT_MIN) return 0;    // every Hessian entry is exactly 0 on X: b = 0, II = 0
  const int sigma = -top;
  for (int e = 0; e < k; ++e)
    for (int i = 0; i < N * N; ++i) H[e * N * N + i] = times_power_of_two(H[e * N * N + i], s[e] + sigma) * IA(c[e]);
  // (a) sum_e h_e^2 and (b) h_max * (row-sum norm of A = sum_e |H_e|), upper bounds (header).
  IA sum_a(0), h_max(0);
  std::vector<IA> A(static_cast<std::size_t>(N) * N, IA(0));
  for (int e = 0; e < k; ++e) {
    IA frob2(0), rows(0);
    for (int v = 0; v < N; ++v) {
      IA row(0);
      for (int w = 0; w < N; ++w) {
        const IA h = H[(e * N + v) * N + w];
        const IA a(magnitude(h));
        frob2 += square(a);
        row += a;
        A[v * N + w] += a;
      }
      rows = interval_max(rows, row);
    }
    const IA frob = sqrt(frob2);
    const IA h_e(std::min(frob.sup(), rows.sup()));  // >= |H_e|_2 for every x in X
    sum_a += square(h_e);
    h_max = interval_max(h_max, h_e);
  }
  IA a_norm(0);
  for (int v = 0; v < N; ++v) {
    IA row(0);
    for (int w = 0; w < N; ++w) row += A[v * N + w];
    a_norm = interval_max(a_norm, row);
  }
  const IA b2(std::min(sum_a.sup(), (h_max * a_norm).sup()));  // >= |b|^2 (scaled)
  const IA K = times_power_of_two(sqrt(b2 / IA(lambda)), -sigma);
  const double out = K.sup();
  return out >= 0 && out < kInf ? out : kInf;
}

double curvature_bound(const ImplicitSystem& F, const Box& X) { return CurvatureBound(F)(X); }

// Φ_K AND ITS SLACK, in MPFR. The exponent range of MPFR (at least [-2^30, 2^30] by default) holds
// every product and quotient of doubles, so nothing overflows or underflows before the final
// conversion to a double, which rounds up (mpfr_get_d with MPFR_RNDU: +infinity beyond DBL_MAX, the
// smallest subnormal above 0). Every operation is correctly rounded in the stated direction, and
// MPFR's rounding does not depend on the FPU's mode.
namespace {

// Validates (K, r); false when the answer is +infinity for a non-finite argument.
bool finite_arguments(double K, double r, const char* who) {
  if (K < 0 || r < 0) throw std::invalid_argument(std::string(who) + ": K and t must be >= 0");
  return std::isfinite(K) && std::isfinite(r);
}

// s = K r / 2 exactly (a product of two doubles has at most 106 significant bits; the halving
// is exact). Returns false when s >= 1.
bool half_product(double K, double r, Mpfr& s) {
  mpfr_set_d(s.x, K, MPFR_RNDN);          // exact (precision >= 53)
  mpfr_mul_d(s.x, s.x, r, MPFR_RNDN);     // exact (precision >= 106)
  mpfr_div_2ui(s.x, s.x, 1, MPFR_RNDN);   // exact
  return mpfr_cmp_ui(s.x, 1) < 0;
}

}  // namespace

// Φ_K(r) = (2/K) asin(s), s = K r / 2 < 1 exact: asin(s) rounded up (asin is increasing, so this is
// >= the true value), doubled (exact) and divided by the exact K rounded up; each step keeps an
// upper bound, and the final conversion rounds up.
double chord_to_geodesic_upper(double K, double r) {
  if (!finite_arguments(K, r, "chord_to_geodesic_upper")) return kInf;
  if (K == 0 || r == 0) return r;
  Mpfr s(128), a(128);
  if (!half_product(K, r, s)) return kInf;
  mpfr_asin(a.x, s.x, MPFR_RNDU);
  mpfr_mul_2ui(a.x, a.x, 1, MPFR_RNDU);
  mpfr_div_d(a.x, a.x, K, MPFR_RNDU);
  return mpfr_get_d(a.x, MPFR_RNDU);
}

// Φ_K(r) - r = (2/K) (asin(s) - s), s = K r / 2. Subtracting r from a rounded Φ would lose
// everything to cancellation for small s (the slack is about K^2 r^3 / 24), so:
//  * s <= 2^-20: the series asin(s) = sum_n c_n s^(2n+1), c_0 = 1, c_n = (2n)! / (4^n (n!)^2 (2n+1))
//    <= c_1 = 1/6 for n >= 1 (c_n = binom(2n, n) / (4^n (2n + 1)) and binom(2n, n) <= 4^n), gives
//    0 <= asin(s) - s <= (s^3 / 6) sum_{n >= 0} s^(2n) = s^3 / (6 (1 - s^2)), so
//    Φ_K(r) - r <= K^2 r^3 / (24 (1 - s^2)): numerator rounded up, denominator rounded down (from
//    s^2 rounded up), quotient rounded up. It exceeds the true slack by the factor
//    (1 + s^2 + ...) / (1 + 9 s^2 / 20 + ...) < 1 + 2^-40, plus the roundings.
//  * s > 2^-20: asin(s) - s >= s^3 / 6 > 2^-63 s, so at 192 bits asin(s) rounded up (absolute error
//    below 2^-191 asin(s) <= 2^-190 s) minus the exact s rounded up keeps 120 correct bits; then
//    times 2 / K rounded up.
double geodesic_slack_upper(double K, double r) {
  if (!finite_arguments(K, r, "geodesic_slack_upper")) return kInf;
  if (K == 0 || r == 0) return 0;
  Mpfr s(192), a(192), b(192);
  if (!half_product(K, r, s)) return kInf;
  if (mpfr_cmp_d(s.x, 0x1p-20) <= 0) {
    mpfr_set_d(a.x, K, MPFR_RNDU);
    mpfr_mul_d(a.x, a.x, K, MPFR_RNDU);
    for (int i = 0; i < 3; ++i) mpfr_mul_d(a.x, a.x, r, MPFR_RNDU);  // K^2 r^3, rounded up
    mpfr_sqr(b.x, s.x, MPFR_RNDU);                                    // s^2 rounded up
    mpfr_ui_sub(b.x, 1, b.x, MPFR_RNDD);                              // 1 - s^2 rounded down (> 0)
    mpfr_mul_ui(b.x, b.x, 24, MPFR_RNDD);
    mpfr_div(a.x, a.x, b.x, MPFR_RNDU);
  } else {
    mpfr_asin(a.x, s.x, MPFR_RNDU);
    mpfr_sub(a.x, a.x, s.x, MPFR_RNDU);
    mpfr_mul_2ui(a.x, a.x, 1, MPFR_RNDU);
    mpfr_div_d(a.x, a.x, K, MPFR_RNDU);
  }
  return mpfr_get_d(a.x, MPFR_RNDU);
}

}  // namespace delcert::exact
