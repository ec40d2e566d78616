#include "exact/krawczyk.hpp"

#include <Eigen/Core>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>

#include "exact/detail/cgal_number_types.hpp"
#include "exact/detail/interval_polynomial.hpp"
#include "exact/enclosed_polynomial.hpp"
#include "exact/number_types.hpp"
#include "exact/small_buffer.hpp"

namespace delcert::exact {

using detail::IA;

// A polynomial with the enclosures of its coefficients, prepared once and shared (immutable)
// between the systems that hold it (SquareSystem(head, tail) shares the head's rows). Every row
// is evaluated from an EnclosedPolynomial e: an exact row keeps its exact polynomial p (for its
// exact derivatives and equations()) and e = its coefficients enclosed, in p's term order; an
// ENCLOSED row (ParametricSystem::from_enclosures) has e only.
struct Prepared {
  enum class Kind { exact, enclosed };
  Polynomial p;  // the exact polynomial (empty unless kind == exact)
  Kind kind = Kind::exact;
  EnclosedPolynomial e;
};
using PreparedPtr = std::shared_ptr<const Prepared>;

// A square system is the parametric system with no parameters (m = 0): one implementation.
struct SquareSystem::Impl {
  int n = 0;                // equations and unknowns
  int m = 0;                // parameters: variables 1..m of every equation
  std::vector<PreparedPtr> f;   // in m + n variables (u, x)
  std::vector<PreparedPtr> df;  // n x n row-major: d f_i / d x_j (unknowns)
  std::vector<PreparedPtr> du;  // n x m row-major: d f_i / d u_a (parameters)
};

using detail::finite;

namespace {

PreparedPtr prepare_enclosed(EnclosedPolynomial e, Polynomial p = Polynomial(),
                             Prepared::Kind kind = Prepared::Kind::enclosed) {
  return std::make_shared<const Prepared>(Prepared{std::move(p), kind, std::move(e)});
}

PreparedPtr prepare(Polynomial p) {
  EnclosedPolynomial e = EnclosedPolynomial::from_exact(p);
  return prepare_enclosed(std::move(e), std::move(p), Prepared::Kind::exact);
}

// Encloses x^e (e >= 1) over the interval x: x^e = (x^(e/2))^2 for even e (CGAL's square: the
// exact range of a square, never below 0, tighter than x * x when x holds 0), x^(e-1) * x for odd
// e; each step encloses its power by inclusion isotonicity (the caller holds upward rounding).
IA power(const IA& x, std::uint32_t e) {
  if (e == 1) return x;
  if (e % 2 == 0) return CGAL::square(power(x, e / 2));
  return power(x, e - 1) * x;
}

// Encloses the row over the box x (the caller holds upward rounding). The row stands for every
// polynomial with its monomials and coefficients in their enclosures (an exact row: the one);
// each term is its coefficient's enclosure times enclosures of the powers of the x_v (power()),
// summed in interval arithmetic, so by inclusion isotonicity the result encloses the value of
// each of them on the box.
IA evaluate(const PreparedPtr& p, std::span<const IA> x) {
  const EnclosedPolynomial& e = p->e;
  IA sum(0);
  for (std::size_t i = 0; i < e.size(); ++i) {
    IA t = detail::to_ia(e.coefficient(i));
    const auto ex = e.exponents(i);
    for (std::size_t v = 0; v < ex.size(); ++v)
      if (ex[v] == 1) t = t * x[v];
      else if (ex[v] > 1) t = t * power(x[v], ex[v]);
    sum = sum + t;
  }
  return sum;
}


// Checks n equations in `vars` variables; `what` names the system in error messages.
void check_shape(const std::vector<Polynomial>& equations, int n, int m, const char* what) {
  if (n < 1) throw std::invalid_argument(std::string("a ") + what + " needs at least one equation");
  if (m < 0) throw std::invalid_argument(std::string("a ") + what + " needs a non-negative number of parameters");
  const int vars = m + n;
  for (std::size_t i = 0; i < equations.size(); ++i)
    if (equations[i].num_variables() != vars && !equations[i].is_zero())
      throw std::invalid_argument(std::string(what) + ": equation " + std::to_string(i + 1) + " has " +
                                  std::to_string(equations[i].num_variables()) + " variables, expected " +
                                  std::to_string(vars) +
                                  (m == 0 ? std::string(" (as many as equations)")
                                          : " (" + std::to_string(m) + " parameters + " + std::to_string(n) +
                                                " unknowns)"));
}

// Prepares n equations in m + n variables (the first m are the parameters). `what` names the
// system in error messages.
std::shared_ptr<const SquareSystem::Impl> make_system(std::vector<Polynomial> equations, int m, const char* what) {
  auto impl = std::make_shared<SquareSystem::Impl>();
  const int n = static_cast<int>(equations.size());
  check_shape(equations, n, m, what);
  const int vars = m + n;
  impl->n = n;
  impl->m = m;
  for (auto& p : equations) {
    if (p.num_variables() != vars) p = Polynomial(vars);  // the zero polynomial, over m + n variables
    impl->f.push_back(prepare(std::move(p)));
  }
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) impl->df.push_back(prepare(impl->f[i]->p.derivative(m + j)));
  for (int i = 0; i < n; ++i)
    for (int a = 0; a < m; ++a) impl->du.push_back(prepare(impl->f[i]->p.derivative(a)));
  return impl;
}

std::vector<Polynomial> polynomials(const std::vector<PreparedPtr>& f) {
  std::vector<Polynomial> out;
  for (const auto& p : f) {
    if (p->kind != Prepared::Kind::exact)
      throw std::logic_error("polynomial system: a row given by coefficient enclosures has no exact polynomial");
    out.push_back(p->p);
  }
  return out;
}

// A square system of n equations in n unknowns starting with the head's rows, its parameters
// taken as unknowns: the head's prepared rows and derivatives are shared, row i's parameter
// derivatives first, then its unknowns' (variable order). The caller appends the tail rows.
std::shared_ptr<SquareSystem::Impl> shared_head(const SquareSystem::Impl& H, int n) {
  auto impl = std::make_shared<SquareSystem::Impl>();
  impl->n = n;
  impl->f = H.f;
  for (int i = 0; i < H.n; ++i) {
    for (int a = 0; a < H.m; ++a) impl->df.push_back(H.du[i * H.m + a]);
    for (int j = 0; j < H.n; ++j) impl->df.push_back(H.df[i * H.n + j]);
  }
  return impl;
}

}  // namespace

SquareSystem::SquareSystem(std::vector<Polynomial> equations)
    : impl_(make_system(std::move(equations), 0, "square system")) {}

SquareSystem::SquareSystem(const ParametricSystem& head, std::vector<Polynomial> tail) {
  const SquareSystem::Impl& H = head.impl();
  const int n = H.n + static_cast<int>(tail.size()), vars = H.m + H.n;
  if (n != vars)
    throw std::invalid_argument("square system: " + std::to_string(H.n) + " + " + std::to_string(tail.size()) +
                                " equations in " + std::to_string(vars) + " variables");
  check_shape(tail, n, 0, "square system");
  auto impl = shared_head(H, n);
  for (auto& p : tail) {
    if (p.num_variables() != vars) p = Polynomial(vars);
    impl->f.push_back(prepare(std::move(p)));
    for (int j = 0; j < n; ++j) impl->df.push_back(prepare(impl->f.back()->p.derivative(j)));
  }
  impl_ = std::move(impl);
}

ParametricSystem ParametricSystem::from_enclosures(std::vector<EnclosedPolynomial> equations, int num_parameters) {
  const int n = static_cast<int>(equations.size()), m = num_parameters;
  if (n < 1) throw std::invalid_argument("a parametric system needs at least one equation");
  if (m < 0) throw std::invalid_argument("a parametric system needs a non-negative number of parameters");
  for (std::size_t i = 0; i < equations.size(); ++i)
    if (equations[i].num_variables() != m + n)
      throw std::invalid_argument("parametric system: equation " + std::to_string(i + 1) + " has " +
                                  std::to_string(equations[i].num_variables()) + " variables, expected " +
                                  std::to_string(m + n));
  auto impl = std::make_shared<SquareSystem::Impl>();
  impl->n = n;
  impl->m = m;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) impl->df.push_back(prepare_enclosed(equations[i].derivative(m + j)));
  for (int i = 0; i < n; ++i)
    for (int a = 0; a < m; ++a) impl->du.push_back(prepare_enclosed(equations[i].derivative(a)));
  for (auto& e : equations) impl->f.push_back(prepare_enclosed(std::move(e)));
  return ParametricSystem(std::move(impl));
}

struct EnclosedRow::Impl {
  PreparedPtr f;
  std::vector<PreparedPtr> df;  // d f / d x_j
};

EnclosedRow::EnclosedRow(EnclosedPolynomial equation) {
  auto impl = std::make_shared<Impl>();
  for (int j = 0; j < equation.num_variables(); ++j) impl->df.push_back(prepare_enclosed(equation.derivative(j)));
  impl->f = prepare_enclosed(std::move(equation));
  impl_ = std::move(impl);
}

ParametricSystem ParametricSystem::from_rows(std::span<const EnclosedRow> rows) {
  const int n = static_cast<int>(rows.size());
  if (n < 1) throw std::invalid_argument("a parametric system needs at least one equation");
  auto impl = std::make_shared<SquareSystem::Impl>();
  impl->n = n;
  impl->m = 0;
  for (int i = 0; i < n; ++i) {
    if (static_cast<int>(rows[i].impl_->df.size()) != n)
      throw std::invalid_argument("parametric system: equation " + std::to_string(i + 1) + " has " +
                                  std::to_string(rows[i].impl_->df.size()) + " variables, expected " + std::to_string(n));
    impl->f.push_back(rows[i].impl_->f);
    for (int j = 0; j < n; ++j) impl->df.push_back(rows[i].impl_->df[j]);
  }
  return ParametricSystem(std::move(impl));
}

ParametricSystem::ParametricSystem(std::vector<Polynomial> equations, int num_parameters)
    : impl_(make_system(std::move(equations), num_parameters, "parametric system")) {}

int ParametricSystem::size() const { return impl_->n; }
int ParametricSystem::num_parameters() const { return impl_->m; }
std::vector<Polynomial> ParametricSystem::equations() const { return polynomials(impl_->f); }

namespace {
Interval enclose_row(const PreparedPtr& row, std::span<const Interval> z) {
  detail::EnsureUpward guard;
  SmallBuffer<IA, 16> x(z.size());
  for (std::size_t v = 0; v < z.size(); ++v) x[v] = detail::to_ia(z[v]);
  return detail::from_ia(evaluate(row, x.span()));
}
}  // namespace

Interval ParametricSystem::enclose(int i, std::span<const Interval> z) const {
  if (i < 0 || i >= impl_->n || static_cast<int>(z.size()) != impl_->m + impl_->n)
    throw std::invalid_argument("parametric system: no such equation, or a box of the wrong dimension");
  return enclose_row(impl_->f[i], z);
}

Interval ParametricSystem::enclose_derivative(int i, int j, std::span<const Interval> z) const {
  if (i < 0 || i >= impl_->n || j < 0 || j >= impl_->n || static_cast<int>(z.size()) != impl_->m + impl_->n)
    throw std::invalid_argument("parametric system: no such derivative, or a box of the wrong dimension");
  return enclose_row(impl_->df[i * impl_->n + j], z);
}

Interval ParametricSystem::enclose_parameter_derivative(int i, int a, std::span<const Interval> z) const {
  if (i < 0 || i >= impl_->n || a < 0 || a >= impl_->m || static_cast<int>(z.size()) != impl_->m + impl_->n)
    throw std::invalid_argument("parametric system: no such parameter derivative, or a box of the wrong dimension");
  return enclose_row(impl_->du[i * impl_->m + a], z);
}

AffineExtension::AffineExtension(const ParametricSystem& head, std::vector<Interval> tail)
    : head_(head), tail_(std::move(tail)), n_(head.size() + head.num_parameters()), k_(head.size()) {
  const std::size_t width = 1 + static_cast<std::size_t>(n_), rows = static_cast<std::size_t>(head.num_parameters());
  if (tail_.size() != rows * width)
    throw std::invalid_argument("square system: " + std::to_string(head.num_parameters()) + " affine rows of " +
                                std::to_string(width) + " coefficient enclosures expected, got " +
                                std::to_string(tail_.size()) + " enclosures");
  for (const Interval& c : tail_)
    if (!(std::isfinite(c.lo) && std::isfinite(c.hi) && c.lo <= c.hi))
      throw std::invalid_argument("square system: an affine row has a non-finite or empty coefficient enclosure");
}

// The head's rows as ParametricSystem::enclose evaluates them (the evaluation SquareSystem(head,
// ...) uses too); a tail row c + l . y under upward rounding, each coefficient's enclosure times
// the exact y_j: an enclosure of the row's value for every c, l in them.
bool AffineExtension::values(std::span<const double> y, std::span<Interval> f) const {
  SmallBuffer<Interval, 16> z(n_);
  for (int v = 0; v < n_; ++v) z[v] = Interval::point(y[v]);
  for (int i = 0; i < k_; ++i) f[i] = head_.enclose(i, z.span());
  detail::EnsureUpward guard;
  for (int i = k_; i < n_; ++i) {
    const Interval* row = &tail_[static_cast<std::size_t>(i - k_) * (1 + n_)];
    IA acc = detail::to_ia(row[0]);
    for (int j = 0; j < n_; ++j) acc += detail::to_ia(row[1 + j]) * IA(y[j]);
    if (!finite(acc)) return false;
    f[i] = detail::from_ia(acc);
  }
  return true;
}

// Head row i: its parameter derivatives, then its unknowns' (variable order), over X; a tail
// row's derivatives are its coefficients' enclosures.
bool AffineExtension::jacobian(const Box& X, std::span<Interval> J) const {
  const int m = n_ - k_;
  for (int i = 0; i < k_; ++i) {
    for (int a = 0; a < m; ++a) J[i * n_ + a] = head_.enclose_parameter_derivative(i, a, X);
    for (int j = 0; j < k_; ++j) J[i * n_ + m + j] = head_.enclose_derivative(i, j, X);
  }
  for (int i = k_; i < n_; ++i)
    for (int j = 0; j < n_; ++j) J[i * n_ + j] = tail_[static_cast<std::size_t>(i - k_) * (1 + n_) + 1 + j];
  return true;
}

int SquareSystem::size() const { return impl_->n; }
std::vector<Polynomial> SquareSystem::equations() const { return polynomials(impl_->f); }

std::string_view to_string(RootStatus status) {
  switch (status) {
    case RootStatus::unique_root: return "unique_root";
    case RootStatus::no_root: return "no_root";
    case RootStatus::undecided: return "undecided";
  }
  return "unknown";
}

namespace {

// One Krawczyk operator evaluation K(U, X) (U: the parameter box, empty for a square system).
// Returns false when it cannot be evaluated (overflow, singular midpoint Jacobian); then nothing
// is known.
//
// Every interval below is an enclosure: the caller-independent EnsureUpward guard makes CGAL's
// Interval_nt_advanced round every bound outward (its lower bounds are computed as -(upward(-x)),
// so a negative overflow gives -inf, never the finite -DBL_MAX; an upper bound that overflows is
// +inf); gradual underflow is rounded in the same direction (IEEE directed rounding; the build
// uses no flush-to-zero). A non-finite bound ends the evaluation (return false), so every box
// that leaves this function has finite bounds that enclose what they claim.
// K = y - Y G(U, y) + (I - Y J_x(U, X)) (X - y), all in interval arithmetic, with Y (n x n,
// column-major) any matrix of doubles.
bool krawczyk_apply(int n, const double* Y, const double* y, const IA* fy, const IA* jx, const Box& X, Box& K) {
  K.assign(n, Interval{});
  detail::EnsureUpward guard;
  for (int i = 0; i < n; ++i) {
    IA acc = IA(y[i]);
    for (int j = 0; j < n; ++j) acc = acc - IA(Y[i + j * n]) * fy[j];
    for (int j = 0; j < n; ++j) {
      IA c = IA(i == j ? 1.0 : 0.0);
      for (int l = 0; l < n; ++l) c = c - IA(Y[i + l * n]) * jx[l * n + j];
      acc = acc + c * (IA(X[j].lo, X[j].hi) - IA(y[j]));
    }
    if (!finite(acc)) return false;
    K[i] = detail::from_ia(acc);
  }
  return true;
}

// Y := A^-1 for a small n x n A (n <= 4, both column-major, as Eigen stores them): Gauss-Jordan
// elimination with partial pivoting, in ordinary floating point (the caller's nearest rounding).
// Only a preconditioner: any Y is correct, a good one makes Krawczyk succeed. Faster than
// Eigen's FullPivLU at these sizes (the restricted Voronoi vertices' 3 x 3 and 4 x 4 systems).
// False when a pivot is 0 or not finite (A singular in floating point, or overflow).
bool small_inverse(int n, const double* A, double* Y) {
  double M[4][8];  // [A | I], row-major
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) M[i][j] = A[i + j * n], M[i][n + j] = i == j ? 1.0 : 0.0;
  for (int c = 0; c < n; ++c) {
    int best = c;
    for (int r = c + 1; r < n; ++r)
      if (std::abs(M[r][c]) > std::abs(M[best][c])) best = r;
    if (!(M[best][c] != 0 && std::isfinite(M[best][c]))) return false;
    if (best != c)
      for (int j = 0; j < 2 * n; ++j) std::swap(M[c][j], M[best][j]);
    const double inv = 1 / M[c][c];
    for (int j = 0; j < 2 * n; ++j) M[c][j] *= inv;
    for (int r = 0; r < n; ++r) {
      if (r == c || M[r][c] == 0) continue;
      const double f = M[r][c];
      for (int j = 0; j < 2 * n; ++j) M[r][j] -= f * M[c][j];
    }
  }
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) Y[i + j * n] = M[i][n + j];
  return true;
}

// The operator itself from G(U, y) (fy, n) and J_x(U, X) (jx, n x n row-major), both enclosures
// with finite bounds, at the point y of X.
template <int MaxN>
bool krawczyk_core(int n, const double* y, const IA* fy, const IA* jx, const Box& X, Box& K) {
  using Mat = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, MaxN, MaxN>;
  Mat Jmid(n, n), Y(n, n);
  // Preconditioner: inverse of the midpoint Jacobian, in ordinary floating point. Any matrix is
  // correct here; a good one makes the tests succeed.
  {
    NearestRounding nearest;
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) Jmid(i, j) = 0.5 * (jx[i * n + j].inf() + jx[i * n + j].sup());
    if (n <= 4) {  // (n = 1, a hypersurface's chart: Y = 1 * (1 / J), the double Eigen's FullPivLU gave)
      if (!small_inverse(n, Jmid.data(), Y.data())) return false;
    } else {
      Eigen::FullPivLU<Mat> lu(Jmid);
      if (!lu.isInvertible()) return false;
      Y = lu.inverse();
    }
    if (!Y.allFinite()) return false;
  }
  return krawczyk_apply(n, Y.data(), y, fy, jx, X, K);
}

template <int MaxN>
bool krawczyk_operator_impl(const SquareSystem::Impl& S, const Box& U, const Box& X, Box& K) {
  const int n = S.n, m = S.m;
  SmallBuffer<double, 8> y(n), u0(m);
  SmallBuffer<IA, 16> xs(m + n), ys(m + n), zs(m > 0 ? m + n : 0);
  SmallBuffer<IA, 8> fy(n);
  SmallBuffer<IA, 64> jx(static_cast<std::size_t>(n) * n);
  // Midpoints, clamped into X and U whatever the rounding mode (any point of X works as the
  // centre; the centred form below needs only u0 in U).
  for (int i = 0; i < n; ++i) y[i] = std::clamp(X[i].lo + 0.5 * (X[i].hi - X[i].lo), X[i].lo, X[i].hi);
  for (int a = 0; a < m; ++a) u0[a] = std::clamp(U[a].lo + 0.5 * (U[a].hi - U[a].lo), U[a].lo, U[a].hi);
  bool ok = true;
  {
    detail::EnsureUpward guard;
    for (int a = 0; a < m; ++a) xs[a] = ys[a] = IA(U[a].lo, U[a].hi);
    for (int i = 0; i < n; ++i) {
      xs[m + i] = IA(X[i].lo, X[i].hi);
      ys[m + i] = IA(y[i]);
    }
    // G(U, y): plain interval evaluation ...
    for (int i = 0; i < n; ++i) {
      fy[i] = evaluate(S.f[i], ys.span());
      ok = ok && finite(fy[i]);
    }
    // ... intersected with the centred (mean-value) form G(u0, y) + J_u(U, y) (U - u0): for each
    // u in U, G_i(u, y) = G_i(u0, y) + grad_u G_i(xi, y) . (u - u0) with xi on the segment
    // [u0, u], inside the convex box U, so both forms enclose G_i(u, y) and so does their
    // intersection (never empty in exact terms; an empty one would mean a bug, and is refused).
    if (m > 0 && ok) {
      std::copy(ys.begin(), ys.end(), zs.begin());
      for (int a = 0; a < m; ++a) zs[a] = IA(u0[a]);
      for (int i = 0; i < n; ++i) {
        IA c = evaluate(S.f[i], zs.span());
        for (int a = 0; a < m; ++a)
          c = c + evaluate(S.du[i * m + a], ys.span()) * (ys[a] - IA(u0[a]));
        if (!finite(c)) continue;  // the plain form alone is still an enclosure
        const double lo = std::max(c.inf(), fy[i].inf()), hi = std::min(c.sup(), fy[i].sup());
        if (!(lo <= hi)) return false;
        fy[i] = IA(lo, hi);
      }
    }
    // J_x(U, X): encloses J_x(u, x) for every u in U and x in X.
    for (int i = 0; i < n * n; ++i) {
      jx[i] = evaluate(S.df[i], xs.span());
      ok = ok && finite(jx[i]);
    }
  }
  if (!ok) return false;
  return krawczyk_core<MaxN>(n, y.begin(), fy.begin(), jx.begin(), X, K);
}

bool krawczyk_operator(const SquareSystem::Impl& S, const Box& U, const Box& X, Box& K) {
  // Small systems (the chart's k, the restricted vertex's N): Eigen storage of bounded size, no
  // heap; the same algorithms, so the same preconditioner.
  if (S.n <= 4) return krawczyk_operator_impl<4>(S, U, X, K);
  return krawczyk_operator_impl<Eigen::Dynamic>(S, U, X, K);
}

// The same operator for an EnclosedFunction: its enclosures stand in for the evaluations above.
bool krawczyk_operator(const EnclosedFunction& F, const Box& X, Box& K) {
  const int n = F.size();
  SmallBuffer<double, 8> y(n);
  SmallBuffer<Interval, 8> f(n);
  SmallBuffer<Interval, 64> J(static_cast<std::size_t>(n) * n);
  SmallBuffer<IA, 8> fy(n);
  SmallBuffer<IA, 64> jx(static_cast<std::size_t>(n) * n);
  for (int i = 0; i < n; ++i) y[i] = std::clamp(X[i].lo + 0.5 * (X[i].hi - X[i].lo), X[i].lo, X[i].hi);
  if (!F.values(y.span(), std::span<Interval>(f.begin(), f.end())) ||
      !F.jacobian(X, std::span<Interval>(J.begin(), J.end())))
    return false;
  for (int i = 0; i < n; ++i) fy[i] = IA(f[i].lo, f[i].hi);
  for (int i = 0; i < n * n; ++i) jx[i] = IA(J[i].lo, J[i].hi);
  for (int i = 0; i < n; ++i)
    if (!finite(fy[i]) || !(f[i].lo <= f[i].hi)) return false;
  for (int i = 0; i < n * n; ++i)
    if (!finite(jx[i]) || !(J[i].lo <= J[i].hi)) return false;
  if (n <= 4) return krawczyk_core<4>(n, y.begin(), fy.begin(), jx.begin(), X, K);
  return krawczyk_core<Eigen::Dynamic>(n, y.begin(), fy.begin(), jx.begin(), X, K);
}

bool strictly_inside(const Box& K, const Box& X) {
  for (std::size_t i = 0; i < K.size(); ++i)
    if (!(K[i].lo > X[i].lo && K[i].hi < X[i].hi)) return false;
  return true;
}

bool box_inside(const Box& a, const Box& b) {
  for (std::size_t i = 0; i < a.size(); ++i)
    if (!b[i].contains(a[i])) return false;
  return true;
}

bool boxes_disjoint(const Box& a, const Box& b) {
  for (std::size_t i = 0; i < a.size(); ++i)
    if (a[i].hi < b[i].lo || b[i].hi < a[i].lo) return true;
  return false;
}

// The full answer for one box, including a root verified in an enlarged box.
struct Attempt {
  RootStatus status = RootStatus::undecided;
  Box box;         // as in KrawczykResult
  int iterations = 0;
  // When set: `region` contains exactly one root r of F, r lies in `root`, and every root of F in
  // the input box lies in `region` (so the input box holds r or nothing). For unique_root,
  // root == box and region is the box where the inclusion was proved.
  std::optional<Box> root, region;
};

// Phases A and B for the operator op(X, K) (false: not evaluated) of a system in n unknowns.
template <class Op>
Attempt attempt_with(int n, const Box& input, const KrawczykOptions& options, const Op& op);

Attempt attempt(const SquareSystem::Impl& S, const Box& U, const Box& input, const KrawczykOptions& options) {
  const int n = S.n;
  if (static_cast<int>(input.size()) != n)
    throw std::invalid_argument("box has dimension " + std::to_string(input.size()) + ", the system has " +
                                std::to_string(n) + " unknowns");
  for (const auto& i : input)
    if (!i.is_finite() || !(i.lo <= i.hi)) throw std::invalid_argument("box intervals must be finite with lo <= hi");
  if (static_cast<int>(U.size()) != S.m)
    throw std::invalid_argument("parameter box has dimension " + std::to_string(U.size()) + ", the system has " +
                                std::to_string(S.m) + " parameters");
  for (const auto& i : U)
    if (!i.is_finite() || !(i.lo <= i.hi))
      throw std::invalid_argument("parameter box intervals must be finite with lo <= hi");
  return attempt_with(n, input, options, [&](const Box& X, Box& K) { return krawczyk_operator(S, U, X, K); });
}

template <class Op>
Attempt attempt_with(int n, const Box& input, const KrawczykOptions& options, const Op& op) {
  Attempt a;
  a.box = input;
  Box& X = a.box;
  Box K, next;
  // Phase A: contraction X <- K(X) n X. Every root of F in X lies in K(X).
  for (int it = 0; it < options.max_iterations; ++it) {
    a.iterations = it + 1;
    if (!op(X, K)) break;
    if (boxes_disjoint(K, X)) {
      a.status = RootStatus::no_root;
      a.box = input;
      a.root.reset();
      a.region.reset();
      return a;
    }
    if (!a.root && strictly_inside(K, X)) {
      a.region = X;  // exactly one root in X (Krawczyk), and it lies in K
      a.root = K;
    }
    next.resize(n);
    for (int i = 0; i < n; ++i) next[i] = {std::max(K[i].lo, X[i].lo), std::min(K[i].hi, X[i].hi)};
    double before = 0, after = 0;
    for (int i = 0; i < n; ++i) {
      before += X[i].width();
      after += next[i].width();
    }
    X = next;
    if (a.root) *a.root = X;  // the root stays in every contracted box
    if (!(after < (1.0 - options.min_improvement) * before)) break;
  }
  if (a.root) {
    a.status = RootStatus::unique_root;
    return a;
  }
  // Phase B: epsilon-inflation around the contracted box (which holds every root of the input
  // box). Contraction alone can shrink some coordinates to a few ulps, where strict inclusion is
  // no longer provable, and a root on the input box's boundary is never strictly inside it.
  Box B = X;
  for (int step = 0; step < options.inflation_steps; ++step) {
    {
      NearestRounding nearest;
      double scale = 0;
      for (const auto& iv : B) scale = std::max({scale, std::abs(iv.lo), std::abs(iv.hi)});
      if (scale == 0) scale = 1;
      for (int i = 0; i < n; ++i) {
        const double c = B[i].midpoint(), r = 0.5 * B[i].width() * 1.0625 + 0x1.0p-40 * scale;
        // Keep B a superset of the contracted box X exactly.
        B[i] = {std::min(c - r, X[i].lo), std::max(c + r, X[i].hi)};
      }
    }
    if (!op(B, K)) break;
    if (strictly_inside(K, B)) {
      a.root = K;
      a.region = B;
      if (box_inside(K, input)) {
        a.status = RootStatus::unique_root;
        a.box = K;
      }
      return a;
    }
    // Next candidate: the hull of K and X (K may have drifted).
    for (int i = 0; i < n; ++i) B[i] = {std::min(K[i].lo, X[i].lo), std::max(K[i].hi, X[i].hi)};
  }
  return a;
}

KrawczykResult to_result(Attempt a) {
  KrawczykResult r;
  r.status = a.status;
  r.box = std::move(a.box);
  r.iterations = a.iterations;
  if (a.status == RootStatus::undecided && a.root) r.nearby_root = std::move(a.root);
  return r;
}

}  // namespace

KrawczykResult krawczyk(const EnclosedFunction& F, const Box& box, const KrawczykOptions& options) {
  const int n = F.size();
  if (n < 1) throw std::invalid_argument("an enclosed function needs at least one equation");
  if (static_cast<int>(box.size()) != n)
    throw std::invalid_argument("box has dimension " + std::to_string(box.size()) + ", the system has " +
                                std::to_string(n) + " unknowns");
  for (const auto& i : box)
    if (!i.is_finite() || !(i.lo <= i.hi)) throw std::invalid_argument("box intervals must be finite with lo <= hi");
  return to_result(attempt_with(n, box, options, [&](const Box& X, Box& K) { return krawczyk_operator(F, X, K); }));
}

KrawczykResult krawczyk(const SquareSystem& system, const Box& box, const KrawczykOptions& options) {
  return to_result(attempt(system.impl(), Box{}, box, options));
}

KrawczykResult krawczyk(const ParametricSystem& system, const Box& parameters, const Box& box,
                        const KrawczykOptions& options) {
  return to_result(attempt(system.impl(), parameters, box, options));
}


RootSearchResult find_roots(const SquareSystem& system, const Box& region, const RootSearchOptions& options) {
  RootSearchResult out;
  struct Item {
    Box box;
    int depth;
  };
  struct Verified {
    Box root, region;
  };
  std::vector<Verified> found;
  std::vector<Box> ambiguous;
  // Records a verified root, merging it with an equal one: if R' lies in B_i then r' = r_i
  // (B_i holds exactly one root), and symmetrically. Disjoint R's are different roots.
  auto record = [&](Box root, Box reg) {
    for (auto& f : found) {
      if (box_inside(root, f.region) || box_inside(f.root, reg)) {
        for (std::size_t i = 0; i < root.size(); ++i)
          f.root[i] = {std::max(f.root[i].lo, root[i].lo), std::min(f.root[i].hi, root[i].hi)};
        return;
      }
      if (!boxes_disjoint(root, f.root)) {
        ambiguous.push_back(std::move(root));  // cannot tell: keep it as undecided (still covered)
        return;
      }
    }
    found.push_back({std::move(root), std::move(reg)});
  };
  std::vector<Item> stack{{region, 0}};
  // Off-centre split fraction: roots at dyadic "round" coordinates rarely land on a split plane.
  constexpr double kSplit = 0.4921875 + 0.0009765625 * 0.3;
  while (!stack.empty()) {
    Item item = std::move(stack.back());
    stack.pop_back();
    if (out.boxes_examined >= options.max_boxes) {
      out.undecided.push_back(std::move(item.box));
      continue;
    }
    ++out.boxes_examined;
    Attempt a = attempt(system.impl(), Box{}, item.box, options.krawczyk);
    if (a.status == RootStatus::no_root) continue;
    if (a.root) {
      // Every root of this box is the verified root (which may lie just outside the box).
      record(std::move(*a.root), std::move(*a.region));
      continue;
    }
    const Box& X = a.box;
    int widest = 0;
    for (int i = 1; i < static_cast<int>(X.size()); ++i)
      if (X[i].width() > X[widest].width()) widest = i;
    const Interval w = X[widest];
    const double split = w.lo + kSplit * (w.hi - w.lo);
    if (item.depth >= options.max_depth || w.width() <= options.min_width || !(w.lo < split && split < w.hi)) {
      out.undecided.push_back(X);
      continue;
    }
    Box lo = X, hi = X;
    lo[widest].hi = split;
    hi[widest].lo = split;
    // Push the upper half first so the lower half is examined first (deterministic order).
    stack.push_back({std::move(hi), item.depth + 1});
    stack.push_back({std::move(lo), item.depth + 1});
  }
  for (auto& f : found) out.roots.push_back(std::move(f.root));
  for (auto& b : ambiguous) out.undecided.push_back(std::move(b));
  return out;
}

std::vector<Polynomial> equidistance_equations(std::span<const double* const> vertices, int N) {
  if (vertices.empty()) throw std::invalid_argument("equidistance equations need at least one vertex");
  std::vector<Polynomial> out;
  const double* v0 = vertices[0];
  mpq_class n0 = 0;
  for (int k = 0; k < N; ++k) n0 += to_rational(v0[k]) * to_rational(v0[k]);
  for (std::size_t i = 1; i < vertices.size(); ++i) {
    const double* vi = vertices[i];
    mpq_class ni = 0;
    Polynomial p(N);
    for (int k = 0; k < N; ++k) {
      const mpq_class a = to_rational(vi[k]), b = to_rational(v0[k]);
      ni += a * a;
      if (a != b) p = p + Polynomial::variable(k, N).scaled(2 * (a - b));
    }
    p = p - Polynomial::constant(ni - n0, N);
    out.push_back(std::move(p));
  }
  return out;
}

}  // namespace delcert::exact
