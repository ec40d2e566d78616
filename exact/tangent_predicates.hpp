// Filtered exact predicates in a tangent space T_p (docs/design.md §3.2, issue 3 predicates 1-3).
//
// Setting. p is a sample point, T_p = p + span U its exact tangent flat (TangentSpace). A
// nearby point q is projected to q' = pi_p(q) with weight w(q) = -|q - q'|^2, so that for x in
// T_p the power |x - q'|^2 - w(q) equals the ambient |x - q|^2. The star of p is the set of
// cells of the regular triangulation of these weighted points that contain p.
//
// Coordinates. A TangentChart stores, for p (local index 0) and for given nearby points (local
// indices 1..), the chart row r(x) = (b(x), s(x)), b(x) = U^T (x - p), s(x) = |x - p|^2, once
// in interval arithmetic and, on demand, exactly. Every predicate below is a sign of a
// polynomial in these rows (see exact/detail/kernels.hpp for the formulas and why they are
// exact); the projections and the Gram matrix are not needed for the signs.
//
//  * orientation(v0..vm) = sign det [b(v1) - b(v0); ...; b(vm) - b(v0)]: the orientation of the
//    projected simplex with respect to the basis U. It is consistent for all calls at the same
//    p (same U), which is what gift-wrapping needs; 0 means the projected simplex is degenerate.
//  * For a cell s = (v0..vm), its centre c in T_p is the point of T_p at equal ambient distance
//    from all vertices (the power centre of the weighted projections). power_sign(q) =
//    sign(|c - q|^2 - |c - v0|^2): -1 when q is strictly inside the ball (q conflicts with s),
//    +1 when strictly outside. With a threshold delta (e.g. delta^2 of power protection),
//    sign(|c - q|^2 - |c - v0|^2 - delta).
//
// Evaluation. Interval arithmetic first (CGAL Interval_nt_advanced, rounding mode upward; see
// interval.hpp for batching the mode switch); the chart rows' enclosures come from a plain
// floating-point evaluation with a rigorous a-priori error bound (tangent_predicates.cpp), the
// rest is interval arithmetic. When an interval contains 0, the same formula is evaluated exactly
// (CGAL::Mpzf: every quantity is dyadic). Each call is counted in FilterContext::stats.
//
// Zeros. Every answer is the exact sign. 0 means exactly on the sphere (or exactly at the
// threshold) OR the cell is degenerate (no unique centre, TangentCell::degenerate()); either way
// "not protected" for a caller deciding protection. No symbolic perturbation.
//
// Cost. Build one TangentCell per candidate cell and test many queries against it: a query
// costs m + 1 interval multiply-adds. The free functions at the end take raw points and
// recompute the chart rows at every call (convenient, slower).
//
// Threads. TangentChart computes its rows (interval and exact) lazily: use a chart (and its
// cells) from one thread at a time. TangentSpace is immutable and may be shared.
#pragma once

#include <gmpxx.h>

#include <array>
#include <initializer_list>
#include <memory>
#include <span>
#include <vector>

#include "exact/filter_stats.hpp"
#include "exact/number_types.hpp"
#include "exact/tangent_space.hpp"

namespace delcert::exact {

inline constexpr int kMaxTangentDimension = 6;  // largest intrinsic dimension m supported here

namespace detail {
struct ExactCellData;
struct FaceData;
}  // namespace detail

class TangentCell;
class TangentFace;

class TangentChart {
 public:
  // points: pointers to N doubles each (copied). Local index 0 is p itself; points[i] gets local
  // index i + 1. A point may equal p or another point (repeated points are allowed).
  TangentChart(const TangentSpace& space, std::span<const double* const> points);
  // Same, for points stored row-major (#points by N).
  TangentChart(const TangentSpace& space, std::span<const double> points_row_major);
  ~TangentChart();
  TangentChart(TangentChart&&) noexcept;
  TangentChart& operator=(TangentChart&&) noexcept;
  TangentChart(const TangentChart&) = delete;
  TangentChart& operator=(const TangentChart&) = delete;

  int size() const;  // 1 + number of points
  const TangentSpace& space() const;
  std::span<const double> coordinates(int local) const;  // N doubles

  // Orientation of m + 1 points given by local indices (any order, p allowed).
  int orientation(std::span<const int> vertices, FilterContext& ctx) const;
  // A cell given by m + 1 local indices (usually including 0 = p). Its orientation is computed
  // exactly at construction (counted as a tangent_orientation call).
  TangentCell cell(std::span<const int> vertices, FilterContext& ctx) const;
  // Convenience: cell(vertices).power_sign(query).
  int power_sign(std::span<const int> vertices, int query, FilterContext& ctx) const;
  // Braced-list forms: chart.orientation({0, a, b}, ctx).
  int orientation(std::initializer_list<int> vertices, FilterContext& ctx) const {
    return orientation(std::span<const int>(vertices.begin(), vertices.size()), ctx);
  }
  TangentCell cell(std::initializer_list<int> vertices, FilterContext& ctx) const;
  int power_sign(std::initializer_list<int> vertices, int query, FilterContext& ctx) const {
    return power_sign(std::span<const int>(vertices.begin(), vertices.size()), query, ctx);
  }

  // A face through p: k + 1 local indices (1 <= k <= m) including 0 = p (see TangentFace).
  // Lower-dimensional faces are what gift-wrapping needs to start a star from scratch.
  TangentFace face(std::span<const int> vertices, FilterContext& ctx) const;
  TangentFace face(std::initializer_list<int> vertices, FilterContext& ctx) const;

  // Exact chart row (b_1..b_m, s) of a local point, as rationals (tests, reports).
  std::vector<mpq_class> row_exact(int local) const;

  struct Impl;

 private:
  friend class TangentCell;
  std::unique_ptr<Impl> impl_;
};

// A cell of the tangential star (or a candidate cell) prepared for many power tests. Refers to
// its chart, which must outlive it. Copyable.
class TangentCell {
 public:
  int dimension() const { return m_; }
  // Local indices, in the order given to TangentChart::cell.
  std::span<const int> vertices() const { return {vertices_.data(), static_cast<std::size_t>(m_ + 1)}; }
  // Exact orientation of the vertices in the given order (see TangentChart::orientation).
  int orientation() const { return orientation_; }
  // True when the projected cell is degenerate (affinely dependent in T_p): no unique centre.
  bool degenerate() const { return det_sign_ == 0; }

  // sign(|c - q|^2 - R^2) with R = |c - v| for any vertex v; 0 when degenerate.
  int power_sign(int query, FilterContext& ctx) const;
  // sign(|c - q|^2 - R^2 - delta); 0 when degenerate.
  int power_sign(int query, const RationalConstant& delta, FilterContext& ctx) const;

  // Exact values (rational arithmetic; slow: reports and witnesses). Throw std::domain_error
  // when the cell is degenerate.
  std::vector<mpq_class> centre_exact() const;  // c, N rationals
  mpq_class squared_radius_exact() const;       // R^2 = |c - v0|^2
  mpq_class power_exact(int query) const;       // |c - q|^2 - R^2

 private:
  friend class TangentChart;
  TangentCell() = default;
  void ensure_exact() const;

  const TangentChart::Impl* chart_ = nullptr;
  int m_ = 0;
  std::array<int, kMaxTangentDimension + 1> vertices_{};  // as given
  std::array<int, kMaxTangentDimension + 1> order_{};     // internal: p (local 0) first if present
  bool origin_ref_ = false;                               // order_[0] == 0
  int det_sign_ = 0;                                      // exact sign of det B in internal order
  int orientation_ = 0;
  bool filter_usable_ = false;  // interval coefficients are finite
  // Interval enclosures of coef_0..coef_m and k0 (see detail::power_cell), as (lo, hi) pairs.
  std::array<double, 2 * (kMaxTangentDimension + 2)> enclosures_{};
  mutable std::shared_ptr<const detail::ExactCellData> exact_;
};

// A k-face f = (p, v_1..v_k) through p, 1 <= k <= m, prepared for power tests. Its centre is
// the point c of T_p in the affine hull of the projections of its vertices with equal ambient
// distance R to all of them (the centre of the smallest power sphere of the weighted projected
// face; for k = m the cell centre). power_sign(q) = sign(|c - q|^2 - R^2).
//
// Formula (division-free; see tangent_predicates.cpp): with D the k x m matrix of rows b(v_i),
// A = adj(G) = det(G) G^{-1} (G = U^T U), K = D A D^T and h_i = s(v_i),
//   |c - q|^2 - R^2 = det [[K, h], [(D A b(q))^T, s(q)]] / det K,   det K >= 0,
// and det K = 0 exactly when the projected face is degenerate.
// Typical use: start a star from the edge (p, q1) with q1 a nearest neighbour of p, then extend
// a face f by the candidate q minimising its power sphere: q2 beats q1 iff
// face(f + q1).power_sign(q2) < 0.
class TangentFace {
 public:
  int dimension() const;
  std::span<const int> vertices() const;  // as given
  bool degenerate() const;
  int power_sign(int query, FilterContext& ctx) const;
  int power_sign(int query, const RationalConstant& delta, FilterContext& ctx) const;
  mpq_class power_exact(int query) const;  // |c - q|^2 - R^2; throws std::domain_error if degenerate

 private:
  friend class TangentChart;
  void ensure_exact() const;
  std::shared_ptr<detail::FaceData> data_;
};

// One-shot versions on raw points (each pointer: N doubles), without a chart.
// Orientation of m + 1 points in T_p.
int tangent_orientation(const TangentSpace& space, std::span<const double* const> points, FilterContext& ctx);
// sign(|c - q|^2 - R^2) for the cell with m + 1 vertices `cell`; 0 when degenerate.
int tangent_power_sign(const TangentSpace& space, std::span<const double* const> cell, const double* query,
                       FilterContext& ctx);
// sign(|c - q|^2 - R^2 - delta); 0 when degenerate.
int tangent_power_sign(const TangentSpace& space, std::span<const double* const> cell, const double* query,
                       const RationalConstant& delta, FilterContext& ctx);

inline TangentCell TangentChart::cell(std::initializer_list<int> vertices, FilterContext& ctx) const {
  return cell(std::span<const int>(vertices.begin(), vertices.size()), ctx);
}
inline TangentFace TangentChart::face(std::initializer_list<int> vertices, FilterContext& ctx) const {
  return face(std::span<const int>(vertices.begin(), vertices.size()), ctx);
}

}  // namespace delcert::exact
