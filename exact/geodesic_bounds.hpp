// Certified bounds for geodesic distances on an implicit manifold M = {x : F(x) = 0}: a bound K of
// the second fundamental form over a box, and the chord-to-arc comparison Φ_K that turns an
// ambient distance into an upper bound of the geodesic one. Also the interval Jacobian of F over a
// box and bounds of the eigenvalues of its Gram matrix J J^T (used here and by certify/reach_check).
//
// F = (F_1..F_k): R^N -> R^k, polynomials with rational coefficients (exact/tangent_space.hpp).
//
// THE CURVATURE BOUND. Let x be a point where J = J_F(x) has rank k, L the level set
// {F = F(x)} (a submanifold of dimension m = N - k near x; L = M when x lies on M), and γ a
// unit-speed curve in L with γ(0) = x, γ'(0) = u. Differentiating F(γ(s)) = const twice gives
//   J γ'' + b = 0,   b_e = u^T H_e u   (H_e the Hessian of F_e at x).
// Split γ'' = P_T γ'' + n with n = P_N γ'' in the row space of J (P_N the orthogonal projection on
// it, (ker J)^⊥). Then J n = J γ'' = -b; writing n = J^T c gives G c = -b with G = J J^T (positive
// definite since rank J = k), so n = -J^T G^{-1} b and
//   |n|^2 = c^T G c = b^T G^{-1} b <= |b|^2 / λ_min(G).
// n is II_x(u, u), the second fundamental form of L (the normal part of the acceleration of any
// curve in L with velocity u). For a geodesic of M, γ'' is normal (its tangential part is the
// covariant acceleration, 0), so |γ''| = |n|: the bound below bounds the curvature of every
// geodesic arc of M inside X. |b|^2 is bounded two ways, the smaller taken:
//   (a) |b_e| <= |H_e|_2 <= h_e := min(|H_e|_F, max_i sum_j |H_e,ij|) (H_e symmetric: |H_e|_2 is
//       its spectral radius, below every induced norm, the row-sum norm included), so
//       |b|^2 <= sum_e h_e^2;
//   (b) |b|^2 <= (max_e |b_e|) sum_e |b_e| <= h_max sum_e |u|^T |H_e| |u| = h_max |u|^T A |u|
//       <= h_max max_i sum_j A_ij, with A = sum_e |H_e| entrywise (|u| the unit vector of |u_i|;
//       A is symmetric and nonnegative, so |u|^T A |u| <= ρ(A) <= its row-sum norm).
// (b) is tight on products (the Clifford torus: sqrt(2) there, against 2 from (a)).
// Over a box X every entry H_e,ij(x) and J_ev(x) lies in its interval evaluation on X (inclusion
// isotonicity), so the sup of the right-hand sides over X is at most the same expressions on the
// intervals' magnitudes, and λ_min(G(x)) is at least the lower bound of gram_eigenvalue_bounds
// below for every x in X. The bound therefore holds at EVERY x in X where J has rank k (which
// λ_min > 0 proves for all of X), points off M included: it bounds II of the level set of F
// through each of them, M's at points of M. No component selector enters: II is local.
// SCALING (against overflow and underflow, and for tightness). Replacing F_e by d_e F_e, any
// d_e > 0 (same zero set, same level sets), multiplies b and J by D = diag(d_e) on the left and G by
// D on both sides: b^T G^{-1} b is unchanged. d_e = 2^{s_e} c_e: the exact power of two brings row e
// of J to magnitude about 1, then c_e (a double) makes the rows' lengths about 1, so that G is near
// the identity when the rows are orthogonal. Then the Hessians are multiplied by one common 2^σ
// (largest entry about 1), which multiplies |n| by 2^σ; the result is multiplied by 2^-σ at the
// end. Each scaling is an interval product by a double, outward rounded.
// ROUNDING. Everything is interval arithmetic under upward rounding (CGAL's Interval_nt_advanced:
// upper bounds rounded up, lower bounds computed as -(upward(-x)), so both are enclosures whatever
// the magnitude). Overflow gives an infinite bound, underflow a bound rounded outward (a lower
// bound of a positive quantity may become 0); square roots are CGAL's outward-rounded interval
// sqrt. A non-finite intermediate, or λ_min not bounded away from 0 (a singular point of F in X,
// or a box too wide), gives +infinity: "cannot bound".
//
// THE COMPARISON (Schur). Theorem: if a unit-speed C^2 curve γ of length L in R^N has curvature
// |γ''| <= K along it and K L <= π, then |γ(L) - γ(0)| >= (2/K) sin(K L / 2) (>= L when K = 0).
// Proof: let t0 = γ'(L/2). The unit tangent γ' moves on the unit sphere at speed |γ''| <= K, so
// the angle between γ'(s) and t0 is at most K |s - L/2| <= K L / 2 <= π/2; hence
// <γ'(s), t0> >= cos(K |s - L/2|) and
//   |γ(L) - γ(0)| >= <γ(L) - γ(0), t0> = ∫_0^L <γ'(s), t0> ds >= ∫_0^L cos(K |s - L/2|) ds
//                  = (2/K) sin(K L / 2).
// Consequence used by callers: let x, y be points of M with d = d_M(x, y) <= π/K, joined by a
// minimising geodesic (unit speed, length d), and let K bound |II| at every point of M within
// (geodesic, hence ambient) distance d of x (e.g. curvature_bound on a box holding the ambient ball
// of radius d around x). The geodesic's curvature is |II(γ', γ')| <= K, so with t = |x - y|,
// t >= (2/K) sin(K d / 2), i.e. K t / 2 >= sin(K d / 2) with K d / 2 <= π/2, where arcsin is the
// increasing inverse of sin: d <= (2/K) arcsin(K t / 2) = Φ_K(t) (and K t / 2 <= 1 necessarily).
#pragma once

#include <memory>
#include <span>
#include <vector>

#include "exact/interval.hpp"
#include "exact/tangent_space.hpp"

namespace delcert::exact {

// A certified upper bound K of |II_x(u, u)| over every x in X where J_F(x) has rank k and every
// unit u in ker J_F(x) (II the second fundamental form of the level set of F through x: M's on
// X ∩ M; see above), rounded up; +infinity when it cannot bound (J_F not proven of rank k on X,
// overflow). 0 when every second derivative of F vanishes identically and the rank is proven.
// No selector: the bound is local and holds on every component. Throws std::invalid_argument on a
// box of the wrong dimension or with a NaN or empty interval. Sets and restores the rounding mode.
double curvature_bound(const ImplicitSystem& F, const Box& X);

// The same with F's first and second derivatives prepared once, for many boxes. Immutable, cheap
// to copy, thread-safe to share.
class CurvatureBound {
 public:
  explicit CurvatureBound(const ImplicitSystem& F);
  double operator()(const Box& X) const;
  struct Impl;

 private:
  std::shared_ptr<const Impl> impl_;
};

// J_F over the box X: k x N intervals, row-major, each enclosing dF_i/dx_v(x) for every x in X
// (interval evaluation of the exact partial derivatives, outward rounded). False when a bound is
// not finite (J then unspecified). Throws std::invalid_argument as curvature_bound.
bool jacobian_enclosure(const ImplicitSystem& F, const Box& X, std::vector<Interval>& J);

// For every real k x N matrix J_r inside the interval matrix J (row-major): every eigenvalue of
// G = J_r J_r^T lies in [lower, upper]. lower rounded down (<= 0 when nothing positive is found),
// upper rounded up (+infinity on overflow). Gershgorin's discs on the interval matrix
// G(J) (G_ii from squares, G_ij from products: enclosures of every G(J_r)'s entries), for the lower
// bound also after the congruence D^{-1/2} G D^{-1/2}, D = diag(inf G_ii) (see the .cpp).
struct GramEigenvalueBounds {
  double lower = 0;
  double upper = 0;
};
GramEigenvalueBounds gram_eigenvalue_bounds(std::span<const Interval> J, int k, int N);

// Φ_K(t) = (2/K) arcsin(K t / 2) (Φ_0(t) = t), rounded up: by the comparison above, an upper bound
// of the geodesic distance of two points at ambient distance t. +infinity when K t / 2 >= 1
// (decided exactly) or K or t is not finite. Throws std::invalid_argument when K < 0 or t < 0.
// MPFR (correctly rounded asin, directed roundings, an exponent range far beyond the doubles'), so
// no underflow or overflow can occur before the final rounding up to a double.
double chord_to_geodesic_upper(double K, double r);

// An upper bound, rounded up, of Φ_K(r) - r >= 0: the most the geodesic distance can exceed an
// ambient distance t <= r, since Φ_K(t) - t is nondecreasing in t (its derivative is
// 1 / sqrt(1 - K^2 t^2 / 4) - 1 >= 0 on [0, 2/K)). +infinity as chord_to_geodesic_upper; throws as
// it does. Computed without cancellation (see the .cpp).
double geodesic_slack_upper(double K, double r);

}  // namespace delcert::exact
