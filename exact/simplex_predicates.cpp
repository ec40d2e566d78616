#include "exact/simplex_predicates.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "exact/detail/cgal_number_types.hpp"
#include "exact/detail/filtered.hpp"
#include "exact/detail/kernels.hpp"

namespace delcert::exact {

using detail::certain_sign;
using detail::count_result;
using detail::EX;
using detail::filtered_sign;
using detail::IA;
using detail::kUndecided;

static_assert(kMaxThicknessSimplexDimension == detail::kMaxSimplexDim);

namespace {

void check_finite(const double* x, int N) {
  if (x == nullptr) throw std::invalid_argument("null point pointer");
  for (int i = 0; i < N; ++i)
    if (!std::isfinite(x[i])) throw std::invalid_argument("non-finite coordinate: exact predicates need finite doubles");
}

// Enclosure of |a - b|^2 (the caller holds upward rounding).
//
// Fast path: evaluate s = sum fl(a_i - b_i)^2 in plain floating point and enclose the exact sum
// T from s. Every term is non-negative, so the rounding error is relative: a term carries at most
// N + 2 rounding factors (1 + delta) (one subtraction, its square counted twice, one product, at
// most N - 1 additions), |delta| < u = 2^-52 in any rounding mode, plus an absolute error of at
// most 2^-1074 per product when it underflows (subtractions and additions of non-negative
// numbers are exact when their result is subnormal). Hence, with g = (N + 2) u / (1 - (N + 2) u)
// <= c = (N + 3) u (for N < 2^40),
//   s in [T (1 - g) - N eta, T (1 + g) + N eta],  eta = 2^-1074,
//   T in [(s - N eta) / (1 + g), (s + N eta) / (1 - g)]  within  (s + [-N eta, N eta]) * [1 - 2c, 1 + 2c].
// The bounds are computed with upward rounding. Reordering or fusing the floating-point
// operations only removes rounding factors, so the bound holds for any evaluation order.
// Overflow, under the upward rounding the caller holds: a difference that overflows is +inf or
// -DBL_MAX, and either squares to +inf (DBL_MAX^2 rounds up to +inf); a square or a sum of
// non-negative terms that overflows rounds up to +inf. So a finite s proves that nothing
// overflowed. (Downward or toward-zero rounding would turn overflows into DBL_MAX: the bound
// needs the upward mode, asserted below.) s = inf falls back to plain interval arithmetic.
// (Contrast the signed dot products of tangent_predicates.cpp, where a finite result does NOT
// prove the absence of overflow.) We use 2^-1000 >= N eta below.
IA interval_squared_distance(const double* a, const double* b, int N) {
  double s = 0;
  for (int i = 0; i < N; ++i) {
    const double d = a[i] - b[i];
    s += d * d;
  }
  if (std::isfinite(s) && N < (1 << 20)) {
    // The rounding mode is upward here (the caller holds it): each operation below rounds up,
    // and the lower bound is the negation of an upper bound. Constants are exact.
    CGAL_assertion(CGAL::FPU_get_cw() == CGAL_FE_UPWARD);
    const double c = (N + 3) * 0x1.0p-52;
    // N eta <= 2^-1000 for N < 2^74. A normal number on purpose: arithmetic that produces
    // subnormals is very slow on x86.
    const double eta = 0x1.0p-1000;
    const double hi = (s + eta) * (1 + 2 * c);
    const double lo = -((eta - s) * (1 - 2 * c));
    return IA(std::max(0.0, lo), hi);
  }
  IA t(0);
  for (int i = 0; i < N; ++i) t = t + CGAL::square(IA(a[i]) - IA(b[i]));
  return t;
}

EX exact_squared_distance(const double* a, const double* b, int N) {
  EX s(0);
  for (int i = 0; i < N; ++i) {
    EX d = EX(a[i]) - EX(b[i]);  // exact
    s = s + d * d;
  }
  return s;
}

// The exact terms of the thickness test: squared distances, Delta^2, gt and gf (see kernels).
struct ExactThickness {
  EX gt, delta2;
  std::vector<EX> gf;
};

ExactThickness exact_thickness_terms(std::span<const double* const> v, int N) {
  const int j = static_cast<int>(v.size()) - 1;
  ExactThickness out;
  std::vector<EX> d((j + 1) * (j + 1));
  out.delta2 = EX(0);
  for (int a = 0; a <= j; ++a)
    for (int b = a + 1; b <= j; ++b) {
      d[a * (j + 1) + b] = d[b * (j + 1) + a] = exact_squared_distance(v[a], v[b], N);
      if (d[a * (j + 1) + b] > out.delta2) out.delta2 = d[a * (j + 1) + b];
    }
  out.gf.resize(j + 1);
  detail::dispatch<1, detail::kMaxSimplexDim>(j, [&](auto J) { detail::thickness_terms<J()>(d.data(), out.gt, out.gf.data()); });
  return out;
}

}  // namespace

int thickness_sign(std::span<const double* const> vertices, int N, const RationalConstant& gamma_squared,
                   FilterContext& ctx) {
  const int j = static_cast<int>(vertices.size()) - 1;
  if (j < 0) throw std::invalid_argument("thickness of an empty simplex");
  if (j > detail::kMaxSimplexDim)
    throw std::invalid_argument("thickness supports simplices of dimension up to " + std::to_string(detail::kMaxSimplexDim));
  if (gamma_squared.sign() < 0) throw std::invalid_argument("thickness threshold Gamma^2 must be non-negative");
  for (const double* x : vertices) check_finite(x, N);
  if (j == 0) {
    // Upsilon = 1 by convention.
    const int s = sgn(mpq_class(1) - gamma_squared.value());
    count_result(ctx, PredicateKind::thickness, false, s);
    return s;
  }
  const int jj = j * j;
  return filtered_sign(
      ctx, PredicateKind::thickness,
      [&] {
        IA d[(detail::kMaxSimplexDim + 1) * (detail::kMaxSimplexDim + 1)];
        IA delta2(0);
        for (int a = 0; a <= j; ++a) {
          d[a * (j + 1) + a] = IA(0);
          for (int b = a + 1; b <= j; ++b) {
            d[a * (j + 1) + b] = d[b * (j + 1) + a] = interval_squared_distance(vertices[a], vertices[b], N);
            delta2 = interval_max(delta2, d[a * (j + 1) + b]);
          }
        }
        IA gt, gf[detail::kMaxSimplexDim + 1];
        detail::dispatch<1, detail::kMaxSimplexDim>(j, [&](auto J) { detail::thickness_terms<J()>(d, gt, gf); });
        const int gts = certain_sign(gt);
        // Exactly degenerate (gt is the point interval [0, 0]): Upsilon = 0.
        if (gts == 0) return -gamma_squared.sign();
        if (gts != 1) return kUndecided;
        // gt > 0: every facet Gram determinant is positive too, and the test per vertex is
        // gt - 2 Gamma^2 j^2 Delta^2 gf_l >= 0. The answer is the minimum of the per-vertex signs.
        const IA scale = IA(2.0 * jj) * detail::to_ia(gamma_squared.enclosure()) * delta2;
        int result = 1;
        bool undecided = false;
        for (int l = 0; l <= j; ++l) {
          const int s = certain_sign(gt - scale * gf[l]);
          if (s == -1) {
            result = -1;
            undecided = false;
            break;
          }
          if (s == kUndecided) undecided = true;
          else result = std::min(result, s);
        }
        return undecided ? kUndecided : result;
      },
      [&] {
        // Exact: gamma^2 = num/den, den > 0: sign(den gt - 2 j^2 num Delta^2 gf_l).
        const ExactThickness t = exact_thickness_terms(vertices, N);
        if (t.gt.is_zero()) return -gamma_squared.sign();
        const EX num = detail::to_ex(gamma_squared.value().get_num()), den = detail::to_ex(gamma_squared.value().get_den());
        const EX dgt = den * t.gt;
        const EX scale = EX(2 * jj) * num * t.delta2;
        int result = 1;
        for (int l = 0; l <= j; ++l) result = std::min(result, detail::exact_sign(dgt - scale * t.gf[l]));
        return result;
      });
}

mpq_class thickness_squared_exact(std::span<const double* const> vertices, int N) {
  const int j = static_cast<int>(vertices.size()) - 1;
  if (j < 0) throw std::invalid_argument("thickness of an empty simplex");
  if (j > detail::kMaxSimplexDim)
    throw std::invalid_argument("thickness supports simplices of dimension up to " + std::to_string(detail::kMaxSimplexDim));
  for (const double* x : vertices) check_finite(x, N);
  if (j == 0) return mpq_class(1);
  const ExactThickness t = exact_thickness_terms(vertices, N);
  if (t.gt.is_zero()) return mpq_class(0);
  // D(v_l)^2 = gt / (2 gf_l); Upsilon^2 = min_l D(v_l)^2 / (j^2 Delta^2).
  const mpq_class gt = detail::to_mpq(t.gt), delta2 = detail::to_mpq(t.delta2);
  mpq_class best;
  for (int l = 0; l <= j; ++l) {
    mpq_class d2 = gt / (2 * detail::to_mpq(t.gf[l]));
    if (l == 0 || d2 < best) best = d2;
  }
  return best / (j * j * delta2);
}

int compare_squared_distances(const double* a, const double* b, const double* c, const double* d, int N,
                              FilterContext& ctx) {
  check_finite(a, N);
  check_finite(b, N);
  check_finite(c, N);
  check_finite(d, N);
  return filtered_sign(
      ctx, PredicateKind::squared_distance,
      [&] { return interval_squared_distance(a, b, N) - interval_squared_distance(c, d, N); },
      [&] { return exact_squared_distance(a, b, N) - exact_squared_distance(c, d, N); });
}

int compare_squared_distance(const double* a, const double* b, const RationalConstant& r2, int N, FilterContext& ctx) {
  check_finite(a, N);
  check_finite(b, N);
  return filtered_sign(
      ctx, PredicateKind::squared_distance,
      [&] { return interval_squared_distance(a, b, N) - detail::to_ia(r2.enclosure()); },
      [&] {
        // r2 = num/den, den > 0: sign(den |a-b|^2 - num).
        const EX num = detail::to_ex(r2.value().get_num()), den = detail::to_ex(r2.value().get_den());
        return den * exact_squared_distance(a, b, N) - num;
      });
}

mpq_class squared_distance_exact(const double* a, const double* b, int N) {
  check_finite(a, N);
  check_finite(b, N);
  return detail::to_mpq(exact_squared_distance(a, b, N));
}

RationalPoint::RationalPoint(std::vector<mpq_class> coordinates) : coords_(std::move(coordinates)) {
  denominator_ = 1;
  for (auto& c : coords_) {
    c.canonicalize();
    mpz_lcm(denominator_.get_mpz_t(), denominator_.get_mpz_t(), c.get_den_mpz_t());
  }
  for (const auto& c : coords_) {
    numerators_.push_back(c.get_num() * (denominator_ / c.get_den()));  // exact division
    enclosure_.push_back(enclose(c));
  }
}

int ambient_power_sign(const RationalPoint& x, const double* p, const double* q, FilterContext& ctx) {
  const int N = x.dimension();
  check_finite(p, N);
  check_finite(q, N);
  // |x - q|^2 - |x - p|^2 = sum_i (q_i - p_i)(q_i + p_i - 2 x_i).
  return filtered_sign(
      ctx, PredicateKind::ambient_power,
      [&] {
        IA s(0);
        for (int i = 0; i < N; ++i)
          s = s + (IA(q[i]) - IA(p[i])) * (IA(q[i]) + IA(p[i]) - IA(2) * detail::to_ia(x.enclosure()[i]));
        return s;
      },
      [&] {
        // With x_i = X_i / D, D > 0: sign = sign(sum_i (q_i - p_i)(D (q_i + p_i) - 2 X_i)), all exact.
        const EX D = detail::to_ex(x.denominator());
        EX s(0);
        for (int i = 0; i < N; ++i) {
          const EX qi(q[i]), pi(p[i]);
          s = s + (qi - pi) * (D * (qi + pi) - EX(2) * detail::to_ex(x.numerators()[i]));
        }
        return s;
      });
}

int ambient_power_sign_on_box(const Box& x, const double* p, const double* q) {
  const int N = static_cast<int>(x.size());
  check_finite(p, N);
  check_finite(q, N);
  detail::EnsureUpward guard;
  IA s(0);
  for (int i = 0; i < N; ++i) {
    if (!(x[i].lo <= x[i].hi)) throw std::invalid_argument("box with an empty or NaN interval");
    s = s + (IA(q[i]) - IA(p[i])) * (IA(q[i]) + IA(p[i]) - IA(2) * IA(x[i].lo, x[i].hi));
  }
  const int r = certain_sign(s);
  return (r == kUndecided) ? 0 : r;
}

}  // namespace delcert::exact
