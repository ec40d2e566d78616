#include "certify/restricted/param_cell.hpp"

#include <gmpxx.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <unordered_set>
#include <stdexcept>
#include <type_traits>
#include <utility>

#include "certify/restricted/cell_checks.hpp"
#include "certify/restricted/charts.hpp"
#include "certify/intrinsic/engines.hpp"
#include "exact/angle_series.hpp"
#include "exact/enclosed_polynomial.hpp"
#include "exact/interval_arithmetic.hpp"
#include "exact/krawczyk.hpp"
#include "exact/linear_algebra.hpp"
#include "exact/number_types.hpp"
#include "exact/polynomial.hpp"
#include "exact/small_vector.hpp"

namespace delcert::certify::detail {

namespace {

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

// The chart's side of a cell's analysis: the model F of each P_q (or of a positive multiple with
// the same sign), the enclosures of phi and |phi - p|^2 over a box, Krawczyk's rows, and V0.
// QUADRATIC: a RationalChart of degree <= 2 (spheres, SO(3)); F = Quadratic.
class QuadraticModel {
 public:
  using F = Quadratic;
  QuadraticModel(const RationalChart& chart, std::span<const double> p)
      : p_(p), N_(static_cast<int>(chart.X.size())), m_(chart.D.num_variables()), t_(chart.t) {
    exact::UpwardRounding up;
    D_enc_ = EnclosedPolynomial::from_exact(chart.D);
    D_ = Quadratic(D_enc_);
    // Y_i = X_i - p_i D: phi(v) - p = Y(v) / D(v).
    for (int i = 0; i < N_; ++i) {
      Y_enc_.push_back(EnclosedPolynomial::from_exact(chart.X[i]) + D_enc_.scaled(Interval::point(-p[i])));
      Y_.emplace_back(Y_enc_.back());
    }
    // |phi - p|^2 D = (radius2 - |p - centre|^2) D - 2 (p - centre).Y (RationalChart).
    IA A = ia(exact::enclose(chart.radius2));
    std::vector<IA> w(N_);
    for (int i = 0; i < N_; ++i) w[i] = IA(p[i]) - ia(exact::enclose(chart.centre[i])), A -= exact::square(w[i]);
    dist2_ = scaled(D_, A);
    for (int i = 0; i < N_; ++i) dist2_.add(Y_[i], IA(-2) * w[i]);
  }
  int m() const { return m_; }
  double t() const { return t_; }
  double search_radius(double r) const { return 2 * r; }
  F::Frame frame(const Box& V) const { return F::Frame(V); }
  Box root() const { return Box(m_, Interval{-t_, t_}); }
  // P_q = |q - p|^2 D - 2 (q - p).Y, its coefficients enclosed from those of D and Y.
  F candidate(std::span<const double> q) const {
    exact::UpwardRounding up;
    IA c(0);
    for (int i = 0; i < N_; ++i) c += exact::square(IA(q[i]) - IA(p_[i]));
    F P = scaled(D_, c);
    for (int i = 0; i < N_; ++i) P.add(Y_[i], IA(-2) * (IA(q[i]) - IA(p_[i])));
    return P;
  }
  // P_q as an EnclosedPolynomial (Krawczyk's rows), from the same enclosures of D and Y.
  EnclosedPolynomial polynomial(std::span<const double> q) const {
    exact::UpwardRounding up;
    IA c(0);
    std::vector<EnclosedPolynomial> terms;
    for (int v = 0; v < N_; ++v) {
      const IA d = IA(q[v]) - IA(p_[v]);
      c += exact::square(d);
      terms.push_back(Y_enc_[v].scaled(exact::to_interval(IA(-2) * d)));
    }
    terms.push_back(D_enc_.scaled(exact::to_interval(c)));
    return EnclosedPolynomial::sum(terms, m_);
  }
  // The enclosure of phi over the box (N intervals) and of |phi - p|^2. Under upward rounding.
  void image(const Centred& B, Box* X, IA* d2) const {
    const IA D = D_.tight_range(B.c.data(), B.W.data());  // >= k > 0
    if (X) {
      X->resize(N_);
      for (int i = 0; i < N_; ++i) (*X)[i] = exact::to_interval(IA(p_[i]) + Y_[i].range(B) / D);
    }
    if (d2) *d2 = dist2_.range(B) / D;
  }

 private:
  static Quadratic scaled(Quadratic Q, const IA& c) {
    Q.a *= c;
    for (int i = 0; i < 3; ++i) Q.b[i] *= c, Q.G[i] *= c, Q.C[i] *= c;
    return Q;
  }
  std::span<const double> p_;
  int N_, m_;
  double t_;
  Quadratic D_, dist2_;              // D, |phi - p|^2 D
  std::vector<Quadratic> Y_;         // X_i - p_i D
  EnclosedPolynomial D_enc_;         // D and Y, for Krawczyk's rows
  std::vector<EnclosedPolynomial> Y_enc_;
};

// A PRODUCT OF CIRCLES (TorusChart): phi(v) = (phi_1(v_1), ..., phi_m(v_m)), so with d = q - p,
//   s_q(phi(v)) = |d|^2 - 2 d.(phi - p) = k + sum_i U(a_i, b_i; v_i),
//   k = |d|^2 - 2 sum_i d_i.(r_i n_i - p_i), a_i = 4 r_i d_i.n_i, b_i = -4 r_i d_i.n_i'
// (d_i, p_i: the pair of circle i; (1 - t^2) / (1 + t^2) = 1 - 2 t^2 / (1 + t^2)): a Separable
// model of s_q itself (no denominator). |phi - p|^2 likewise with d = p (|phi_i|^2 = r_i^2), k =
// sum_i |r_i n_i - p_i|^2, and each coordinate r n + U(-2 r n, 2 r n'; t). Krawczyk's rows are
// the s_q themselves (SeparableSystem).
class TorusModel {
 public:
  using F = Separable;
  TorusModel(const TorusChart& chart, std::span<const double> p) : p_(p), m_(static_cast<int>(chart.r.size())) {
    exact::UpwardRounding up;
    t_ = *std::max_element(chart.t.begin(), chart.t.end());
    for (int i = 0; i < m_; ++i) {
      r_[i] = ia(exact::enclose(chart.r[i])), h_[i] = chart.t[i];
      for (int j = 0; j < 2; ++j) n_[i][j] = ia(exact::enclose(chart.n[i][j]));
    }
    dist2_ = along(p);
    dist2_.k = IA(0);
    for (int i = 0; i < m_; ++i)
      for (int j = 0; j < 2; ++j) dist2_.k += exact::square(r_[i] * n_[i][j] - IA(p[2 * i + j]));
  }
  int m() const { return m_; }
  double t() const { return t_; }
  double search_radius(double r) const { return 2 * r; }
  F::Frame frame(const Box& V) const { return F::Frame(V); }
  Box root() const {
    Box V(m_);
    for (int i = 0; i < m_; ++i) V[i] = Interval{-h_[i], h_[i]};
    return V;
  }
  F candidate(std::span<const double> q) const {
    exact::UpwardRounding up;
    std::array<IA, 6> d;
    IA d2(0);
    for (int i = 0; i < 2 * m_; ++i) d[i] = IA(q[i]) - IA(p_[i]), d2 += exact::square(d[i]);
    F s = along(d);
    s.k = d2;
    for (int i = 0; i < m_; ++i)
      for (int j = 0; j < 2; ++j) s.k -= IA(2) * d[2 * i + j] * (r_[i] * n_[i][j] - IA(p_[2 * i + j]));
    return s;
  }
  void image(const SeparableFrame& B, Box* X, IA* d2) const {
    if (X) {
      X->resize(2 * m_);
      for (int i = 0; i < m_; ++i) {
        const IA rn0 = r_[i] * n_[i][0], rn1 = r_[i] * n_[i][1];  // n' = (-n1, n0)
        (*X)[2 * i] = exact::to_interval(rn0 + B.axis[i].range(IA(-2) * rn0, IA(-2) * rn1));
        (*X)[2 * i + 1] = exact::to_interval(rn1 + B.axis[i].range(IA(-2) * rn1, IA(2) * rn0));
      }
    }
    if (d2) *d2 = dist2_.range(B);
  }

 private:
  // a_i = 4 r_i w_i.n_i, b_i = -4 r_i w_i.n_i' for the vector w (pairs per circle); k left 0.
  template <class V>
  F along(const V& w) const {
    F s;
    s.m = m_;
    for (int i = 0; i < m_; ++i) {
      const IA w0 = IA(w[2 * i]), w1 = IA(w[2 * i + 1]);
      s.a[i] = IA(4) * r_[i] * (w0 * n_[i][0] + w1 * n_[i][1]);
      s.b[i] = IA(-4) * r_[i] * (w1 * n_[i][0] - w0 * n_[i][1]);  // w.n' = -w0 n1 + w1 n0
    }
    return s;
  }
  std::span<const double> p_;
  int m_;
  double t_ = 0;
  std::array<IA, 3> r_{IA(0), IA(0), IA(0)};
  std::array<double, 3> h_{0, 0, 0};
  std::array<std::array<IA, 2>, 3> n_{};
  F dist2_;
};

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

std::optional<ProductChart> product_chart(const io::ShapeSpec& g, std::span<const double> p, double r, double slack) {
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
Box tighten(const GeodesicSystem& system, const Box& B) {
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

template <class Model>
class Analysis final : public ParamCell {
 public:
  using F = typename Model::F;
  using Frame = typename F::Frame;
  Analysis(Model chart, const io::PointSet& points, const PointGrid& grid, int p, const RestrictedCellOptions& o)
      : points_(points), grid_(grid), p_(p), opt_(o), chart_(std::move(chart)), m_(chart_.m()), t_(chart_.t()) {
    report_.graph_radius = r_ = o.graph_radius;
    report_.rational_chart = true;
    const auto pp = points.point(p);
    exact::UpwardRounding up;
    r2_ = IA(r_) * IA(r_);
    for (int q : grid.ball(pp, chart_.search_radius(r_))) {  // every point of the closed ball B(p, 2r) (rvd.hpp; GEODESIC: 2r + 2E)
      if (q == p) continue;
      index_.push_back(q);
      cands_.push_back(chart_.candidate(points.point(q)));
    }
    poly_cache_.resize(cands_.size());
  }

  double first_pass() override {
    report_.point = p_;
    Work root;
    root.V = chart_.root();
    for (int i = 0; i < static_cast<int>(cands_.size()); ++i) root.S.push_back(i);
    subdivide({root});
    refine_below_ = std::max(refine_below_, farthest_vertex(report_, points_, p_));
    return refine_below_;
  }

  RestrictedCellReport second_pass(double covering_target) override {
    refining_ = true;
    refine_below_ = std::max(refine_below_, covering_target);
    std::reverse(pending_.begin(), pending_.end());
    subdivide(std::move(pending_));
    finish();
    return std::move(report_);
  }

 private:
  void subdivide(std::vector<Work> stack) {
    while (!stack.empty()) {
      Work w = std::move(stack.back());
      stack.pop_back();
      if (report_.boxes >= opt_.max_boxes) {
        undecided(w.V, w.S, "box budget exhausted");
        continue;
      }
      visit(std::move(w), stack);
    }
  }

  // The enclosure of phi over V (N intervals) and of |phi - p|^2.
  void image(const Box& V, Box* X, IA* d2) const { image(chart_.frame(V), X, d2); }
  void image(const Frame& B, Box* X, IA* d2) const {
    exact::UpwardRounding up;
    IA s;
    chart_.image(B, X, d2 ? &s : nullptr);
    if (d2) *d2 = IA(std::max(0.0, s.inf()), std::max(0.0, s.sup()));  // (a square: >= 0)
  }
  void undecided(const Box& V, std::span<const int> S, std::string reason) {
    Box X;
    image(V, &X, nullptr);
    std::vector<double> loc;
    for (const auto& i : X) loc.push_back(i.midpoint());
    report_.undecided.push_back({std::move(loc), simplex_of(S), std::move(reason)});
  }
  std::vector<int> simplex_of(std::span<const int> S) const {
    std::vector<int> s{p_};
    for (int i : S) s.push_back(index_[i]);
    std::sort(s.begin(), s.end());
    return s;
  }

  void visit(Work w, std::vector<Work>& stack) {
    ++report_.boxes;
    report_.max_depth = std::max(report_.max_depth, w.depth);
    exact::UpwardRounding up;
    const Frame B = chart_.frame(w.V);
    IA d2;
    image(B, nullptr, &d2);
    if (d2.inf() >= r2_.sup()) return discard();  // |phi - p| >= r on V: outside the open ball
    // A candidate certainly closer than p on all of phi(V) leaves no point of Vor(p) there; one
    // certainly farther can neither bound the cell in V nor exclude any part of it: dropped. (A
    // box the first pass left pending has had exactly this done to it: not repeated.)
    for (auto* list : {&w.S, &w.far}) {
      if (w.pending) break;
      std::size_t out = 0;
      for (int i : *list) {
        const IA s = cands_[i].range(B);
        if (s.sup() < 0) return discard();
        if (!(s.inf() > 0)) (*list)[out++] = i;
      }
      list->resize(out);
    }
    const int all = static_cast<int>(w.S.size() + w.far.size());
    if constexpr (!std::is_same_v<F, Geodesic>)  // (linear combinations need a polynomial model)
      if (all >= 2 && all <= opt_.combined_signs_max && (refining_ || static_cast<int>(w.S.size()) >= m_) &&
          combined_signs(w, B))
        return discard();
    const int n = static_cast<int>(w.S.size()) + 1;
    bool resolved = n <= m_;  // a vertex needs m + 1 nearest points, all in {p} + S
    if (n == m_ + 1) resolved = w.vertex_decided || krawczyk_vertex(w);
    w.vertex_decided = resolved && n == m_ + 1;
    double widest = 0;
    for (const auto& i : w.V) widest = std::max(widest, i.width());
    const double raw_bound = exact::sqrt(d2).sup();
    const double bound = std::isnan(raw_bound) ? INFINITY : raw_bound;
    const bool fine = (n == 1 && w.far.empty()) || widest <= opt_.covering_width * t_ || w.depth >= opt_.max_depth ||
                      (refining_ && bound <= std::max(refine_below_, report_.covering_bound));
    if (resolved && !refining_ && (!fine || n >= 2)) {  // waits for the second pass (rvd.cpp)
      w.pending = true;
      pending_.push_back(std::move(w));
      return;
    }
    std::vector<int> face;
    const bool faces_ok = !resolved || n == 1 || known_faces(w.S, face);
    const bool purity_floor = widest <= opt_.purity_width * t_;
    if (resolved && ((fine && (faces_ok || purity_floor)) || w.depth >= opt_.max_depth)) {
      if (bound > report_.covering_bound || report_.covering_location.empty()) {
        Box X;
        image(w.V, &X, nullptr);
        report_.covering_bound = bound;
        report_.covering_location.clear();
        for (const auto& i : X) report_.covering_location.push_back(i.midpoint());
      }
      if (!faces_ok && std::none_of(report_.unresolved_faces.begin(), report_.unresolved_faces.end(),
                                    [&](const UndecidedBox& b) { return b.candidates == face; })) {
        Box X;
        image(w.V, &X, nullptr);
        std::vector<double> loc;
        for (const auto& i : X) loc.push_back(i.midpoint());
        report_.unresolved_faces.push_back({std::move(loc), std::move(face),
                                            "a face of the candidate set that is in no restricted Voronoi vertex's "
                                            "simplex, still possible in a box of the finest purity width"});
      }
      ++report_.kept;
      return;
    }
    if (w.depth >= opt_.max_depth) {
      undecided(w.V, w.S, n > m_ + 1 ? "more than m + 1 candidates at the depth limit" : "Krawczyk undecided at the depth limit");
      return;
    }
    for (int corner = (1 << m_) - 1; corner >= 0; --corner) {
      Work ch;
      ch.V = w.V;
      for (int a = 0; a < m_; ++a) {
        const double mid = w.V[a].midpoint();
        ch.V[a] = (corner >> a) & 1 ? Interval{mid, w.V[a].hi} : Interval{w.V[a].lo, mid};
      }
      ch.S = corner ? w.S : std::move(w.S);
      ch.far = corner ? w.far : std::move(w.far);
      ch.depth = w.depth + 1;
      ch.vertex_decided = w.vertex_decided;
      stack.push_back(std::move(ch));
    }
  }
  void discard() { ++report_.discarded; }

  // PURITY (cell_checks.hpp) for a resolved box's S, remembered once true (the vertices found only
  // grow, so a known face stays known): the key is S itself, at most 4 positions of 16 bits.
  bool known_faces(std::span<const int> S, std::vector<int>& face) {
    const bool cacheable = S.size() <= 4 && cands_.size() < 0xFFFF;
    std::uint64_t key = 0;
    for (int i : S) key = key << 16 | static_cast<std::uint64_t>(i + 1);
    if (cacheable && faces_known_.count(key)) return true;
    std::vector<int> idx;
    for (int i : S) idx.push_back(index_[i]);
    if (!faces_known(p_, m_, idx, report_.vertices, report_.face_points, face)) return false;
    if (cacheable) faces_known_.insert(key);
    return true;
  }

  // COMBINED SIGNS (rvd.cpp's argument, unchanged: R = the points of phi(V) where every P_q of S
  // and `far` is >= 0 holds every point of Vor(p) there, D > 0). With t_i >= 0: P_A + sum t_i P_Bi
  // < 0 on V empties R (true: discard); P_A - sum t_i P_Bi > 0 on V (A in S) makes A strictly
  // farther than p on R: A moves to `far`. The t_i are chosen in double (pairs: where one slope of
  // the combination vanishes at the centre; m of them, near a vertex: all slopes), and only the
  // enclosure of the combination, with those exact doubles, decides.
  bool combined_signs(Work& w, const Frame& B) const {
    int n = static_cast<int>(w.S.size());
    const int all = n + static_cast<int>(w.far.size());
    auto at = [&](int i) -> const F& { return cands_[i < n ? w.S[i] : w.far[i - n]]; };
    double c[3], h[3];
    for (int a = 0; a < m_; ++a) c[a] = B.c[a].inf(), h[a] = std::max(-B.W[a].inf(), B.W[a].sup());
    if (all > kMaxCombined) return false;
    Local L[kMaxCombined];  // each candidate near the centre (only to choose t and skip hopeless combinations)
    for (int i = 0; i < all; ++i) L[i] = at(i).local(c);
    // sign * (the extreme of L_A + sum t_i L_Bi towards -sign) over the box, approximately.
    auto approx = [&](int A, int j, const int* Bs, const double* t, double sign) {
      double f = L[A].f, q = 0;
      for (int a = 0; a < m_; ++a) {
        double g = L[A].g[a], G = L[A].G[a];
        for (int i = 0; i < j; ++i) g += t[i] * L[Bs[i]].g[a], G += t[i] * L[Bs[i]].G[a];
        q -= std::abs(g) * h[a] + (sign > 0 ? std::max(-G, 0.0) : std::max(G, 0.0)) * h[a] * h[a];
      }
      for (int k = 0; k < 3; ++k) {
        if (Quadratic::pair[k][1] >= m_) continue;
        double C = L[A].C[k];
        for (int i = 0; i < j; ++i) C += t[i] * L[Bs[i]].C[k];
        q -= std::abs(C) * h[Quadratic::pair[k][0]] * h[Quadratic::pair[k][1]];
      }
      for (int i = 0; i < j; ++i) f += t[i] * L[Bs[i]].f;
      return sign * f + q;  // > 0: the combination looks decided
    };
    auto range_of = [&](int A, int j, const int* Bs, const double* t) {
      F Q = at(A);
      for (int i = 0; i < j; ++i) Q.add(at(Bs[i]), IA(t[i]));
      return Q.range(B);
    };
    // sign -1: sup (P_A + t P_B) < 0 for some t > 0?  sign +1: inf (P_A - t P_B) > 0?
    auto decides = [&](int A, int Bi, double sign) {
      double best = 0, best_v = 0;
      for (int a = 0; a < m_; ++a) {
        const double t = sign * L[A].g[a] / L[Bi].g[a], st = -sign * t;
        if (!(t > 0) || !std::isfinite(t)) continue;
        const double v = approx(A, 1, &Bi, &st, sign);
        if (v > best_v) best_v = v, best = st;
      }
      if (best == 0) return false;
      const IA f = range_of(A, 1, &Bi, &best);
      return sign > 0 ? f.inf() > 0 : f.sup() < 0;
    };
    for (int i = 0; i < all; ++i)
      for (int j = i + 1; j < all; ++j)
        if (decides(i, j, -1)) return true;
    char drop[kMaxCombined] = {};
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < all && !drop[i]; ++j) drop[i] = j != i && decides(i, j, 1);
    if (n > m_)  // near a vertex: A against m others, the slopes matched at the centre
      for (int A = 0; A < n; ++A)
        for (int mask = 0, tried = 0; mask < (1 << (all - 1)) && tried < 8 && !drop[A]; ++mask) {
          if (__builtin_popcount(mask) != m_) continue;
          ++tried;
          int Bs[3];
          double M[9], rhs[3], t[3];
          for (int o = 0, i = 0; i < m_; ++o)
            if (mask >> o & 1) Bs[i++] = o < A ? o : o + 1;
          for (int r = 0; r < m_; ++r) {
            for (int i = 0; i < m_; ++i) M[r * m_ + i] = L[Bs[i]].g[r];
            rhs[r] = L[A].g[r];
          }
          const double det = exact::determinant(M, m_);
          if (!(std::abs(det) > 0) || !std::isfinite(det)) continue;
          exact::cramer_solve(M, rhs, det, m_, t);
          bool pos = true, neg = true;
          for (int i = 0; i < m_; ++i) {
            pos &= t[i] >= 0, neg &= t[i] <= 0;
            if (!std::isfinite(t[i])) pos = neg = false;
            t[i] = -t[i];  // P_A - sum t_i P_Bi has no slope at the centre
          }
          if (neg && approx(A, m_, Bs, t, -1) > 0 && range_of(A, m_, Bs, t).sup() < 0) return true;
          if (pos && approx(A, m_, Bs, t, 1) > 0 && range_of(A, m_, Bs, t).inf() > 0) drop[A] = 1;
        }
    exact::SmallVector<int, 16> kept;
    for (int i = 0; i < n; ++i) (drop[i] ? w.far : kept).push_back(w.S[i]);
    w.S = std::move(kept);
    return false;
  }

  // Krawczyk on {P_q = 0 : q in S} in V (|S| = m). True when decided: the vertex of {p} + S in V
  // recorded (unique root, image enclosed, every other point strictly farther), or none in V.
  // A root proven unique in a tight box around V (rvd.cpp: a vertex on a split plane) decides too.
  bool krawczyk_vertex(const Work& w) {
    const std::vector<int> simplex = simplex_of(w.S);
    ++report_.krawczyk_calls;
    for (const auto& i : w.V)
      if (!i.is_finite()) return ++report_.krawczyk_failures, false;
    exact::KrawczykResult kr;
    if constexpr (std::is_same_v<F, Separable>) {
      kr = exact::krawczyk(SeparableSystem(cands_, w.S), w.V);
    } else if constexpr (std::is_same_v<F, Geodesic>) {
      const GeodesicSystem system(chart_, cands_, w.S, chart_.site());
      kr = exact::krawczyk(system, w.V);
      if (kr.status == exact::RootStatus::unique_root) kr.box = tighten(system, kr.box);
    } else {
      auto it = systems_.find(simplex);
      if (it == systems_.end()) {
        std::vector<exact::EnclosedRow> rows;
        for (int i : w.S) {
          if (!poly_cache_[i]) poly_cache_[i] = exact::EnclosedRow(chart_.polynomial(points_.point(index_[i])));
          rows.push_back(*poly_cache_[i]);
        }
        it = systems_.emplace(simplex, exact::ParametricSystem::from_rows(rows)).first;
      }
      kr = exact::krawczyk(it->second, Box{}, w.V);
    }
    bool nearby = kr.status == exact::RootStatus::undecided && kr.nearby_root;
    for (std::size_t i = 0; nearby && i < w.V.size(); ++i) nearby = (*kr.nearby_root)[i].width() <= w.V[i].width() / 8;
    if (kr.status == exact::RootStatus::undecided && !nearby) {
      ++report_.krawczyk_failures;
      return false;
    }
    if (kr.status != exact::RootStatus::no_root) {
      Box X;
      image(kr.nearby_root ? *kr.nearby_root : kr.box, &X, nullptr);
      if constexpr (std::is_same_v<F, Geodesic>) {
        if (!chart_.others_farther(points_, grid_, simplex, kr.nearby_root ? *kr.nearby_root : kr.box)) return false;
      } else if (!others_strictly_farther(points_, grid_, p_, simplex, X)) {
        return false;
      }
      report_.vertices.push_back({simplex, std::move(X)});
    }
    return true;
  }

  // Sorted, deduplicated, complete or not (certify/detail/cell_checks.hpp).
  void finish() { finish_report(report_, p_, r_); }

  const io::PointSet& points_;
  const PointGrid& grid_;
  int p_;
  RestrictedCellOptions opt_;
  Model chart_;
  int m_;
  double t_, r_ = 0;
  IA r2_;
  std::vector<F> cands_;                    // P_q (or s_q: the same sign)
  std::vector<std::optional<exact::EnclosedRow>> poly_cache_;  // polynomial(i) prepared, once built
  static constexpr int kMaxCombined = 16;  // COMBINED SIGNS on at most this many candidates
  std::unordered_set<std::uint64_t> faces_known_;  // candidate sets (known_faces' keys) whose faces are known
  std::vector<int> index_;        // cands_[i] is P_{index_[i]}
  std::map<std::vector<int>, exact::ParametricSystem> systems_;
  bool refining_ = false;
  double refine_below_ = 0;
  std::vector<Work> pending_;
  RestrictedCellReport report_;
};

// A GEODESIC cell with no chart (a ball too large for one stereographic chart per factor, or a
// point whose factor block is 0): one undecided box, so the cell is not complete.
class NoChart final : public ParamCell {
 public:
  NoChart(const io::PointSet& points, int p, double r) {
    report_.point = p, report_.graph_radius = r_ = r;
    const auto pp = points.point(p);
    report_.undecided.push_back({{pp.begin(), pp.end()}, {p}, "no stereographic chart per factor covers the geodesic ball"});
  }
  double first_pass() override { return 0; }
  RestrictedCellReport second_pass(double) override {
    finish_report(report_, report_.point, r_);
    report_.reason = "no stereographic chart per factor covers the geodesic ball (of radius " + std::to_string(r_) + ")";
    return std::move(report_);
  }

 private:
  RestrictedCellReport report_;
  double r_ = 0;
};

}  // namespace

std::unique_ptr<ParamCell> ParamCell::make(const io::ShapeSpec& shape, const io::PointSet& points, const PointGrid& grid,
                                           int p, const RestrictedCellOptions& options) {
  if (!(options.graph_radius > 0)) throw std::invalid_argument("restricted cell: graph_radius must be > 0");
  const auto pp = points.point(p);
  if (options.geodesic) {  // never the ambient distance: no chart leaves the cell undecided
    if (std::optional<ProductChart> C = product_chart(shape, pp, options.graph_radius, options.projection_slack))
      return std::make_unique<Analysis<GeodesicModel>>(GeodesicModel(std::move(*C), pp), points, grid, p, options);
    return std::make_unique<NoChart>(points, p, options.graph_radius);
  }
  if (std::optional<TorusChart> T = torus_chart(shape, pp, options.graph_radius))
    return std::make_unique<Analysis<TorusModel>>(TorusModel(*T, pp), points, grid, p, options);
  std::optional<RationalChart> chart = rational_chart(shape, pp, options.graph_radius);
  if (!chart) return nullptr;
  return std::make_unique<Analysis<QuadraticModel>>(QuadraticModel(*chart, pp), points, grid, p, options);
}

}  // namespace delcert::certify::detail
