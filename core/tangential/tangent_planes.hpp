// Tangent planes of a point set: per point an orthonormal basis of T_p (docs/design.md §2, §4.6).
//
// The producer takes T_p = p + ker J_F(p) from Manifold::frame; callers that already have
// bases (a benchmark feeding the very same planes to GUDHI, a test with hand-made planes) pass
// them directly. Only the linear part is stored: the flat itself passes through the point.
#pragma once

#include <Eigen/Core>

#include <cstddef>
#include <span>
#include <vector>

#include "core/manifold/manifold.hpp"
#include "io/points.hpp"

namespace delcert::tangential {

class TangentPlanes {
 public:
  TangentPlanes() = default;
  TangentPlanes(int ambient_dimension, int intrinsic_dimension) : N_(ambient_dimension), m_(intrinsic_dimension) {}

  int ambient_dimension() const { return N_; }    // N
  int intrinsic_dimension() const { return m_; }  // m
  std::size_t size() const { return N_ > 0 && m_ > 0 ? bases_.size() / (static_cast<std::size_t>(N_) * m_) : 0; }

  // The basis of point i: N*m doubles, column-major (tangent vector j is basis(i)[j*N .. j*N+N-1]).
  std::span<const double> basis(std::size_t i) const {
    const std::size_t s = static_cast<std::size_t>(N_) * m_;
    return {bases_.data() + i * s, s};
  }
  Eigen::Map<const Eigen::MatrixXd> matrix(std::size_t i) const {  // N by m
    return {bases_.data() + i * N_ * m_, N_, m_};
  }

  // Appends a basis (N*m doubles, column-major). Throws std::invalid_argument when it has the
  // wrong size, is not finite, or is not orthonormal to 1e-9 (the star computation relies on
  // ||T x|| = ||x||).
  void push_back(std::span<const double> basis);
  void push_back(const Eigen::MatrixXd& tangent);  // N by m

  void reserve(std::size_t count) { bases_.reserve(count * N_ * m_); }
  const std::vector<double>& data() const { return bases_; }  // #points by N*m

 private:
  int N_ = 0, m_ = 0;
  std::vector<double> bases_;
};

// T_p for every point from Manifold::frame (the tangent block of the QR of J_F(p)^T).
// Throws std::domain_error naming the first point (0-based) where J_F is rank deficient.
TangentPlanes compute_tangent_planes(const manifold::Manifold& manifold, const io::PointSet& points, int threads = 1);

// Appends the planes of points [planes.size(), points.size()) (for the refiner after insertions).
void extend_tangent_planes(const manifold::Manifold& manifold, const io::PointSet& points, TangentPlanes& planes);

}  // namespace delcert::tangential
