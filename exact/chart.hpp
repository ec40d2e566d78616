// Certified chart enclosures of an implicit manifold (docs/design.md §3.8, §4.1).
//
// M = { x in R^N : F(x) = 0 }, F = (F_1..F_k) polynomials with exact rational coefficients,
// k = N - m. A chart at a base point p (N doubles, taken as exact rationals) uses two exact
// rational bases, T (N x m, ideally tangent: J_F(p) T = 0) and Nn (N x k, ideally complementary,
// e.g. the rows of J_F(p)), and writes points near p as
//   x(u, h) = p + T u + Nn h,   u in R^m (chart parameters), h in R^k (normal coordinates).
// The chart equations G(u, h) = F(p + T u + Nn h) are formed by substituting the affine
// expressions into F and expanding BY ENCLOSURES (exact/enclosed_polynomial.hpp: p exact, T and
// Nn enclosed, every product and sum in interval arithmetic under upward rounding), so G stands
// for a set of polynomials that contains the exact one, and the parametric Krawczyk operator of
// exact/krawczyk.hpp answers for all of them at once (ParametricSystem::from_enclosures), the
// exact G included. Coefficients enclosed by [0, 0] are exactly 0 and dropped; when T spans
// ker J_F(p) (checked exactly here), the terms of degree 1 in u alone, whose exact coefficients
// are J_F(p) T = 0, are dropped too, which keeps a sparse chart sparse. (Until 2026-12 the
// expansion was exact, in rationals: a third of the restricted Voronoi diagram's time at m = 2.
// The constant term is now F(p) to a few ulps of the magnitudes summed rather than of F(p)
// itself, which no Krawczyk test notices. The alternative, evaluating F and J_F on the interval
// box x(U, H) with the chain rule, keeps F's structure but loses the cancellation of F(p) ~ 0
// and of the terms linear in u, which the expansion keeps.)
//
// enclose(U) for a box U of parameters returns, when it succeeds (status unique), a box H of h
// and an interval box X of x such that:
//   for EVERY u in U there is exactly one h in H with F(p + T u + Nn h) = 0, i.e. exactly one
//   point x(u) of M with parameter u and normal coordinate in H; it lies in X.
// Whether a point of M with parameter u and normal coordinate OUTSIDE H exists (another sheet
// of M over the same u, e.g. the far side of a sphere) is not decided here: that is the graph
// property of the chart, which the caller establishes (reach, or an ambient search; docs/design.md §3.8).
// T and Nn need not be exactly tangent / normal: the statement above holds for any T and Nn;
// tangency only makes the Krawczyk test succeed more often.
//
// Every enclosure is computed in interval arithmetic under upward rounding (exact/interval.hpp;
// the proof comment of krawczyk.cpp covers overflow and underflow); the ordinary floating-point
// steps (Newton for the centre, the slope estimate for H, the preconditioner) only choose boxes
// and never decide anything. Non-finite intermediate bounds make the answer "undecided".
#pragma once

#include <gmpxx.h>

#include <memory>
#include <span>
#include <string_view>
#include <vector>

#include "exact/interval.hpp"
#include "exact/krawczyk.hpp"
#include "exact/tangent_space.hpp"

namespace delcert::exact {

enum class ChartStatus {
  unique,     // for every u in U exactly one h in H (see above); X encloses those points
  none,       // (enclose_in only) no u in U has a point of M with normal coordinate in the given H
  undecided,  // nothing is claimed
};
std::string_view to_string(ChartStatus status);

struct ChartOptions {
  // enclose(): the initial H is h0 +- (safety * predicted spread + floor); after each undecided
  // Krawczyk test its radius is multiplied by `growth`, at most `attempts` boxes in all.
  int attempts = 5;
  double growth = 4.0;
  double safety = 1.5;
  int newton_steps = 40;  // Newton iterations (double) for h0 at the centre of U
  KrawczykOptions krawczyk;
};

struct ChartResult {
  ChartStatus status = ChartStatus::undecided;
  // unique: encloses h(u) for all u in U (contracted by Krawczyk); none: the H shown empty;
  // undecided: the last H tried (empty when no approximate centre was found).
  Box H;
  // unique: interval hull of p + T U + Nn H (outward rounded), the enclosure of the points x(u).
  Box X;
  int krawczyk_calls = 0;
};

class ChartEnclosure {
 public:
  // T: N x m and Nn: N x (N - m), row-major, exact rationals. Throws std::invalid_argument on
  // dimension mismatches or a non-finite coordinate of p.
  ChartEnclosure(const ImplicitSystem& F, std::span<const double> p, std::vector<mpq_class> T,
                 std::vector<mpq_class> Nn, ChartOptions options = {});
  // The standard chart at p: T is TangentSpace(F, p)'s exact kernel basis and Nn = J_F(p)^T
  // (exact), every column scaled by a power of two (exactly) so that its largest entry lies in
  // [1/2, 1). Throws std::domain_error when J_F(p) is rank deficient.
  static ChartEnclosure at(const ImplicitSystem& F, std::span<const double> p, ChartOptions options = {});

  int ambient_dimension() const;    // N
  int intrinsic_dimension() const;  // m
  int codimension() const;          // k = N - m
  std::span<const double> base_point() const;
  const mpq_class& tangent(int row, int col) const;  // T
  const mpq_class& normal(int row, int col) const;   // Nn
  // G(u, h) = F(p + T u + Nn h): k polynomials in the m + k variables (u, h).
  const ParametricSystem& chart_system() const;
  // Enclosures of the exact T and Nn (row-major, as above).
  std::span<const Interval> tangent_enclosure() const;
  std::span<const Interval> normal_enclosure() const;
  // Certified lower bounds, > 0 and rounded down, of the smallest eigenvalues of T^T T and
  // Nn^T Nn (then |T u|^2 >= tangent |u|^2 and |Nn h|^2 >= normal |h|^2). Throws
  // std::domain_error when a Gram matrix cannot be bounded away from 0.
  struct GramBounds {
    double tangent = 0, normal = 0;
  };
  GramBounds gram_bounds() const;

  // Encloses the piece of M over U, choosing H itself: an approximate h0 at the centre u0 of U
  // by Newton from `h_hint` (default 0, i.e. from p; pass the h of a neighbouring box), then
  // H = h0 +- r with r the predicted spread of h over U times `safety`: the larger of the
  // linear prediction |dh/du| rad U (dh/du = -J_h^{-1} J_u at (u0, h0)) and the distance from h0
  // of the Newton solutions at the 2^m corners of U (which sees the curvature where the slope
  // at the centre is 0), plus a floor of 2^-30 (|h0| + rad U) (or 2^-30 |p| when both are 0)
  // for boxes U of zero width; if Krawczyk cannot decide, r grows by `growth`, up to `attempts`
  // boxes. Never returns `none` (a root-free guessed H says nothing about M over U).
  ChartResult enclose(const Box& U, std::span<const double> h_hint = {}) const;
  // The parametric Krawczyk test on the given H (with its contraction and inflation).
  ChartResult enclose_in(const Box& U, const Box& H) const;
  // Interval hull of p + T U + Nn H, outward rounded. False (and X unspecified) on overflow.
  bool image(const Box& U, const Box& H, Box& X) const;
  // Enclosure of |x(u, h) - p|^2 = |T u + Nn h|^2 over U x H, outward rounded (an overflow gives
  // an infinite or NaN bound).
  Interval offset_norm2(const Box& U, const Box& H) const;
  // True when no (u, h) in U x H has G(u, h) = 0 (no point of M there): some G_e's enclosure on
  // the box has a strict sign, or G_e is monotone in some h_l on the box (dG_e/dh_l excludes 0)
  // and its enclosures on the faces h_l = lo and h_l = hi have the same strict sign (every value
  // on the box lies between values on those faces). The face test sees the sign near a slab edge
  // that the plain enclosure of a wide box loses.
  bool free_of_M(const Box& U, const Box& H) const;

  // THE BASE POINT AND THE TILT (for the graph lemma of certify/rvd.cpp, docs/design.md §3.8).
  // `F` must be the system this chart was built from, `selector` null or the s of M = {F = 0, s > 0}.
  // certified: the chart proves exactly one point p* of {F = 0} over u = 0 with normal coordinate in
  // a box H0 (enclose of a tiny box U0 around 0), s > 0 on the box `x`, the image of U0 x H0 (so p*
  // is a point of M),
  // |p* - p| <= distance, and for EVERY x in `x` with J_F(x) of rank k,
  //   sin θ(span T, ker J_F(x)) <= sin_tilt < 1,
  // θ the largest principal angle, and J_F has rank k on all of `x`. Proof (chart.cpp,
  // base_point): Weyl's inequality on B = W J_F(x) against A = Nn^T, W any k x k matrix of doubles.
  // Not certified: nothing is claimed.
  struct BasePoint {
    bool certified = false;
    Box x;                // N intervals holding p*
    double distance = 0;  // >= |p* - p|, rounded up
    double sin_tilt = 1;  // >= sin θ, rounded up
  };
  BasePoint base_point(const ImplicitSystem& F, const Polynomial* selector = nullptr) const;

  struct Impl;

 private:
  // J: J_F(p) (k x N, row-major, exact) when the caller has it (at()), else empty (computed here).
  ChartEnclosure(const ImplicitSystem& F, std::span<const double> p, std::vector<mpq_class> T,
                 std::vector<mpq_class> Nn, ChartOptions options, const std::vector<mpq_class>& J);
  std::shared_ptr<const Impl> impl_;
};

}  // namespace delcert::exact
