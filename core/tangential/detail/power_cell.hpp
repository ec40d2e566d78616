// Internal to core/tangential: the power cell of p in T_p by certified halfspace clipping.
//
// p sits at the origin of the local coordinates; neighbour q contributes the halfspace
// h_q = { x : 2 u_q . x <= a_q } with a_q = ||u_q||^2 - w_q (see local_problem.hpp). The cell
// starts as a box [-L, L]^M (2M artificial halfspaces, L a power of two) and is clipped by the
// neighbours' halfspaces one at a time. It stays a *simple* polytope: every vertex lies on
// exactly M facets, because a vertex found within rounding of a new hyperplane stops the
// computation (Status::uncertain) and the caller falls back to the exact regular triangulation.
//
// Exactness. A vertex v_S (facets S = {f_1 < ... < f_M}) is stored homogeneously as the last
// row cofactors lambda of the (M+1) by (M+1) matrix [[u_f a_f]_{f in S}; x]: for a halfspace
// x = (u, a), det = sum_j x_j lambda_j = det(U_S) (a - 2 u . v_S). With lambda_M = det(U_S)
// made positive, sign(sum_j x_j lambda_j) says whether v_S is strictly inside h (q outside the
// ball of the cell) or outside. The determinants are evaluated by Laplace expansion in double
// together with their permanents |.|, and the forward error bound
//     |computed - exact| <= K eps sum_j |x_j| perm_j,  K = 2 (M(M+1)/2 + 5M + 4)
// covers the M(M+1)/2 roundings along a Laplace term, the 2M roundings of a_q = fl(||u||^2 - w),
// and the M+1 roundings of the final dot product, with a factor 2 to spare (eps = 2^-53). A sign
// is used only when the computed value exceeds that bound, so every combinatorial decision is
// the exact one for the rounded input (u_q, w_q).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

namespace delcert::tangential::detail {

template <int M>
class PowerCell {
  static_assert(M >= 2 && M <= 4, "power cells are implemented for m = 2, 3, 4");

 public:
  static constexpr int kBoxFacets = 2 * M;  // halfspace ids 0 .. 2M-1: x_j <= L (2j), -x_j <= L (2j+1)
  enum class Status { ok, uncertain };

  struct Vertex {
    std::array<int, M> f;             // sorted facet (halfspace) ids
    std::array<int, M> adj;           // adj[j]: the vertex across the edge that leaves facet f[j]
    std::array<double, M + 1> lam;    // homogeneous coordinates (cofactors), lam[M] = det U_S > 0
    std::array<double, M + 1> err;    // K eps perm_j: the test bound is sum_j |x_j| err_j
    double r2 = 0;                    // rigorous upper bound of ||v||^2
    bool box = false;                 // has a box facet
    bool alive = false;
  };

  // Starts over with the box [-L, L]^M.
  Status reset(double L) {
    hs_.clear();
    verts_.clear();
    free_.clear();
    for (int j = 0; j < M; ++j)
      for (int s = 0; s < 2; ++s) {
        Halfspace h{};
        h.u[j] = s ? -1.0 : 1.0;
        h.abs_u[j] = 1.0;
        h.a = 2 * L;  // exact: L is a power of two
        h.norm_u = 1.0;
        hs_.push_back(h);
      }
    for (int b = 0; b < (1 << M); ++b) {
      Vertex v{};
      for (int j = 0; j < M; ++j) {
        v.f[j] = 2 * j + ((b >> j) & 1);
        v.adj[j] = b ^ (1 << j);
      }
      v.box = true;
      v.alive = true;
      if (!compute(v)) return Status::uncertain;  // cannot happen: the box corners are exact
      verts_.push_back(v);
    }
    alive_ = 1 << M;
    box_vertices_ = alive_;
    r2max_ = std::numeric_limits<double>::infinity();
    return Status::ok;
  }

  // Adds the halfspace 2 u.x <= a (u: M doubles; a = fl(||u||^2 - w), see the error model) as
  // the next facet id and clips the cell with it.
  Status clip(const double* u, double a) {
    Halfspace h{};
    double n2 = 0;
    for (int j = 0; j < M; ++j) h.u[j] = u[j], h.abs_u[j] = std::abs(u[j]), n2 += u[j] * u[j];
    h.a = a;
    h.norm_u = std::sqrt(n2);
    const int id = static_cast<int>(hs_.size());
    hs_.push_back(h);
    // Quick accept: for ||v|| <= R, 2 u.v <= 2 ||u|| R < a means the halfspace contains the whole
    // cell strictly. The margins cover the rounding of sqrt, the products and of a.
    if (box_vertices_ == 0 && 2 * h.norm_u * std::sqrt(r2max_) * (1 + 1e-12) < a * (1 - 1e-13)) return Status::ok;

    state_.assign(verts_.size(), 0);
    out_.clear();
    for (int i = 0; i < static_cast<int>(verts_.size()); ++i) {
      const Vertex& v = verts_[i];
      if (!v.alive) continue;
      double t = h.a * v.lam[M], bound = h.a * v.err[M];
      for (int j = 0; j < M; ++j) t += h.u[j] * v.lam[j], bound += h.abs_u[j] * v.err[j];
      bound = bound * (1 + 1e-12) + 1e-300;
      if (t > bound) state_[i] = 1;  // strictly inside
      else if (t < -bound) state_[i] = -1, out_.push_back(i);
      else return Status::uncertain;
    }
    if (out_.empty()) return Status::ok;
    if (out_.size() == static_cast<std::size_t>(alive_)) return Status::uncertain;  // impossible: 0 is interior

    keys_.clear();
    created_.clear();
    for (int o : out_) {
      for (int j = 0; j < M; ++j) {
        const int n = verts_[o].adj[j];
        if (state_[n] != 1) continue;
        // New vertex on the edge (o, n): the edge's M-1 facets (o's facets without f[j]) plus h.
        Vertex w{};
        int k = 0;
        for (int i = 0; i < M; ++i)
          if (i != j) w.f[k++] = verts_[o].f[i];
        w.f[M - 1] = id;  // the largest id so far: the list stays sorted
        w.adj[M - 1] = n;
        w.alive = true;
        w.box = false;
        for (int i = 0; i < M - 1; ++i) w.box = w.box || w.f[i] < kBoxFacets;
        if (!compute(w)) return Status::uncertain;
        const int wi = allocate(w);
        Vertex& nv = verts_[n];
        for (int i = 0; i < M; ++i)
          if (nv.adj[i] == o) nv.adj[i] = wi;
        created_.push_back(wi);
        // The other edges of w lie on h and on M-2 of the edge's facets; the vertex at their
        // other end is the new vertex sharing the same M-2 facets.
        for (int i = 0; i < M - 1; ++i) {
          std::uint64_t key = 0;
          for (int t = 0; t < M - 1; ++t)
            if (t != i) key = (key << 32) | static_cast<std::uint32_t>(verts_[wi].f[t]);
          keys_.push_back({key, wi, i});
        }
      }
    }
    std::sort(keys_.begin(), keys_.end(), [](const Key& x, const Key& y) {
      return x.key < y.key || (x.key == y.key && (x.v < y.v || (x.v == y.v && x.slot < y.slot)));
    });
    if (keys_.size() % 2) return Status::uncertain;
    for (std::size_t i = 0; i < keys_.size(); i += 2) {
      if (keys_[i].key != keys_[i + 1].key || (i + 2 < keys_.size() && keys_[i + 2].key == keys_[i].key))
        return Status::uncertain;  // not a simple polytope: cannot happen with certified signs
      verts_[keys_[i].v].adj[keys_[i].slot] = keys_[i + 1].v;
      verts_[keys_[i + 1].v].adj[keys_[i + 1].slot] = keys_[i].v;
    }
    for (int o : out_) {
      verts_[o].alive = false;
      free_.push_back(o);
      --alive_;
      if (verts_[o].box) --box_vertices_;
    }
    for (int c : created_) {
      ++alive_;
      if (verts_[c].box) ++box_vertices_;
    }
    if (box_vertices_ == 0) {
      r2max_ = 0;
      for (const Vertex& v : verts_)
        if (v.alive) r2max_ = std::max(r2max_, v.r2);
    }
    return Status::ok;
  }

  bool bounded() const { return box_vertices_ == 0; }
  // Upper bound of max ||v||^2 over the vertices (infinite while a box facet is active).
  double max_radius2() const { return r2max_; }
  std::size_t num_facets() const { return hs_.size(); }
  const std::vector<Vertex>& vertices() const { return verts_; }  // check Vertex::alive

 private:
  struct Halfspace {
    double u[M];
    double abs_u[M];
    double a;
    double norm_u;
  };
  struct Key {
    std::uint64_t key;
    int v, slot;
  };

  static constexpr double kEps = 0x1p-53;
  static constexpr std::array<int, 32> kPopcount = [] {
    std::array<int, 32> t{};
    for (int i = 0; i < 32; ++i) t[i] = (i & 1) + (i & 2 ? 1 : 0) + (i & 4 ? 1 : 0) + (i & 8 ? 1 : 0) + (i & 16 ? 1 : 0);
    return t;
  }();
  static constexpr double kErrorFactor = 2.0 * (M * (M + 1) / 2 + 5 * M + 4) * kEps;

  int allocate(const Vertex& v) {
    if (!free_.empty()) {
      int i = free_.back();
      free_.pop_back();
      verts_[i] = v;
      state_[i] = 0;  // a new vertex is not classified in this round
      return i;
    }
    verts_.push_back(v);
    state_.push_back(0);
    return static_cast<int>(verts_.size()) - 1;
  }

  // lambda, error weights and the radius bound of v from its facets. False when det U_S has no
  // certified sign (the facets' normals are nearly dependent).
  bool compute(Vertex& v) const {
    constexpr int C = M + 1;
    constexpr int kMasks = 1 << C;
    double A[M][C];
    for (int i = 0; i < M; ++i) {
      const Halfspace& h = hs_[v.f[i]];
      for (int j = 0; j < M; ++j) A[i][j] = h.u[j];
      A[i][M] = h.a;
    }
    // D[mask]: determinant of rows (M - |mask|) .. M-1 and the columns in mask (increasing),
    // by Laplace expansion along its first row; P[mask]: the same with absolute values.
    double D[kMasks], P[kMasks];
    // Masks in increasing order: every sub-mask comes before the mask; the row is M - |mask|.
    D[0] = 1;
    P[0] = 1;
    for (int mask = 1; mask < kMasks - 1; ++mask) {
      const int r = M - kPopcount[mask];
      if (r < 0) continue;
      double s = 0, ps = 0;
      int k = 0;
      for (int c = 0; c < C; ++c) {
        if (!(mask & (1 << c))) continue;
        const int sub = mask ^ (1 << c);
        const double term = A[r][c] * D[sub];
        s = (k & 1) ? s - term : s + term;
        ps += std::abs(A[r][c]) * P[sub];
        ++k;
      }
      D[mask] = s;
      P[mask] = ps;
    }
    const int full = kMasks - 1;
    for (int j = 0; j < C; ++j) {
      const double minor = D[full ^ (1 << j)];
      v.lam[j] = ((M + j) & 1) ? -minor : minor;  // cofactor (-1)^(M+j) of the last row
      v.err[j] = kErrorFactor * P[full ^ (1 << j)];
    }
    if (!(std::abs(v.lam[M]) > v.err[M] * (1 + 1e-12) + 1e-300)) return false;
    if (v.lam[M] < 0)
      for (double& l : v.lam) l = -l;
    // v_j = -lam_j / (2 lam_M); bound |lam_j| from above and lam_M from below.
    const double den = 2 * (v.lam[M] - v.err[M]);
    double r2 = 0;
    for (int j = 0; j < M; ++j) {
      const double c = (std::abs(v.lam[j]) + v.err[j]) / den;
      r2 += c * c;
    }
    v.r2 = r2 * (1 + 1e-12);
    return std::isfinite(v.r2);
  }

  std::vector<Halfspace> hs_;
  std::vector<Vertex> verts_;
  std::vector<int> free_, out_, created_;
  std::vector<signed char> state_;
  std::vector<Key> keys_;
  int alive_ = 0, box_vertices_ = 0;
  double r2max_ = std::numeric_limits<double>::infinity();
};

}  // namespace delcert::tangential::detail
