#include "core/refine/weight_functions.hpp"

#include <Eigen/Cholesky>

#include <algorithm>
#include <cmath>
#include <limits>

namespace delcert::refine {

double WeightedRadiusQuadratic::argmin(double t_max) const {
  t_max = std::max(0.0, t_max);
  double best_t = 0, best = (*this)(0.0);
  if ((*this)(t_max) < best) best_t = t_max, best = (*this)(t_max);
  if (c2 > 0) {
    double t = -c1 / (2 * c2);
    if (t > 0 && t < t_max && (*this)(t) < best) best_t = t;
  }
  return best_t;
}

namespace {

using SmallMatrix = SimplexGeometry::SmallMatrix;
using SmallVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxSimplexVertices, 1>;

// G (k by k, k = #vertices - 1) and h from the geometry's Gram matrix (origin v0).
struct Normal {
  SmallMatrix G;
  SmallVector h;
  Eigen::LDLT<SmallMatrix> ldlt;
  bool ok = false;
};

Normal factor(const SimplexGeometry& tau) {
  Normal n;
  const int k = tau.num_vertices() - 1;
  if (k < 1) return n;
  const auto& H = tau.gram();
  n.G = H.block(1, 1, k, k);
  n.h.resize(k);
  for (int u = 0; u < k; ++u) n.h[u] = n.G(u, u);
  n.ldlt.compute(n.G);
  if (n.ldlt.info() != Eigen::Success) return n;
  // Positive definite to working precision: every pivot positive and not negligible against
  // the largest squared edge (a relative test, so the answer does not depend on the scale).
  const auto D = n.ldlt.vectorD();
  const double scale = n.h.maxCoeff();
  if (!(scale > 0)) return n;
  for (int u = 0; u < k; ++u)
    if (!(D[u] > 1e-14 * scale)) return n;
  n.ok = true;
  return n;
}

}  // namespace

std::optional<WeightedRadiusQuadratic> weighted_radius_quadratic(const SimplexGeometry& tau, int vertex) {
  Normal n = factor(tau);
  if (!n.ok) return std::nullopt;
  const int k = static_cast<int>(n.h.size());
  SmallVector a = n.ldlt.solve(n.h) / 2;  // λ at t = 0: the circumcentre
  SmallVector d = SmallVector::Zero(k);
  if (vertex == 0)
    d.setOnes();
  else
    d[vertex - 1] = 1;
  SmallVector y = n.ldlt.solve(d);  // G^-1 d
  WeightedRadiusQuadratic q;
  q.c0 = a.dot(n.h) / 2;                                 // a^T G a = a^T h / 2
  q.c1 = vertex == 0 ? a.sum() - 1 : -a[vertex - 1];     // 2 a^T G b - [i = 0]
  q.c2 = std::max(0.0, d.dot(y) / 4);                    // b^T G b = d^T G^-1 d / 4
  return q;
}

double weighted_radius2(const SimplexGeometry& tau, int vertex, double t) {
  auto q = weighted_radius_quadratic(tau, vertex);
  return q ? (*q)(t) : std::numeric_limits<double>::infinity();
}

std::optional<Eigen::VectorXd> weighted_centre(std::span<const std::span<const double>> vertices, int vertex, double t) {
  SimplexGeometry tau(vertices);
  Normal n = factor(tau);
  if (!n.ok) return std::nullopt;
  const int k = static_cast<int>(n.h.size());
  SmallVector rhs = n.h;
  if (vertex == 0)
    rhs.array() += t;
  else
    rhs[vertex - 1] -= t;
  SmallVector lambda = n.ldlt.solve(rhs) / 2;
  const std::size_t N = vertices[0].size();
  Eigen::VectorXd c(N);
  for (std::size_t j = 0; j < N; ++j) {
    double s = vertices[0][j];
    for (int u = 0; u < k; ++u) s += lambda[u] * (vertices[u + 1][j] - vertices[0][j]);
    c[static_cast<Eigen::Index>(j)] = s;
  }
  return c;
}

MinWeightedRadius min_weighted_radius2(const SimplexGeometry& tau, double delta0) {
  MinWeightedRadius best;
  best.radius2 = std::numeric_limits<double>::infinity();
  Normal n = factor(tau);
  if (!n.ok) return best;
  const int k = static_cast<int>(n.h.size());
  const double L = tau.shortest_edge();
  const double t_max = delta0 * delta0 * L * L;
  SmallVector a = n.ldlt.solve(n.h) / 2;
  const double c0 = a.dot(n.h) / 2;
  SmallMatrix Ginv = n.ldlt.solve(SmallMatrix::Identity(k, k));
  for (int i = 0; i <= k; ++i) {
    WeightedRadiusQuadratic q;
    q.c0 = c0;
    if (i == 0) {
      q.c1 = a.sum() - 1;
      q.c2 = std::max(0.0, Ginv.sum() / 4);
    } else {
      q.c1 = -a[i - 1];
      q.c2 = std::max(0.0, Ginv(i - 1, i - 1) / 4);
    }
    const double t = q.argmin(t_max);
    const double r2 = q(t);
    if (r2 < best.radius2) best = {r2, i, t};
  }
  return best;
}

}  // namespace delcert::refine
