// The GEODESIC sign model of param_cell.cpp: the Voronoi cell of p for the geodesic distance of a product of
// round spheres, in one stereographic chart per factor (its argument below). Included by param_cell.cpp only.
#pragma once

#include <optional>
#include <span>
#include <vector>

#include "certify/intrinsic/engines.hpp"
#include "certify/restricted/cell_checks.hpp"
#include "certify/restricted/charts.hpp"
#include "certify/restricted/param_pieces.hpp"
#include "exact/angle_series.hpp"

namespace delcert::certify::detail::param {

// GEODESIC: the Voronoi cell of p for the GEODESIC distance of a product of round spheres
// M = S^k1(r_1) x ... x S^kF(r_F) (factor f on its own block of coordinates, centred at 0, any
// k_f >= 1, m = sum k_f <= 3), for Del_M (certify/intrinsic_product.cpp). d_M^2(x, y) =
// sum_f r_f^2 theta_f^2 with theta_f the angle between the blocks x_f, y_f (the product metric),
// and d_M(x, q) := d_M(x, pi(q)) for a sample point q near M, pi(q)_f = r_f q_f / |q_f|
// (intrinsic.hpp's convention). With qh_f = q_f / |q_f| and x_f = r_f e_f, cos theta_f = e_f.qh_f =
// 1 - u_f and r_f^2 theta_f^2 = r_f^2 g(u_f), g(u) = acos(1 - u)^2 (exact/angle_series.hpp: increasing,
// analytic on [0, 2), enclosed in double intervals).
// THE CHART is the sphere's stereographic one per factor: e_f(v_f) = (-n_f + (n_f + E_f v_f) w_f),
// w_f = 2 / (1 + |v_f|^2), with n_f a rational unit vector near p_f and E_f = householder_frame(n_f)
// (orthonormal, orthogonal to n_f: |e_f| = 1 exactly, as for the sphere chart above). So
//   u_f^q(v) = 1 + a_f - (a_f + b_f.v_f) w_f,  a_f = n_f.qh_f,  b_f = E_f^T qh_f,
// and s_q(v) = d_M^2(phi(v), q) - d_M^2(phi(v), p) = sum_f r_f^2 (g(u_f^q) - g(u_f^p)): its sign
// is the geodesic Voronoi sign. a_f, b_f are enclosed from the exact doubles (and intersected
// with [-1, 1], where their true values lie); u with [0, 2] (acos_squared).
// COVERAGE (Lemma (b) of the sphere chart per factor): the cell is analysed in the geodesic ball
// B_M(pi(p), r). A point x of it has |x_f - pi(p)_f| <= r_f theta_f <= d_M(x, pi(p)) < r (chord <=
// arc), so |x_f - r_f n_f| < r + E + |p_f - r_f n_f| =: r'_f, E >= |p - pi(p)| the projection slack
// (RestrictedCellOptions::projection_slack, a bound over all points); with s_f = r'_f / (2 r_f) < 1
// it is e_f(v_f) with |v_f| < t_f = s_f / sqrt(1 - s_f^2). A box is discarded outside the ball when
// sum_f r_f^2 g(u_f^p) >= r^2 on it.
// CANDIDATES: q with d_M(x, pi(q)) < d_M(x, pi(p)) < r for some x of the ball has
// |pi(q) - pi(p)| <= d_M(pi(q), pi(p)) < 2r, so |q - p| < 2r + 2E: grid.ball(p, 2r + 2E) holds them.
// A VERTEX x (Krawczyk's root in V, every s_q of S zero there, every g C^1 since u <= 1 is required
// for the slopes) has d_M(x, pi(q)) = d_M(x, pi(p)) =: R for q in S; any q with d_M(x, pi(q)) <= R
// has |q - x| <= R + E, so the points of grid.ball(X~, R + E + |X - X~|) (X the enclosure of
// phi(V), X~ its midpoint) are the only ones to prove strictly farther (s_q > 0 on V).
// ROUNDING: double intervals under UpwardRounding throughout (exact/interval_arithmetic.hpp);
// rationals (n_f, E_f, r_f) enter as enclosures (exact::enclose).
struct ProductChart {
  struct Factor {
    std::vector<int> coords;               // k + 1 coordinates of the block
    IA r, r2;                               // radius and its square
    std::vector<IA> n;                      // k + 1
    std::vector<std::vector<IA>> E;         // (k + 1) x k
    double t = 0;
    int offset = 0, k = 0;                  // the chart variables offset .. offset + k - 1
  };
  std::vector<Factor> f;
  int m = 0;
  double slack = 0;
};

inline std::optional<ProductChart> product_chart(const io::ShapeSpec& g, std::span<const double> p, double r, double slack) {
  if (g.kind != io::ShapeSpec::Kind::product) return std::nullopt;
  ProductChart C;
  C.slack = slack;
  for (const io::ShapeFactor& sf : g.factors) {
    if (sf.kind != io::ShapeFactor::Kind::sphere) return std::nullopt;
    ProductChart::Factor F;
    F.coords = sf.coordinates;
    F.k = static_cast<int>(F.coords.size()) - 1;
    F.offset = C.m;
    C.m += F.k;
    if (F.k < 1 || C.m > 3) return std::nullopt;
    std::vector<double> pf;
    for (int c : F.coords) pf.push_back(p[c]);
    const std::optional<std::vector<mpq_class>> n = rational_unit_near(pf);
    if (!n) return std::nullopt;
    const std::vector<std::vector<mpq_class>> E = householder_frame(*n);
    std::vector<mpq_class> apex;
    for (const auto& x : *n) apex.push_back(sf.radius * x);
    exact::UpwardRounding up;
    F.r = ia(exact::enclose(sf.radius)), F.r2 = exact::square(F.r);
    for (int i = 0; i <= F.k; ++i) {
      F.n.push_back(ia(exact::enclose((*n)[i])));
      F.E.emplace_back();
      for (int j = 0; j < F.k; ++j) F.E[i].push_back(ia(exact::enclose(E[i][j])));
    }
    F.t = half_width(IA(r) + IA(slack) + distance_to(pf, apex), IA(2) * F.r);
    if (!(F.t > 0)) return std::nullopt;
    C.f.push_back(std::move(F));
  }
  if (C.m < 1) return std::nullopt;
  return C;
}

// s_q (GEODESIC above) by its a_f (per factor) and b (per chart variable); p's own (a, b) too.
// Its range over a box is the natural extension, intersected (both are enclosures) with the MEAN
// VALUE FORM s_q(c) + sum_j ds_q/dv_j(V) (v_j - c_j) where the slopes exist (u <= 1 on the box): the
// difference of two squared angles nearly cancels along a bisector, which only the latter sees.
struct Geodesic {
  // A box's side of every s_q: the box V, w_f over it and p's term g(u_f^p) over it; for the mean
  // value form the same at the centre c (point intervals; the centre's g to 2^-30 relative), W =
  // V - c, and p's slopes d(sum_f r_f^2 g(u_f^p))/dv_j over V.
  struct Frame {
    const ProductChart* C = nullptr;
    std::array<IA, 3> V, w, gp;
    std::array<IA, 3> c, wc, gpc, W, dp;
    bool mean_value = false;  // dp exists (p's u <= 1 on V) and V is not a point
  };
  std::array<IA, 3> a, b;

  // u_f = 1 + a_f - (a_f + b_f.V_f) w_f over V (or at a point).
  IA u(const ProductChart::Factor& F, int fi, const std::array<IA, 3>& V, const IA& w) const {
    IA dot = a[fi];
    for (int j = 0; j < F.k; ++j) dot += b[F.offset + j] * V[F.offset + j];
    return IA(1) + a[fi] - dot * w;
  }
  // Encloses s_q over the box (or at a point: a box of point intervals).
  IA range(const Frame& B) const {
    IA s(0), centre(0), grad[3];
    bool mean_value = B.mean_value;
    for (std::size_t fi = 0; fi < B.C->f.size(); ++fi) {
      const auto& F = B.C->f[fi];
      const int i = static_cast<int>(fi);
      const IA U = u(F, i, B.V, B.w[fi]);
      s += F.r2 * (exact::acos_squared(U) - B.gp[fi]);
      if (!mean_value) continue;
      centre += F.r2 * (exact::acos_squared(u(F, i, B.c, B.wc[fi]), 0x1p-30) - B.gpc[fi]);
      mean_value = slope(F, i, B, U, grad + F.offset);
    }
    if (!mean_value) return s;
    for (int j = 0; j < B.C->m; ++j) centre += (grad[j] - B.dp[j]) * B.W[j];
    const double lo = std::max(s.inf(), centre.inf()), hi = std::min(s.sup(), centre.sup());
    return lo <= hi ? IA(lo, hi) : s;  // (disjoint enclosures of one value cannot happen)
  }
  // d(r_f^2 g(u_f)) / dv_j for j in factor fi over the box, U = u_f over it (du/dv_j = (a + b.V) w^2
  // V_j - b_j w); false when U may exceed 1 (acos_squared_slope: no slope enclosure there).
  bool slope(const ProductChart::Factor& F, int fi, const Frame& B, const IA& U, IA* out) const {
    const std::optional<IA> gs = exact::acos_squared_slope(U);
    if (!gs) return false;
    IA dot = a[fi];
    for (int j = 0; j < F.k; ++j) dot += b[F.offset + j] * B.V[F.offset + j];
    const IA w2 = exact::square(B.w[fi]);
    for (int j = 0; j < F.k; ++j)
      out[j] = F.r2 * *gs * (dot * w2 * B.V[F.offset + j] - b[F.offset + j] * B.w[fi]);
    return true;
  }
  bool slope(const ProductChart::Factor& F, int fi, const Frame& B, IA* out) const {
    return slope(F, fi, B, u(F, fi, B.V, B.w[fi]), out);
  }
};

class GeodesicModel {
 public:
  using F = Geodesic;
  GeodesicModel(ProductChart chart, std::span<const double> p) : C_(std::move(chart)) {
    for (const auto& f : C_.f) t_ = std::max(t_, f.t);
    p_ = candidate(p);
  }
  int m() const { return C_.m; }
  double t() const { return t_; }
  Box root() const {
    Box V(C_.m);
    for (const auto& f : C_.f)
      for (int j = 0; j < f.k; ++j) V[f.offset + j] = Interval{-f.t, f.t};
    return V;
  }
  double search_radius(double r) const {
    exact::UpwardRounding up;
    return (IA(2) * (IA(r) + IA(C_.slack))).sup();
  }
  // a_f = n_f.qh_f, b = E_f^T qh_f, qh_f = q_f / |q_f| ([-1, 1] when |q_f| is not certainly > 0).
  F candidate(std::span<const double> q) const {
    exact::UpwardRounding up;
    F s;
    const IA unit(-1, 1);
    for (std::size_t fi = 0; fi < C_.f.size(); ++fi) {
      const auto& f = C_.f[fi];
      IA len2(0);
      for (int c : f.coords) len2 += exact::square(IA(q[c]));
      const IA len = exact::sqrt(len2);
      const bool ok = len.inf() > 0;
      auto clamp = [&](const IA& x) { return ok ? IA(std::max(x.inf(), -1.0), std::min(x.sup(), 1.0)) : unit; };
      IA a(0);
      for (int i = 0; i <= f.k; ++i) a += f.n[i] * IA(q[f.coords[i]]);
      s.a[fi] = ok ? clamp(a / len) : unit;
      for (int j = 0; j < f.k; ++j) {
        IA b(0);
        for (int i = 0; i <= f.k; ++i) b += f.E[i][j] * IA(q[f.coords[i]]);
        s.b[f.offset + j] = ok ? clamp(b / len) : unit;
      }
    }
    return s;
  }
  F::Frame frame(const Box& V) const {
    exact::UpwardRounding up;
    F::Frame B;
    B.C = &C_;
    bool point = true;
    for (int i = 0; i < C_.m; ++i) {
      B.V[i] = ia(V[i]), B.c[i] = IA(V[i].midpoint());
      B.W[i] = IA((IA(V[i].lo) - B.c[i]).inf(), (IA(V[i].hi) - B.c[i]).sup());
      point = point && V[i].lo == V[i].hi;
    }
    auto w_of = [&](const std::array<IA, 3>& X, const ProductChart::Factor& f) {
      IA v2(0);
      for (int j = 0; j < f.k; ++j) v2 += exact::square(X[f.offset + j]);
      return IA(2) / (IA(1) + v2);
    };
    B.mean_value = !point;
    for (std::size_t fi = 0; fi < C_.f.size(); ++fi) {
      const auto& f = C_.f[fi];
      const int i = static_cast<int>(fi);
      B.w[fi] = w_of(B.V, f);
      const IA U = p_.u(f, i, B.V, B.w[fi]);
      B.gp[fi] = exact::acos_squared(U);
      if (!B.mean_value) continue;
      B.wc[fi] = w_of(B.c, f);
      B.gpc[fi] = exact::acos_squared(p_.u(f, i, B.c, B.wc[fi]), 0x1p-30);
      B.mean_value = p_.slope(f, i, B, U, B.dp.data() + f.offset);
    }
    return B;
  }
  // phi(V) = (r_f (-n_f + (n_f + E_f V_f) w_f))_f and d_M^2(phi(V), pi(p)) = sum_f r_f^2 g(u_f^p).
  void image(const F::Frame& B, Box* X, IA* d2) const {
    exact::UpwardRounding up;
    if (X) {
      int N = 0;
      for (const auto& f : C_.f) N += f.k + 1;
      X->assign(N, Interval{0, 0});
      for (const auto& f : C_.f)
        for (int i = 0; i <= f.k; ++i) {
          IA e = f.n[i];
          for (int j = 0; j < f.k; ++j) e += f.E[i][j] * B.V[f.offset + j];
          (*X)[f.coords[i]] = exact::to_interval(f.r * (e * B.w[&f - C_.f.data()] - f.n[i]));
        }
    }
    if (d2) {
      *d2 = IA(0);
      for (std::size_t fi = 0; fi < C_.f.size(); ++fi) *d2 += C_.f[fi].r2 * B.gp[fi];
    }
  }
  // Every point other than the simplex's strictly farther from phi(V) than pi(p) (VERTEX above).
  bool others_farther(const io::PointSet& points, const PointGrid& grid, const std::vector<int>& simplex,
                      const Box& V) const {
    exact::UpwardRounding up;
    const F::Frame B = frame(V);
    Box X;
    IA d2;
    image(B, &X, &d2);
    std::vector<double> c;
    IA dc(0);
    for (const auto& x : X) c.push_back(x.midpoint()), dc += exact::square(ia(x) - IA(x.midpoint()));
    const double radius = (exact::sqrt(IA(0, d2.sup())) + IA(C_.slack) + exact::sqrt(dc)).sup();
    for (int q : grid.ball(c, radius)) {
      if (std::binary_search(simplex.begin(), simplex.end(), q)) continue;
      if (!(candidate(points.point(q)).range(B).inf() > 0)) return false;
    }
    return true;
  }
  const ProductChart& chart() const { return C_; }
  const F& site() const { return p_; }

 private:
  ProductChart C_;
  double t_ = 0;
  F p_;
};

// {s_q = 0 : q in S} for Geodesic s_q (Krawczyk's rows): values at a point as a box of point
// intervals; the Jacobian from Geodesic::slope of q's and p's terms.
class GeodesicSystem final : public exact::EnclosedFunction {
 public:
  GeodesicSystem(const GeodesicModel& model, const std::vector<Geodesic>& all, std::span<const int> S,
                 const Geodesic& p)
      : model_(model), p_(p) {
    for (int i : S) rows_.push_back(&all[i]);
  }
  int size() const override { return static_cast<int>(rows_.size()); }
  bool values(std::span<const double> y, std::span<Interval> f) const override {
    Box Y;
    for (double x : y) Y.push_back(Interval{x, x});
    const Geodesic::Frame B = model_.frame(Y);
    exact::UpwardRounding up;
    for (std::size_t r = 0; r < rows_.size(); ++r) f[r] = exact::to_interval(rows_[r]->range(B));
    return true;
  }
  bool jacobian(const Box& X, std::span<Interval> J) const override {
    const Geodesic::Frame B = model_.frame(X);
    exact::UpwardRounding up;
    const int n = size();
    const ProductChart& C = model_.chart();
    for (std::size_t fi = 0; fi < C.f.size(); ++fi) {
      const auto& F = C.f[fi];
      IA dp[3], dq[3];
      if (!p_.slope(F, static_cast<int>(fi), B, dp)) return false;
      for (int r = 0; r < n; ++r) {
        if (!rows_[r]->slope(F, static_cast<int>(fi), B, dq)) return false;
        for (int j = 0; j < F.k; ++j) J[r * n + F.offset + j] = exact::to_interval(dq[j] - dp[j]);
      }
    }
    return true;
  }

 private:
  const GeodesicModel& model_;
  const Geodesic& p_;
  std::vector<const Geodesic*> rows_;
};

// A unique root's box tightened (GEODESIC vertices): contraction over a wide box stalls, the slope
// enclosures being loose there. A few floating-point Newton steps from B's centre (only a guess),
// then Krawczyk on small boxes around the guess, intersected with B: a root proven in one is THE
// root of B (B holds exactly one). B itself when none is proven.
inline Box tighten(const GeodesicSystem& system, const Box& B) {
  const int n = system.size();
  std::vector<double> y(n);
  for (int i = 0; i < n; ++i) y[i] = B[i].midpoint();
  std::vector<Interval> f(n), J(n * n);
  for (int step = 0; step < 8; ++step) {
    Box Y;
    for (double x : y) Y.push_back(Interval{x, x});
    if (!system.values(y, f) || !system.jacobian(Y, J)) return B;
    double M[9], rhs[3], d[3];
    for (int i = 0; i < n * n; ++i) M[i] = J[i].midpoint();
    for (int i = 0; i < n; ++i) rhs[i] = f[i].midpoint();
    const double det = exact::determinant(M, n);
    if (!(std::abs(det) > 0) || !std::isfinite(det)) return B;
    exact::cramer_solve(M, rhs, det, n, d);
    for (int i = 0; i < n; ++i) y[i] = std::clamp(y[i] - d[i], B[i].lo, B[i].hi);
  }
  for (double h : {0x1p-40, 0x1p-30, 0x1p-20}) {
    Box T(n);
    bool inside = true;
    for (int i = 0; i < n; ++i) {
      T[i] = Interval{std::max(y[i] - h, B[i].lo), std::min(y[i] + h, B[i].hi)};
      inside = inside && T[i].lo <= T[i].hi;
    }
    if (!inside) return B;
    const exact::KrawczykResult r = exact::krawczyk(system, T);
    if (r.status == exact::RootStatus::unique_root) return r.box;
  }
  return B;
}

}  // namespace delcert::certify::detail::param
