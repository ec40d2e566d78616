#include "certify/restricted/rvd.hpp"

#include <gmpxx.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <stdexcept>
#include <utility>

#include "certify/restricted/cell_checks.hpp"
#include "certify/restricted/param_cell.hpp"
#include "exact/chart.hpp"
#include "exact/interval_arithmetic.hpp"
#include "exact/krawczyk.hpp"
#include "exact/linear_algebra.hpp"
#include "exact/max_affine.hpp"
#include "exact/number_types.hpp"
#include "exact/small_buffer.hpp"
#include "exact/small_vector.hpp"

namespace delcert::certify {

namespace {

using exact::Box;
using exact::Interval;
using exact::SmallBuffer;
using IA = exact::IntervalNumber;

IA ia(const Interval& i) { return exact::to_interval_number(i); }

// A candidate q relative to p: s_q(u, h) = |q|^2 - |p|^2 - 2 x.(q - p) = c - 2 a.u - 2 b.h with
// d = q - p, c = |d|^2, a = T^T d, b = Nn^T d (x = p + T u + Nn h). The subdivision needs only
// enclosures of c, 2a and 2b, computed in interval arithmetic from the coordinates (the enclosure
// of d = q - p holds the exact difference of the two doubles; T_enc, N_enc hold the exact bases),
// so they hold the exact values; an overflow gives an infinite or NaN bound, which decides nothing.
// The vertex systems (krawczyk_vertex) take these enclosures too (exact::AffineExtension).
struct Candidate {
  int index = -1;
  IA c;
  exact::SmallVector<IA, 4> a2, b2;  // 2 a (m of them) and 2 b (k of them); inline for m, k <= 4
};

struct Work {
  Box U;
  Box H;                     // the parent's slab H_eff (empty at the root: no constraint)
  std::vector<int> S;       // positions in `cands` of the candidates other than p
  // Candidates dropped from S by COMBINED SIGNS: strictly farther than p on Vor(p) in the box, so
  // not in S, but kept to discard sub-boxes they are certainly closer on (a box is inside the
  // cell, and its covering bound tight, only when S and `far` are both empty).
  std::vector<int> far;
  int depth = 0;
  // Krawczyk decided this box or an ancestor with |S| = m: the vertex of {p} + S in the region (a
  // superset of this box's) is recorded, or there is none; a box with the same S needs no new call.
  bool vertex_decided = false;
  bool chart_slab = false;   // H is the parent's slab from the chart (not Hpar)
  bool unique_slab = false;  // ... and Krawczyk proved one point of M over each u in it
  bool settled = false;      // H is the chart's slab of this very box (left for the second pass)
};

class CellAnalysis {
 public:
  CellAnalysis(const exact::ImplicitSystem& system, const io::PointSet& points, const detail::PointGrid& grid, int p,
               const RestrictedCellOptions& options)
      : points_(points), grid_(grid), p_(p), opt_(options),
        chart_(options.chart ? *options.chart : exact::ChartEnclosure::at(system, points.point(p))),
        N_(chart_.ambient_dimension()), m_(chart_.intrinsic_dimension()), k_(chart_.codimension()) {
    if (!(options.graph_radius > 0)) throw std::invalid_argument("restricted cell: graph_radius must be > 0");
    T_enc_ = chart_.tangent_enclosure();
    N_enc_ = chart_.normal_enclosure();
    const exact::ChartEnclosure::GramBounds gram = chart_.gram_bounds();
    const double gT = gram.tangent;
    gN_ = gram.normal;
    const double r = options.graph_radius;
    report_.graph_radius = r_ = r;
    zero_slab_.assign(k_, Interval{0, 0});
    {
      exact::UpwardRounding up;  // rho = r / sqrt(g) rounded up: |u_a| <= |u| <= |T u| / sqrt(g_T) < rho_u
      rho_u_ = (IA(r) / exact::sqrt(IA(gT))).sup();
      r2_ = IA(r) * IA(r);
    }
    // Candidates: every point of the closed ball B(p, 2r) (see the header); 2r is exact.
    const std::span<const double> pp = points.point(p);
    const std::vector<int> ball = grid.ball(pp, 2 * r);
    cands_.reserve(ball.size());
    exact::UpwardRounding up;
    SmallBuffer<IA, 16> d(N_);
    for (int q : ball) {
      if (q == p) continue;
      Candidate C;
      C.index = q;
      C.c = IA(0);
      for (int v = 0; v < N_; ++v) {
        d[v] = IA(points.point(q)[v]) - IA(pp[v]);
        C.c += exact::square(d[v]);
      }
      C.a2.resize(m_);
      C.b2.resize(k_);
      for (int a = 0; a < m_; ++a) {
        IA t(0);
        for (int v = 0; v < N_; ++v) t += ia(T_enc_[v * m_ + a]) * d[v];
        C.a2[a] = IA(2) * t;
      }
      for (int l = 0; l < k_; ++l) {
        IA t(0);
        for (int v = 0; v < N_; ++v) t += ia(N_enc_[v * k_ + l]) * d[v];
        C.b2[l] = IA(2) * t;
      }
      cands_.push_back(std::move(C));
    }
    if (options.selector)
      for (const auto& t : options.selector->terms()) sel_coef_.push_back(ia(exact::enclose(t.coefficient)));
    zero_u_.assign(m_, Interval{0, 0});
    const exact::ChartEnclosure::BasePoint base =
        options.reach > 0 ? chart_.base_point(system, options.selector) : exact::ChartEnclosure::BasePoint{};
    if (base.certified) {
      exact::UpwardRounding up2;  // THE GRAPH LEMMA's 2 tau cos Θ, rounded down (0: not available)
      const IA two_tau = IA(2) * IA(options.reach), sigma(0, base.sin_tilt), q = (IA(r) + IA(base.distance)) / two_tau;
      if (q.sup() < 1) {
        const IA cos_theta = (IA(1) - IA(2) * exact::square(q)) * exact::sqrt(IA(1) - exact::square(sigma)) -
                             IA(2) * q * exact::sqrt(IA(1) - exact::square(q)) * sigma;
        lemma_bound_ = std::max(0.0, (two_tau * cos_theta).inf());
      }
    }
  }

  // The first pass: subdivision until every box is resolved; returns the largest distance from p
  // to a vertex found (a lower bound of max_{x in M} d(x, P): a vertex is a point of M at that
  // distance from its nearest points), 0 when none.
  double first_pass() {
    report_.point = p_;
    Work root;
    root.U.assign(m_, Interval{-rho_u_, rho_u_});
    for (int i = 0; i < static_cast<int>(cands_.size()); ++i) root.S.push_back(i);
    subdivide({root});
    refine_below_ = std::max(refine_below_, detail::farthest_vertex(report_, points_, p_));
    return refine_below_;
  }

  // The second pass: the resolved boxes kept for covering refinement. A box whose bound is at most
  // covering_target or the distance from p to a vertex found (a point of the cell) need not be
  // refined: the largest bound is attained elsewhere or is already that close. (Only the work
  // depends on this; every kept box still contributes its own certified bound.)
  RestrictedCellReport second_pass(double covering_target) {
    refining_ = true;
    if (covering_target > refine_below_) refine_below_ = covering_target;
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
        undecided(w, box_centre(w.U, Box(k_, Interval{0, 0})), "box budget exhausted");
        continue;
      }
      visit(std::move(w), stack);
    }
  }

  // PURITY (rvd.hpp), on the candidates' point indices (certify/detail/cell_checks.hpp).
  bool faces_known(const std::vector<int>& S, std::vector<int>& face) const {
    std::vector<int> idx;
    for (int i : S) idx.push_back(cands_[i].index);
    return detail::faces_known(p_, m_, idx, report_.vertices, report_.face_points, face);
  }

  // Interval hull of s_q over U x H.
  IA sign_form(const Candidate& C, const Box& U, const Box& H) const {
    IA s = C.c;
    for (int a = 0; a < m_; ++a) s -= C.a2[a] * ia(U[a]);
    for (int l = 0; l < k_; ++l) s -= C.b2[l] * ia(H[l]);
    return s;
  }
  void discard() { ++report_.discarded; }
  // True when U x H is outside the ball or some candidate of S or `far` is certainly closer than
  // p on all of it; else drops from them those certainly farther.
  bool outside_or_closer(Work& w, const Box& H) const {
    if (dist2(w.U, H).inf() >= r2_.sup()) return true;
    for (auto* list : {&w.S, &w.far}) {
      std::size_t out = 0;
      for (int i : *list) {
        const IA s = sign_form(cands_[i], w.U, H);
        if (s.sup() < 0) return true;
        if (!(s.inf() > opt_.window)) (*list)[out++] = i;  // THE WINDOW (rvd.hpp): 0 without it
      }
      list->resize(out);
    }
    return false;
  }

  // COMBINED SIGNS. With R = {x in U x H : s_q(x) >= 0 for all q in S and in `far`} (R holds
  // every point of Vor(p) in the box), for some t_i >= 0 and candidates A, B_1..B_j of these:
  //   * s_A + sum t_i s_Bi < 0 on all of U x H: R is empty (at a point of R every term is >= 0),
  //     and the box is discarded (true is returned);
  //   * s_A - sum t_i s_Bi > 0 on all of U x H (A in S): at a point of R, s_A > sum t_i s_Bi >= 0,
  //     so A is strictly farther than p at every point of Vor(p) in the box and its sub-boxes
  //     (THE SLAB INVARIANT holds without it) and moves from S to `far`.
  // Every statement is about the same R, so the order of the moves does not matter. The t_i are
  // chosen in floating point; only the interval hull with the double t_i (exact) decides. Pairs
  // (j = 1): the best t for the midpoint coefficients (at 0 or at a breakpoint of a piecewise
  // linear bound). VERTEX COMBINATIONS (j = m, with more than m + 1 candidates: near a vertex of
  // the cell): t solves sum_i t_i grad_u s_Bi = -+ grad_u s_A at the lower ends (Cramer), so the
  // form hardly varies with u; tried when the t_i have the needed sign, on 8 m-subsets at most.
  bool combined_signs(std::vector<int>& S, std::vector<int>& far, const Box& U, const Box& H) const {
    const int d = m_ + k_;
    int n = static_cast<int>(S.size()), all = n + static_cast<int>(far.size());
    auto at = [&](int i) -> const Candidate& { return cands_[i < n ? S[i] : far[i - n]]; };
    auto box = [&](int a) -> const Interval& { return a < m_ ? U[a] : H[a - m_]; };
    auto coef = [&](const Candidate& C, int a) -> const IA& { return a < m_ ? C.a2[a] : C.b2[a - m_]; };
    auto hull = [&](const Candidate& A, int j, const Candidate* const* B, const double* t) {  // of s_A + sum t_i s_Bi
      IA f = A.c;
      for (int i = 0; i < j; ++i) f += IA(t[i]) * B[i]->c;
      for (int a = 0; a < d; ++a) {
        IA g = coef(A, a);
        for (int i = 0; i < j; ++i) g += IA(t[i]) * coef(*B[i], a);
        f -= g * ia(box(a));
      }
      return f;
    };
    SmallBuffer<char, 64> drop(n);  // zero-initialised, no heap for the usual sizes (most boxes)
    auto move_dropped = [&] {
      int kept = 0;
      for (int i = 0; i < n; ++i)
        if (drop[i]) far.push_back(S[i]), drop[i] = 0; else S[kept++] = S[i];
      S.resize(kept);
      n = kept;
    };
    // sign -1: is sup (s_A + t s_B) < 0? sign +1: is inf (s_A - t s_B) > 0?
    auto decides = [&](const Candidate& A, const Candidate& B, double sign) {
      auto value = [&](double t) {  // sign * (the bound at the midpoint coefficients)
        double v = A.c.inf() - sign * t * B.c.inf();
        for (int a = 0; a < d; ++a) {
          const double g = coef(A, a).inf() - sign * t * coef(B, a).inf();
          v -= g * box(a).midpoint() + sign * std::abs(g) * 0.5 * box(a).width();
        }
        return sign * v;
      };
      double best = 0, best_v = 0;
      for (int a = 0; a < d; ++a) {
        const double t = sign * coef(A, a).inf() / coef(B, a).inf(), v = t > 0 && std::isfinite(t) ? value(t) : 0;
        if (v > best_v) best_v = v, best = t;
      }
      if (best == 0) return false;
      const Candidate* Bp = &B;
      const double t = -sign * best;
      const IA f = hull(A, 1, &Bp, &t);
      return sign > 0 ? f.inf() > 0 : f.sup() < 0;
    };
    for (int i = 0; i < all; ++i)
      for (int j = i + 1; j < all; ++j)
        if (decides(at(i), at(j), -1)) return true;
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < all && !drop[i]; ++j) drop[i] = j != i && decides(at(i), at(j), 1);
    move_dropped();
    if (n <= m_ || m_ > 3) return false;
    for (int A = 0; A < n; ++A)  // the m-subsets of the others (all <= combined_signs_max), as masks
      for (int mask = 0, tried = 0; mask < (1 << std::min(all - 1, 20)) && tried < 8 && !drop[A]; ++mask) {
        if (__builtin_popcount(mask) != m_) continue;
        ++tried;
        const Candidate* B[3];
        double M[9], rhs[3], t[3];  // M t = grad_u s_A, column i = grad_u s_Bi
        for (int o = 0, i = 0; i < m_; ++o)
          if (mask >> o & 1) B[i++] = &at(o < A ? o : o + 1);
        for (int r = 0; r < m_; ++r) {
          for (int i = 0; i < m_; ++i) M[r * m_ + i] = B[i]->a2[r].inf();
          rhs[r] = at(A).a2[r].inf();
        }
        const double det = exact::determinant(M, m_);
        if (!(std::abs(det) > 0)) continue;
        exact::cramer_solve(M, rhs, det, m_, t);
        bool pos_t = true, neg_t = true;
        for (double& x : std::span(t, m_)) {
          pos_t &= x >= 0, neg_t &= x <= 0;
          if (!std::isfinite(x)) pos_t = neg_t = false;
          x = -x;  // s_A - sum t_i s_Bi has no u-gradient (at the lower ends)
        }
        if (neg_t && hull(at(A), m_, B, t).sup() < 0) return true;
        if (pos_t && hull(at(A), m_, B, t).inf() > 0) drop[A] = 1;
      }
    move_dropped();
    return false;
  }

  IA dist2(const Box& U, const Box& H) const { return ia(chart_.offset_norm2(U, H)); }
  std::vector<double> box_centre(const Box& U, const Box& H) const {
    Box X;
    std::vector<double> c(N_);
    Box Uc(m_), Hc(k_);
    for (int a = 0; a < m_; ++a) Uc[a] = Interval::point(U[a].midpoint());
    for (int l = 0; l < k_; ++l) Hc[l] = Interval::point(H[l].midpoint());
    if (chart_.image(Uc, Hc, X))
      for (int v = 0; v < N_; ++v) c[v] = X[v].midpoint();
    return c;
  }
  std::vector<int> simplex_of(const std::vector<int>& S) const {
    std::vector<int> s{p_};
    for (int i : S) s.push_back(cands_[i].index);
    std::sort(s.begin(), s.end());
    return s;
  }
  void undecided(const Work& w, std::vector<double> location, std::string reason) {
    report_.undecided.push_back({std::move(location), simplex_of(w.S), std::move(reason)});
  }

  // a := a ∩ b; false when empty.
  static bool intersect(Box& a, const Box& b) {
    for (std::size_t i = 0; i < a.size(); ++i) {
      a[i] = Interval{std::max(a[i].lo, b[i].lo), std::min(a[i].hi, b[i].hi)};
      if (a[i].lo > a[i].hi) return false;
    }
    return true;
  }
  // Is U x (A \ B) excluded (no point of M ∩ B(p, r) ∩ Vor(p)), B ⊆ A? A \ B is covered by at
  // most 2k boxes: along each normal axis l in turn, the parts of A below and above B (with the
  // axes before l already cut to B).
  bool difference_excluded(const Box& U, Box A, const Box& B, const std::vector<int>& S) const {
    for (int l = 0; l < k_; ++l) {
      if (A[l].lo < B[l].lo) {
        Box piece = A;
        piece[l] = Interval{A[l].lo, B[l].lo};
        if (!excluded(U, piece, S, opt_.normal_levels)) return false;
      }
      if (B[l].hi < A[l].hi) {
        Box piece = A;
        piece[l] = Interval{B[l].hi, A[l].hi};
        if (!excluded(U, piece, S, opt_.normal_levels)) return false;
      }
      A[l] = B[l];
    }
    return true;
  }

  // True when no point of M ∩ B(p, r) over U with normal coordinate in H is in the Voronoi cell of
  // p: either the box is outside the ball, or some G_i has no zero on it (no point of M), or some
  // candidate is certainly closer on all of it; else H is halved along its widest side, up to
  // `levels` times (an ambient search in the normal directions). Under upward rounding.
  bool excluded(const Box& U, Box H, const std::vector<int>& S, int levels) const {
    if (dist2(U, H).inf() >= r2_.sup()) return true;
    if (chart_.free_of_M(U, H)) return true;
    for (int i : S)
      if (sign_form(cands_[i], U, H).sup() < 0) return true;
    if (levels == 0) return false;
    int wide = 0;
    for (int l = 1; l < k_; ++l)
      if (H[l].width() > H[wide].width()) wide = l;
    Box H2 = H;
    const double mid = H[wide].midpoint();
    H[wide].hi = mid;
    H2[wide].lo = mid;
    return excluded(U, H, S, levels - 1) && excluded(U, H2, S, levels - 1);
  }

  // THE GRAPH LEMMA. Hypothesis: tau = options.reach <= reach(M). exact::ChartEnclosure::base_point
  // (in the constructor): p* in M, |p* - p| <= delta, sin θ(span T, T_{p*} M) <= sigma. Claim: when the chart
  // proves exactly one point x(u) of {F = 0} in U x Hc for every u in U, s > 0 on that box's image,
  // and sqrt(r^2 - inf_U |T u|^2) + sup_Hc |Nn h| <= 2 tau cos Θ, Θ = 2 arcsin((r + delta) / (2 tau))
  // + arcsin sigma, then x(u) is the only point of M ∩ B(p, r) over u (Hc holds them all: THE SLAB
  // INVARIANT with no difference test). Proof: x(u) is in M (F = 0, s > 0). Let y != x(u) be in
  // M ∩ B(p, r) over the same u. |y - p*| < r + delta < 2 tau, so the largest principal angle
  // θ(T_y M, T_{p*} M) <= 2 arcsin(|y - p*| / (2 tau)) (Boissonnat, Lieutier, Wintraecken 2019,
  // Cor. 3); largest principal angles obey the triangle inequality, so θ_y := θ(T_y M, span T) <= Θ.
  // v = x - y is orthogonal to span T (same u): v = Nn (h_x - h_y), and |Nn h_y|^2 = |y - p|^2 -
  // |T u|^2 < r^2 - |T u|^2, so |v| < sqrt(r^2 - inf |T u|^2) + sup |Nn h_x|. Federer (1959, Thm
  // 4.18): |P_N v| <= |v|^2 / (2 tau), N the normal space at y; |P_T v| = |(P_T - P_span T) v| <=
  // sin θ_y |v|; so |v|^2 <= sin^2 θ_y |v|^2 + |v|^4 / (4 tau^2) and |v| >= 2 tau cos θ_y >= 2 tau cos
  // Θ: impossible. Θ depends on the cell only (lemma_bound_ = 2 tau cos Θ, computed in interval
  // arithmetic in the constructor: with q = (r + delta) / (2 tau) < 1, cos Θ = (1 - 2q^2) sqrt(1 -
  // sigma^2) - 2q sqrt(1 - q^2) sigma; Θ <= 3π/2, so cos Θ > 0 already proves Θ < π/2). The
  // inequality holds out to r close to tau where M is nearly flat over T_p.
  bool graph_lemma(const Box& U, const Box& Hc, const IA& room) const {
    Box X;
    if (!(lemma_bound_ > 0) || !chart_.image(U, Hc, X) || !selected(X)) return false;
    exact::UpwardRounding up;
    const IA v = exact::sqrt(IA(0, room.sup())) + exact::sqrt(dist2(zero_u_, Hc));
    return v.sup() <= lemma_bound_;
  }
  // s > 0 on all of X (no selector: true).
  bool selected(const Box& X) const {
    if (sel_coef_.empty()) return true;
    exact::UpwardRounding up;
    SmallBuffer<IA, 16> x(N_);
    for (int v = 0; v < N_; ++v) x[v] = ia(X[v]);
    return opt_.selector->evaluate_with<IA>(x.span(), [&](std::size_t i) { return sel_coef_[i]; }).inf() > 0;
  }

  void visit(Work w, std::vector<Work>& stack) {
    ++report_.boxes;
    report_.max_depth = std::max(report_.max_depth, w.depth);
    exact::UpwardRounding up;
    // The region: U x Hpar, Hpar = the parent's slab cut to H_ball(U) = [-b, b]^k with
    // b^2 = (r^2 - inf |T u|^2) / g_N >= |Nn h|^2 / g_N >= |h|^2 for x in B(p, r) over U.
    const IA room = r2_ - dist2(w.U, zero_slab_);  // |T u|^2 (the zero products add nothing)
    if (room.sup() <= 0) return discard();  // |T u| >= r over U: outside the ball
    const double b = exact::sqrt(IA(0, room.sup()) / IA(gN_)).sup();
    Box H(k_, Interval{-b, b});
    if (!w.H.empty() && !intersect(H, w.H)) return discard();  // the parent's slab: nothing over U in the ball
    // Cheap first: the region itself outside the ball or certainly closer to a candidate.
    // Candidates certainly farther than p on U x H are dropped here already: H contains every slab
    // used below for this box (the chart's slab is cut to H, the normal halving splits H), and the
    // interval hull of the affine form s_q is inclusion-isotone, so such a q is certainly farther on
    // each of those regions too and can decide nothing there.
    if (outside_or_closer(w, H)) return discard();
    // A parent's slab proved unique by the chart is handed down (THE SLAB INVARIANT: H = Hpar holds
    // every point of M ∩ B(p, r) ∩ Vor(p) over U) and Krawczyk on U x H contracts it to this box's
    // own: no Newton guess, no difference test. `none`: no point of M in the region. Any outcome
    // but a proved unique point takes the full path below on the same region.
    // A box left for the second pass keeps the chart's slab it got on its first visit: the chart
    // step would only repeat itself.
    bool chart_slab = w.settled, unique_slab = w.settled && w.unique_slab;
    if (w.unique_slab && !w.settled) {
      const exact::ChartResult tight = chart_.enclose_in(w.U, H);
      if (tight.status == exact::ChartStatus::none) return discard();
      if (tight.status == exact::ChartStatus::unique) {
        H = tight.H, chart_slab = unique_slab = true;
        // Where the slope of the chart varies (far from p) one step contracts little: repeat on the
        // contraction (each result holds the unique point over every u) while a side shrinks by 1/4.
        // (Needed: with one step, cells of a torus of revolution reach their ball's boundary.)
        for (int again = 0, shrunk = 1; again < 8 && shrunk; ++again) {
          const exact::ChartResult next = chart_.enclose_in(w.U, H);
          if (next.status != exact::ChartStatus::unique) break;
          shrunk = 0;
          for (int l = 0; l < k_; ++l) shrunk |= next.H[l].width() <= 0.75 * H[l].width();
          H = next.H;
        }
      }
    }
    if (!chart_slab) {
      // The chart's slab replaces it when the rest of the region is excluded (THE SLAB INVARIANT).
      // Newton starts from the centre of the parent's slab when it is the chart's, else from p.
      std::vector<double> hint;
      if (w.chart_slab)
        for (const auto& i : w.H) hint.push_back(i.midpoint());
      const exact::ChartResult ch = chart_.enclose(w.U, hint);
      // Krawczyk contracts Hc to (nearly) the hull of the piece of M over U, which then touches
      // Hc's faces: the difference is taken with Hc widened on each side by twice its width plus the
      // widest side of U (the enclosure of G on a face loses about |dG/du| width(U), which the
      // widening must beat) plus 2^-40 (|Hc| + b), then by 16 times that if the difference is not
      // excluded. Sound for any widening: it only decides how much of the region the chart's slab
      // takes over.
      double widest_u = 0;
      for (const auto& i : w.U) widest_u = std::max(widest_u, i.width());
      // THE GRAPH LEMMA: ch.H, Krawczyk's contraction, holds every point of M ∩ B(p, r) over U, and
      // exactly one point of {F = 0} over each u: it is the slab as it stands (cut to Hpar).
      const bool lemma = ch.status == exact::ChartStatus::unique && graph_lemma(w.U, ch.H, room);
      Box Hc = ch.H;
      if (lemma) {
        if (!intersect(Hc, H)) return discard();  // no point of M ∩ B(p, r) over U in Hpar
        H = std::move(Hc), chart_slab = unique_slab = true, ++report_.reach_slabs;
      }
      for (int attempt = 0; attempt < 2 && !chart_slab && ch.status == exact::ChartStatus::unique; ++attempt) {
        Hc = ch.H;
        for (auto& i : Hc) {
          const IA d = (IA(2) * (IA(i.hi) - IA(i.lo)) + IA(widest_u) +
                        (IA(std::abs(i.lo)) + IA(std::abs(i.hi)) + IA(b)) * IA(0x1p-40)) *
                       IA(attempt ? 16 : 1);
          i = Interval{(IA(i.lo) - d).inf(), (IA(i.hi) + d).sup()};
        }
        chart_slab = intersect(Hc, H) && difference_excluded(w.U, H, Hc, w.S);
        if (chart_slab) {
          // Krawczyk on the widened slab: when it proves one point of M over each u in it, that point
          // lies in its contraction, which is then the slab (tight covering bounds and signs).
          // (Parametric Krawczyk: whatever its status, its box holds every root in Hc of every u in U;
          // `none`: there is none, and the box is free of M.)
          const exact::ChartResult tight = chart_.enclose_in(w.U, Hc);
          if (tight.status == exact::ChartStatus::none) return discard();
          H = tight.H;
          unique_slab = tight.status == exact::ChartStatus::unique;
        }
      }
      if (!chart_slab) {
        ++report_.chart_failures;
        if (excluded(w.U, H, w.S, opt_.normal_levels)) return discard();
      }
    }
    w.H = H;
    // COMBINED SIGNS where a smaller S saves work: a box that would need Krawczyk or a split, or
    // any box of the second pass (a smaller S has fewer faces for PURITY).
    if (outside_or_closer(w, H)) return discard();
    const int s_size = static_cast<int>(w.S.size()), all = s_size + static_cast<int>(w.far.size());
    if (!(opt_.window > 0) && all >= 2 && all <= opt_.combined_signs_max && (refining_ || s_size >= m_) &&
        combined_signs(w.S, w.far, w.U, H))
      return discard();
    const IA d2 = dist2(w.U, H);
    const int n = static_cast<int>(w.S.size()) + 1;
    bool resolved = n <= m_;  // no restricted Voronoi vertex can lie here
    // The candidate sets only shrink down the tree and the regions only shrink (U inside the
    // parent's U, H inside the parent's slab H_eff), so an ancestor's decision with m + 1
    // candidates covers this box when it still has m + 1: they are the same set.
    if (n == m_ + 1) resolved = w.vertex_decided || (chart_slab && krawczyk_vertex(w, H));
    w.vertex_decided = resolved && n == m_ + 1;
    double widest = 0;
    for (const auto& i : w.U) widest = std::max(widest, i.width());
    // A NaN enclosure (an overflow inside an operation) bounds nothing: +inf, never skipped.
    double raw_bound = exact::sqrt(d2).sup();
    if (refining_ && resolved && n >= 2 && raw_bound > std::max(refine_below_, report_.covering_bound)) {
      const double B = lagrangian_bound(w, H);  // sharper where a bisector cuts the box's far corner
      if (B < 0) return discard();              // no point of Vor(p) in the box
      raw_bound = std::min(raw_bound, exact::sqrt(IA(0, B)).sup());
    }
    const double bound = std::isnan(raw_bound) ? INFINITY : raw_bound;
    // A box with `far` candidates may still hold parts outside the cell that their bisectors cut
    // off (a box with all of them in S would be split on): one more halving for its bound.
    const double fine_width = opt_.covering_width * rho_u_ * (w.far.empty() ? 1 : 0.5);
    const bool fine = (n == 1 && w.far.empty()) || widest <= fine_width || w.depth >= opt_.max_depth ||
                      (refining_ && bound <= std::max(refine_below_, report_.covering_bound));
    // First pass: every resolved box with another candidate waits for the second pass, where the
    // vertices of the cell are known and PURITY can be checked.
    // It keeps its own slab and lists (THE SLAB INVARIANT holds for them on its own box).
    if (resolved && !refining_ && (!fine || n >= 2)) {
      w.chart_slab = chart_slab, w.unique_slab = unique_slab, w.settled = chart_slab;
      pending_.push_back(std::move(w));
      return;
    }
    std::vector<int> face;
    bool faces_ok = !resolved || n == 1 || faces_known(w.S, face);  // only read for resolved boxes
    const char* window_fault = resolved && opt_.window > 0 ? window_fault_of(w, H, chart_slab && unique_slab) : nullptr;
    // Second pass (every vertex known): a face in doubt is sought as a FACE POINT, which settles it
    // (and its faces) for good. Work only: a face in doubt only by a loose sign fails every search,
    // so the search waits for boxes of 1/16 the covering width and gives up on a face after kFaceTries.
    const bool seek = fine && refining_ && widest <= opt_.covering_width * rho_u_ / 16;
    while (!faces_ok && seek && face_failures_[face] < kFaceTries) {
      if (!prove_face(w.U, H, face)) {
        ++face_failures_[face];
        break;
      }
      faces_ok = faces_known(w.S, face);
    }
    const bool purity_floor = widest <= opt_.purity_width * rho_u_;
    if (window_fault && (purity_floor || w.depth >= opt_.max_depth)) {
      undecided(w, box_centre(w.U, H), std::string("window: ") + window_fault);
      return;
    }
    if (!window_fault && resolved && ((fine && (faces_ok || purity_floor)) || w.depth >= opt_.max_depth)) {
      if (bound > report_.covering_bound || report_.covering_location.empty()) {
        report_.covering_bound = bound;
        report_.covering_location = box_centre(w.U, H);
      }
      if (!faces_ok && std::none_of(report_.unresolved_faces.begin(), report_.unresolved_faces.end(),
                                    [&](const UndecidedBox& b) { return b.candidates == face; }))
        report_.unresolved_faces.push_back({box_centre(w.U, H), std::move(face),
                                            "a face of the candidate set that is in no restricted Voronoi vertex's "
                                            "simplex, still possible in a box of the finest purity width"});
      ++report_.kept;
      return;
    }
    if (w.depth >= opt_.max_depth) {
      undecided(w, box_centre(w.U, H),
                n > m_ + 1 ? "more than m + 1 candidates at the depth limit"
                           : (chart_slab ? "Krawczyk undecided at the depth limit" : "no chart enclosure at the depth limit"));
      return;
    }
    // Split every side at its midpoint; children pushed in reverse so that the first is visited
    // first (the last one pushed takes the parent's lists).
    for (int corner = (1 << m_) - 1; corner >= 0; --corner) {
      Work c;
      c.U = w.U;
      for (int a = 0; a < m_; ++a) {
        const double mid = w.U[a].midpoint();
        c.U[a] = (corner >> a) & 1 ? Interval{mid, w.U[a].hi} : Interval{w.U[a].lo, mid};
      }
      c.S = corner ? w.S : std::move(w.S);
      c.far = corner ? w.far : std::move(w.far);
      c.H = corner ? w.H : std::move(w.H);
      c.depth = w.depth + 1;
      c.vertex_decided = w.vertex_decided;
      c.chart_slab = chart_slab;
      c.unique_slab = unique_slab;
      stack.push_back(std::move(c));
    }
  }

  // THE WINDOW (rvd.hpp): why the resolved box U x H cannot be kept yet, or nullptr. (a) Its slab is
  // the chart's, proved unique, and the caller's graph holds U x H; (b) {p} + S(U) lies in a vertex simplex
  // found here (first pass: only {p} alone passes, the others wait for the second pass anyway).
  const char* window_fault_of(const Work& w, const Box& H, bool unique_chart_slab) const {
    if (!unique_chart_slab) return "the box's slab is not the chart's proved graph";
    if (!opt_.window_graph || !opt_.window_graph(w.U, H)) return "the box leaves the graph of M proved around p";
    if (w.S.empty()) return nullptr;
    std::vector<int> K = simplex_of(w.S);
    for (const RestrictedVoronoiVertex& v : report_.vertices)
      if (std::includes(v.simplex.begin(), v.simplex.end(), K.begin(), K.end())) return nullptr;
    return "the points within the window are in no restricted Voronoi vertex's simplex";
  }

  // LAGRANGIAN COVERING BOUND. On Vor(p), |x - p|^2 <= g = |x - p|^2 + sum_q lambda_q s_q (all s_q >= 0,
  // lambda >= 0). g is convex in (u, h), so max g on U x H is at some u = corner c of U: with F_c, S_cq
  // the upper ends of enclosures of |x - p|^2, s_q on {c} x H, max_c (F_c + sum_q lambda_q S_cq) rounded
  // up (exact/max_affine.hpp) bounds |x - p|^2 on Vor(p) ∩ (U x H), empty if < 0. q: S, then `far`.
  double lagrangian_bound(const Work& w, const Box& H) const {
    std::vector<const Candidate*> Q;
    for (auto* list : {&w.S, &w.far})
      for (int i : *list) Q.push_back(&cands_[i]);
    const int nc = 1 << m_, nq = std::min(static_cast<int>(Q.size()), opt_.combined_signs_max);
    SmallBuffer<double, 8> F(nc);
    SmallBuffer<double, 64> S(nc * nq);
    Box Uc(m_);
    for (int c = 0; c < nc; ++c) {
      for (int a = 0; a < m_; ++a) Uc[a] = Interval::point((c >> a) & 1 ? w.U[a].hi : w.U[a].lo);
      F[c] = chart_.offset_norm2(Uc, H).hi;
      for (int j = 0; j < nq; ++j) S[c * nq + j] = sign_form(*Q[j], Uc, H).sup();
    }
    return exact::max_affine_upper_bound(F.span(), S.span(), nq);
  }

  // Appends the row s_q = c - 2 a.u - 2 b.h of candidate C, by its enclosures (see Candidate), in
  // exact::AffineExtension's layout; false when one overflowed (an infinite or NaN bound).
  static bool affine_row(const Candidate& C, std::vector<Interval>& rows) {
    rows.push_back({C.c.inf(), C.c.sup()});
    for (const IA& a : C.a2) rows.push_back({-a.sup(), -a.inf()});
    for (const IA& b : C.b2) rows.push_back({-b.sup(), -b.inf()});
    return std::all_of(rows.end() - (1 + C.a2.size() + C.b2.size()), rows.end(),
                       [](const Interval& i) { return i.is_finite(); });
  }

  // A FACE POINT for C = {p, q_1..q_j}, j < m (PURITY in rvd.hpp). Krawczyk on the square system
  // {G(u, h) = 0, s_{q_i} = 0 (i = 1..j), u_a = c_a (a in A)}, for each set A of m - j chart axes,
  // c_a the midpoint of U's side a (a double, so the row u_a - c_a is exact), in U x H with side a
  // cut to an interval around c_a (the box needs an interior) and the others widened 4 times about
  // their centres (the face crosses U, but not always on the lines through its centre; any box
  // will do, it only has to hold a root Krawczyk can prove). A root proven (unique in the box,
  // or by inflation next to it: either way it exists) is a point x of {F = 0} equidistant from the
  // points of C; s > 0 on its image X and the direct check that every other point of P is
  // strictly farther than p on X (separated) make C exactly the set of points of P nearest to x,
  // a point of M: C is in Del_RM(P), with no assumption. A failure concludes nothing.
  bool prove_face(const Box& U, const Box& H, const std::vector<int>& C) {
    const int j = static_cast<int>(C.size()) - 1;
    std::vector<Interval> rows;
    for (int q : C) {
      if (q == p_) continue;
      const auto it = std::find_if(cands_.begin(), cands_.end(), [&](const Candidate& c) { return c.index == q; });
      if (it == cands_.end() || !affine_row(*it, rows)) return false;
    }
    for (int A = 0; A < (1 << m_); ++A) {
      if (__builtin_popcount(A) != m_ - j) continue;
      std::vector<Interval> all = rows;
      Box UH = U;
      UH.insert(UH.end(), H.begin(), H.end());
      for (auto& i : UH) {  // (rounded outwards or not, a box is a box)
        const double c = i.midpoint(), w = i.width();
        i = Interval{c - 2 * w, c + 2 * w};
      }
      bool interior = true;
      for (int a = 0; a < m_; ++a) {
        if (!(A >> a & 1)) continue;
        const double c = U[a].midpoint(), w = U[a].width() / 64;
        UH[a] = Interval{c - w, c + w};
        interior &= UH[a].lo < c && c < UH[a].hi;
        all.push_back(Interval::point(-c));
        for (int v = 0; v < m_ + k_; ++v) all.push_back(Interval::point(v == a ? 1 : 0));
      }
      if (!interior) continue;
      ++report_.krawczyk_calls;
      const exact::KrawczykResult kr = exact::krawczyk(exact::AffineExtension(chart_.chart_system(), std::move(all)), UH);
      const Box* root = kr.status == exact::RootStatus::unique_root ? &kr.box : kr.nearby_root ? &*kr.nearby_root : nullptr;
      Box X;
      if (root && chart_.image(Box(root->begin(), root->begin() + m_), Box(root->begin() + m_, root->end()), X) &&
          selected(X) && separated(C, X)) {
        report_.face_points.push_back({C, std::move(X)});
        return true;
      }
    }
    return false;
  }

  // Krawczyk on {G = 0, s_{q_i} = 0} in U x H. True when decided (a vertex recorded, or none).
  bool krawczyk_vertex(const Work& w, const Box& H) {
    const std::vector<int> simplex = simplex_of(w.S);
    // The chart's rows G(u, h) (evaluated where they are), then s_q = c - 2 a.u - 2 b.h for each q,
    // known by the candidate's enclosures (which hold the exact values, see Candidate): Krawczyk
    // answers for every affine row within them, the true one included (exact::AffineExtension).
    std::vector<Interval> rows;
    rows.reserve(w.S.size() * (1 + m_ + k_));
    for (int i : w.S)
      if (!affine_row(cands_[i], rows)) {
        ++report_.krawczyk_failures;  // an overflow decides nothing
        return false;
      }
    const exact::AffineExtension system(chart_.chart_system(), std::move(rows));
    Box UH = w.U;
    UH.insert(UH.end(), H.begin(), H.end());
    ++report_.krawczyk_calls;
    const exact::KrawczykResult kr = exact::krawczyk(system, UH);
    // A tight root (each side at most 1/8 of the box's; else splitting gives a sharper one) proved
    // unique around this box decides it too (it holds that root or none): a vertex on a split plane.
    bool nearby = kr.status == exact::RootStatus::undecided && kr.nearby_root;
    for (std::size_t i = 0; nearby && i < UH.size(); ++i) nearby = (*kr.nearby_root)[i].width() <= UH[i].width() / 8;
    if (kr.status == exact::RootStatus::undecided && !nearby) {
      ++report_.krawczyk_failures;
      return false;
    }
    if (kr.status != exact::RootStatus::no_root) {
      const Box& root = kr.nearby_root ? *kr.nearby_root : kr.box;
      const Box U(root.begin(), root.begin() + m_), Hv(root.begin() + m_, root.end());
      Box X;
      if (!chart_.image(U, Hv, X) || !selected(X) || !separated(simplex, X)) return false;
      report_.vertices.push_back({simplex, std::move(X)});
    }
    return true;
  }

  // Direct check (certify/detail/cell_checks.hpp): every other point strictly farther than p on X.
  bool separated(const std::vector<int>& simplex, const Box& X) const {
    return detail::others_strictly_farther(points_, grid_, p_, simplex, X);
  }

  // Sorted, deduplicated, complete or not (certify/detail/cell_checks.hpp).
  void finish() { detail::finish_report(report_, p_, r_); }

  const io::PointSet& points_;
  const detail::PointGrid& grid_;
  int p_;
  RestrictedCellOptions opt_;
  bool refining_ = false;     // second pass (covering refinement)
  double refine_below_ = 0;   // max distance from p to a vertex found (a lower bound)
  std::vector<Work> pending_; // resolved boxes left for the second pass
  exact::ChartEnclosure chart_;
  int N_, m_, k_;
  std::span<const Interval> T_enc_, N_enc_;  // the chart's (exact T and Nn, enclosed)
  Box zero_slab_;  // k times [0, 0]
  double r_ = 0, rho_u_ = 0, gN_ = 0;
  IA r2_;                                        // r^2, enclosed
  std::vector<Candidate> cands_;
  std::vector<IA> sel_coef_;                     // the selector's coefficients, enclosed
  double lemma_bound_ = 0;                       // THE GRAPH LEMMA's 2 tau cos Θ (0: not used)
  Box zero_u_;                                   // m times [0, 0]
  static constexpr int kFaceTries = 4;
  std::map<std::vector<int>, int> face_failures_;  // failed FACE POINT searches, per face
  RestrictedCellReport report_;
};

}  // namespace

struct RestrictedCell::Impl {
  std::unique_ptr<detail::ParamCell> param;  // a rational chart (detail/param_cell.hpp), when there is one
  std::optional<CellAnalysis> cell;          // else the implicit chart
};

RestrictedCell::RestrictedCell(const exact::ImplicitSystem& system, const io::PointSet& points,
                               const detail::PointGrid& grid, int p, const RestrictedCellOptions& options)
    : impl_(std::make_unique<Impl>()) {
  if (options.shape) impl_->param = detail::ParamCell::make(*options.shape, points, grid, p, options);
  if (!impl_->param && options.geodesic) throw std::logic_error("restricted cell: a geodesic cell needs its product shape");
  if (!impl_->param) impl_->cell.emplace(system, points, grid, p, options);
}
RestrictedCell::~RestrictedCell() = default;
RestrictedCell::RestrictedCell(RestrictedCell&&) noexcept = default;
RestrictedCell& RestrictedCell::operator=(RestrictedCell&&) noexcept = default;
double RestrictedCell::first_pass() { return impl_->param ? impl_->param->first_pass() : impl_->cell->first_pass(); }
RestrictedCellReport RestrictedCell::second_pass(double covering_target) {
  return impl_->param ? impl_->param->second_pass(covering_target) : impl_->cell->second_pass(covering_target);
}

RestrictedCellReport analyse_restricted_cell(const exact::ImplicitSystem& system, const io::PointSet& points,
                                             const detail::PointGrid& grid, int p, const RestrictedCellOptions& options) {
  RestrictedCell cell(system, points, grid, p, options);
  cell.first_pass();
  return cell.second_pass(0);
}

}  // namespace delcert::certify
