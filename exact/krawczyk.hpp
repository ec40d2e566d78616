// Interval Newton (Krawczyk) for square polynomial systems: certified root isolation.
//
// For F : R^n -> R^n (polynomials with exact rational coefficients, exact symbolic Jacobian)
// and a box X, the Krawczyk operator is
//   K(X) = y - Y F(y) + (I - Y J_F(X)) (X - y),   y = midpoint of X, Y ~ J_F(y)^{-1} (any matrix),
// evaluated in interval arithmetic (outward rounding). Every root of F in X lies in K(X), so
//   * K(X) and X disjoint              => no root in X;
//   * K(X) inside the interior of X     => exactly one root in X, and it lies in K(X) intersected
//                                          with X (Krawczyk 1969, Moore 1977; see Rump,
//                                          "Verification methods", Acta Numerica 2010);
//   * otherwise X is replaced by K(X) intersected with X and the step repeated while it shrinks;
//   * when that stalls, the contracted box X' (which holds every root of X) is enlarged a little
//     to B (epsilon-inflation); K(B) inside the interior of B proves exactly one root in B, in
//     K(B); if K(B) lies inside X that root is the unique root of X.
// Only the preconditioner Y is computed in ordinary floating point (round-to-nearest, Eigen);
// it affects how often the tests succeed, never their correctness.
//
// A tangency (a singular root) can never be certified unique: the answer there is "undecided",
// which is the correct answer.
//
// Parametric version (ParametricSystem; the chart enclosures of exact/chart.hpp). For a system
// G(u, x) = 0 of n equations in m parameters u, ranging over a box U, and n unknowns x, in a box X:
//   K(U, X) = c - Y G(U, c) + (I - Y J_x(U, X)) (X - c),   c = midpoint of X,
// with G(U, c) any enclosure of { G(u, c) : u in U } (we take the intersection of the plain
// interval evaluation and the centred form G(u0, c) + J_u(U, c) (U - u0), u0 = midpoint of U)
// and J_x(U, X) an enclosure of { J_x(u, x) : u in U, x in X }. Claim:
//   * K(U, X) inside the interior of X => for EVERY u in U, G(u, .) has exactly one root in X,
//                                         and it lies in K(U, X) intersected with X;
//   * K(U, X) and X disjoint           => no u in U has a root in X.
// Proof: fix u in U and let K_u(X) = c - Y G(u, c) + (I - Y J_x(u, X)) (X - c) be the ordinary
// Krawczyk operator of the square system G(u, .) with the SAME c and Y. Since G(u, c) lies in
// G(U, c) and J_x(u, X) lies in J_x(U, X), inclusion isotonicity of interval arithmetic gives
// K_u(X) inside K(U, X). The standard theorem for the square system G(u, .) (Krawczyk 1969;
// Neumaier, "Interval methods for systems of equations", CUP 1990, Thm. 5.1.7 and 5.1.8; Rump,
// Acta Numerica 2010, Thm. 8.1) applied to K_u(X) gives both claims for this u: every root of
// G(u, .) in X lies in K_u(X) (hence the "disjoint" case), and K_u(X) inside int X implies a
// unique root in X (the continuous map x -> x - Y G(u, x) sends X into K_u(X) by the mean value
// form, so Brouwer gives a fixed point; the strict inclusion forces the spectral radius of
// |I - Y J_x(u, X)| below 1, so Y and every matrix of J_x(u, X) are nonsingular, and two roots
// x, x' would give 0 = Y J (x - x') with J in J_x(u, X), i.e. x = x'). As u was
// arbitrary, the claims hold for all u in U. The contraction X <- K(U, X) n X and the
// epsilon-inflation of krawczyk() keep every root of every u, by the same argument per u.
// The centred form is an enclosure by the mean value theorem per component: G_i(u, c) =
// G_i(u0, c) + grad_u G_i(xi, c) . (u - u0) for some xi on [u0, u], inside U because U is
// convex. A square system is the case m = 0.
#pragma once

#include <memory>
#include <span>
#include <optional>
#include <string_view>
#include <vector>

#include "exact/enclosed_polynomial.hpp"
#include "exact/interval.hpp"
#include "exact/polynomial.hpp"

namespace delcert::exact {

class ParametricSystem;

// n polynomials in n variables, with their exact partial derivatives, prepared for interval
// evaluation. Immutable, cheap to copy, thread-safe to share.
class SquareSystem {
 public:
  // Throws std::invalid_argument unless there are n >= 1 polynomials in n variables.
  explicit SquareSystem(std::vector<Polynomial> equations);
  // The system of head's n equations, its m parameters and n unknowns all taken as unknowns (in
  // that variable order), followed by the m equations of `tail` in those m + n variables. The
  // head's prepared rows and derivatives are shared, not recomputed (the restricted Voronoi
  // vertex systems of one cell all start with the chart's equations). Throws
  // std::invalid_argument unless tail has m equations in m + n variables.
  SquareSystem(const ParametricSystem& head, std::vector<Polynomial> tail);
  int size() const;
  std::vector<Polynomial> equations() const;

  struct Impl;
  const Impl& impl() const { return *impl_; }

 private:
  explicit SquareSystem(std::shared_ptr<const Impl> impl) : impl_(std::move(impl)) {}
  std::shared_ptr<const Impl> impl_;
};

// One equation known by coefficient enclosures, in n variables and no parameters, with its n
// derivatives prepared once: systems that share equations (ParametricSystem::from_rows) then
// share their preparation. Immutable, cheap to copy, thread-safe to share.
class EnclosedRow {
 public:
  explicit EnclosedRow(EnclosedPolynomial equation);
  struct Impl;

 private:
  std::shared_ptr<const Impl> impl_;
  friend class ParametricSystem;
};

// n polynomials in m + n variables: variables 1..m are the parameters u, m+1..m+n the unknowns
// x, with the exact partial derivatives in both. Immutable, cheap to copy, thread-safe to share.
class ParametricSystem {
 public:
  // Throws std::invalid_argument unless there are n >= 1 polynomials in m + n variables, m >= 0.
  ParametricSystem(std::vector<Polynomial> equations, int num_parameters);
  // The same from polynomials known by coefficient enclosures (exact/enclosed_polynomial.hpp):
  // krawczyk() answers for every polynomial system they stand for at once, by the argument of
  // AffineExtension (their derivatives are enclosed the same way). equations()
  // then throws std::logic_error. Throws std::invalid_argument as the constructor.
  static ParametricSystem from_enclosures(std::vector<EnclosedPolynomial> equations, int num_parameters);
  // from_enclosures(equations of the rows, 0), without preparing the rows again. Throws
  // std::invalid_argument as the constructor (n rows, each in n variables).
  static ParametricSystem from_rows(std::span<const EnclosedRow> rows);
  int size() const;            // n
  int num_parameters() const;  // m
  std::vector<Polynomial> equations() const;
  // Enclosures, outward rounded whatever the caller's rounding mode, of equation i (0-based) and
  // of its derivative in unknown j (variable m + j) over the box z (m + n intervals: parameters,
  // then unknowns). The interval evaluation Krawczyk itself uses.
  Interval enclose(int i, std::span<const Interval> z) const;
  Interval enclose_derivative(int i, int j, std::span<const Interval> z) const;
  // ... and of its derivative in parameter a (variable a).
  Interval enclose_parameter_derivative(int i, int a, std::span<const Interval> z) const;

  const SquareSystem::Impl& impl() const { return *impl_; }

 private:
  explicit ParametricSystem(std::shared_ptr<const SquareSystem::Impl> impl) : impl_(std::move(impl)) {}
  std::shared_ptr<const SquareSystem::Impl> impl_;
};

enum class RootStatus { unique_root, no_root, undecided };
std::string_view to_string(RootStatus status);

struct KrawczykOptions {
  int max_iterations = 40;         // contraction steps per box
  double min_improvement = 0.125;  // stop when a step shrinks the box's total width by less
  // When contraction stalls, up to this many epsilon-inflation attempts around the contracted
  // box (proves roots that contraction squeezes to a few ulps or that sit on the box boundary).
  int inflation_steps = 4;
};

struct KrawczykResult {
  RootStatus status = RootStatus::undecided;
  // unique_root: a box containing the unique root of F in the input box (contracted as far as
  // the iteration goes); undecided: a sub-box containing every root of F in the input box;
  // no_root: the input box.
  Box box;
  int iterations = 0;
  // undecided only, when set: epsilon inflation proved exactly one root r of F in a box that
  // contains every root of F in the input box (a root on the input box's boundary, or just
  // outside it), and r lies in this box. So the input box holds r or no root at all.
  std::optional<Box> nearby_root;
};

// Throws std::invalid_argument for a box of the wrong dimension or with non-finite or empty
// intervals.
KrawczykResult krawczyk(const SquareSystem& system, const Box& box, const KrawczykOptions& options = {});

// A square system F: R^n -> R^n known through enclosures only, e.g. a family of C^1 functions
// with coefficients in intervals, as ParametricSystem::from_enclosures: values() encloses F(y) at
// a point y and jacobian() dF_i/dx_j over a box X (row-major, n x n), each for every F the
// family stands for, outward rounded whatever the caller's rounding mode; false when it cannot
// (nothing is then concluded). krawczyk() then answers for every F of the family at once (for
// each, K(X) lies in the operator computed from the enclosures).
class EnclosedFunction {
 public:
  virtual ~EnclosedFunction() = default;
  virtual int size() const = 0;
  virtual bool values(std::span<const double> y, std::span<Interval> f) const = 0;
  virtual bool jacobian(const Box& X, std::span<Interval> J) const = 0;
};
// As krawczyk(SquareSystem) (same phases, same operator), for F on `box` (every F of the family
// C^1 there). Throws std::invalid_argument as it does.
KrawczykResult krawczyk(const EnclosedFunction& F, const Box& box, const KrawczykOptions& options = {});

// The square system of head's n equations, its m parameters and n unknowns all taken as unknowns
// (in that variable order, z = (u, x)), followed by m affine rows known only by ENCLOSURES of
// their coefficients: row i is some c_i + l_i . z, with c_i in tail[i (1 + m + n)] and l_ij in
// tail[i (1 + m + n) + 1 + j]. The family is every such choice of rows (with the head's own
// equations, enclosed as head.enclose does): krawczyk() answers for each of them at once, the
// true one included (for a fixed choice, its rows' values and derivatives lie in the interval
// evaluations used, by inclusion isotonicity). The restricted Voronoi vertex systems: the
// chart's equations, then the equidistance rows enclosed from the doubles of the points, with no
// rational arithmetic. Nothing is prepared (the head's rows are evaluated where they are): cheap
// to build, one per candidate vertex. Throws std::invalid_argument unless tail holds m rows of
// 1 + m + n finite, non-empty intervals.
class AffineExtension final : public EnclosedFunction {
 public:
  AffineExtension(const ParametricSystem& head, std::vector<Interval> tail);
  int size() const override { return n_; }
  bool values(std::span<const double> y, std::span<Interval> f) const override;
  bool jacobian(const Box& X, std::span<Interval> J) const override;

 private:
  ParametricSystem head_;
  std::vector<Interval> tail_;
  int n_ = 0, k_ = 0;  // n_ = m + n unknowns in all, k_ = the head's n
};

// The parametric Krawczyk test: unique_root means that for EVERY u in `parameters` exactly one
// root of G(u, .) lies in `box`, and it lies in the result's box; no_root means that no u in
// `parameters` has a root in `box`; undecided: the result's box holds every root in `box` of
// every u in `parameters`. Throws std::invalid_argument for boxes of the wrong dimensions or
// with non-finite or empty intervals.
KrawczykResult krawczyk(const ParametricSystem& system, const Box& parameters, const Box& box,
                        const KrawczykOptions& options = {});

struct RootSearchOptions {
  int max_depth = 40;         // bisection depth limit
  long max_boxes = 200000;    // Krawczyk calls limit (then the remaining boxes are undecided)
  double min_width = 0.0;     // do not bisect boxes whose widest side is <= this
  KrawczykOptions krawczyk;
};

struct RootSearchResult {
  // Each box contains exactly one root of F, and different boxes contain different roots. A
  // root box may stick out of the search region by a few ulps when the root is on its boundary.
  std::vector<Box> roots;
  // Every root of F in the region lies in a root box or in an undecided box.
  std::vector<Box> undecided;
  long boxes_examined = 0;
  bool complete() const { return undecided.empty(); }
};

// Isolates the roots of F in `region` by Krawczyk tests and bisection (deterministic; boxes are
// split slightly off-centre so that roots at "round" coordinates rarely fall on a split).
RootSearchResult find_roots(const SquareSystem& system, const Box& region, const RootSearchOptions& options = {});

// The affine equations of the set of points equidistant from the vertices v0..vj (each N
// doubles, taken exactly): 2 (v_i - v0) . x - (|v_i|^2 - |v0|^2) = 0 for i = 1..j. Appended to
// the N - m equations of M with j = m, they give the square system whose roots are the points
// of M on the Voronoi flat of an m-simplex (restricted Delaunay test).
std::vector<Polynomial> equidistance_equations(std::span<const double* const> vertices, int N);

}  // namespace delcert::exact
