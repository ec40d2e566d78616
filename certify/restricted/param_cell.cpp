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
#include "certify/restricted/geodesic_model.hpp"
#include "certify/restricted/param_pieces.hpp"
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
using namespace param;  // the pieces (param_pieces.hpp) and the GEODESIC model (geodesic_model.hpp)

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
