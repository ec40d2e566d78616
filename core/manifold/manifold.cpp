#include "core/manifold/manifold.hpp"

#include <Eigen/Dense>

#include <cmath>
#include <cstdint>
#include <stdexcept>

namespace delcert::manifold {

Manifold::Manifold(io::ManifoldSpec spec) : spec_(std::move(spec)) {
  m_ = spec_.intrinsic_dimension;
  N_ = spec_.ambient_dimension;
  for (const auto& f : spec_.equations) {
    f_.emplace_back(f);
    std::vector<exact::DoublePolynomial> row;
    std::vector<exact::DoublePolynomial> second(static_cast<std::size_t>(N_) * N_);
    for (int j = 0; j < N_; ++j) {
      const exact::Polynomial dj = f.derivative(j);
      row.emplace_back(dj);
      for (int l = j; l < N_; ++l) second[static_cast<std::size_t>(j) * N_ + l] = exact::DoublePolynomial(dj.derivative(l));
    }
    df_.push_back(std::move(row));
    d2f_.push_back(std::move(second));
  }
  if (spec_.selector) selector_.emplace(*spec_.selector);
}

Eigen::VectorXd Manifold::evaluate(std::span<const double> x) const {
  Eigen::VectorXd v(codimension());
  for (int i = 0; i < codimension(); ++i) v[i] = f_[i](x);
  return v;
}

Eigen::MatrixXd Manifold::jacobian(std::span<const double> x) const {
  Eigen::MatrixXd J(codimension(), N_);
  for (int i = 0; i < codimension(); ++i)
    for (int j = 0; j < N_; ++j) J(i, j) = df_[i][j](x);
  return J;
}

Eigen::MatrixXd Manifold::hessian(int i, std::span<const double> x) const {
  Eigen::MatrixXd H(N_, N_);
  for (int j = 0; j < N_; ++j)
    for (int l = j; l < N_; ++l) H(j, l) = H(l, j) = d2f_[i][static_cast<std::size_t>(j) * N_ + l](x);
  return H;
}

std::optional<double> Manifold::max_normal_curvature(std::span<const double> x) const {
  const auto fr = frame(x);
  if (!fr) return std::nullopt;
  const int k = codimension();
  const Eigen::MatrixXd J = jacobian(x);
  const Eigen::MatrixXd JJt = J * J.transpose();
  const Eigen::LDLT<Eigen::MatrixXd> solve(JJt);
  // Tᵀ H_i T for every i (m by m), and the map from normal coordinates a (ν = normal · a) to w.
  std::vector<Eigen::MatrixXd> THT;
  for (int i = 0; i < k; ++i) THT.push_back(fr->tangent.transpose() * hessian(i, x) * fr->tangent);
  const Eigen::MatrixXd W = solve.solve(J * fr->normal);  // k by k: w = W a
  auto curvature = [&](const Eigen::VectorXd& a) {
    const Eigen::VectorXd w = W * (a / a.norm());
    Eigen::MatrixXd S = Eigen::MatrixXd::Zero(m_, m_);
    for (int i = 0; i < k; ++i) S -= w[i] * THT[i];
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(S, Eigen::EigenvaluesOnly);
    return es.eigenvalues().cwiseAbs().maxCoeff();
  };
  if (k == 1) return curvature(Eigen::VectorXd::Ones(1));
  // Codimension > 1: the best of a deterministic set of normal directions (±a give the same value),
  // then alternating ascent from it. For a fixed unit tangent u, <ν, II(u, u)> = -aᵀ Wᵀ h(u) with
  // h_i = uᵀ (Tᵀ H_i T) u is linear in a, so |II(u, u)| = |Wᵀ h(u)|: take u the top eigenvector of
  // S_ν, then a = Wᵀ h(u) / |Wᵀ h(u)|, and so on; each step can only raise the value.
  Eigen::VectorXd best_a = Eigen::VectorXd::Unit(k, 0);
  double best = curvature(best_a);
  const int samples = k == 2 ? 64 : 256;
  std::uint64_t state = 0x9e3779b97f4a7c15ull;  // a fixed splitmix64 sequence: the same directions every call
  auto uniform = [&state] {
    std::uint64_t z = (state += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return static_cast<double>((z ^ (z >> 31)) >> 11) * 0x1p-53;
  };
  for (int s = 0; s < samples; ++s) {
    Eigen::VectorXd a(k);
    if (k == 2) {
      const double t = M_PI * s / samples;
      a << std::cos(t), std::sin(t);
    } else {
      for (int i = 0; i < k; ++i) a[i] = 2 * uniform() - 1;
      if (!(a.norm() > 1e-3)) continue;
    }
    const double c = curvature(a);
    if (c > best) best = c, best_a = a / a.norm();
  }
  Eigen::VectorXd a = best_a;
  for (int it = 0; it < 50; ++it) {
    const Eigen::VectorXd w = W * a;
    Eigen::MatrixXd S = Eigen::MatrixXd::Zero(m_, m_);
    for (int i = 0; i < k; ++i) S -= w[i] * THT[i];
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(S);
    Eigen::Index top = 0;
    es.eigenvalues().cwiseAbs().maxCoeff(&top);
    const Eigen::VectorXd u = es.eigenvectors().col(top);
    Eigen::VectorXd h(k);
    for (int i = 0; i < k; ++i) h[i] = u.dot(THT[i] * u);
    const Eigen::VectorXd g = W.transpose() * h;
    const double value = g.norm();
    if (!(value > best * (1 + 1e-14))) break;
    best = value;
    a = g / value;
  }
  return best;
}

double Manifold::residual(std::span<const double> x) const { return evaluate(x).cwiseAbs().maxCoeff(); }

bool Manifold::on_selected_component(std::span<const double> x) const { return !selector_ || (*selector_)(x) > 0; }

std::optional<Frame> Manifold::frame(std::span<const double> p) const {
  const int k = codimension();
  Eigen::MatrixXd Jt = jacobian(p).transpose();  // N by k; its range is the normal space
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(Jt);
  const auto& R = qr.matrixR();
  double rmax = std::abs(R(0, 0));
  if (!(rmax > 0) || !std::isfinite(rmax)) return std::nullopt;
  for (int i = 0; i < k; ++i)
    if (std::abs(R(i, i)) <= 1e-10 * rmax) return std::nullopt;
  Eigen::MatrixXd Q = qr.householderQ() * Eigen::MatrixXd::Identity(N_, N_);
  return Frame{Q.rightCols(m_), Q.leftCols(k)};
}

std::optional<Eigen::VectorXd> Manifold::psi(std::span<const double> /*p*/, const Frame& frame, const Eigen::VectorXd& y,
                                             const NewtonOptions& options) const {
  const Eigen::MatrixXd& W = frame.normal;
  Eigen::VectorXd t = Eigen::VectorXd::Zero(codimension());
  Eigen::VectorXd x = y;
  for (int it = 0; it < options.max_iterations; ++it) {
    Eigen::VectorXd F = evaluate(as_span(x));
    Eigen::MatrixXd A = jacobian(as_span(x)) * W;
    Eigen::FullPivLU<Eigen::MatrixXd> lu(A);
    if (!lu.isInvertible()) return std::nullopt;
    Eigen::VectorXd step = lu.solve(F);
    if (!step.allFinite()) return std::nullopt;
    t -= step;
    x = y + W * t;
    if (options.max_distance > 0 && t.norm() > options.max_distance) return std::nullopt;
    if (step.norm() <= options.tolerance * (1 + x.norm())) return x;
  }
  // Accept a last iterate that satisfies the equations to rounding even if the steps stalled.
  if (residual(as_span(x)) <= 1e-13 * (1 + x.squaredNorm())) return x;
  return std::nullopt;
}

std::optional<Eigen::VectorXd> Manifold::project(std::span<const double> x0, const NewtonOptions& options) const {
  Eigen::Map<const Eigen::VectorXd> x(x0.data(), N_);
  Eigen::VectorXd z = x;
  // Gauss-Newton with minimum-norm steps: lands on M near x.
  bool converged = false;
  for (int it = 0; it < options.max_iterations && !converged; ++it) {
    Eigen::VectorXd F = evaluate(as_span(z));
    Eigen::MatrixXd J = jacobian(as_span(z));
    Eigen::MatrixXd JJt = J * J.transpose();
    Eigen::FullPivLU<Eigen::MatrixXd> lu(JJt);
    if (!lu.isInvertible()) return std::nullopt;
    Eigen::VectorXd step = J.transpose() * lu.solve(F);
    if (!step.allFinite()) return std::nullopt;
    z -= step;
    converged = step.norm() <= options.tolerance * (1 + z.norm());
  }
  if (!converged && residual(as_span(z)) > 1e-12 * (1 + z.squaredNorm())) return std::nullopt;
  // Slide along M until x - z is normal at z: z <- psi_z(projection of x onto T_z).
  for (int it = 0; it < options.max_iterations; ++it) {
    auto fr = frame(as_span(z));
    if (!fr) return std::nullopt;
    Eigen::VectorXd tangential = fr->tangent.transpose() * (x - z);
    Eigen::VectorXd y = z + fr->tangent * tangential;
    auto next = psi(as_span(z), *fr, y, options);
    if (!next) return std::nullopt;
    double move = (*next - z).norm();
    z = *next;
    if (move <= options.tolerance * (1 + z.norm()) || tangential.norm() <= options.tolerance * (1 + z.norm())) break;
  }
  if (options.max_distance > 0 && (z - x).norm() > options.max_distance) return std::nullopt;
  return z;
}

std::optional<Eigen::VectorXd> Manifold::equidistant_point(const Eigen::MatrixXd& vertices, const Eigen::VectorXd& start,
                                                            const NewtonOptions& options) const {
  const int k = codimension();
  if (vertices.rows() != N_ || vertices.cols() != m_ + 1 || start.size() != N_)
    throw std::invalid_argument("equidistant_point: needs m + 1 vertices and a start of dimension N");
  // The m equidistance equations are linear: row i - 1 is (v_i - v_0)ᵀ, right-hand side
  // (v_i - v_0)ᵀ (v_i + v_0) / 2 (|x - v_i|² = |x - v_0|² halved).
  Eigen::MatrixXd A(m_, N_);
  Eigen::VectorXd b(m_);
  for (int i = 1; i <= m_; ++i) {
    const Eigen::VectorXd d = vertices.col(i) - vertices.col(0);
    A.row(i - 1) = d.transpose();
    b[i - 1] = d.dot((vertices.col(i) + vertices.col(0)) / 2);
  }
  Eigen::VectorXd x = start;
  Eigen::VectorXd G(N_);
  Eigen::MatrixXd J(N_, N_);
  J.bottomRows(m_) = A;
  for (int it = 0; it < options.max_iterations; ++it) {
    G.head(k) = evaluate(as_span(x));
    G.tail(m_) = A * x - b;
    J.topRows(k) = jacobian(as_span(x));
    Eigen::FullPivLU<Eigen::MatrixXd> lu(J);
    if (!lu.isInvertible()) return std::nullopt;
    const Eigen::VectorXd step = lu.solve(G);
    if (!step.allFinite()) return std::nullopt;
    x -= step;
    if (options.max_distance > 0 && (x - start).norm() > options.max_distance) return std::nullopt;
    if (step.norm() <= options.tolerance * (1 + x.norm())) return x;
  }
  // As psi: a last iterate that satisfies the equations to rounding is accepted.
  if (residual(as_span(x)) <= 1e-13 * (1 + x.squaredNorm()) && ((A * x - b).array().abs() <= 1e-13 * (1 + x.squaredNorm())).all())
    return x;
  return std::nullopt;
}

}  // namespace delcert::manifold
