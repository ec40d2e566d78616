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
#pragma once

#include <memory>
#include <span>
#include <string_view>
#include <vector>

#include "exact/interval.hpp"
#include "exact/polynomial.hpp"

namespace delcert::exact {

// n polynomials in n variables, with their exact partial derivatives, prepared for interval
// evaluation. Immutable, cheap to copy, thread-safe to share.
class SquareSystem {
 public:
  // Throws std::invalid_argument unless there are n >= 1 polynomials in n variables.
  explicit SquareSystem(std::vector<Polynomial> equations);
  int size() const;
  const std::vector<Polynomial>& equations() const;

  struct Impl;
  const Impl& impl() const { return *impl_; }

 private:
  std::shared_ptr<const Impl> impl_;
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
};

// Throws std::invalid_argument for a box of the wrong dimension or with non-finite or empty
// intervals.
KrawczykResult krawczyk(const SquareSystem& system, const Box& box, const KrawczykOptions& options = {});

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
