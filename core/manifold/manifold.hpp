// The manifold model used by the producer, in double precision (docs/design.md §4.3, §2).
//
// M = { x in R^N : F(x) = 0 } (plus selector > 0 when the spec has one), with F the spec's
// N - m polynomials. At a point p the tangent flat is T_p = p + ker J_F(p), evaluated at p
// itself even when p is only within rounding of M (docs/design.md §2).
#pragma once

#include <Eigen/Core>

#include <optional>
#include <span>
#include <vector>

#include "exact/polynomial.hpp"
#include "io/spec.hpp"

namespace delcert::manifold {

// Orthonormal frame at a point: tangent is N by m, normal is N by (N - m); together an
// orthonormal basis of R^N with span(tangent) = ker J_F(p).
struct Frame {
  Eigen::MatrixXd tangent;  // N by m
  Eigen::MatrixXd normal;   // N by (N - m)
};

struct NewtonOptions {
  int max_iterations = 50;
  double tolerance = 1e-14;     // stop when the step is below tolerance * (1 + |x|)
  double max_distance = 0.0;    // 0: no bound; otherwise fail if the solution moves farther than this
};

class Manifold {
 public:
  explicit Manifold(io::ManifoldSpec spec);

  const io::ManifoldSpec& spec() const { return spec_; }
  int intrinsic_dimension() const { return m_; }  // m
  int ambient_dimension() const { return N_; }    // N
  int codimension() const { return N_ - m_; }

  // F(x), N - m values.
  Eigen::VectorXd evaluate(std::span<const double> x) const;
  // J_F(x), (N - m) by N.
  Eigen::MatrixXd jacobian(std::span<const double> x) const;
  // max_i |F_i(x)|
  double residual(std::span<const double> x) const;
  // True when the spec has no selector or selector(x) > 0.
  bool on_selected_component(std::span<const double> x) const;

  // The Hessian of F_i at x, N by N, from the spec's polynomial differentiated twice exactly (then
  // evaluated in doubles; no finite differences).
  Eigen::MatrixXd hessian(int i, std::span<const double> x) const;

  // κ_max(x): the largest normal curvature of M at x, max over unit tangent u of |II(u, u)| with the
  // second fundamental form II(u, v) = -J⁺ (uᵀ H_i v)_i, J⁺ = Jᵀ (J Jᵀ)⁻¹. For a unit normal ν,
  // <ν, II(u, u)> = uᵀ S_ν u with the shape operator S_ν = -Σ_i w_i Tᵀ H_i T, w = (J Jᵀ)⁻¹ J ν (T an
  // orthonormal tangent basis), so κ_max = max over unit ν of the largest |eigenvalue| of S_ν. In
  // codimension 1 there is one ν (up to sign): κ_max is exact up to rounding. In codimension k > 1
  // the max over ν is taken over a deterministic set of directions (k = 2: 64 on a half circle;
  // k >= 3: 256 quasi-random ones), then raised by alternating ascent (u the top eigenvector of S_ν,
  // ν along II(u, u)) to a local maximum: a lower ESTIMATE of κ_max, for the sizing field only
  // (nothing downstream trusts it).
  // nullopt where J_F(x) is rank deficient.
  std::optional<double> max_normal_curvature(std::span<const double> x) const;

  // Orthonormal tangent and normal bases at p, from a full QR of J_F(p)^T.
  // Returns nullopt when J_F(p) is numerically rank deficient (p is not a regular point).
  std::optional<Frame> frame(std::span<const double> p) const;

  // psi_p: the inverse of the orthogonal projection of M onto T_p near p. `y` is a point of
  // T_p (ambient coordinates); returns x on M with x - y in span(frame.normal), found by Newton
  // on t -> F(y + normal t). nullopt when Newton does not converge, the Jacobian becomes
  // singular, or x is farther than options.max_distance from y.
  std::optional<Eigen::VectorXd> psi(std::span<const double> p, const Frame& frame, const Eigen::VectorXd& y,
                                     const NewtonOptions& options = {}) const;

  // Closest point of M to x (a local minimiser of |x - z| reached from x): Gauss-Newton onto M,
  // then alternating tangent projection and psi until x - z is normal at z. nullopt on failure.
  std::optional<Eigen::VectorXd> project(std::span<const double> x, const NewtonOptions& options = {}) const;

  // A point of M equidistant from the m + 1 columns of `vertices` (N by m + 1): where the Voronoi
  // flat of the simplex they span meets M, a vertex of the restricted Voronoi diagram when no other
  // point is nearer. Newton from `start` on the N by N system F(x) = 0, (v_i - v_0)ᵀ (x - (v_i + v_0) / 2) = 0
  // (i = 1..m). nullopt when Newton does not converge, the system becomes singular (the flat is
  // tangent to M) or x moves farther than options.max_distance from start. Throws
  // std::invalid_argument unless vertices has m + 1 columns of dimension N.
  std::optional<Eigen::VectorXd> equidistant_point(const Eigen::MatrixXd& vertices, const Eigen::VectorXd& start,
                                                   const NewtonOptions& options = {}) const;

 private:
  io::ManifoldSpec spec_;
  int m_ = 0, N_ = 0;
  std::vector<exact::DoublePolynomial> f_;
  std::vector<std::vector<exact::DoublePolynomial>> df_;  // df_[i][j] = dF_i / dx_j
  std::vector<std::vector<exact::DoublePolynomial>> d2f_;  // d2f_[i][j * N + l] = d²F_i / dx_j dx_l (j <= l)
  std::optional<exact::DoublePolynomial> selector_;
};

inline std::span<const double> as_span(const Eigen::VectorXd& v) {
  return {v.data(), static_cast<std::size_t>(v.size())};
}

}  // namespace delcert::manifold
