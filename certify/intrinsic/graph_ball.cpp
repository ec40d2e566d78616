// THE GRAPH BALL (certify/intrinsic/graph_ball.hpp). Rounding as in general.cpp: every bound that
// decides anything in double intervals under exact::UpwardRounding or MPFR's directed roundings;
// Eigen only chooses frames and boxes.
#include "certify/intrinsic/graph_ball.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "exact/number_types.hpp"

namespace delcert::certify::detail {

exact::IntervalNumber ball_distance(const exact::Box& X, std::span<const double> q) {
  exact::IntervalNumber s(0);
  for (std::size_t v = 0; v < X.size(); ++v)
    s += exact::square(exact::to_interval_number(X[v]) - exact::IntervalNumber(q[v]));
  return exact::sqrt(s);
}

namespace {

using exact::Box;
using exact::Interval;
using IA = exact::IntervalNumber;

IA ia(const Interval& i) { return exact::to_interval_number(i); }

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


// An upper bound of the spectral norm of every symmetric matrix in the m x m interval matrix S
// (row-major; S[a][c] and S[c][a] both enclose the same entries), rounded up: the largest row sum of
// absolute values (a norm, >= the spectral radius); for m = 2 also the eigenvalue formula
// max |lambda| = |s + d| / 2 + sqrt((s - d)^2 / 4 + b^2) ([[s, b], [b, d]]), each term bounded by its
// sup over the intervals (b the intersection of the two enclosures of the off-diagonal entry).
// Call under exact::UpwardRounding.
double symmetric_norm_bound(const std::vector<IA>& S, int m) {
  auto mag = [](const IA& x) { return std::max(std::abs(x.inf()), std::abs(x.sup())); };
  double rows = 0;
  for (int a = 0; a < m; ++a) {
    IA row(0);
    for (int c = 0; c < m; ++c) row += IA(mag(S[a * m + c]));
    rows = std::max(rows, row.sup());
  }
  if (m != 2) return rows;
  const double blo = std::max(S[1].inf(), S[2].inf()), bhi = std::min(S[1].sup(), S[2].sup());
  const IA b = blo <= bhi ? IA(std::max(std::abs(blo), std::abs(bhi))) : IA(mag(S[1]));
  const IA half_sum = IA(mag(S[0] + S[3])) / IA(2), half_diff = IA(mag(S[0] - S[3])) / IA(2);
  const double eig = (half_sum + exact::sqrt(exact::square(half_diff) + exact::square(b))).sup();
  return std::isfinite(eig) ? std::min(rows, eig) : rows;
}

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
// ||H_e|| the largest row sum of absolute values (>= the spectral norm of a symmetric matrix),
// ||T^T H_e T|| bounded by symmetric_norm_bound, J enclosed in its centred form (below), and
// |II(u, u)|^2 <= sum_e (u^T H_e u)^2 / lambda_min(J J^T) (exact/geodesic_bounds.hpp's derivation).
// Every enclosure is an interval evaluation over X under upward rounding; +inf when a bound fails.
double tangential_curvature(const exact::ImplicitSystem& F, const Hessians& D, const Frame& fr, const Box& X) {
  const int N = D.N, k = D.k, m = N - k;
  std::vector<Interval> Jv, Jm;
  std::vector<double> mid(N);
  Box Xm(N);
  for (int v = 0; v < N; ++v) mid[v] = X[v].midpoint(), Xm[v] = Interval::point(mid[v]);
  if (!exact::jacobian_enclosure(F, X, Jv) || !exact::jacobian_enclosure(F, Xm, Jm)) return INFINITY;
  const std::vector<Interval>&T = fr.T_enc, &Nn = fr.Nn_enc;
  std::vector<IA> H(static_cast<std::size_t>(k) * N * N);  // H_e(X), e x N x N
  {
    exact::UpwardRounding up;
    std::vector<IA> xs(N);
    for (int v = 0; v < N; ++v) xs[v] = ia(X[v]);
    for (std::size_t i = 0; i < H.size(); ++i)
      H[i] = D.d2[i].evaluate_with<IA>(std::span<const IA>(xs), [&](std::size_t t) { return D.coef[i][t]; });
    // THE CENTRED JACOBIAN: grad F_e(x) = grad F_e(mid) + integral of H_e(mid + s (x - mid)) (x - mid)
    // ds, mid in X, X convex: grad F_e(x) in J(mid) + H_e(X) (X - mid) for x in X. Far from the
    // origin the plain evaluation over X loses to the dependency problem what this form keeps; both
    // hold J(x), so their intersection does (never empty; a guard keeps the plain one).
    for (int e = 0; e < k; ++e)
      for (int v = 0; v < N; ++v) {
        IA s = ia(Jm[e * N + v]);
        for (int w = 0; w < N; ++w) s += H[(e * N + v) * N + w] * (ia(X[w]) - IA(mid[w]));
        const Interval c = exact::to_interval(s);
        Interval& j = Jv[e * N + v];
        if (std::max(c.lo, j.lo) <= std::min(c.hi, j.hi)) j = Interval{std::max(c.lo, j.lo), std::min(c.hi, j.hi)};
      }
  }
  const double lmin = exact::gram_eigenvalue_bounds(Jv, k, N).lower;
  if (!(lmin > 0)) return INFINITY;
  exact::UpwardRounding up;
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
  for (int e = 0; e < k; ++e) {
    const IA* He = &H[static_cast<std::size_t>(e) * N * N];
    double norm = 0;
    for (int v = 0; v < N; ++v) {
      IA row(0);
      for (int w = 0; w < N; ++w) row += IA(std::max(std::abs(He[v * N + w].inf()), std::abs(He[v * N + w].sup())));
      norm = std::max(norm, row.sup());
    }
    std::vector<IA> S(m * m);  // T^T H_e T
    for (int a = 0; a < m; ++a)
      for (int c = 0; c < m; ++c) {
        IA s(0);
        for (int v = 0; v < N; ++v) {
          IA hv(0);
          for (int w = 0; w < N; ++w) hv += He[v * N + w] * ia(T[w * m + c]);
          s += ia(T[v * m + a]) * hv;
        }
        S[a * m + c] = s;
      }
    const double tnorm = symmetric_norm_bound(S, m);
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

struct Leaf {
  Box U, H, X;
  double K = 0;
  int depth = 0;
};

// THE CURVATURE LEAVES of a cell U_c of A (slab H_c): sub-boxes U of U_c, each with the contraction
// of H_c over U (Krawczyk's, which holds the cell's points over U; H_c itself when it fails), its
// image X and a curvature bound on X (the least of exact::curvature_bound and the tangential bound
// in a frame at X's centre). They start as a grid (`sides` per side); then, while
// a budget of twice the grid lasts, the leaf with the largest bound is split in 2^m (3 times at
// most), each child bounded by the least of its own bound and its parent's (both hold on its
// points). The leaves cover the cell's graph: the largest bound, returned, bounds |II| on it. The
// selector is proved positive on every leaf of the grid (`selected`; the children's points are
// theirs). +inf when an image overflows.
double curvature_leaves(const exact::ImplicitSystem& F, const exact::CurvatureBound& curvature, const Hessians& D2,
                        const exact::ChartEnclosure& C, const Box& Uc, const Box& Hc, const exact::Polynomial* selector,
                        const std::vector<IA>& coef, int sides, std::vector<Leaf>& out, bool& selected) {
  const int N = F.ambient_dimension(), m = F.intrinsic_dimension();
  auto make = [&](const Box& U, const Box& Hp, double cap, int depth, Leaf& leaf) {
    const exact::ChartResult tight = C.enclose_in(U, Hp);
    leaf.U = U, leaf.H = tight.status == exact::ChartStatus::unique ? tight.H : Hp, leaf.depth = depth;
    if (!C.image(U, leaf.H, leaf.X)) return false;
    std::vector<double> mid(N);
    for (int v = 0; v < N; ++v) mid[v] = leaf.X[v].midpoint();
    double Kt = INFINITY;
    try {
      Kt = tangential_curvature(F, D2, make_frame(F, mid), leaf.X);
    } catch (const std::domain_error&) {
    }
    leaf.K = std::min({cap, curvature(leaf.X), Kt});
    return true;
  };
  int subs = 1;
  for (int a = 0; a < m; ++a) subs *= sides;
  std::vector<Leaf> L;
  for (int sub = 0; sub < subs; ++sub) {
    Box U = Uc;
    for (int a = 0, rest = sub; a < m; ++a, rest /= sides) {
      const double w = Uc[a].width() / sides, lo = Uc[a].lo + w * (rest % sides);
      U[a] = Interval{rest % sides == 0 ? Uc[a].lo : lo, rest % sides == sides - 1 ? Uc[a].hi : lo + w};
    }
    Leaf leaf;
    if (!make(U, Hc, INFINITY, 0, leaf)) return INFINITY;
    if (selector) {
      exact::UpwardRounding up;
      std::vector<IA> xs(N);
      for (int v = 0; v < N; ++v) xs[v] = ia(leaf.X[v]);
      if (!(selector->evaluate_with<IA>(std::span<const IA>(xs), [&](std::size_t i) { return coef[i]; }).inf() > 0)) {
        selected = false;
        return INFINITY;
      }
    }
    L.push_back(std::move(leaf));
  }
  auto less = [&](std::size_t a, std::size_t b) { return L[a].K < L[b].K; };
  std::vector<std::size_t> heap(L.size());
  for (std::size_t i = 0; i < heap.size(); ++i) heap[i] = i;
  std::make_heap(heap.begin(), heap.end(), less);
  for (int budget = 2 * subs; budget > 0 && std::isfinite(L[heap.front()].K) && L[heap.front()].depth < 3;) {
    std::pop_heap(heap.begin(), heap.end(), less);
    const std::size_t top = heap.back();
    heap.pop_back();
    const Leaf parent = L[top];
    for (int child = 0; child < (1 << m); ++child, --budget) {
      Box U = parent.U;
      for (int a = 0; a < m; ++a) {
        const double midp = parent.U[a].midpoint();
        U[a] = (child >> a) & 1 ? Interval{midp, parent.U[a].hi} : Interval{parent.U[a].lo, midp};
      }
      Leaf leaf;
      if (!make(U, parent.H, parent.K, parent.depth + 1, leaf)) return INFINITY;
      if (child == 0) L[top] = std::move(leaf), heap.push_back(top);
      else L.push_back(std::move(leaf)), heap.push_back(L.size() - 1);
      std::push_heap(heap.begin(), heap.end(), less);
    }
  }
  const double K = L[heap.front()].K;
  for (auto& leaf : L) out.push_back(std::move(leaf));
  return K;
}

// The profile of B (GraphBall::local_K): per leaf, inf |x - q| over its X rounded down, sorted, with
// the running max of the leaves' bounds.
void set_profile(GraphBall& B, const std::vector<Leaf>& leaves, std::span<const double> q) {
  std::vector<std::pair<double, double>> p;
  for (const Leaf& leaf : leaves) {
    exact::UpwardRounding up;
    p.emplace_back(ball_distance(leaf.X, q).inf(), leaf.K);
  }
  std::sort(p.begin(), p.end());
  double run = 0;
  for (auto& [d, k] : p) run = std::max(run, k), k = run;
  B.profile = std::move(p);
}

}  // namespace

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
    // Grids of 1, 2, 4 cells per side (and 8 for m <= 2), each tried twice (the second time reaching
    // farther when the first did not reach far enough).
    for (int attempt = 0; attempt < (m <= 2 ? 8 : 6); ++attempt) {
      B.n = 1 << (attempt / 2);
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
      // s > 0 there. The leaves' bounds also give the local profile (GraphBall::local_K).
      double K = 0;
      bool selected = true;
      std::vector<Leaf> leaves;
      for (std::size_t c = 0; c < B.in_A.size() && selected && K < INFINITY; ++c) {
        if (!B.in_A[c]) continue;
        const int sides = B.n >= 8 ? 2 : m <= 2 ? 8 : 4;  // (about as many leaves in all at n = 8 as at 4)
        K = std::max(K, curvature_leaves(F, curvature, D2, C, B.cell_box(static_cast<int>(c)), B.H[c], selector, coef,
                                         sides, leaves, selected));
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
      const double phi = std::isfinite(K) ? exact::chord_to_geodesic_upper(K, t) : INFINITY;
      if (!std::isfinite(phi)) {  // (an infinite double must never enter an interval)
        B.why = "the curvature bound around the point is too large for its graph";
        continue;
      }
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
      set_profile(B, leaves, x);
      return B;
    }
  } catch (const std::domain_error& e) {
    B.why = e.what();
  }
  if (B.why.empty()) B.why = "the chart of the point does not prove M a graph around it";
  return B;
}

}  // namespace delcert::certify::detail
