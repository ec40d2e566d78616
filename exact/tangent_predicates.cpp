#include "exact/tangent_predicates.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "exact/detail/filtered.hpp"
#include "exact/detail/kernels.hpp"
#include "exact/detail/tangent_impl.hpp"
#include "exact/linear_algebra.hpp"

namespace delcert::exact {

using detail::certain_sign;
using detail::count_result;
using detail::EX;
using detail::filtered_sign;
using detail::IA;
using detail::kUndecided;

static_assert(kMaxTangentDimension == detail::kMaxIntrinsicDim);

namespace {

constexpr int kMaxRowLength = kMaxTangentDimension + 1;

void check_finite(const double* x, int N) {
  for (int i = 0; i < N; ++i)
    if (!std::isfinite(x[i]))
      throw std::invalid_argument("non-finite coordinate: exact predicates need finite doubles");
}

// Enclosure of the chart row r(x) = (U^T (x - p), |x - p|^2); the caller holds upward rounding.
//
// Fast path: plain floating-point dot products with a rigorous error bound, turned into
// intervals (several times cheaper than interval dot products). Notation: eps = 2^-52 bounds the
// relative error of one rounding of a result in the normal range, in any rounding mode;
// e_i = fl(x_i - p_i), exact d_i = x_i - p_i; u_i = U_ia exactly, m_i = U_mid, |u_i - m_i| <= r_i =
// U_rad, w_i = U_err >= (N + 3) eps |m_i| + (1 + 2 eps) r_i (computed in interval arithmetic and
// rounded up, tangent_space.cpp).
//
// Overflow. Under upward rounding a result below -DBL_MAX rounds to -DBL_MAX, which is finite: a
// finite computed value does NOT prove that nothing overflowed (this was a false CERTIFIED, see
// fixtures/soundness/overflow). So the fast path is taken only when every intermediate is
// provably in range, by two magnitude checks made on quantities that are themselves rounded up:
//  (a) S^ = fl(sum e_i^2) is finite. A positive result that overflows rounds up to +inf, so every
//      e_i^2 < DBL_MAX, |e_i| < 2^512: no subtraction x_i - p_i overflowed (an overflowing e_i
//      would be +-DBL_MAX or +-inf, whose square is +inf).
//  (b) Z^ = fl(sum w_i |e_i|) <= 2^900. Every product and sum of non-negative terms rounds up,
//      so Z^ >= sum w_i |e_i| >= (N + 3) eps A, A = sum |m_i| |e_i|, hence
//      A <= 2^900 / ((N + 3) 2^-52) < 2^952. Each |m_i e_i| and each partial sum of the m_i e_i is
//      at most A, far below DBL_MAX: no product or sum in B overflowed.
// Underflow. A product with a subnormal result has absolute error < eta = 2^-1074; a subtraction
// or addition with a subnormal result is exact (Sterbenz / no bits lost below 2^-1074).
// With (a) and (b), for b = sum u_i d_i:
//  * |d_i - e_i| <= eps' |e_i|, eps' = eps / (1 - eps);
//  * the computed B = fl(sum m_i e_i) has |B - sum m_i e_i| <= gamma_N A + N eta,
//    gamma_N = N eps / (1 - N eps) (in any rounding mode, any summation order);
//  * |b - sum m_i e_i| <= sum |u_i - m_i| |d_i| + sum |m_i| |d_i - e_i| <= (1 + eps') R + eps' A,
//    R = sum r_i |e_i|;
//  so |b - B| <= c1 A + c2 R + N eta with c1 = (N + 3) eps >= gamma_N + eps', c2 = 1 + 2 eps.
//  Then c1 A + c2 R <= Z = sum w_i |e_i| <= Z^ (Z^ is rounded up term by term).
//  Hence |b - B| <= E = Z^ (1 + 2 (N + 2) eps) + 2^-1000 (>= Z^ + 2 N eta for N < 2^70),
//  evaluated with upward rounding (E <= 2^902, finite), and b lies in [B - E, B + E].
// The squared norm s = |x - p|^2 uses the relative bound of a sum of non-negative terms (see
// simplex_predicates.cpp): s in (S + [-2^-1000, 2^-1000]) [1 - 2c, 1 + 2c], c = (N + 3) eps;
// S^ finite by (a), and an upper bound that overflows to +inf is still an upper bound.
// Anything else (a non-finite value, Z^ > 2^900, N >= 2^20) falls back to plain interval
// arithmetic, which is correct at every magnitude (CGAL's Interval_nt rounds each bound outward,
// overflow going to +-inf).
template <int M>
void interval_row(const TangentSpace::Impl& s, const double* x, IA* row) {
  const int N = s.N;
  double B[M] = {}, Z[M] = {}, S = 0;
  for (int i = 0; i < N; ++i) {
    const double e = x[i] - s.p[i];
    const double ae = std::abs(e);
    S += e * e;
    const double* m = s.U_mid.data() + i * M;
    const double* w = s.U_err.data() + i * M;
    for (int a = 0; a < M; ++a) {
      B[a] += m[a] * e;
      Z[a] += w[a] * ae;
    }
  }
  constexpr double kSafeBound = 0x1.0p900;  // (b) above
  bool safe = std::isfinite(S) && N < (1 << 20);
  for (int a = 0; a < M; ++a) safe = safe && Z[a] <= kSafeBound;  // false for NaN and +inf too
  if (!safe) {
    check_finite(x, N);  // reject NaN / inf coordinates here
    detail::chart_row<M>(s.U_interval.data(), [&](int i) { return IA(x[i]) - IA(s.p[i]); }, N, row);
    return;
  }
  // Final bounds in plain doubles: the rounding mode is upward here (the caller holds it, as
  // Interval_nt_advanced requires), so every operation rounds up, and a lower bound is computed
  // as the negation of an upper bound. All constants are exact.
  CGAL_assertion(CGAL::FPU_get_cw() == CGAL_FE_UPWARD);
  const double eps = 0x1.0p-52, tiny = 0x1.0p-1000;
  const double grow = 1 + 2 * (N + 2) * eps;
  for (int a = 0; a < M; ++a) {
    const double E = Z[a] * grow + tiny;          // >= Z^ (1 + 2 (N + 2) eps) + 2^-1000
    row[a] = IA(-(E - B[a]), B[a] + E);           // [B - E rounded down, B + E rounded up]
  }
  const double c = (N + 3) * eps;
  const double hi = (S + tiny) * (1 + 2 * c);     // >= (S + 2^-1000)(1 + 2c)
  const double lo = -((tiny - S) * (1 - 2 * c));  // <= (S - 2^-1000)(1 - 2c); |x - p|^2 >= 0 anyway
  row[M] = IA(std::max(0.0, lo), hi);
}

// Exact chart row of x: Mpzf differences of doubles are exact.
template <int M>
void exact_row(const TangentSpace::Impl& s, const double* x, EX* row) {
  detail::chart_row<M>(s.U_exact.data(), [&](int i) { return EX(x[i]) - s.p_exact[i]; }, s.N, row);
}

// The chart row of x in either number type (the same overloaded name for the templates below).
template <int M>
void chart_row_of(const TangentSpace::Impl& s, const double* x, IA* row) {
  interval_row<M>(s, x, row);
}
template <int M>
void chart_row_of(const TangentSpace::Impl& s, const double* x, EX* row) {
  exact_row<M>(s, x, row);
}

// The chart rows of `points` (and of `query` when given, after them) into buf, L = M + 1 entries
// each, with rows[i] pointing at the row of points[i]; returns the query's row.
template <int M, class NT>
const NT* chart_rows_of(const TangentSpace::Impl& s, std::span<const double* const> points, const double* query, NT* buf,
                        const NT** rows) {
  constexpr int L = M + 1;
  for (int i = 0; i < L; ++i) {
    chart_row_of<M>(s, points[i], buf + i * L);
    rows[i] = buf + i * L;
  }
  if (query) chart_row_of<M>(s, query, buf + L * L);
  return buf + L * L;
}

// The interval coefficients and k0 of a cell's power test (see power_cell) from the bounds
// TangentChart::cell stored: coef_j in [e[2j], e[2j+1]], k0 in [e[2M+2], e[2M+3]].
template <int M>
void stored_power_cell(const double* e, IA* coef, IA& k0) {
  for (int j = 0; j <= M; ++j) coef[j] = IA(e[2 * j], e[2 * j + 1]);
  k0 = IA(e[2 * (M + 1)], e[2 * (M + 1) + 1]);
}

// Moves local index 0 (p) to the front by one transposition; returns the permutation's sign.
int put_origin_first(std::span<const int> given, int* order) {
  const int n = static_cast<int>(given.size());
  for (int i = 0; i < n; ++i) order[i] = given[i];
  for (int i = 1; i < n; ++i)
    if (order[i] == 0) {
      std::swap(order[0], order[i]);
      return -1;
    }
  return 1;
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// TangentChart
// ---------------------------------------------------------------------------------------------

void TangentChart::Impl::compute_row(int i) const {
  detail::EnsureUpward guard;
  detail::dispatch<1, detail::kMaxIntrinsicDim>(m, [&](auto M) {
    interval_row<M()>(*space_impl, coords.data() + static_cast<std::size_t>(i) * N, rows.data() + static_cast<std::size_t>(i) * (m + 1));
  });
  have_row[i] = 1;
}

const EX* TangentChart::Impl::exact_row(int i) const {
  if (exact_rows.empty()) exact_rows.resize(static_cast<std::size_t>(count) * (m + 1));  // zeros; row 0 (p) is exactly zero
  EX* row = exact_rows.data() + static_cast<std::size_t>(i) * (m + 1);
  if (!have_exact[i]) {
    detail::dispatch<1, detail::kMaxIntrinsicDim>(
        m, [&](auto M) { ::delcert::exact::exact_row<M()>(*space_impl, coords.data() + static_cast<std::size_t>(i) * N, row); });
    have_exact[i] = 1;
  }
  return row;
}

void TangentChart::Impl::check_index(int i) const {
  if (i < 0 || i >= count)
    throw std::out_of_range("chart index " + std::to_string(i) + " out of range 0.." + std::to_string(count - 1));
}

TangentChart::TangentChart(const TangentSpace& space, std::span<const double* const> points)
    : impl_(std::make_unique<Impl>(space)) {
  Impl& c = *impl_;
  c.space_impl = space.shared_impl();
  c.N = space.ambient_dimension();
  c.m = space.intrinsic_dimension();
  if (c.m < 1 || c.m > kMaxTangentDimension)
    throw std::invalid_argument("intrinsic dimension " + std::to_string(c.m) + " is not supported (1.." +
                                std::to_string(kMaxTangentDimension) + ")");
  c.count = 1 + static_cast<int>(points.size());
  const std::size_t N = c.N, L = c.m + 1;
  c.coords.resize(c.count * N);
  std::copy(c.space_impl->p.begin(), c.space_impl->p.end(), c.coords.begin());
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (points[i] == nullptr) throw std::invalid_argument("null point pointer");
    check_finite(points[i], c.N);
    std::copy(points[i], points[i] + N, c.coords.begin() + (i + 1) * N);
  }
  c.rows.assign(c.count * L, IA(0));  // row 0 (p) is exactly zero
  c.have_row.assign(c.count, 0);
  c.have_row[0] = 1;
  c.have_exact.assign(c.count, 0);
  c.have_exact[0] = 1;
}

namespace {
std::vector<const double*> row_pointers(std::span<const double> data, int N) {
  if (N <= 0 || data.size() % static_cast<std::size_t>(N) != 0)
    throw std::invalid_argument("row-major point data size is not a multiple of the ambient dimension");
  std::vector<const double*> out;
  for (std::size_t i = 0; i < data.size(); i += N) out.push_back(data.data() + i);
  return out;
}
}  // namespace

TangentChart::TangentChart(const TangentSpace& space, std::span<const double> points_row_major)
    : TangentChart(space, std::span<const double* const>(row_pointers(points_row_major, space.ambient_dimension()))) {}

TangentChart::~TangentChart() = default;
TangentChart::TangentChart(TangentChart&&) noexcept = default;
TangentChart& TangentChart::operator=(TangentChart&&) noexcept = default;

int TangentChart::size() const { return impl_->count; }
const TangentSpace& TangentChart::space() const { return impl_->space; }
std::span<const double> TangentChart::coordinates(int local) const {
  impl_->check_index(local);
  return {impl_->coords.data() + static_cast<std::size_t>(local) * impl_->N, static_cast<std::size_t>(impl_->N)};
}

std::vector<mpq_class> TangentChart::row_exact(int local) const {
  impl_->check_index(local);
  const EX* r = impl_->exact_row(local);
  std::vector<mpq_class> out;
  for (int a = 0; a <= impl_->m; ++a) out.push_back(detail::to_mpq(r[a]));
  return out;
}

int TangentChart::orientation(std::span<const int> vertices, FilterContext& ctx) const {
  const Impl& c = *impl_;
  if (static_cast<int>(vertices.size()) != c.m + 1)
    throw std::invalid_argument("orientation needs m + 1 = " + std::to_string(c.m + 1) + " points");
  for (int v : vertices) c.check_index(v);
  int order[kMaxRowLength];
  const int parity = put_origin_first(vertices, order);
  const bool origin = order[0] == 0;
  return detail::dispatch<1, detail::kMaxIntrinsicDim>(c.m, [&](auto Mc) {
    constexpr int M = Mc();
    return parity * filtered_sign(
                        ctx, PredicateKind::tangent_orientation,
                        [&] {
                          const IA* rows[M + 1];
                          for (int i = 0; i <= M; ++i) rows[i] = c.row(order[i]);
                          return detail::orientation_det<M>(rows, origin);
                        },
                        [&] {
                          const EX* rows[M + 1];
                          for (int i = 0; i <= M; ++i) rows[i] = c.exact_row(order[i]);
                          return detail::orientation_det<M>(rows, origin);
                        });
  });
}

TangentCell TangentChart::cell(std::span<const int> vertices, FilterContext& ctx) const {
  const Impl& c = *impl_;
  if (static_cast<int>(vertices.size()) != c.m + 1)
    throw std::invalid_argument("a cell needs m + 1 = " + std::to_string(c.m + 1) + " vertices");
  for (int v : vertices) c.check_index(v);
  TangentCell cell;
  cell.chart_ = impl_.get();
  cell.m_ = c.m;
  for (int i = 0; i <= c.m; ++i) cell.vertices_[i] = vertices[i];
  const int parity = put_origin_first(vertices, cell.order_.data());
  cell.origin_ref_ = cell.order_[0] == 0;
  detail::EnsureUpward guard;
  detail::dispatch<1, detail::kMaxIntrinsicDim>(c.m, [&](auto Mc) {
    constexpr int M = Mc();
    const IA* rows[M + 1];
    for (int i = 0; i <= M; ++i) rows[i] = c.row(cell.order_[i]);
    IA coef[M + 1];
    IA k0;
    detail::power_cell<M>(rows, cell.origin_ref_, coef, k0);
    bool finite = std::isfinite(k0.inf()) && std::isfinite(k0.sup());
    for (int j = 0; j <= M; ++j) {
      cell.enclosures_[2 * j] = coef[j].inf();
      cell.enclosures_[2 * j + 1] = coef[j].sup();
      finite = finite && std::isfinite(coef[j].inf()) && std::isfinite(coef[j].sup());
    }
    cell.enclosures_[2 * (M + 1)] = k0.inf();
    cell.enclosures_[2 * (M + 1) + 1] = k0.sup();
    cell.filter_usable_ = finite;
    // det B = coef_m (see power_cell).
    const int s = filtered_sign(
        ctx, PredicateKind::tangent_orientation, [&] { return coef[M]; },
        [&] {
          cell.ensure_exact();
          return cell.exact_->coef[M];
        });
    cell.det_sign_ = s;
    cell.orientation_ = parity * s;
  });
  return cell;
}

int TangentChart::power_sign(std::span<const int> vertices, int query, FilterContext& ctx) const {
  return cell(vertices, ctx).power_sign(query, ctx);
}

// ---------------------------------------------------------------------------------------------
// TangentCell
// ---------------------------------------------------------------------------------------------

void TangentCell::ensure_exact() const {
  if (exact_) return;
  auto data = std::make_shared<detail::ExactCellData>();
  detail::dispatch<1, detail::kMaxIntrinsicDim>(m_, [&](auto Mc) {
    constexpr int M = Mc();
    const EX* rows[M + 1];
    for (int i = 0; i <= M; ++i) rows[i] = chart_->exact_row(order_[i]);
    detail::power_cell<M>(rows, origin_ref_, data->coef.data(), data->k0);
  });
  exact_ = std::move(data);
}

int TangentCell::power_sign(int query, FilterContext& ctx) const {
  chart_->check_index(query);
  if (det_sign_ == 0) {
    count_result(ctx, PredicateKind::power, false, 0);
    return 0;
  }
  return detail::dispatch<1, detail::kMaxIntrinsicDim>(m_, [&](auto Mc) {
    constexpr int M = Mc();
    return det_sign_ * filtered_sign(
                           ctx, PredicateKind::power, filter_usable_,
                           [&] {
                             IA coef[M + 1], k0;
                             stored_power_cell<M>(enclosures_.data(), coef, k0);
                             return detail::power_value<M>(coef, k0, chart_->row(query), origin_ref_);
                           },
                           [&] {
                             ensure_exact();
                             return detail::power_value<M>(exact_->coef.data(), exact_->k0, chart_->exact_row(query),
                                                           origin_ref_);
                           });
  });
}

int TangentCell::power_sign(int query, const RationalConstant& delta, FilterContext& ctx) const {
  chart_->check_index(query);
  if (det_sign_ == 0) {
    count_result(ctx, PredicateKind::power_threshold, false, 0);
    return 0;
  }
  return detail::dispatch<1, detail::kMaxIntrinsicDim>(m_, [&](auto Mc) {
    constexpr int M = Mc();
    return det_sign_ * filtered_sign(
                           ctx, PredicateKind::power_threshold, filter_usable_,
                           [&] {
                             IA coef[M + 1], k0;
                             stored_power_cell<M>(enclosures_.data(), coef, k0);
                             // det M(q) - delta det B, det B = coef_m.
                             return detail::power_value<M>(coef, k0, chart_->row(query), origin_ref_) -
                                    detail::to_ia(delta.enclosure()) * coef[M];
                           },
                           [&] {
                             ensure_exact();
                             // delta = num/den with den > 0: sign(det M - delta det B) = sign(den det M - num det B).
                             const EX num = detail::to_ex(delta.value().get_num());
                             const EX den = detail::to_ex(delta.value().get_den());
                             return den * detail::power_value<M>(exact_->coef.data(), exact_->k0,
                                                                 chart_->exact_row(query), origin_ref_) -
                                    num * exact_->coef[M];
                           });
  });
}

std::vector<mpq_class> TangentCell::centre_exact() const {
  if (det_sign_ == 0) throw std::domain_error("degenerate cell: its projection to T_p has no unique centre");
  const int m = m_, N = chart_->N;
  // 2 (b(v_i) - b(v0)).z = s(v_i) - s(v0): with y = 2z, B y = h; then c = p + U y / 2.
  std::vector<std::vector<mpq_class>> r(m + 1);
  for (int i = 0; i <= m; ++i) {
    const EX* e = chart_->exact_row(order_[i]);
    for (int a = 0; a <= m; ++a) r[i].push_back(detail::to_mpq(e[a]));
  }
  std::vector<mpq_class> B(m * m), h(m);
  for (int i = 0; i < m; ++i) {
    for (int a = 0; a < m; ++a) B[i * m + a] = r[i + 1][a] - r[0][a];
    h[i] = r[i + 1][m] - r[0][m];
  }
  const auto y = solve(B, h, m);
  if (!y) throw std::domain_error("degenerate cell: its projection to T_p has no unique centre");
  const auto& sp = *chart_->space_impl;
  std::vector<mpq_class> c(N);
  for (int i = 0; i < N; ++i) {
    mpq_class acc = 0;
    for (int a = 0; a < m; ++a) acc += sp.U_rational()[i * m + a] * (*y)[a];
    c[i] = to_rational(sp.p[i]) + acc / 2;
  }
  return c;
}

mpq_class TangentCell::squared_radius_exact() const {
  auto c = centre_exact();
  const int N = chart_->N;
  const double* v0 = chart_->coords.data() + static_cast<std::size_t>(vertices_[0]) * N;
  mpq_class s = 0;
  for (int i = 0; i < N; ++i) {
    mpq_class d = c[i] - to_rational(v0[i]);
    s += d * d;
  }
  return s;
}

mpq_class TangentCell::power_exact(int query) const {
  chart_->check_index(query);
  if (det_sign_ == 0) throw std::domain_error("degenerate cell: its projection to T_p has no unique centre");
  ensure_exact();
  return detail::dispatch<1, detail::kMaxIntrinsicDim>(m_, [&](auto Mc) {
    constexpr int M = Mc();
    const EX v = detail::power_value<M>(exact_->coef.data(), exact_->k0, chart_->exact_row(query), origin_ref_);
    // |c - q|^2 - R^2 = det M(q) / det B (Schur complement), det B = coef_m != 0.
    mpq_class out = detail::to_mpq(v) / detail::to_mpq(exact_->coef[M]);
    return out;
  });
}

// ---------------------------------------------------------------------------------------------
// TangentFace
//
// Derivation. Chart rows are relative to p: b(x) = U^T (x - p), s(x) = |x - p|^2. A point
// c = p + U z of T_p has |c - x|^2 = z^T G z - 2 b(x).z + s(x). The projection of v_i is
// p + U G^{-1} b(v_i), so the affine hull of the projected face (through p) is
// { p + U G^{-1} D^T l : l in R^k }. Equal distances |c - v_i|^2 = |c - p|^2 give
// 2 b(v_i).z = s(v_i), i.e. 2 D G^{-1} D^T l = h, and for a query q
//   |c - q|^2 - |c - p|^2 = s(q) - 2 b(q).z = s(q) - b(q)^T G^{-1} D^T (D G^{-1} D^T)^{-1} h.
// With A = adj(G) = g G^{-1} (g = det G > 0) the g's cancel:
//   = s(q) - (D A b(q))^T (D A D^T)^{-1} h = det [[K, h], [w^T, s(q)]] / det K,
// K = D A D^T, w = D A b(q) (Schur complement). A is positive definite, so det K >= 0, with
// equality iff D has rank < k (the projected face is degenerate). Expanding the bordered
// determinant along its last row: det = sum_{j<k} coef_j w_j + coef_k s(q), coef_j =
// (-1)^(k+j) det([K | h] without column j), coef_k = det K. Only ring operations.
// ---------------------------------------------------------------------------------------------

namespace {

// Prepares coef (k + 1) and DA (k x m) from the rows of v_1..v_k (relative to p) and A = adj(G).
template <int K, class NT>
void face_prepare(const NT* const* rows, const NT* A, int m, NT* DA, NT* coef) {
  for (int i = 0; i < K; ++i)
    for (int a = 0; a < m; ++a) {
      NT acc(0);
      for (int c = 0; c < m; ++c) acc = acc + rows[i][c] * A[c * m + a];
      DA[i * m + a] = acc;
    }
  constexpr int C = K + 1;
  NT kh[K * C];
  for (int i = 0; i < K; ++i) {
    for (int j = 0; j < K; ++j) {
      NT acc(0);
      for (int a = 0; a < m; ++a) acc = acc + DA[i * m + a] * rows[j][a];
      kh[i * C + j] = acc;
    }
    kh[i * C + K] = rows[i][m];
  }
  NT table[1u << C];
  minor_table<K, C>(kh, table);
  const unsigned full = (1u << C) - 1;
  for (int j = 0; j < C; ++j) {
    const NT& minor = table[full ^ (1u << j)];
    coef[j] = ((K + j) % 2 == 0) ? minor : NT(0) - minor;
  }
}

// det [[K, h], [w^T, s(q)]] with w = DA b(q).
template <class NT>
NT face_value(const NT* coef, const NT* DA, int k, int m, const NT* rq) {
  NT v = coef[k] * rq[m];
  for (int j = 0; j < k; ++j) {
    NT w(0);
    for (int a = 0; a < m; ++a) w = w + DA[j * m + a] * rq[a];
    v = v + coef[j] * w;
  }
  return v;
}

}  // namespace

TangentFace TangentChart::face(std::span<const int> vertices, FilterContext& ctx) const {
  const Impl& c = *impl_;
  const int k = static_cast<int>(vertices.size()) - 1;
  if (k < 1 || k > c.m)
    throw std::invalid_argument("a face needs 2 to m + 1 = " + std::to_string(c.m + 1) + " vertices");
  for (int v : vertices) c.check_index(v);
  auto d = std::make_shared<detail::FaceData>();
  d->chart = impl_.get();
  d->k = k;
  d->m = c.m;
  d->vertices.assign(vertices.begin(), vertices.end());
  bool has_p = false;
  for (int v : vertices) {
    if (v == 0 && !has_p) has_p = true;
    else d->others.push_back(v);
  }
  if (!has_p) throw std::invalid_argument("a face must contain p (local index 0)");
  const auto& sp = *c.space_impl;
  d->coef.resize(k + 1);
  d->DA.resize(static_cast<std::size_t>(k) * c.m);
  detail::EnsureUpward guard;
  detail::dispatch<1, detail::kMaxIntrinsicDim>(k, [&](auto Kc) {
    constexpr int K = Kc();
    const IA* rows[K];
    for (int i = 0; i < K; ++i) rows[i] = c.row(d->others[i]);
    face_prepare<K>(rows, sp.adj_gram_interval.data(), c.m, d->DA.data(), d->coef.data());
  });
  bool finite = true;
  for (const auto& x : d->coef) finite = finite && std::isfinite(x.inf()) && std::isfinite(x.sup());
  for (const auto& x : d->DA) finite = finite && std::isfinite(x.inf()) && std::isfinite(x.sup());
  d->usable = finite;
  TangentFace face;
  face.data_ = d;
  d->det_sign = filtered_sign(  // det K >= 0: 0 (degenerate) or 1
      ctx, PredicateKind::tangent_orientation, finite, [&] { return d->coef[k]; },
      [&] {
        face.ensure_exact();
        return d->coef_exact[k];
      });
  return face;
}

void TangentFace::ensure_exact() const {
  auto& d = *data_;
  if (d.have_exact) return;
  const auto& c = *d.chart;
  d.coef_exact.assign(d.k + 1, EX(0));
  d.DA_exact.assign(static_cast<std::size_t>(d.k) * d.m, EX(0));
  detail::dispatch<1, detail::kMaxIntrinsicDim>(d.k, [&](auto Kc) {
    constexpr int K = Kc();
    const EX* rows[K];
    for (int i = 0; i < K; ++i) rows[i] = c.exact_row(d.others[i]);
    face_prepare<K>(rows, c.space_impl->adj_gram_exact.data(), d.m, d.DA_exact.data(), d.coef_exact.data());
  });
  d.have_exact = true;
}

int TangentFace::dimension() const { return data_->k; }
std::span<const int> TangentFace::vertices() const { return data_->vertices; }
bool TangentFace::degenerate() const { return data_->det_sign == 0; }

int TangentFace::power_sign(int query, FilterContext& ctx) const {
  const auto& d = *data_;
  d.chart->check_index(query);
  if (d.det_sign == 0) {
    count_result(ctx, PredicateKind::power, false, 0);
    return 0;
  }
  return filtered_sign(
      ctx, PredicateKind::power, d.usable,
      [&] { return face_value(d.coef.data(), d.DA.data(), d.k, d.m, d.chart->row(query)); },
      [&] {
        ensure_exact();
        return face_value(d.coef_exact.data(), d.DA_exact.data(), d.k, d.m, d.chart->exact_row(query));
      });
}

int TangentFace::power_sign(int query, const RationalConstant& delta, FilterContext& ctx) const {
  const auto& d = *data_;
  d.chart->check_index(query);
  if (d.det_sign == 0) {
    count_result(ctx, PredicateKind::power_threshold, false, 0);
    return 0;
  }
  return filtered_sign(
      ctx, PredicateKind::power_threshold, d.usable,
      [&] {
        return face_value(d.coef.data(), d.DA.data(), d.k, d.m, d.chart->row(query)) -
               detail::to_ia(delta.enclosure()) * d.coef[d.k];
      },
      [&] {
        ensure_exact();
        // delta = num/den with den > 0 (as for cells).
        const EX num = detail::to_ex(delta.value().get_num()), den = detail::to_ex(delta.value().get_den());
        return den * face_value(d.coef_exact.data(), d.DA_exact.data(), d.k, d.m, d.chart->exact_row(query)) -
               num * d.coef_exact[d.k];
      });
}

mpq_class TangentFace::power_exact(int query) const {
  const auto& d = *data_;
  d.chart->check_index(query);
  if (d.det_sign == 0) throw std::domain_error("degenerate face: its projection to T_p has no unique centre");
  ensure_exact();
  const EX v = face_value(d.coef_exact.data(), d.DA_exact.data(), d.k, d.m, d.chart->exact_row(query));
  return detail::to_mpq(v) / detail::to_mpq(d.coef_exact[d.k]);
}

// ---------------------------------------------------------------------------------------------
// One-shot functions
// ---------------------------------------------------------------------------------------------

namespace {

// Checks the number of points and null pointers. Finiteness is checked where the coordinates are
// read: by interval_row (a finite floating-point row implies finite coordinates) and, on the
// exact-only path, by check_all_finite.
void check_points(std::span<const double* const> pts, int expected, const char* what) {
  if (static_cast<int>(pts.size()) != expected)
    throw std::invalid_argument(std::string(what) + " needs m + 1 = " + std::to_string(expected) + " points");
  for (const double* x : pts)
    if (x == nullptr) throw std::invalid_argument("null point pointer");
}

void check_all_finite(std::span<const double* const> pts, const double* query, int N) {
  for (const double* x : pts) check_finite(x, N);
  if (query) check_finite(query, N);
}

// The interval evaluation of the one-shot power tests: a sign, or kUndecided.
template <int M>
int interval_power(const TangentSpace::Impl& s, std::span<const double* const> cell, const double* query,
                   const RationalConstant* delta) {
  constexpr int L = M + 1;
  IA buf[(M + 2) * L];
  const IA* rows[L];
  const IA* rq = chart_rows_of<M>(s, cell, query, buf, rows);
  IA coef[L], k0;
  detail::power_cell<M>(rows, false, coef, k0);
  const int ds = certain_sign(coef[M]);
  if (ds == 0 || ds == kUndecided) return ds;
  IA v = detail::power_value<M>(coef, k0, rq, false);
  if (delta) v = v - detail::to_ia(delta->enclosure()) * coef[M];
  const int vs = certain_sign(v);
  return vs == kUndecided ? kUndecided : ds * vs;
}

// The exact evaluation of the one-shot power tests.
template <int M>
int exact_power(const TangentSpace::Impl& s, std::span<const double* const> cell, const double* query,
                const RationalConstant* delta, int N) {
  constexpr int L = M + 1;
  check_all_finite(cell, query, N);
  EX buf[(M + 2) * L];
  const EX* rows[L];
  const EX* rq = chart_rows_of<M>(s, cell, query, buf, rows);
  EX coef[L], k0;
  detail::power_cell<M>(rows, false, coef, k0);
  const int ds = detail::exact_sign(coef[M]);
  if (ds == 0) return 0;
  EX v = detail::power_value<M>(coef, k0, rq, false);
  if (delta) {
    const EX num = detail::to_ex(delta->value().get_num()), den = detail::to_ex(delta->value().get_den());
    v = den * v - num * coef[M];
  }
  return ds * detail::exact_sign(v);
}

// The orientation determinant of m + 1 points from their chart rows, in either number type.
template <int M, class NT>
NT one_shot_orientation(const TangentSpace::Impl& s, std::span<const double* const> points) {
  constexpr int L = M + 1;
  NT buf[L * L];
  const NT* rows[L];
  chart_rows_of<M>(s, points, nullptr, buf, rows);
  return detail::orientation_det<M>(rows, false);
}

// Shared body of the two one-shot power tests; delta == nullptr for the plain test.
// sign(det B) * sign(det M(q) [- delta det B]), and 0 when det B = 0 (see power_cell).
int one_shot_power(const TangentSpace& space, std::span<const double* const> cell, const double* query,
                   const RationalConstant* delta, FilterContext& ctx) {
  const int m = space.intrinsic_dimension();
  check_points(cell, m + 1, "a cell");
  if (query == nullptr) throw std::invalid_argument("null point pointer");
  const auto& s = space.impl();
  const PredicateKind kind = delta ? PredicateKind::power_threshold : PredicateKind::power;
  return detail::dispatch<1, detail::kMaxIntrinsicDim>(m, [&](auto Mc) {
    constexpr int M = Mc();
    return filtered_sign(ctx, kind, [&] { return interval_power<M>(s, cell, query, delta); },
                         [&] { return exact_power<M>(s, cell, query, delta, space.ambient_dimension()); });
  });
}

}  // namespace

int tangent_orientation(const TangentSpace& space, std::span<const double* const> points, FilterContext& ctx) {
  const int m = space.intrinsic_dimension();
  check_points(points, m + 1, "orientation");
  const auto& s = space.impl();
  return detail::dispatch<1, detail::kMaxIntrinsicDim>(m, [&](auto Mc) {
    constexpr int M = Mc();
    return filtered_sign(
        ctx, PredicateKind::tangent_orientation, [&] { return one_shot_orientation<M, IA>(s, points); },
        [&] {
          check_all_finite(points, nullptr, space.ambient_dimension());
          return one_shot_orientation<M, EX>(s, points);
        });
  });
}

int tangent_power_sign(const TangentSpace& space, std::span<const double* const> cell, const double* query,
                       FilterContext& ctx) {
  return one_shot_power(space, cell, query, nullptr, ctx);
}

int tangent_power_sign(const TangentSpace& space, std::span<const double* const> cell, const double* query,
                       const RationalConstant& delta, FilterContext& ctx) {
  return one_shot_power(space, cell, query, &delta, ctx);
}

}  // namespace delcert::exact
