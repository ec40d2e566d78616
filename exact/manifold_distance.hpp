// Certified distance from a sample point to a manifold M = {x : F(x) = 0, s(x) > 0}, with a
// certificate that J_F has full rank near the point (interval Krawczyk on the normal slice).
//
// F : R^N -> R^k (k = N - m polynomials with exact rational coefficients), s an optional
// component selector. For a point p (N doubles, taken exactly):
//
//   1. (floating point, any result is fine) A = a k x N matrix of doubles whose rows span about
//      the row space of J_F(p) (orthonormalised), and t~ ~ the Newton solution of G(t) = 0, where
//          G(t) = F(p + A^T t),   J_G(t) = J_F(p + A^T t) A^T   (a square k x k system).
//   2. (interval arithmetic, rounding upward) the Krawczyk operator of G on a box T around t~,
//          K(T) = y - Y G(y) + (I - Y J_G(T)) (T - y),   y in T, Y ~ mid(J_G(T))^{-1},
//      with J_G(T) enclosed by the interval product J_F(X) A^T, X = the interval hull of
//      p + A^T T (every x = p + A^T t, t in T, lies in X, and J_F(x) lies in J_F(X) since
//      polynomials are evaluated in interval arithmetic term by term). By the mean value theorem
//      G(t) - G(y) = M (t - y) with M in the convex interval matrix J_G(T), so every zero of G
//      in T lies in K(T); when K(T) lies in the interior of T, G has exactly one zero t* in T
//      (Krawczyk 1969; Rump, "Verification methods", Acta Numerica 2010).
//   3. Then x* = p + A^T t* satisfies F(x*) = 0, and the distance from p to M is at most
//      |x* - p| = |A^T t*| <= sup { |A^T t| : t in R }, R a box containing t* (K(T), contracted
//      further by K(R) n R, which keeps t*), bounded with outward rounding.
//   4. Full rank. What is relied on: for every real matrix M of the interval matrix J_G(T)
//      (in particular M = J_F(x) A^T for every x in X), C = I - Y M satisfies, with w = the
//      widths of T (all > 0, since K(T) lies strictly inside T),
//          sum_j |C_ij| w_j  <=  width(K(T)_i)  <  w_i     for every i,
//      because K(T) contains y - Y G(y) + C (T - y), whose i-th coordinate ranges over an
//      interval of width sum_j |C_ij| w_j. So the w-weighted max-norm of C is < 1, its spectral
//      radius is < 1, Y M = I - C is nonsingular, hence M = J_F(x) A^T is nonsingular and
//      J_F(x) has rank k at every x in X. X contains x*, so M is a smooth m-manifold near x*
//      (implicit function theorem), which is what docs/design.md §2 requires.
//   5. With a selector, s > 0 is checked on the interval hull of p + A^T R (which holds x*), so
//      x* is on the selected component: x* is a point of M.
//
// Failure (never a false certificate): a rank-deficient J_F on M (e.g. the squared sphere
// (|x|^2 - 1)^2 = 0: J_G vanishes at the zero, so K(T) never lies inside T), a point far from M,
// overflow, or a selector not certainly positive near p. Only the matrix Y, the orthonormal rows
// A and the Newton guess t~ are computed in round-to-nearest floating point; they affect how often
// the test succeeds, never its correctness (A is used exactly as the doubles it holds).
//
// Cost: a handful of interval evaluations of F and J_F per point (typically 2-3 Krawczyk steps),
// O(k N) polynomial evaluations each; no exact arithmetic (about 6 us per point on S^2, 60 us
// on SO(3), one core).
#pragma once

#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "exact/interval.hpp"
#include "exact/polynomial.hpp"

namespace delcert::exact {

struct DistanceCertificate {
  bool certified = false;
  // certified: a point x* of M with |x* - p| <= distance_upper (a double rounded upward), J_F
  // of full rank k on the box `region`, which contains x*.
  double distance_upper = 0;
  Box zero_box;  // contains x*
  Box region;    // J_F has rank k at every point of this box
  int krawczyk_steps = 0;
  // Not certified: what failed, for the error message.
  std::string failure;
  // Not certified: the largest distance from p that the tested boxes reached (an estimate).
  double searched_radius = 0;
};

class ManifoldDistance {
 public:
  // `equations`: the k = N - m polynomials of F over N variables (1 <= k <= N); `selector`: null
  // or a polynomial over N variables that must be > 0 on M. Throws std::invalid_argument on
  // inconsistent sizes. Immutable, cheap to copy, thread-safe to share.
  //
  // `scale_exponent` e: the test runs in the coordinates y = x / 2^e, on the equations
  // F(2^e y) divided by a power of two near their largest coefficient (neither changes the zero
  // set, the selected component or the rank of the Jacobian), and the results are scaled back by
  // the exact factor 2^e, rounded outward. Choose 2^e near the size of the points' coordinates
  // (sanity.cpp takes the largest one): at 2^-600, say, F itself is far below the double range
  // and no interval test could succeed without it. e = 0 keeps the equations as they are.
  ManifoldDistance(const std::vector<Polynomial>& equations, int ambient_dimension, const Polynomial* selector = nullptr,
                   int scale_exponent = 0);

  // p: N doubles (taken exactly). Never throws for finite or non-finite p: failures are reported
  // in the result. Sets (and restores) the rounding mode itself.
  DistanceCertificate certify(std::span<const double> p) const;

  struct Impl;

 private:
  DistanceCertificate certify_scaled(std::span<const double> y) const;  // in the scaled coordinates
  std::shared_ptr<const Impl> impl_;
};

}  // namespace delcert::exact
