// Del_M(P) on a general M (certify/intrinsic/general.hpp holds the argument; docs/certificate.md
// "Del_M without a closed-form metric"). Rounding: every bound that decides anything is computed in
// double intervals under exact::UpwardRounding (CGAL's Interval_nt_advanced: outward results, an
// overflow gives an infinite or NaN bound, which decides nothing) or by exact/geodesic_bounds.hpp
// (MPFR, directed rounding). Floating-point estimates (Eigen, midpoints) only choose boxes.
#include "certify/intrinsic/general.hpp"
#include "certify/intrinsic/graph_ball.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "certify/detail/parallel.hpp"
#include "certify/restricted/rvd.hpp"
#include "exact/chart.hpp"
#include "exact/geodesic_bounds.hpp"
#include "exact/interval_arithmetic.hpp"
#include "exact/krawczyk.hpp"
#include "exact/linear_algebra.hpp"
#include "exact/number_types.hpp"

namespace delcert::certify::detail {

namespace {

using exact::Box;
using exact::Interval;
using IA = exact::IntervalNumber;
using json = nlohmann::json;

IA ia(const Interval& i) { return exact::to_interval_number(i); }

// One m-simplex's EXISTENCE argument (general.hpp). Fills the witness or the reason.
struct Existence {
  bool proven = false;
  json witness;
  std::string reason;
};

// The affine row s_i = |x - p_i|^2 - |x - p|^2 = c - 2 a.u - 2 b.h in p's chart (x = p + T u + Nn h):
// d = p_i - p, c = |d|^2, a = T^T d, b = Nn^T d, enclosed from the exact doubles and bases.
std::vector<IA> affine_row(const exact::ChartEnclosure& C, std::span<const double> p, std::span<const double> pi) {
  const int N = C.ambient_dimension(), m = C.intrinsic_dimension(), k = C.codimension();
  const auto T = C.tangent_enclosure(), Nn = C.normal_enclosure();
  std::vector<IA> row(1 + m + k, IA(0));
  for (int v = 0; v < N; ++v) {
    const IA d = IA(pi[v]) - IA(p[v]);
    row[0] += exact::square(d);
    for (int a = 0; a < m; ++a) row[1 + a] -= IA(2) * ia(T[v * m + a]) * d;
    for (int l = 0; l < k; ++l) row[1 + m + l] -= IA(2) * ia(Nn[v * k + l]) * d;
  }
  return row;
}
IA eval_row(const std::vector<IA>& row, const Box& U, const Box& H) {
  IA s = row[0];
  const int m = static_cast<int>(U.size());
  for (int a = 0; a < m; ++a) s += row[1 + a] * ia(U[a]);
  for (std::size_t l = 0; l < H.size(); ++l) s += row[1 + m + l] * ia(H[l]);
  return s;
}

class ExistenceProver {
 public:
  ExistenceProver(const exact::ImplicitSystem& F, const io::PointSet& P, const PointGrid& grid,
                  const std::vector<GraphBall>& balls, double delta_max)
      : F_(F), P_(P), grid_(grid), balls_(balls), delta_max_(delta_max) {}

  Existence prove(const std::vector<int>& sigma, int p, const Box& Xv) const {
    Existence out;
    const GraphBall& Bp = balls_[p];
    for (int i : sigma)
      if (!balls_[i].ok) return fail(out, "no graph ball at point " + std::to_string(i) + ": " + balls_[i].why);
    const exact::ChartEnclosure& C = *Bp.chart;
    const int N = C.ambient_dimension(), m = C.intrinsic_dimension();
    const std::span<const double> pp = P_.point(p);
    std::vector<int> others;
    for (int i : sigma)
      if (i != p) others.push_back(i);
    // E's rows, and B ~ (D(E o x))^-1 at the vertex (Eigen: a choice only).
    std::vector<std::vector<IA>> rows;
    Eigen::VectorXd vmid(N);
    for (int v = 0; v < N; ++v) vmid[v] = Xv[v].midpoint();
    Eigen::MatrixXd T(N, m), Nn(N, C.codimension());
    for (int v = 0; v < N; ++v) {
      for (int a = 0; a < m; ++a) T(v, a) = C.tangent_enclosure()[v * m + a].midpoint();
      for (int l = 0; l < C.codimension(); ++l) Nn(v, l) = C.normal_enclosure()[v * C.codimension() + l].midpoint();
    }
    const Eigen::MatrixXd J = F_.jacobian(std::span<const double>(vmid.data(), N));
    const Eigen::MatrixXd dphi = T - Nn * (J * Nn).lu().solve(J * T);
    Eigen::MatrixXd A(m, m);
    {
      exact::UpwardRounding up;
      for (int i : others) rows.push_back(affine_row(C, pp, P_.point(i)));
    }
    for (int i = 0; i < m; ++i)
      for (int a = 0; a < m; ++a) A(i, a) = -2 * (Eigen::Map<const Eigen::VectorXd>(P_.point(others[i]).data(), N) -
                                                  Eigen::Map<const Eigen::VectorXd>(pp.data(), N)).dot(dphi.col(a));
    const Eigen::MatrixXd Binv = A.inverse();
    if (!Binv.allFinite()) return fail(out, "the equidistance map is degenerate at the vertex");
    {  // B nonsingular, exactly (its entries are doubles)
      std::vector<mpq_class> M(m * m);
      for (int i = 0; i < m; ++i)
        for (int j = 0; j < m; ++j) M[i * m + j] = Binv(i, j);
      if (exact::determinant(M.data(), m) == 0) return fail(out, "the preconditioner is singular");
    }
    // The transformed rows B E (affine, so combined exactly in interval arithmetic).
    std::vector<std::vector<IA>> brows(m, std::vector<IA>(rows[0].size(), IA(0)));
    {
      exact::UpwardRounding up;
      for (int j = 0; j < m; ++j)
        for (int i = 0; i < m; ++i)
          for (std::size_t c = 0; c < rows[i].size(); ++c) brows[j][c] += IA(Binv(j, i)) * rows[i][c];
    }
    // The vertex in p's chart coordinates.
    std::vector<double> uc(m);
    {
      exact::UpwardRounding up;
      for (int a = 0; a < m; ++a) {
        IA s(0);
        for (int v = 0; v < N; ++v) s += ia(Bp.L[a * N + v]) * (ia(Xv[v]) - IA(pp[v]));
        uc[a] = exact::to_interval(s).midpoint();
      }
    }
    // The distortion at the vertex (an estimate, to size the box), transformed by B.
    const std::vector<double> e0 = distortion(sigma, p, others, Xv);
    double e_est = 0;
    for (int j = 0; j < m; ++j) {
      double s = 0;
      for (int i = 0; i < m; ++i) s += std::abs(Binv(j, i)) * e0[i];
      e_est = std::max(e_est, s);
    }
    if (!std::isfinite(e_est)) return fail(out, "the geodesic distortion at the vertex is not bounded");
    std::string last = "no box tried";
    for (double factor : {1.5, 2.5, 4.0, 16.0, 64.0, 256.0}) {
      const double w = std::max(factor * e_est, 1e-12 * (1 + std::abs(uc[0])));
      Box U(m);
      for (int a = 0; a < m; ++a) U[a] = Interval{uc[a] - w, uc[a] + w};
      // The slab: the intersection of the atlas cells' over U (their points over U are the same).
      std::vector<int> cs;
      if (!Bp.cells_meeting(U, cs)) return fail(out, "the box around the vertex leaves the graph ball of its point");
      Box Hi;
      for (int c : cs) {
        if (!Bp.in_A[c]) return fail(out, "the box around the vertex leaves the graph ball of its point");
        if (Hi.empty()) Hi = Bp.H[c];
        for (std::size_t l = 0; l < Hi.size(); ++l)
          Hi[l] = Interval{std::max(Hi[l].lo, Bp.H[c][l].lo), std::min(Hi[l].hi, Bp.H[c][l].hi)};
      }
      const exact::ChartResult ch = C.enclose_in(U, Hi);
      if (ch.status != exact::ChartStatus::unique) {
        last = "the chart is undecided around the vertex";
        continue;
      }
      const Box H = ch.H;
      if (!Bp.holds(U, H)) return fail(out, "the box around the vertex leaves the graph ball of its point");
      // The Euclidean equidistance map has exactly one zero there, nondegenerate.
      std::vector<Interval> tail;
      for (const auto& row : rows)
        for (const IA& c : row) tail.push_back(exact::to_interval(c));
      Box UH = U;
      UH.insert(UH.end(), H.begin(), H.end());
      const exact::KrawczykResult kr = exact::krawczyk(exact::AffineExtension(C.chart_system(), std::move(tail)), UH);
      if (kr.status != exact::RootStatus::unique_root) {
        last = "Krawczyk does not isolate the restricted Voronoi vertex in the box";
        continue;
      }
      Box X;
      if (!C.image(U, H, X)) return fail(out, "overflow in the chart image");
      for (int i : sigma)
        if (!balls_[i].contains(X, P_.point(i)))
          return fail(out, "the box around the vertex leaves the graph ball of point " + std::to_string(i));
      // The boundary: on each face some component of B E beats the bound of B (G - E).
      if (!boundary_ok(C, brows, Binv, sigma, p, others, U, H)) {
        last = "the distortion is not beaten on the boundary of the box";
        continue;
      }
      // Emptiness: every other point q certainly farther in d_M than rho = d_M(w, p_i') at the zero
      // w in X. At w the distances to all points of sigma are equal, so rho <= each
      // Φ_{K_i}(|w - p_i| + delta_i), hence rho <= ub = min_i sup_X of that.
      const double ub = radius_upper(sigma, X);
      if (!std::isfinite(ub)) return fail(out, "the geodesic distance to the simplex's points is not bounded there");
      std::vector<double> centre(N);
      double rad;
      {
        exact::UpwardRounding up;
        IA r2(0);
        for (int v = 0; v < N; ++v) centre[v] = X[v].midpoint(), r2 += exact::square(IA(X[v].hi) - IA(X[v].lo));
        rad = (exact::sqrt(r2) + IA(ub) + IA(delta_max_)).sup();
      }
      // Each q is tried on all of X first; where that does not separate (X's width counts twice: the
      // inf of |x - q| and the sup of |x - p_i| are taken at different points of X), on pieces of U
      // (PIECES, farther_on_halves): w is over one of them.
      double lb_min = INFINITY;
      int nearest = -1;
      json piecewise = json::array();
      for (int q : grid_.ball(centre, rad)) {
        if (std::binary_search(sigma.begin(), sigma.end(), q)) continue;
        const double lb = lower_on(X, q);
        if (lb > ub) {
          if (lb < lb_min) lb_min = lb, nearest = q;
          continue;
        }
        Piecewise pw;  // (the region itself was the first piece tried)
        if (!farther_on_halves(C, sigma, q, U, H, X, 3 * m, pw)) {
          return fail(out, "point " + std::to_string(q) + " is not proven farther: its geodesic distance is in [" +
                               std::to_string(lb) + ", ...] and the simplex's is in [..., " + std::to_string(ub) +
                               "] on the region, and not separated on " + std::to_string(pw.pieces) + " pieces of it");
        }
        piecewise.push_back({{"point", q}, {"pieces", pw.pieces}, {"margin_lower", pw.margin}});
      }
      out.proven = true;
      json region = json::array();
      for (const auto& i : X) region.push_back({i.lo, i.hi});
      out.witness = {{"kind", "intrinsic_voronoi_vertex"},
                     {"simplex", sigma},
                     {"region", region},
                     {"geodesic_radius_upper", ub},
                     {"others_distance_lower", lb_min},
                     {"nearest_other", nearest},
                     {"others_on_pieces", piecewise},
                     {"argument", "degree: the Euclidean equidistance map's zero survives the geodesic distortion"}};
      return out;
    }
    return fail(out, last);
  }

 private:
  static Existence& fail(Existence& e, std::string why) {
    e.reason = std::move(why);
    return e;
  }

  // inf over X of |x - q| - delta_q, rounded down: d_M(x, q') >= it for every x in X.
  double lower_on(const Box& X, int q) const {
    exact::UpwardRounding up;
    return (ball_distance(X, P_.point(q)) - IA(balls_[q].delta)).inf();
  }
  // min_i sup_X Φ_{K_i}(|x - p_i| + delta_i) over the points p_i of sigma, rounded up: rho is at most
  // it when the zero w is in X (the graph balls of sigma hold X).
  double radius_upper(const std::vector<int>& sigma, const Box& X) const {
    double ub = INFINITY;
    for (int i : sigma) ub = std::min(ub, balls_[i].upper(X, P_.point(i)));
    return ub;
  }

  // PIECES. A U over which q is not separated is bisected (widest side first, `levels` times at
  // most); on a half U_j, with H_j holding the graph over U_j (H, or Krawczyk's tighter slab) and
  // X_j = X ∩ image(U_j, H_j) (both enclose x(U_j)), q is farther than rho when lower_on(X_j, q) >
  // radius_upper(sigma, X_j): if w is over U_j, d_M(w, q') exceeds that and rho is at most it. The
  // pieces cover U, and w is over U: q is farther than rho. X_j ⊆ X, so the graph balls that hold X
  // hold X_j. `pw` counts the pieces tried (U itself, tried by the caller, included) and keeps the
  // least margin of the pieces proven.
  struct Piecewise {
    long pieces = 1;
    double margin = INFINITY;  // min over the pieces of (lower - upper), rounded down
  };
  bool farther_on_halves(const exact::ChartEnclosure& C, const std::vector<int>& sigma, int q, const Box& U,
                         const Box& H, const Box& X, int levels, Piecewise& pw) const {
    if (levels == 0) return false;
    int wide = 0;
    for (std::size_t a = 1; a < U.size(); ++a)
      if (U[a].width() > U[wide].width()) wide = static_cast<int>(a);
    Box lo = U, hi = U;
    lo[wide].hi = hi[wide].lo = U[wide].midpoint();
    for (const Box* half : {&lo, &hi}) {
      ++pw.pieces;
      const exact::ChartResult ch = C.enclose_in(*half, H);
      const Box& Hh = ch.status == exact::ChartStatus::unique ? ch.H : H;
      Box Xj;
      if (!C.image(*half, Hh, Xj)) return false;
      for (std::size_t v = 0; v < Xj.size(); ++v) {
        Xj[v] = Interval{std::max(Xj[v].lo, X[v].lo), std::min(Xj[v].hi, X[v].hi)};
        if (!(Xj[v].lo <= Xj[v].hi)) return false;  // (cannot happen: both enclose x(U_j))
      }
      const double ub = radius_upper(sigma, Xj), lb = lower_on(Xj, q);
      if (lb > ub) {
        exact::UpwardRounding up;
        pw.margin = std::min(pw.margin, (IA(lb) - IA(ub)).inf());
      } else if (!farther_on_halves(C, sigma, q, *half, Hh, X, levels - 1, pw)) {
        return false;
      }
    }
    return true;
  }

  // Upper bounds e_i of |G_i - E_i| on X ∩ Y (rows i of `others`): with t_j = |x - p_j|,
  // d_M(x, p_j')^2 - t_j^2 lies in [-2 t_j delta_j, g_j = Φ(t_j + delta_j)^2 - t_j^2] (d >= t - delta;
  // the upper end nondecreasing in t: Φ' >= 1, Φ(t) >= t), and G_i - E_i is the difference of the
  // terms of p_i and p: it lies in [-2 t_i delta_i - g_p, g_i + 2 t_p delta_p], so e_i = max(g_i +
  // 2 t_p delta_p, g_p + 2 t_i delta_i) at the sups of t (the two distortions never add up).
  std::vector<double> distortion(const std::vector<int>& sigma, int p, const std::vector<int>& others, const Box& X) const {
    (void)sigma;
    auto g = [&](int j, double& tsup) {
      exact::UpwardRounding up;
      tsup = ball_distance(X, P_.point(j)).sup();
      const double phi = balls_[j].phi((IA(tsup) + IA(balls_[j].delta)).sup());
      if (!std::isfinite(phi) || !std::isfinite(tsup)) return static_cast<double>(INFINITY);
      return (exact::square(IA(phi)) - exact::square(IA(tsup))).sup();
    };
    double tp;
    const double gp = g(p, tp);
    std::vector<double> e;
    for (int i : others) {
      double ti;
      const double gi = g(i, ti);
      exact::UpwardRounding up;
      if (!std::isfinite(gi) || !std::isfinite(gp)) {
        e.push_back(INFINITY);
        continue;
      }
      e.push_back(std::max((IA(gi) + IA(2) * IA(tp) * IA(balls_[p].delta)).sup(),
                           (IA(gp) + IA(2) * IA(ti) * IA(balls_[i].delta)).sup()));
    }
    return e;
  }

  bool boundary_ok(const exact::ChartEnclosure& C, const std::vector<std::vector<IA>>& brows, const Eigen::MatrixXd& Binv,
                   const std::vector<int>& sigma, int p, const std::vector<int>& others, const Box& U,
                   const Box& H) const {
    const int m = static_cast<int>(U.size());
    for (int a = 0; a < m; ++a)
      for (double side : {U[a].lo, U[a].hi}) {
        Box face = U;
        face[a] = Interval::point(side);
        if (!face_ok(C, brows, Binv, sigma, p, others, face, H, 3)) return false;
      }
    return true;
  }
  bool face_ok(const exact::ChartEnclosure& C, const std::vector<std::vector<IA>>& brows, const Eigen::MatrixXd& Binv,
               const std::vector<int>& sigma, int p, const std::vector<int>& others, const Box& face, const Box& H,
               int levels) const {
    const int m = static_cast<int>(face.size());
    const exact::ChartResult ch = C.enclose_in(face, H);
    const Box& Hf = ch.status == exact::ChartStatus::unique ? ch.H : H;  // H holds h over the face too
    Box X;
    if (!C.image(face, Hf, X)) return false;
    const std::vector<double> e = distortion(sigma, p, others, X);
    for (int j = 0; j < m; ++j) {
      exact::UpwardRounding up;
      IA bound(0);
      bool finite = true;
      for (int i = 0; i < m; ++i) finite &= std::isfinite(e[i]);
      if (!finite) return false;
      for (int i = 0; i < m; ++i) bound += IA(std::abs(Binv(j, i))) * IA(e[i]);
      const IA v = eval_row(brows[j], face, Hf);
      if (v.inf() > bound.sup() || v.sup() < -bound.sup()) return true;
    }
    if (levels == 0) return false;
    int wide = -1;
    for (int a = 0; a < m; ++a)
      if (face[a].width() > 0 && (wide < 0 || face[a].width() > face[wide].width())) wide = a;
    if (wide < 0) return false;
    Box lo = face, hi = face;
    lo[wide].hi = hi[wide].lo = face[wide].midpoint();
    return face_ok(C, brows, Binv, sigma, p, others, lo, H, levels - 1) &&
           face_ok(C, brows, Binv, sigma, p, others, hi, H, levels - 1);
  }

  const exact::ImplicitSystem& F_;
  const io::PointSet& P_;
  const PointGrid& grid_;
  const std::vector<GraphBall>& balls_;
  double delta_max_;
};

}  // namespace

IntrinsicDelaunay intrinsic_delaunay_general(const io::ManifoldSpec& spec, const io::PointSet& points,
                                             const PointGrid& grid, const std::vector<std::vector<int>>& candidates,
                                             const GeneralMetricInput& in, int threads) {
  IntrinsicDelaunay D;
  D.metric = "general";
  D.convention =
      "d_M(x, p) := d_M(x, p') for any point p' of M within check 1's certified distance bound delta_p of p (a nearest "
      "point among them); bounded by |x - p| - delta_p <= d_M(x, p') <= Φ_K(|x - p| + delta_p), Φ_K(t) = (2/K) "
      "arcsin(K t / 2), K a certified bound of M's normal curvature around p (Schur's comparison on a graph ball)";
  D.completeness =
      "THE WINDOW: every point of M within check 11's covering radius of P, and around each point p the restricted cells "
      "recomputed with candidates dropped only when farther than p by more than the geodesic distortion: every set of "
      "points nearest in d_M lies in an m-simplex of Del_RM(P)";
  const RestrictedDelaunay* R = in.restricted;
  if (!R || !in.system || !in.distance_to_M) {
    D.reason = "no closed-form geodesic distance, and Del_RM(P) (check 12) was not computed";
    return D;
  }
  D.computed = true;
  const int n = static_cast<int>(points.size());
  const exact::ImplicitSystem& F = *in.system;
  const std::vector<double>& delta = *in.distance_to_M;
  double delta_max = 0;
  for (double d : delta) delta_max = std::max(delta_max, d);
  std::string incomplete;
  if (!R->covering_certified) incomplete = "Del_RM(P) is not known completely (check 11): " + R->reason;
  std::vector<GraphBall> balls(n);
  std::vector<RestrictedCellReport> cells(n);
  const exact::CurvatureBound curvature(F);
  const Hessians hessians(F);
  parallel_for(static_cast<std::size_t>(n), threads, [&](std::size_t i, int) {
    const int p = static_cast<int>(i);
    // The ball's radius: beyond the covering bound c_p of p's restricted cell (check 12: M ∩ Vor(p)
    // lies within c_p of p, and so do the vertices of p's simplices), by a 16th.
    double rg;
    {
      exact::UpwardRounding up;
      const double cp = i < R->cells.size() ? R->cells[i].covering_bound : R->covering;
      rg = (IA(cp) * IA(1.0625) + IA(delta_max)).sup();
    }
    balls[i] = make_ball(F, curvature, hessians, in.cell.selector, points, p, delta[i], rg);
    if (!balls[i].ok || !incomplete.empty()) return;
    RestrictedCellOptions o = in.cell;
    o.shape = nullptr, o.geodesic = false, o.graph_radius = rg, o.max_depth = std::min(o.max_depth, 16), o.window_graph = [&ball = balls[i]](const Box& U, const Box& H) { return ball.holds(U, H); };
    o.chart = &*balls[i].chart;
    {
      exact::UpwardRounding up;
      const double phi = balls[i].phi((IA(rg) + IA(delta[i])).sup());
      if (!std::isfinite(phi)) {  // no window: the cell stays unanalysed, so incomplete (below)
        cells[i].reason = "no window: the curvature bound is too large for the ball";
        return;
      }
      const IA s = IA(phi) - IA(rg) + IA(delta_max);
      o.window = (IA(2) * s * IA(rg) + exact::square(s)).sup();
    }
    cells[i] = analyse_restricted_cell(F, points, grid, p, o);
  });
  // Completeness: every window cell complete, and it found Del_RM's m-simplices and no other.
  std::set<std::vector<int>> S;
  for (const auto& s : R->simplices) S.insert(s.simplex);
  // Every failing cell is recorded (a place for the refiner); the first one is the reason.
  const bool covered = incomplete.empty();
  for (int p = 0; p < n && covered; ++p) {
    IntrinsicUndecidedPlace place{{p}, "", {}};
    const RestrictedCellReport& c = cells[p];
    if (static_cast<std::size_t>(p) < R->cells.size()) place.location = R->cells[p].covering_location;
    if (!balls[p].ok) {
      place.reason = "no graph ball around point " + std::to_string(p) + ": " + balls[p].why;
    } else if (!c.complete || !c.unresolved_faces.empty() || !c.face_points.empty()) {
      std::string why = c.reason;
      if (why.empty() && !c.unresolved_faces.empty()) why = c.unresolved_faces.front().reason;
      if (why.empty()) why = "Del_RM(P) has a face that is in no m-simplex";
      if (!c.undecided.empty()) {
        why += " (" + c.undecided.front().reason + ")";
        place.points = c.undecided.front().candidates, place.location = c.undecided.front().location;
      } else if (!c.unresolved_faces.empty()) {
        place.points = c.unresolved_faces.front().candidates, place.location = c.unresolved_faces.front().location;
      }
      place.reason = "the window cell of point " + std::to_string(p) + " is not complete: " + why;
    } else {
      for (const auto& v : c.vertices)
        if (!S.count(v.simplex)) {
          place.reason = "the window cell of point " + std::to_string(p) + " found a simplex that check 12 did not";
          place.points = v.simplex;
          for (const auto& iv : v.x) place.location.push_back(iv.midpoint());
          break;
        }
    }
    if (place.reason.empty()) continue;
    if (incomplete.empty()) incomplete = place.reason;
    D.undecided_places.push_back(std::move(place));
  }
  // Existence, per m-simplex of Del_RM(P).
  const ExistenceProver prover(F, points, grid, balls, delta_max);
  std::vector<Existence> proofs(R->simplices.size());
  parallel_for(R->simplices.size(), threads, [&](std::size_t i, int) {
    const RestrictedSimplex& s = R->simplices[i];
    proofs[i] = prover.prove(s.simplex, s.found_at, s.vertex.x);
  });
  std::set<std::vector<int>> seen;
  for (const auto& c : candidates) seen.insert(c);
  bool all_proven = true;
  for (const auto& c : seen) {
    const auto it = std::lower_bound(R->simplices.begin(), R->simplices.end(), c,
                                     [](const RestrictedSimplex& s, const std::vector<int>& v) { return s.simplex < v; });
    if (it != R->simplices.end() && it->simplex == c) {
      const Existence& e = proofs[it - R->simplices.begin()];
      if (e.proven) D.simplices.push_back({c, e.witness});
      else D.undecided.push_back({c, "in Del_RM(P), not proven in Del_M(P): " + e.reason}), all_proven = false;
    } else if (incomplete.empty()) {
      D.rejected.push_back({c, {{"kind", "not_intrinsic"},
                                {"simplex", c},
                                {"detail", "not an m-simplex of Del_RM(P), and every m-simplex of Del_M(P) is one (THE WINDOW)"}}});
    } else {
      D.undecided.push_back({c, "not in Del_RM(P); Del_M(P) is not known completely: " + incomplete});
    }
  }
  for (std::size_t i = 0; i < R->simplices.size(); ++i)  // (they are all candidates; a guard)
    if (!seen.count(R->simplices[i].simplex)) all_proven = false;
  D.complete = incomplete.empty() && all_proven;
  D.reason = !incomplete.empty() ? incomplete
             : all_proven        ? ""
                                 : "some m-simplices of Del_RM(P) are not proven in Del_M(P)";
  (void)spec;
  return D;
}

}  // namespace delcert::certify::detail
