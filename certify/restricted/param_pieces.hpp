// The pieces the sign models of param_cell.cpp share (QUADRATIC, PRODUCT OF CIRCLES, GEODESIC): a box centred,
// the points a cell looks at, a quadratic form and the SEPARABLE functions of v, and a cell's work counters.
// Included by param_cell.cpp and geodesic_model.hpp only.
#pragma once

#include <gmpxx.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "certify/detail/grid.hpp"
#include "certify/restricted/charts.hpp"
#include "certify/restricted/param_cell.hpp"
#include "exact/enclosed_polynomial.hpp"
#include "exact/interval_arithmetic.hpp"
#include "exact/krawczyk.hpp"
#include "exact/linear_algebra.hpp"
#include "exact/number_types.hpp"
#include "exact/polynomial.hpp"
#include "exact/small_vector.hpp"

namespace delcert::certify::detail::param {

using exact::Box;
using exact::EnclosedPolynomial;
using exact::Interval;
using exact::Polynomial;
using IA = exact::IntervalNumber;

// A box V as its centre c (point intervals of the midpoints) and W = V - c, enclosed.
struct Centred {
  std::array<IA, 3> c, W;
  explicit Centred(const Box& V) {
    exact::UpwardRounding up;
    for (std::size_t i = 0; i < V.size(); ++i) {
      const double mid = V[i].midpoint();
      c[i] = IA(mid);
      W[i] = IA((IA(V[i].lo) - c[i]).inf(), (IA(V[i].hi) - c[i]).sup());
    }
  }
};

// A candidate's model near a box's centre, in double from the lower ends of its coefficient
// enclosures: value f, slopes g, second-order coefficients G (v_i^2) and C (v_i v_j, pairs (0,1),
// (0,2), (1,2)). Only to choose combinations and skip hopeless ones: never a decision.
struct Local {
  double f = 0, g[3] = {0, 0, 0}, G[3] = {0, 0, 0}, C[3] = {0, 0, 0};
};

// A polynomial of degree <= 2 in m <= 3 variables (the sphere and SO(3) charts: X, D and so each
// P_q are quadratic), known by coefficient enclosures: P(v) = a + sum_i b_i v_i + sum_i G_i v_i^2 +
// sum_{i<j} C_ij v_i v_j. Over a box V with centre c (doubles) and v = c + w, w in W = V - c:
//   P(c + w) = P(c) + sum_i g_i w_i + sum_i G_i w_i^2 + sum_{i<j} C_ij w_i w_j,
//   g_i = dP/dv_i (c) = b_i + 2 G_i c_i + sum_{j != i} C_ij c_j,
// an identity (Taylor at c is exact at degree 2), so enclosing each term of the right side over W
// (w_i^2 by exact::square: tight at 0) encloses the range of P on V for every polynomial the
// enclosures stand for. Second order exact: much tighter than the natural extension on wide boxes.
struct Quadratic {
  using Frame = Centred;
  IA a{0};
  std::array<IA, 3> b{IA(0), IA(0), IA(0)}, G{IA(0), IA(0), IA(0)}, C{IA(0), IA(0), IA(0)};  // C: (0,1), (0,2), (1,2)
  int m = 0;
  static constexpr int pair[3][2] = {{0, 1}, {0, 2}, {1, 2}};
  Quadratic() = default;
  explicit Quadratic(const EnclosedPolynomial& P) : m(P.num_variables()) {
    if (m > 3) throw std::logic_error("restricted cell: a rational chart has more than 3 parameters");
    for (std::size_t t = 0; t < P.size(); ++t) {
      const auto e = P.exponents(t);
      int deg = 0, first = -1, second = -1;
      for (int i = 0; i < m; ++i) {
        deg += static_cast<int>(e[i]);
        for (std::uint32_t k = 0; k < e[i]; ++k) (first < 0 ? first : second) = i;
      }
      const IA c = ia(P.coefficient(t));
      if (deg == 0) a = c;
      else if (deg == 1) b[first] = c;
      else if (deg == 2 && first == second) G[first] = c;
      else if (deg == 2) C[first + second - 1] = c;  // (0,1) -> 0, (0,2) -> 1, (1,2) -> 2
      else throw std::logic_error("restricted cell: a rational chart is not quadratic");
    }
  }
  // The range over the box c + W (c: the centre, point intervals). Under upward rounding.
  IA range(const IA* c, const IA* W) const {
    IA v = a;
    for (int i = 0; i < m; ++i) v += (b[i] + G[i] * c[i]) * c[i];
    for (int k = 0; k < 3; ++k)
      if (pair[k][1] < m) v += C[k] * c[pair[k][0]] * c[pair[k][1]];
    for (int i = 0; i < m; ++i) {
      IA g = b[i] + IA(2) * G[i] * c[i];
      for (int k = 0; k < 3; ++k)
        if (pair[k][1] < m && (pair[k][0] == i || pair[k][1] == i)) g += C[k] * c[pair[k][0] == i ? pair[k][1] : pair[k][0]];
      v += g * W[i] + G[i] * exact::square(W[i]);
    }
    for (int k = 0; k < 3; ++k)
      if (pair[k][1] < m) v += C[k] * (W[pair[k][0]] * W[pair[k][1]]);
    return v;
  }
  IA range(const Centred& B) const { return range(B.c.data(), B.W.data()); }
  Local local(const double* c) const {
    Local l;
    l.f = a.inf();
    for (int i = 0; i < m; ++i) l.f += (b[i].inf() + G[i].inf() * c[i]) * c[i], l.g[i] = slope(i, c), l.G[i] = G[i].inf();
    for (int k = 0; k < 3; ++k)
      if (pair[k][1] < m) l.f += C[k].inf() * c[pair[k][0]] * c[pair[k][1]], l.C[k] = C[k].inf();
    return l;
  }
  // This + t B (interval coefficients). Under upward rounding.
  void add(const Quadratic& B, const IA& T) {
    a += T * B.a;
    for (int i = 0; i < 3; ++i) b[i] += T * B.b[i], G[i] += T * B.G[i], C[i] += T * B.C[i];
  }
  // dP/dv_i at the centre, in double from the lower ends (a guess for choosing combinations).
  double slope(int i, const double* c) const {
    double g = b[i].inf() + 2 * G[i].inf() * c[i];
    for (int k = 0; k < 3; ++k)
      if (pair[k][1] < m && (pair[k][0] == i || pair[k][1] == i)) g += C[k].inf() * c[pair[k][0] == i ? pair[k][1] : pair[k][0]];
    return g;
  }
  // The natural extension over the box c + W, intersected with range(): the denominators
  // D = k (1 + |v|^2) are then enclosed by intervals >= k > 0 on every box.
  IA tight_range(const IA* c, const IA* W) const {
    IA v = a;
    std::array<IA, 3> V;
    for (int i = 0; i < m; ++i) V[i] = c[i] + W[i], v += b[i] * V[i] + G[i] * exact::square(V[i]);
    for (int k = 0; k < 3; ++k)
      if (pair[k][1] < m) v += C[k] * (V[pair[k][0]] * V[pair[k][1]]);
    const IA t = range(c, W);
    const double lo = std::max(v.inf(), t.inf()), hi = std::min(v.sup(), t.sup());
    return lo <= hi ? IA(lo, hi) : v;  // (both hold the range: disjoint only through a NaN)
  }
};

// A SEPARABLE function of v in R^m (m <= 3): k + sum_i U(a_i, b_i; v_i), with the univariate
// U(a, b; t) = (a t^2 + b t) / (1 + t^2), known by enclosures of k, a_i, b_i. On a product of
// circles every sign, distance and coordinate of the chart is one (TorusModel below).
// RANGE of U over an interval T, for every (a, b) in their enclosures: U' = N / (1 + t^2)^2 with
// N(t) = b (1 - t^2) + 2 a t. If the enclosure of N over T is >= 0, U is non-decreasing on T and
// its range is [U(inf T), U(sup T)], each end enclosed at a point; <= 0 likewise. Otherwise the
// mean value form U(c) + U'(T) (T - c), intersected with |U - a/2| <= sqrt(a^2 + b^2) / 2 (with
// t = tan(theta / 2), U = a/2 - (a/2) cos theta + (b/2) sin theta). Under upward rounding.
// Everything U needs of one axis of a box, the same for every candidate (no division left per
// candidate): with q(t) = 1 + t^2, U(t) = a t^2 / q + b t / q at the ends lo, hi of T and at the
// centre c; N = b (1 - T^2) + a (2 T); and W / q(T)^2 for the mean value form.
struct AxisFrame {
  IA sq_lo, lin_lo, sq_hi, lin_hi, sq_c, lin_c, one_minus, two_t, slope_scale, W;
  AxisFrame() = default;
  AxisFrame(const IA& c, const IA& w) : W(w) {
    const IA T = c + W, T2 = exact::square(T);
    auto at = [](double t, IA& sq, IA& lin) {
      const IA ti(t), q = IA(1) + exact::square(ti);
      sq = exact::square(ti) / q, lin = ti / q;
    };
    at(T.inf(), sq_lo, lin_lo), at(T.sup(), sq_hi, lin_hi), at(c.inf(), sq_c, lin_c);  // (c: a point)
    one_minus = IA(1) - T2, two_t = IA(2) * T, slope_scale = W / exact::square(IA(1) + T2);
  }
  IA range(const IA& a, const IA& b) const {
    if (a.inf() == 0 && a.sup() == 0 && b.inf() == 0 && b.sup() == 0) return IA(0);
    const IA N = b * one_minus + a * two_t;
    if (N.inf() >= 0) return IA((a * sq_lo + b * lin_lo).inf(), (a * sq_hi + b * lin_hi).sup());
    if (N.sup() <= 0) return IA((a * sq_hi + b * lin_hi).inf(), (a * sq_lo + b * lin_lo).sup());
    const IA mv = a * sq_c + b * lin_c + N * slope_scale;
    const IA g = a / IA(2) + IA(-1, 1) * (exact::sqrt(exact::square(a) + exact::square(b)) / IA(2));
    const double lo = std::max(mv.inf(), g.inf()), hi = std::min(mv.sup(), g.sup());
    return lo <= hi ? IA(lo, hi) : g;  // (both hold the range: disjoint only through a NaN)
  }
};
// A box with its AxisFrames (Separable's Frame). Under upward rounding.
struct SeparableFrame : Centred {
  std::array<AxisFrame, 3> axis;
  explicit SeparableFrame(const Box& V) : Centred(V) {
    exact::UpwardRounding up;
    for (std::size_t i = 0; i < V.size(); ++i) axis[i] = AxisFrame(c[i], W[i]);
  }
};
struct Separable {
  using Frame = SeparableFrame;
  IA k{0};
  std::array<IA, 3> a{IA(0), IA(0), IA(0)}, b{IA(0), IA(0), IA(0)};
  int m = 0;
  IA range(const Frame& B) const {
    IA v = k;
    for (int i = 0; i < m; ++i) v += B.axis[i].range(a[i], b[i]);
    return v;
  }
  void add(const Separable& o, const IA& T) {
    k += T * o.k;
    for (int i = 0; i < 3; ++i) a[i] += T * o.a[i], b[i] += T * o.b[i];
  }
  // U = (a t^2 + b t) / q, q = 1 + t^2: U' = (b (1 - t^2) + 2 a t) / q^2, U'' / 2 = (b t^3 - 3 a t^2 - 3 b t + a) / q^3.
  Local local(const double* c) const {
    Local l;
    l.f = k.inf();
    for (int i = 0; i < m; ++i) {
      const double A = a[i].inf(), B = b[i].inf(), t = c[i], q = 1 + t * t;
      l.f += (A * t * t + B * t) / q;
      l.g[i] = (B * (1 - t * t) + 2 * A * t) / (q * q);
      l.G[i] = (B * t * t * t - 3 * A * t * t - 3 * B * t + A) / (q * q * q);
    }
    return l;
  }
};

// {s_q = 0 : q in S} for Separable s_q as an exact::EnclosedFunction (Krawczyk's rows on a flat
// torus): s_q(y) enclosed at the point y, and ds_q/dv_i = N(v_i) / (1 + v_i^2)^2 over the box
// (Separable's U'). Each s_q the enclosures stand for is smooth on R^m (1 + t^2 >= 1).
class SeparableSystem final : public exact::EnclosedFunction {
 public:
  SeparableSystem(const std::vector<Separable>& all, std::span<const int> S) {
    for (int i : S) rows_.push_back(&all[i]);
  }
  int size() const override { return static_cast<int>(rows_.size()); }
  bool values(std::span<const double> y, std::span<Interval> f) const override {
    exact::UpwardRounding up;
    for (std::size_t r = 0; r < rows_.size(); ++r) {
      const Separable& s = *rows_[r];
      IA v = s.k;
      for (int i = 0; i < s.m; ++i) {
        const IA t(y[i]), t2 = exact::square(t);
        v += (s.a[i] * t2 + s.b[i] * t) / (IA(1) + t2);
      }
      f[r] = exact::to_interval(v);
    }
    return true;
  }
  bool jacobian(const Box& X, std::span<Interval> J) const override {
    exact::UpwardRounding up;
    const int n = size();
    for (int i = 0; i < n; ++i) {
      const IA T(X[i].lo, X[i].hi), T2 = exact::square(T), one_minus = IA(1) - T2, two_t = IA(2) * T,
          q2 = exact::square(IA(1) + T2);
      for (int r = 0; r < n; ++r) J[r * n + i] = exact::to_interval((rows_[r]->b[i] * one_minus + rows_[r]->a[i] * two_t) / q2);
    }
    return true;
  }

 private:
  std::vector<const Separable*> rows_;
};

struct Work {
  Box V;
  exact::SmallVector<int, 16> S;  // positions in cands_ of the candidates other than p
  // Dropped from S by COMBINED SIGNS (strictly farther than p on Vor(p) in the box, not on all of
  // it): kept to discard sub-boxes where they are certainly closer, as in rvd.cpp.
  exact::SmallVector<int, 16> far;
  int depth = 0;
  bool vertex_decided = false;  // as rvd.cpp: Krawczyk decided this box or an ancestor with |S| = m
  bool pending = false;         // left by the first pass for the second, its candidates' signs done
};

}  // namespace delcert::certify::detail::param
