#include "core/tangential/tangent_planes.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "core/support/parallel.hpp"

namespace delcert::tangential {

using support::parallel_chunks;

void TangentPlanes::push_back(std::span<const double> basis) {
  const std::size_t s = static_cast<std::size_t>(N_) * m_;
  if (s == 0 || basis.size() != s)
    throw std::invalid_argument("tangent basis has " + std::to_string(basis.size()) + " entries, expected N*m = " +
                                std::to_string(s));
  for (int a = 0; a < m_; ++a)
    for (int b = a; b < m_; ++b) {
      double dot = 0;
      for (int k = 0; k < N_; ++k) dot += basis[a * N_ + k] * basis[b * N_ + k];
      double expected = a == b ? 1.0 : 0.0;
      if (!std::isfinite(dot) || std::abs(dot - expected) > 1e-9)
        throw std::invalid_argument("tangent basis " + std::to_string(size()) +
                                    " is not orthonormal (orthonormalise it, e.g. with a QR factorisation)");
    }
  bases_.insert(bases_.end(), basis.begin(), basis.end());
}

void TangentPlanes::push_back(const Eigen::MatrixXd& tangent) {
  if (tangent.rows() != N_ || tangent.cols() != m_)
    throw std::invalid_argument("tangent basis is " + std::to_string(tangent.rows()) + " by " +
                                std::to_string(tangent.cols()) + ", expected N by m = " + std::to_string(N_) + " by " +
                                std::to_string(m_));
  push_back(std::span<const double>(tangent.data(), static_cast<std::size_t>(tangent.size())));
}

void extend_tangent_planes(const manifold::Manifold& manifold, const io::PointSet& points, TangentPlanes& planes) {
  const int N = manifold.ambient_dimension(), m = manifold.intrinsic_dimension();
  if (points.dimension != N)
    throw std::invalid_argument("points have dimension " + std::to_string(points.dimension) + ", the manifold N = " +
                                std::to_string(N));
  if (planes.size() == 0 && planes.ambient_dimension() == 0) planes = TangentPlanes(N, m);
  for (std::size_t i = planes.size(); i < points.size(); ++i) {
    auto frame = manifold.frame(points.point(i));
    if (!frame)
      throw std::domain_error("point " + std::to_string(i) +
                              ": the Jacobian of F is rank deficient there, so T_p is undefined; is the point on M?");
    planes.push_back(frame->tangent);
  }
}

TangentPlanes compute_tangent_planes(const manifold::Manifold& manifold, const io::PointSet& points, int threads) {
  const int N = manifold.ambient_dimension(), m = manifold.intrinsic_dimension();
  if (points.dimension != N)
    throw std::invalid_argument("points have dimension " + std::to_string(points.dimension) + ", the manifold N = " +
                                std::to_string(N));
  const std::size_t n = points.size(), s = static_cast<std::size_t>(N) * m;
  std::vector<double> bases(n * s);
  std::vector<char> ok(n, 0);
  parallel_chunks(n, threads, 256, [&](int) {
    return [&](std::size_t b, std::size_t e) {
      for (std::size_t i = b; i < e; ++i) {
        auto frame = manifold.frame(points.point(i));
        if (!frame) continue;
        std::copy(frame->tangent.data(), frame->tangent.data() + s, bases.begin() + i * s);
        ok[i] = 1;
      }
    };
  });
  TangentPlanes planes(N, m);
  planes.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    if (!ok[i])
      throw std::domain_error("point " + std::to_string(i) +
                              ": the Jacobian of F is rank deficient there, so T_p is undefined; is the point on M?");
    planes.push_back(std::span<const double>(bases.data() + i * s, s));
  }
  return planes;
}

}  // namespace delcert::tangential
