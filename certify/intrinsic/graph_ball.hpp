// THE GRAPH BALL of a sample point (certify/intrinsic/general.hpp has the argument it serves): a
// certified piece Y_q of M around q on which d_M(x, q') <= Φ_K(|x - q| + delta_q), K a certified
// curvature bound. Built by make_ball (graph_ball.cpp); read by the general Del_M engine.
#pragma once

#include <gmpxx.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <optional>
#include <utility>
#include <span>
#include <string>
#include <vector>

#include "exact/chart.hpp"
#include "exact/geodesic_bounds.hpp"
#include "exact/interval_arithmetic.hpp"
#include "exact/number_types.hpp"
#include "exact/polynomial.hpp"
#include "exact/tangent_space.hpp"
#include "io/points.hpp"

namespace delcert::certify::detail {

// |x - q| over the box X, enclosed (call under exact::UpwardRounding).
exact::IntervalNumber ball_distance(const exact::Box& X, std::span<const double> q);

// THE GRAPH BALL of a point q (general.hpp). Its chart x = q + T u + Nn h has Nn a nearly orthonormal
// normal basis (Eigen's doubles, exact as they are) and T a nearly orthonormal tangent basis made
// EXACTLY orthogonal to Nn (T = T0 - Nn (Nn^T Nn)^-1 Nn^T T0, T0 Eigen's doubles), so |x - q|^2 =
// |T u|^2 + |Nn h|^2, between g_T |u|^2 + g_N |h|^2 and G_T |u|^2 + G_N |h|^2 (g the Gram matrices'
// smallest eigenvalues, chart.hpp; G their largest, Gershgorin on the exact Gram matrices), and a
// u-box hugs a ball.
//   Y_q: the graph over U_Y = [-rho_Y, rho_Y]^m, rho_Y = r / sqrt(g_T) (every point of B(q, r) has
//     its u there), a part of the graph of A, so connected (a box is).
//   A: an ATLAS over U_A = [-rho_A, rho_A]^m cut into n^m cells (n = 1, 2, 4: the first that
//     works). Cells with |T u| beyond the reach needed are left out; every other cell U_c gets a slab
//     H_c in which Krawczyk proves exactly one point of M over each u (chart.hpp, enclose_in: unique
//     in the box given), h(u) strictly inside it; A is the component of the cells around u = 0 through
//     faces where the two graphs agree (Krawczyk: one point over each u of the face in the hull of
//     the two slabs), and EVERY face between two cells of A must agree: the graph over A's domain D
//     is then the graph of a continuous function (pasting lemma). The cells around u = 0 hold q'
//     (|h| <= delta / sqrt(g_N)), and U_Y lies in D.
// A point of M whose chart coordinates lie in U_c x H_c for a cell c of A is on A's graph
// (uniqueness in H_c).
struct GraphBall {
  using Box = exact::Box;
  using Interval = exact::Interval;
  using IA = exact::IntervalNumber;
  static IA ia(const Interval& i) { return exact::to_interval_number(i); }
  bool ok = false;
  std::string why;
  std::optional<exact::ChartEnclosure> chart;     // the orthogonal chart above
  double rho = 0;     // rho_A
  Box UY;             // U_Y
  int n = 1, m = 0;
  std::vector<char> in_A;        // per grid cell (row-major in the axes)
  std::vector<Box> H;            // per cell of A: its slab
  std::vector<Interval> L;       // [T Nn]^-1 (N x N, row-major), enclosed: (u, h) of x - q
  double K = INFINITY, delta = 0;
  double gT = 0, gN = 0, GT = INFINITY, GN = INFINITY;  // the Gram bounds above

  // sup |x - q|^2 over U x Hb (G_T sup |u|^2 + G_N sup |h|^2), and inf |T u|^2 over U, rounded.
  double dist2_upper(const Box& U, const Box& Hb) const {
    exact::UpwardRounding up;
    IA u2(0), h2(0);
    for (const auto& i : U) u2 += IA(std::max(i.lo * i.lo, i.hi * i.hi));
    for (const auto& i : Hb) h2 += IA(std::max(i.lo * i.lo, i.hi * i.hi));
    return (IA(GT) * u2 + IA(GN) * h2).sup();
  }
  double tangent2_lower(const Box& U) const {
    exact::UpwardRounding up;
    IA u2(0);
    for (const auto& i : U) {
      const double d = i.lo > 0 ? i.lo : i.hi < 0 ? -i.hi : 0;  // |u_a| >= d on U
      u2 += exact::square(IA(d));
    }
    return (IA(gT) * u2).inf();
  }

  Box cell_box(int c) const {
    Box U(m);
    const double w = 2 * rho / n;  // (any doubles do: the cells only need to cover U_A and share faces)
    for (int a = 0; a < m; ++a, c /= n) {
      const int i = c % n;
      U[a] = Interval{i == 0 ? -rho : -rho + w * i, i == n - 1 ? rho : -rho + w * (i + 1)};
    }
    return U;
  }
  // The cells of the grid meeting the u-box U; false when U leaves U_A.
  bool cells_meeting(const Box& U, std::vector<int>& out) const {
    out.clear();
    for (int a = 0; a < m; ++a)
      if (!(U[a].lo >= -rho && U[a].hi <= rho)) return false;
    int cells = 1;
    for (int a = 0; a < m; ++a) cells *= n;
    for (int c = 0; c < cells; ++c) {
      const Box Uc = cell_box(c);
      bool meets = true;
      for (int a = 0; a < m; ++a) meets &= Uc[a].lo <= U[a].hi && U[a].lo <= Uc[a].hi;
      if (meets) out.push_back(c);
    }
    return true;
  }
  // Every point of M with chart coordinates in U x Hb is on Y_q.
  bool holds(const Box& U, const Box& Hb) const {
    if (!ok) return false;
    for (int a = 0; a < m; ++a)
      if (!(U[a].lo >= UY[a].lo && U[a].hi <= UY[a].hi)) return false;
    std::vector<int> cs;
    if (!cells_meeting(U, cs)) return false;
    for (int c : cs) {
      if (!in_A[c]) return false;
      for (std::size_t l = 0; l < Hb.size(); ++l)
        if (!(H[c][l].lo <= Hb[l].lo && Hb[l].hi <= H[c][l].hi)) return false;
    }
    return true;
  }
  // Every point of M in the ambient box X is on Y_q.
  bool contains(const Box& X, std::span<const double> q) const {
    if (!ok) return false;
    const int N = static_cast<int>(X.size());
    Box U(m), Hb(N - m);
    {
      exact::UpwardRounding up;
      for (int r = 0; r < N; ++r) {
        IA s(0);
        for (int v = 0; v < N; ++v) s += ia(L[r * N + v]) * (ia(X[v]) - IA(q[v]));
        (r < m ? U[r] : Hb[r - m]) = exact::to_interval(s);
      }
    }
    return holds(U, Hb);
  }
  // THE LOCAL PROFILE: per curvature leaf of A (graph_ball.cpp, curvature_leaves; they cover A's
  // graph), (inf |x - q| over its image box, rounded down; the largest leaf bound among the leaves up
  // to there), sorted. local_K(s) bounds |II| on every point of A's graph within s of q (each lies
  // in a leaf whose box comes within s); K where the profile does not reach.
  std::vector<std::pair<double, double>> profile;
  double local_K(double s) const {
    auto it = std::upper_bound(profile.begin(), profile.end(), std::make_pair(s, static_cast<double>(INFINITY)));
    return it == profile.begin() ? 0 : std::min(K, std::prev(it)->second);
  }
  // Φ for q: d_M(x, q') <= phi(t) for x in Y_q with |x - q| + delta <= t <= c_Y + delta, rounded
  // up. Why: L = Φ_K(t) bounds d_M(x, q') (the ball's argument); a minimizing geodesic from x to q'
  // has length d <= L < R, stays on A's graph (the ball's argument) and within d of q', so within
  // L + delta of q: its curvature is at most K1 = local_K(L + delta) <= K, and K1 d <= K R <= π, so
  // by Schur's comparison d <= Φ_{K1}(|x - q'|) <= Φ_{K1}(t).
  double phi(double t) const {
    const double L = exact::chord_to_geodesic_upper(K, t);
    if (!std::isfinite(L)) return L;
    double s;
    {
      exact::UpwardRounding up;
      s = (IA(L) + IA(delta)).sup();
    }
    const double K1 = local_K(s);
    return K1 < K ? std::min(L, exact::chord_to_geodesic_upper(K1, t)) : L;
  }
  // d_M(x, q') <= this for every x in X ∩ Y_q (the caller checked contains(X)), rounded up.
  double upper(const Box& X, std::span<const double> q) const {
    double t;
    {
      exact::UpwardRounding up;
      t = (ball_distance(X, q) + IA(delta)).sup();
    }
    return phi(t);
  }
};

// F's second derivatives, prepared once (exact polynomials and their coefficients' enclosures).
struct Hessians {
  using IA = exact::IntervalNumber;
  int N = 0, k = 0;
  std::vector<exact::Polynomial> d2;        // k x N x N, d2[(e N + v) N + w] = d^2 F_e / dx_v dx_w
  std::vector<std::vector<IA>> coef;
  explicit Hessians(const exact::ImplicitSystem& F) : N(F.ambient_dimension()), k(F.codimension()) {
    for (const auto& P : F.equations())
      for (int v = 0; v < N; ++v) {
        const exact::Polynomial dv = P.derivative(v);
        for (int w = 0; w < N; ++w) d2.push_back(dv.derivative(w));
      }
    for (const auto& P : d2) {
      coef.emplace_back();
      for (const auto& t : P.terms()) coef.back().push_back(exact::to_interval_number(exact::enclose(t.coefficient)));
    }
  }
};

// THE GRAPH BALL of q for the radius r. K bounds |II| on A's graph within B(q, R + delta), R =
// f (c_Y + delta), c_Y >= max |x - q| on Y_q. Why that K serves (general.hpp's open-and-closed
// argument): a minimizing geodesic from x~ in Y_q to q' of length L < R has every point within L
// of q' (so in the open ball B(q, R + delta)); it starts on A's graph and cannot leave it there:
// where it would, at a point over u0, either every cell around u0 is in A (the graphs agree on the
// faces, h(u0) strictly inside each slab: nearby points of M are on the graph, by uniqueness), or
// u0 is on a face of A's boundary, where |x - q| >= exit distance >= R + delta (checked).
GraphBall make_ball(const exact::ImplicitSystem& F, const exact::CurvatureBound& curvature, const Hessians& D2,
                    const exact::Polynomial* selector,
                    const io::PointSet& P, int q, double delta, double r);

}  // namespace delcert::certify::detail
