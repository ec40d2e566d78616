// Del_M(P) on a general M (certify/intrinsic/general.hpp holds the argument; docs/certificate.md
// "Del_M without a closed-form metric"). Rounding: every bound that decides anything is computed in
// double intervals under exact::UpwardRounding (CGAL's Interval_nt_advanced: outward results, an
// overflow gives an infinite or NaN bound, which decides nothing) or by exact/geodesic_bounds.hpp
// (MPFR, directed rounding). Floating-point estimates (Eigen, midpoints) only choose boxes.
#include "certify/intrinsic/general.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "certify/detail/parallel.hpp"
#include "certify/rvd.hpp"
#include "exact/chart.hpp"
#include "exact/geodesic_bounds.hpp"
#include "exact/interval_arithmetic.hpp"
#include "exact/krawczyk.hpp"
#include "exact/number_types.hpp"

namespace delcert::certify::detail {

namespace {

using exact::Box;
using exact::Interval;
using IA = exact::IntervalNumber;
using json = nlohmann::json;

IA ia(const Interval& i) { return exact::to_interval_number(i); }

// |x - q| over the box X, enclosed (call under UpwardRounding).
IA distance(const Box& X, std::span<const double> q) {
  IA s(0);
  for (std::size_t v = 0; v < X.size(); ++v) s += exact::square(ia(X[v]) - IA(q[v]));
  return exact::sqrt(s);
}

// Gauss-Jordan on the exact n x w matrix G (row-major), first n columns reduced to the identity.
// False when they are singular.
bool gauss_jordan(std::vector<mpq_class>& G, int n, int w) {
  for (int c = 0; c < n; ++c) {
    int piv = c;
    while (piv < n && G[piv * w + c] == 0) ++piv;
    if (piv == n) return false;
    for (int j = 0; j < w; ++j) std::swap(G[c * w + j], G[piv * w + j]);
    const mpq_class inv = 1 / G[c * w + c];
    for (int j = 0; j < w; ++j) G[c * w + j] *= inv;
    for (int i = 0; i < n; ++i)
      if (i != c && G[i * w + c] != 0) {
        const mpq_class f = G[i * w + c];
        for (int j = 0; j < w; ++j) G[i * w + j] -= f * G[c * w + j];
      }
  }
  return true;
}

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
  // d_M(x, q') <= this for every x in X ∩ Y_q (the caller checked contains(X)), rounded up.
  double upper(const Box& X, std::span<const double> q) const {
    double t;
    {
      exact::UpwardRounding up;
      t = (distance(X, q) + IA(delta)).sup();
    }
    return exact::chord_to_geodesic_upper(K, t);
  }
};

// A FRAME at a point x: Nn a nearly orthonormal normal basis (Eigen's SVD of J_F(x), doubles, exact
// as they are) and T a nearly orthonormal tangent basis made EXACTLY orthogonal to Nn (T = T0 - Nn
// (Nn^T Nn)^-1 Nn^T T0, T0 Eigen's doubles). Throws std::domain_error when J_F(x) is rank deficient.
struct Frame {
  std::vector<mpq_class> T, Nn;  // N x m, N x k, row-major, exact
  std::vector<Interval> T_enc, Nn_enc;
  double gT = 0, GN = INFINITY;  // <= lambda_min(T^T T), >= lambda_max(Nn^T Nn), by Gershgorin
};
Frame make_frame(const exact::ImplicitSystem& F, std::span<const double> x) {
  const int N = F.ambient_dimension(), k = F.codimension(), m = N - k;
  const Eigen::MatrixXd Jd = F.jacobian(x);
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(Jd, Eigen::ComputeFullV);
  const Eigen::MatrixXd V = svd.matrixV();  // first k columns: the normal space; last m: ker J
  if (!V.allFinite() || !(svd.singularValues().minCoeff() > 0)) throw std::domain_error("frame: J_F is rank deficient");
  std::vector<mpq_class> W(k * N);  // Nn^T, k x N
  for (int l = 0; l < k; ++l)
    for (int v = 0; v < N; ++v) W[l * N + v] = V(v, l);
  // G = [Nn^T Nn | Nn^T T0] (k x (k + m)); after Gauss-Jordan its right block is (Nn^T Nn)^-1 Nn^T T0.
  std::vector<mpq_class> G(k * (k + m));
  for (int i = 0; i < k; ++i) {
    for (int j = 0; j < k; ++j)
      for (int v = 0; v < N; ++v) G[i * (k + m) + j] += W[i * N + v] * W[j * N + v];
    for (int a = 0; a < m; ++a)
      for (int v = 0; v < N; ++v) G[i * (k + m) + k + a] += W[i * N + v] * mpq_class(V(v, k + a));
  }
  if (!gauss_jordan(G, k, k + m)) throw std::domain_error("frame: J_F is rank deficient");
  Frame f;
  f.T.resize(N * m), f.Nn.resize(N * k);
  for (int v = 0; v < N; ++v) {
    for (int l = 0; l < k; ++l) f.Nn[v * k + l] = W[l * N + v];
    for (int a = 0; a < m; ++a) {
      mpq_class t = V(v, k + a);
      for (int l = 0; l < k; ++l) t -= W[l * N + v] * G[l * (k + m) + k + a];
      f.T[v * m + a] = t;
    }
  }
  for (const auto& q : f.T) f.T_enc.push_back(exact::enclose(q));
  for (const auto& q : f.Nn) f.Nn_enc.push_back(exact::enclose(q));
  auto gersh = [&](const std::vector<mpq_class>& A, int d, bool lower) {
    double best = lower ? INFINITY : 0;
    for (int i = 0; i < d; ++i) {
      mpq_class diag = 0, off = 0;
      for (int j = 0; j < d; ++j) {
        mpq_class gij = 0;
        for (int v = 0; v < N; ++v) gij += A[v * d + i] * A[v * d + j];
        if (i == j) diag = gij; else off += abs(gij);
      }
      best = lower ? std::min(best, exact::enclose(diag - off).lo) : std::max(best, exact::enclose(diag + off).hi);
    }
    return best;
  };
  f.gT = gersh(f.T, m, true), f.GN = gersh(f.Nn, k, false);
  if (!(f.gT > 0)) throw std::domain_error("frame: the tangent basis is degenerate");
  return f;
}

// The orthogonal chart at q (GraphBall): the frame at q. Throws std::domain_error.
exact::ChartEnclosure orthogonal_chart(const exact::ImplicitSystem& F, std::span<const double> q) {
  Frame f = make_frame(F, q);
  return exact::ChartEnclosure(F, q, std::move(f.T), std::move(f.Nn));
}

// F's second derivatives, prepared once (exact polynomials and their coefficients' enclosures).
struct Hessians {
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
      for (const auto& t : P.terms()) coef.back().push_back(ia(exact::enclose(t.coefficient)));
    }
  }
};

// THE TANGENTIAL CURVATURE BOUND on a box X, in a frame (T, Nn) (T^T Nn = 0 exactly; g_T, G_N its
// Gram bounds; any frame is valid, one taken at X's centre makes the tilt small). exact::curvature_bound bounds |II(u, u)| by the Hessians' norms in
// every direction, the normal ones included (twice the truth on a torus of revolution); here only
// their tangential part counts, up to the tilt. For x in X (J = J_F(x) of rank k) and u a unit
// tangent vector at x: u = a + n, a = T alpha, n = Nn beta (|a|^2 + |n|^2 = 1). J u = 0 gives
// (J Nn) beta = -(J T) alpha, so |beta| <= ||J T||_F |alpha| / sigma_min(J Nn), |alpha| <= |a| /
// sqrt(g_T), and |n| <= sqrt(G_N) |beta| <= tau |a| with tau = sqrt(G_N / g_T) ||J T||_F /
// sigma_min(J Nn) (sigma_min^2 from gram_eigenvalue_bounds on the k x k matrix J Nn). Then
//   |u^T H_e u| <= |alpha^T (T^T H_e T) alpha| + 2 |a| |n| ||H_e|| + |n|^2 ||H_e||
//               <= ||T^T H_e T|| / g_T + (2 tau + tau^2) ||H_e||,
// ||.|| the largest row sum of absolute values (>= the spectral norm of a symmetric matrix), and
// |II(u, u)|^2 <= sum_e (u^T H_e u)^2 / lambda_min(J J^T) (exact/geodesic_bounds.hpp's derivation).
// Every enclosure is an interval evaluation over X under upward rounding; +inf when a bound fails.
double tangential_curvature(const exact::ImplicitSystem& F, const Hessians& D, const Frame& fr, const Box& X) {
  const int N = D.N, k = D.k, m = N - k;
  std::vector<Interval> Jv;
  if (!exact::jacobian_enclosure(F, X, Jv)) return INFINITY;
  const double lmin = exact::gram_eigenvalue_bounds(Jv, k, N).lower;
  if (!(lmin > 0)) return INFINITY;
  const std::vector<Interval>&T = fr.T_enc, &Nn = fr.Nn_enc;
  exact::UpwardRounding up;
  std::vector<IA> xs(N);
  for (int v = 0; v < N; ++v) xs[v] = ia(X[v]);
  // J T (k x m), J Nn (k x k).
  IA jt2(0);
  std::vector<Interval> JN(k * k);
  for (int e = 0; e < k; ++e) {
    for (int a = 0; a < m; ++a) {
      IA s(0);
      for (int v = 0; v < N; ++v) s += ia(Jv[e * N + v]) * ia(T[v * m + a]);
      jt2 += exact::square(s);
    }
    for (int l = 0; l < k; ++l) {
      IA s(0);
      for (int v = 0; v < N; ++v) s += ia(Jv[e * N + v]) * ia(Nn[v * k + l]);
      JN[e * k + l] = exact::to_interval(s);
    }
  }
  const double smin2 = exact::gram_eigenvalue_bounds(JN, k, k).lower;
  exact::UpwardRounding up2;  // (gram_eigenvalue_bounds restores the mode it found; to be safe)
  if (!(smin2 > 0)) return INFINITY;
  const IA tau = exact::sqrt(IA(fr.GN) / IA(fr.gT) * jt2 / IA(smin2));
  IA b2(0);
  std::vector<IA> H(N * N);
  for (int e = 0; e < k; ++e) {
    double norm = 0;
    for (int v = 0; v < N; ++v) {
      IA row(0);
      for (int w = 0; w < N; ++w) {
        const std::size_t i = (static_cast<std::size_t>(e) * N + v) * N + w;
        H[v * N + w] = D.d2[i].evaluate_with<IA>(std::span<const IA>(xs), [&](std::size_t t) { return D.coef[i][t]; });
        row += IA(std::max(std::abs(H[v * N + w].inf()), std::abs(H[v * N + w].sup())));
      }
      norm = std::max(norm, row.sup());
    }
    double tnorm = 0;  // T^T H_e T, largest row sum
    for (int a = 0; a < m; ++a) {
      IA row(0);
      for (int c = 0; c < m; ++c) {
        IA s(0);
        for (int v = 0; v < N; ++v) {
          IA hv(0);
          for (int w = 0; w < N; ++w) hv += H[v * N + w] * ia(T[w * m + c]);
          s += ia(T[v * m + a]) * hv;
        }
        row += IA(std::max(std::abs(s.inf()), std::abs(s.sup())));
      }
      tnorm = std::max(tnorm, row.sup());
    }
    const IA be = IA(tnorm) / IA(fr.gT) + (IA(2) * tau + exact::square(tau)) * IA(norm);
    b2 += exact::square(be);
  }
  const double K = exact::sqrt(b2 / IA(lmin)).sup();
  return std::isnan(K) ? INFINITY : K;
}

// The atlas A at grid size B.n over [-B.rho, B.rho]^m, cells beyond |T u| >= reach left out. False
// (B.why set) when the cells around u = 0 are not proved, two neighbouring cells of A do not agree,
// or U_Y is not inside A's domain.
bool build_atlas(GraphBall& B, double reach, double hd) {
  const exact::ChartEnclosure& C = *B.chart;
  const int m = B.m, n = B.n, k = C.codimension();
  int cells = 1;
  for (int a = 0; a < m; ++a) cells *= n;
  B.in_A.assign(cells, 0);
  B.H.assign(cells, Box());
  std::vector<char> kept(cells, 0);
  IA reach2;
  double ud;
  {
    exact::UpwardRounding up;
    reach2 = IA(reach) * IA(reach);
    ud = (IA(hd) * IA(2)).sup();  // generous: |u| of q' is below delta / sqrt(g_T), about hd
  }
  std::vector<int> origin;  // cells meeting the u-box of q'
  for (int c = 0; c < cells; ++c) {
    const Box U = B.cell_box(c);
    bool at_origin = true;
    for (int a = 0; a < m; ++a) at_origin &= U[a].lo <= ud && -ud <= U[a].hi;
    if (at_origin) origin.push_back(c);
    if (!at_origin && B.tangent2_lower(U) >= reach2.sup()) continue;
    const exact::ChartResult first = C.enclose(U);
    if (first.status != exact::ChartStatus::unique) continue;
    Box Hw = first.H;
    for (auto& i : Hw) {  // room: h(u) strictly inside (and q' at the origin); uniqueness is proved on Hw
      const double w = std::max({i.width() / 4, hd, 0x1p-30 * (std::abs(i.lo) + std::abs(i.hi)), 0x1p-1000});
      i = Interval{(at_origin ? std::min(i.lo, -hd) : i.lo) - w, (at_origin ? std::max(i.hi, hd) : i.hi) + w};
    }
    if (C.enclose_in(U, Hw).status != exact::ChartStatus::unique) continue;
    B.H[c] = std::move(Hw);
    kept[c] = 1;
  }
  for (int c : origin)
    if (!kept[c]) {
      B.why = "the chart of the point does not prove M a graph around it";
      return false;
    }
  auto agree = [&](int c, int d, int a, int dir) {  // c's face towards d (d = c + dir n^a)
    Box face = B.cell_box(c);
    face[a] = Interval::point(dir > 0 ? face[a].hi : face[a].lo);
    Box hull(k);
    for (int l = 0; l < k; ++l)
      hull[l] = Interval{std::min(B.H[c][l].lo, B.H[d][l].lo), std::max(B.H[c][l].hi, B.H[d][l].hi)};
    return C.enclose_in(face, hull).status == exact::ChartStatus::unique;
  };
  auto neighbours = [&](int c, auto&& f) {
    for (int a = 0, stride = 1; a < m; ++a, stride *= n) {
      const int i = (c / stride) % n;
      for (int dir : {-1, 1})
        if (i + dir >= 0 && i + dir < n) f(c + dir * stride, a, dir);
    }
  };
  std::vector<int> queue = origin;  // A: breadth first from the origin's cells through agreeing faces
  for (int c : origin) B.in_A[c] = 1;
  for (std::size_t head = 0; head < queue.size(); ++head)
    neighbours(queue[head], [&](int d, int a, int dir) {
      if (kept[d] && !B.in_A[d] && agree(queue[head], d, a, dir)) B.in_A[d] = 1, queue.push_back(d);
    });
  bool all = true;  // every face between two cells of A agrees (the BFS tree's were tested)
  for (int c = 0; c < cells && all; ++c)
    if (B.in_A[c])
      neighbours(c, [&](int d, int a, int dir) {
        if (all && d > c && B.in_A[d] && !agree(c, d, a, dir)) all = false;
      });
  if (!all) {
    B.why = "two neighbouring pieces of the graph around the point are not proved to agree";
    return false;
  }
  std::vector<int> cs;
  if (!B.cells_meeting(B.UY, cs)) return false;
  for (int c : cs)
    if (!B.in_A[c]) {
      B.why = "the chart of the point does not prove M a graph over its ball";
      return false;
    }
  return true;
}

// The smallest |x - q|^2 >= |T u|^2 on the faces of A's cells not shared with another cell of A
// (where a curve on A's graph could leave it), rounded down.
double exit_distance2(const GraphBall& B) {
  const int m = B.m, n = B.n;
  double low = INFINITY;
  for (std::size_t c = 0; c < B.in_A.size(); ++c) {
    if (!B.in_A[c]) continue;
    for (int a = 0, stride = 1; a < m; ++a, stride *= n) {
      const int i = (static_cast<int>(c) / stride) % n;
      for (int dir : {-1, 1}) {
        if (i + dir >= 0 && i + dir < n && B.in_A[c + dir * stride]) continue;
        Box face = B.cell_box(static_cast<int>(c));
        face[a] = Interval::point(dir > 0 ? face[a].hi : face[a].lo);
        low = std::min(low, B.tangent2_lower(face));
      }
    }
  }
  return low;
}

// THE GRAPH BALL of q for the radius r. K bounds |II| on A's graph within B(q, R + delta), R =
// f (c_Y + delta), c_Y >= max |x - q| on Y_q. Why that K serves (general.hpp's open-and-closed
// argument): a minimizing geodesic from x~ in Y_q to q' of length L < R has every point within L
// of q' (so in the open ball B(q, R + delta)); it starts on A's graph and cannot leave it there:
// where it would, at a point over u0, either every cell around u0 is in A (the graphs agree on the
// faces, h(u0) strictly inside each slab: nearby points of M are on the graph, by uniqueness), or
// u0 is on a face of A's boundary, where |x - q| >= exit distance >= R + delta (checked).
GraphBall make_ball(const exact::ImplicitSystem& F, const exact::CurvatureBound& curvature, const Hessians& D2,
                    const exact::Polynomial* selector,
                    const io::PointSet& P, int q, double delta, double r) {
  GraphBall B;
  B.delta = delta;
  const std::span<const double> x = P.point(q);
  const int N = F.ambient_dimension(), m = F.intrinsic_dimension(), k = F.codimension();
  B.m = m;
  try {
    B.chart.emplace(orthogonal_chart(F, x));
    const exact::ChartEnclosure& C = *B.chart;
    const exact::ChartEnclosure::GramBounds g = C.gram_bounds();
    B.gT = g.tangent, B.gN = g.normal;
    {  // G_T, G_N: Gershgorin on the exact Gram matrices, rounded up
      auto gersh = [&](int d, auto col) {
        double best = 0;
        for (int i = 0; i < d; ++i) {
          mpq_class row = 0;
          for (int j = 0; j < d; ++j) {
            mpq_class gij = 0;
            for (int v = 0; v < N; ++v) gij += col(v, i) * col(v, j);
            row += abs(gij);
          }
          best = std::max(best, exact::enclose(row).hi);
        }
        return best;
      };
      B.GT = gersh(m, [&](int v, int a) { return C.tangent(v, a); });
      B.GN = gersh(k, [&](int v, int l) { return C.normal(v, l); });
    }
    double hd, rhoY;
    {
      exact::UpwardRounding up;
      rhoY = (IA(r) / exact::sqrt(IA(g.tangent))).sup();  // |u| <= |T u| / sqrt(g_T)
      hd = (IA(delta) / exact::sqrt(IA(g.normal))).sup();  // |h| <= |Nn h| / sqrt(g_N), q' within delta of q
    }
    B.UY.assign(m, Interval{-rhoY, rhoY});
    {  // [T Nn]^-1, exact
      std::vector<mpq_class> G(N * 2 * N);
      for (int v = 0; v < N; ++v) {
        for (int a = 0; a < m; ++a) G[v * 2 * N + a] = C.tangent(v, a);
        for (int l = 0; l < k; ++l) G[v * 2 * N + m + l] = C.normal(v, l);
        G[v * 2 * N + N + v] = 1;
      }
      if (!gauss_jordan(G, N, 2 * N)) throw std::domain_error("graph ball: the chart's bases are singular");
      B.L.resize(N * N);
      for (int i = 0; i < N; ++i)
        for (int v = 0; v < N; ++v) B.L[i * N + v] = exact::enclose(G[i * 2 * N + N + v]);
    }
    // Sizing only: c_Y about the corner of U_Y.
    const exact::ChartResult y = C.enclose(B.UY);
    double cY_guess = r * std::sqrt(double(m)) * 1.25;
    if (y.status == exact::ChartStatus::unique) cY_guess = std::sqrt(B.dist2_upper(B.UY, y.H));
    const double cY_first = cY_guess;
    std::vector<IA> coef;
    if (selector)
      for (const auto& t : selector->terms()) coef.push_back(ia(exact::enclose(t.coefficient)));
    for (int attempt = 0; attempt < 6; ++attempt) {
      B.n = attempt < 2 ? 1 : attempt < 4 ? 2 : 4;
      if (attempt % 2 == 0) cY_guess = cY_first;
      double need;
      {
        exact::UpwardRounding up;
        need = ((IA(cY_guess) + IA(delta)) * IA(1.0625) + IA(delta)).sup();  // R + delta at f = 1.0625
        B.rho = (IA(need) * IA(1.03125) / exact::sqrt(IA(g.tangent))).sup();
      }
      if (!build_atlas(B, need, hd)) continue;
      B.why.clear();
      std::vector<int> cs;
      B.cells_meeting(B.UY, cs);
      double cY = 0;
      for (int c : cs) {
        Box U = B.cell_box(c);
        for (int a = 0; a < m; ++a) U[a] = Interval{std::max(U[a].lo, B.UY[a].lo), std::min(U[a].hi, B.UY[a].hi)};
        // The points of Y over U are the unique ones in H_c, so in the contraction of H_c over U.
        const exact::ChartResult tight = C.enclose_in(U, B.H[c]);
        const Box& Hu = tight.status == exact::ChartStatus::unique ? tight.H : B.H[c];
        exact::UpwardRounding up;
        cY = std::max(cY, exact::sqrt(IA(B.dist2_upper(U, Hu))).sup());
      }
      const double exit2 = exit_distance2(B);
      // K on every cell of A (the geodesics' region is checked against the exit distance below);
      // s > 0 there.
      double K = 0;
      bool selected = true;
      for (std::size_t c = 0; c < B.in_A.size() && selected && K < INFINITY; ++c) {
        if (!B.in_A[c]) continue;
        // On sub-boxes of the cell (s per side), each with the contraction of H_c over it (which holds
        // the cell's points over it): tighter images, a tighter K.
        const Box Uc = B.cell_box(static_cast<int>(c));
        const int sides = m <= 2 ? 8 : 4;
        int subs = 1;
        for (int a = 0; a < m; ++a) subs *= sides;
        for (int sub = 0; sub < subs && selected && K < INFINITY; ++sub) {
          Box U = Uc;
          for (int a = 0, rest = sub; a < m; ++a, rest /= sides) {
            const double w = Uc[a].width() / sides, lo = Uc[a].lo + w * (rest % sides);
            U[a] = Interval{rest % sides == 0 ? Uc[a].lo : lo, rest % sides == sides - 1 ? Uc[a].hi : lo + w};
          }
          const exact::ChartResult tight = C.enclose_in(U, B.H[c]);
          Box X;
          if (!C.image(U, tight.status == exact::ChartStatus::unique ? tight.H : B.H[c], X)) {
            K = INFINITY;
            break;
          }
          if (selector) {
            exact::UpwardRounding up;
            std::vector<IA> xs(N);
            for (int v = 0; v < N; ++v) xs[v] = ia(X[v]);
            selected = selector->evaluate_with<IA>(std::span<const IA>(xs), [&](std::size_t i) { return coef[i]; }).inf() > 0;
          }
          std::vector<double> mid(N);
          for (int v = 0; v < N; ++v) mid[v] = X[v].midpoint();
          double Kt = INFINITY;
          try {
            Kt = tangential_curvature(F, D2, make_frame(F, mid), X);
          } catch (const std::domain_error&) {
          }
          K = std::max(K, std::min(curvature(X), Kt));
        }
      }
      if (!selected) {
        B.why = "the selector is not proven positive on the graph around the point";
        continue;
      }
      // R = Φ_K(c_Y + delta) (1 + 1/64) > Φ_K(c_Y + delta); the geodesics stay in B(q, R + delta).
      double R, t, reach, KR;
      {
        exact::UpwardRounding up;
        t = (IA(cY) + IA(delta)).sup();
      }
      const double phi = exact::chord_to_geodesic_upper(K, t);
      {
        exact::UpwardRounding up;
        R = (IA(phi) * IA(1.015625)).sup();
        reach = (IA(R) + IA(delta)).sup();
        KR = (IA(K) * IA(R)).sup();
      }
      if (!(KR <= 3.14159)) {
        B.why = "the curvature bound around the point is too large for its graph";
        continue;
      }
      if (!(exit2 >= (IA(reach) * IA(reach)).sup())) {
        B.why = "the graph around the point does not reach far enough for its geodesics";
        cY_guess = R;  // the same grid once more, reaching farther
        continue;
      }
      B.K = K, B.ok = true;
      return B;
    }
  } catch (const std::domain_error& e) {
    B.why = e.what();
  }
  if (B.why.empty()) B.why = "the chart of the point does not prove M a graph around it";
  return B;
}

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
      if (exact_det(M, m) == 0) return fail(out, "the preconditioner is singular");
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
    for (double factor : {4.0, 16.0, 64.0, 256.0}) {
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
      // Emptiness: every other point certainly farther in d_M than every point of sigma, on all of X.
      double ub = 0;
      for (int i : sigma) ub = std::max(ub, balls_[i].upper(X, P_.point(i)));
      std::vector<double> centre(N);
      double rad;
      {
        exact::UpwardRounding up;
        IA r2(0);
        for (int v = 0; v < N; ++v) centre[v] = X[v].midpoint(), r2 += exact::square(IA(X[v].hi) - IA(X[v].lo));
        rad = (exact::sqrt(r2) + IA(ub) + IA(delta_max_)).sup();
      }
      double lb_min = INFINITY;
      int nearest = -1;
      for (int q : grid_.ball(centre, rad)) {
        if (std::binary_search(sigma.begin(), sigma.end(), q)) continue;
        double lb;
        {
          exact::UpwardRounding up;
          lb = (distance(X, P_.point(q)) - IA(balls_[q].delta)).inf();
        }
        if (lb < lb_min) lb_min = lb, nearest = q;
      }
      if (!(lb_min > ub)) {
        return fail(out, "point " + std::to_string(nearest) + " is not proven farther: its geodesic distance is in [" +
                             std::to_string(lb_min) + ", ...] and the simplex's is in [..., " + std::to_string(ub) + "]");
      }
      // The boundary: on each face some component of B E beats the bound of B (G - E).
      if (!boundary_ok(C, brows, Binv, sigma, p, others, U, H)) {
        last = "the distortion is not beaten on the boundary of the box";
        continue;
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
  static mpq_class exact_det(std::vector<mpq_class> M, int n) {
    mpq_class det = 1;
    for (int c = 0; c < n; ++c) {
      int piv = c;
      while (piv < n && M[piv * n + c] == 0) ++piv;
      if (piv == n) return 0;
      if (piv != c) {
        for (int j = 0; j < n; ++j) std::swap(M[c * n + j], M[piv * n + j]);
        det = -det;
      }
      det *= M[c * n + c];
      for (int i = c + 1; i < n; ++i) {
        const mpq_class f = M[i * n + c] / M[c * n + c];
        for (int j = c; j < n; ++j) M[i * n + j] -= f * M[c * n + j];
      }
    }
    return det;
  }

  // Upper bounds e_i of |G_i - E_i| on X ∩ Y (rows i of `others`): with t = |x - p_j|,
  // d_M(x, p_j')^2 - t^2 lies in [-2 t delta_j, Φ(t + delta_j)^2 - t^2], the upper end nondecreasing
  // in t (Φ' >= 1, Φ(t) >= t), so e_i = g_i + g_p + 2 max(t_i delta_i, t_p delta_p) at the sup of t.
  std::vector<double> distortion(const std::vector<int>& sigma, int p, const std::vector<int>& others, const Box& X) const {
    (void)sigma;
    auto g = [&](int j, double& tsup) {
      exact::UpwardRounding up;
      tsup = distance(X, P_.point(j)).sup();
      const double phi = exact::chord_to_geodesic_upper(balls_[j].K, (IA(tsup) + IA(balls_[j].delta)).sup());
      return (exact::square(IA(phi)) - exact::square(IA(tsup))).sup();
    };
    double tp;
    const double gp = g(p, tp);
    std::vector<double> e;
    for (int i : others) {
      double ti;
      const double gi = g(i, ti);
      exact::UpwardRounding up;
      const IA cross = IA(2) * std::max((IA(ti) * IA(balls_[i].delta)).sup(), (IA(tp) * IA(balls_[p].delta)).sup());
      e.push_back((IA(gi) + IA(gp) + cross).sup());
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
      const IA s = IA(exact::chord_to_geodesic_upper(balls[i].K, (IA(rg) + IA(delta[i])).sup())) - IA(rg) + IA(delta_max);
      o.window = (IA(2) * s * IA(rg) + exact::square(s)).sup();
    }
    cells[i] = analyse_restricted_cell(F, points, grid, p, o);
  });
  // Completeness: every window cell complete, and it found Del_RM's m-simplices and no other.
  std::set<std::vector<int>> S;
  for (const auto& s : R->simplices) S.insert(s.simplex);
  for (int p = 0; p < n && incomplete.empty(); ++p) {
    if (!balls[p].ok) {
      incomplete = "no graph ball around point " + std::to_string(p) + ": " + balls[p].why;
      break;
    }
    const RestrictedCellReport& c = cells[p];
    if (!c.complete || !c.unresolved_faces.empty() || !c.face_points.empty()) {
      std::string why = c.reason;
      if (why.empty() && !c.unresolved_faces.empty()) why = c.unresolved_faces.front().reason;
      if (why.empty()) why = "Del_RM(P) has a face that is in no m-simplex";
      if (!c.undecided.empty()) why += " (" + c.undecided.front().reason + ")";
      incomplete = "the window cell of point " + std::to_string(p) + " is not complete: " + why;
      break;
    }
    for (const auto& v : c.vertices)
      if (!S.count(v.simplex)) {
        incomplete = "the window cell of point " + std::to_string(p) + " found a simplex that check 12 did not";
        break;
      }
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
