#include "core/refine/simplex_measures.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace delcert::refine {

const char* to_string(SimplexQuality q) {
  switch (q) {
    case SimplexQuality::good: return "good";
    case SimplexQuality::flake: return "flake";
    case SimplexQuality::bad: return "bad";
  }
  return "?";
}

SimplexGeometry::SimplexGeometry(std::span<const std::span<const double>> vertices) {
  k_ = static_cast<int>(vertices.size());
  if (k_ < 1 || k_ > kMaxSimplexVertices)
    throw std::invalid_argument("SimplexGeometry: a simplex needs 1 to 6 vertices");
  const std::size_t N = vertices[0].size();
  for (const auto& v : vertices)
    if (v.size() != N) throw std::invalid_argument("SimplexGeometry: vertices of different dimensions");
  H_.setZero(k_, k_);
  // Dot products of the difference vectors (each difference is one rounding).
  for (int u = 1; u < k_; ++u)
    for (int v = u; v < k_; ++v) {
      double s = 0;
      for (std::size_t c = 0; c < N; ++c) {
        double du = vertices[u][c] - vertices[0][c];
        double dv = vertices[v][c] - vertices[0][c];
        s += du * dv;
      }
      H_(u, v) = H_(v, u) = s;
    }
}

SimplexGeometry SimplexGeometry::from_gram(const SmallMatrix& H) {
  if (H.rows() < 1 || H.rows() > kMaxSimplexVertices || H.rows() != H.cols())
    throw std::invalid_argument("SimplexGeometry::from_gram: needs a square matrix of size 1 to 6");
  SimplexGeometry g;
  g.k_ = static_cast<int>(H.rows());
  g.H_ = H;
  return g;
}

double SimplexGeometry::squared_distance(int u, int v) const {
  if (u == v) return 0;
  // |v_u - v_v|^2 = H_uu + H_vv - 2 H_uv (H row/col 0 is zero, so this also covers vertex 0).
  return std::max(0.0, H_(u, u) + H_(v, v) - 2 * H_(u, v));
}

SimplexGeometry::SmallMatrix SimplexGeometry::face_gram(FaceMask face, int* origin) const {
  int idx[kMaxSimplexVertices];
  int n = 0;
  for (int u = 0; u < k_; ++u)
    if (face & (FaceMask{1} << u)) idx[n++] = u;
  SmallMatrix G(std::max(0, n - 1), std::max(0, n - 1));
  if (origin) *origin = n ? idx[0] : -1;
  if (n <= 1) return G;
  const int a = idx[0];
  for (int s = 1; s < n; ++s)
    for (int t = s; t < n; ++t) {
      // (v_s - v_a).(v_t - v_a) = H_st - H_sa - H_at + H_aa
      double g = H_(idx[s], idx[t]) - H_(idx[s], a) - H_(a, idx[t]) + H_(a, a);
      G(s - 1, t - 1) = G(t - 1, s - 1) = g;
    }
  return G;
}

namespace {

double small_determinant(const SimplexGeometry::SmallMatrix& G) {
  const auto n = G.rows();
  if (n == 0) return 1.0;
  if (n == 1) return G(0, 0);
  if (n == 2) return G(0, 0) * G(1, 1) - G(0, 1) * G(1, 0);
  return G.partialPivLu().determinant();
}

}  // namespace

double SimplexGeometry::gram_determinant(FaceMask face) const { return small_determinant(face_gram(face)); }

double SimplexGeometry::longest_edge(FaceMask face) const {
  double best = 0;
  for (int u = 0; u < k_; ++u)
    if (face & (FaceMask{1} << u))
      for (int v = u + 1; v < k_; ++v)
        if (face & (FaceMask{1} << v)) best = std::max(best, squared_distance(u, v));
  return std::sqrt(best);
}

double SimplexGeometry::shortest_edge(FaceMask face) const {
  double best = std::numeric_limits<double>::infinity();
  for (int u = 0; u < k_; ++u)
    if (face & (FaceMask{1} << u))
      for (int v = u + 1; v < k_; ++v)
        if (face & (FaceMask{1} << v)) best = std::min(best, squared_distance(u, v));
  return std::isinf(best) ? 0.0 : std::sqrt(best);
}

double SimplexGeometry::altitude(int u, FaceMask face) const {
  if (!(face & (FaceMask{1} << u))) throw std::invalid_argument("SimplexGeometry::altitude: vertex not in face");
  const FaceMask facet = face & ~(FaceMask{1} << u);
  if (facet == 0) return 0;
  const double dg = gram_determinant(face);
  const double df = gram_determinant(facet);
  // Relative test: the facet is non-degenerate when its Gram determinant is not negligible
  // against the product of its squared edge lengths (Hadamard's bound).
  double scale = 1;
  {
    int o;
    auto G = face_gram(facet, &o);
    for (int i = 0; i < G.rows(); ++i) scale *= G(i, i);
  }
  if (df > 1e-13 * scale && df > 0) return std::sqrt(std::max(0.0, dg) / df);
  // Degenerate facet: project v_u onto the affine hull of the facet by least squares.
  int origin;
  auto G = face_gram(facet, &origin);
  if (G.rows() == 0) return std::sqrt(squared_distance(u, origin));
  Eigen::VectorXd b(G.rows());
  int r = 0;
  for (int t = 0; t < k_; ++t)
    if ((facet & (FaceMask{1} << t)) && t != origin) {
      b[r++] = H_(u, t) - H_(u, origin) - H_(origin, t) + H_(origin, origin);
    }
  Eigen::MatrixXd Gd = G;
  Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod(Gd);
  Eigen::VectorXd lambda = cod.solve(b);
  double d2 = squared_distance(u, origin) - b.dot(lambda);
  return std::sqrt(std::max(0.0, d2));
}

double SimplexGeometry::thickness(FaceMask face) const {
  const int n = face_size(face);
  if (n <= 1) return 1.0;
  const int j = n - 1;
  const double delta = longest_edge(face);
  if (!(delta > 0)) return 0.0;
  if (j == 1) return 1.0;  // D = the edge length = Δ
  // Altitudes from one factorisation of the face's Gram matrix G (origin a = its lowest vertex):
  // by Cramer, (G^-1)_uu = det G(face \ u) / det G(face), so D_u^2 = det G(face) / det G(face \ u)
  // = 1 / (G^-1)_uu; for the origin itself, D_a^2 = 1 / (1^T G^-1 1) (the distance from a to the
  // affine hull of the others). A G that is not positive definite to working precision is a
  // degenerate face: thickness 0.
  const SmallMatrix G = face_gram(face);
  Eigen::LDLT<SmallMatrix> ldlt(G);
  if (ldlt.info() != Eigen::Success) return 0.0;
  const auto D = ldlt.vectorD();
  const double scale = delta * delta;
  for (int u = 0; u < j; ++u)
    if (!(D[u] > 1e-15 * scale)) return 0.0;
  const SmallMatrix inv = ldlt.solve(SmallMatrix::Identity(j, j));
  double worst = inv.sum();  // 1^T G^-1 1, the origin's 1 / D^2
  for (int u = 0; u < j; ++u) worst = std::max(worst, inv(u, u));
  if (!(worst > 0)) return 0.0;
  return 1.0 / (std::sqrt(worst) * j * delta);
}

bool SimplexGeometry::face_thick(FaceMask face, double gamma0) const {
  const int j = face_size(face) - 1;
  if (j <= 0) return true;
  double power = gamma0;
  for (int i = 1; i < j; ++i) power *= gamma0;
  return thickness(face) >= power;
}

bool SimplexGeometry::is_good(double gamma0, FaceMask face) const {
  // Enumerate the sub-masks of `face` with at least two vertices.
  for (FaceMask sub = face; sub; sub = (sub - 1) & face)
    if (face_size(sub) >= 2 && !face_thick(sub, gamma0)) return false;
  return true;
}

SimplexQuality SimplexGeometry::quality(double gamma0) const {
  const FaceMask full = all();
  bool proper_bad = false;
  for (FaceMask sub = (full - 1) & full; sub; sub = (sub - 1) & full)
    if (face_size(sub) >= 2 && !face_thick(sub, gamma0)) {
      proper_bad = true;
      break;
    }
  if (proper_bad) return SimplexQuality::bad;
  if (face_thick(full, gamma0)) return SimplexQuality::good;
  return dimension() >= 2 ? SimplexQuality::flake : SimplexQuality::bad;  // a flake has dimension >= 2
}

double SimplexGeometry::goodness_ratio(double gamma0) const {
  double best = std::numeric_limits<double>::infinity();
  const FaceMask full = all();
  for (FaceMask sub = full; sub; sub = (sub - 1) & full) {
    const int j = face_size(sub) - 1;
    if (j >= 2) best = std::min(best, thickness(sub) / std::pow(gamma0, j));
  }
  return best;
}

SimplexGeometry make_simplex(const io::PointSet& points, std::span<const int> indices) {
  std::array<std::span<const double>, kMaxSimplexVertices> v;
  if (indices.size() > v.size()) throw std::invalid_argument("make_simplex: more than 6 vertices");
  for (std::size_t i = 0; i < indices.size(); ++i) v[i] = points.point(static_cast<std::size_t>(indices[i]));
  return SimplexGeometry(std::span<const std::span<const double>>(v.data(), indices.size()));
}

SimplexGeometry make_simplex(std::span<const double> extra, const io::PointSet& points, std::span<const int> indices) {
  std::array<std::span<const double>, kMaxSimplexVertices> v;
  if (indices.size() + 1 > v.size()) throw std::invalid_argument("make_simplex: more than 6 vertices");
  v[0] = extra;
  for (std::size_t i = 0; i < indices.size(); ++i) v[i + 1] = points.point(static_cast<std::size_t>(indices[i]));
  return SimplexGeometry(std::span<const std::span<const double>>(v.data(), indices.size() + 1));
}

}  // namespace delcert::refine
