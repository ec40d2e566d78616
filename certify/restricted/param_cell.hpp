// Restricted Voronoi cells in a RATIONAL CHART of M (docs/design.md §3.8), for the shapes whose
// equations certify/intrinsic.hpp has verified (verify_declared_shape): a round sphere with
// N = m + 1, a product of m <= 3 circles, and SO(3). The report and its statements are those of
// certify/rvd.hpp; only the way M ∩ B(p, r) is parametrised differs, and no reach is assumed.
//
// A RATIONAL CHART at p is phi(v) = X(v) / D(v), v in R^m, with X (N polynomials) and D
// polynomials with rational coefficients such that
//   (a) D(v) > 0 and phi(v) is in M for every v in R^m: checked here exactly, as polynomial
//       identities over Q (below), so an error in a formula cannot pass unnoticed;
//   (b) every x in M ∩ B(p, r) is phi(v) for some v in V0 = [-t, t]^m: a lemma per shape (below),
//       with t computed under upward rounding.
// Then the analysis of rvd.hpp runs on boxes V of V0 instead of (U, slab) pairs: every sign of
// s_q(x) = |x - q|^2 - |x - p|^2 = |q - p|^2 - 2 (q - p).(x - p) at x = phi(v) is the sign of
// P_q(v) = D(v) s_q(phi(v)) = |q - p|^2 D(v) - 2 (q - p).(X(v) - p D(v)), a polynomial in v whose
// coefficients are enclosed from the exact doubles of p and q (exact/enclosed_polynomial.hpp).
//
// SPHERE, centre c, radius rho (rational), N = m + 1. n is a rational unit vector near
// (p - c) / |p - c| (the inverse stereographic image of a dyadic point: exactly unit), E an N x m
// rational matrix of orthonormal columns orthogonal to n (columns of the rational Householder
// reflection sending -sgn(n_l) e_l to n). phi(v) = c + rho ((1 - |v|^2) n + 2 E v) / (1 + |v|^2):
// the inverse stereographic projection from -n; identity (a): |X - c D|^2 = rho^2 D^2, D = 1 + |v|^2.
// Lemma (b): x = phi(v) makes the angle theta with n where cos theta = (1 - |v|^2) / (1 + |v|^2),
// so |v| = tan(theta / 2), and |x - a| = 2 rho sin(theta / 2) with a = c + rho n; every x of the
// sphere but -n's point is phi(v) for one v. For x in B(p, r), |x - a| < r + |p - a| =: r', so
// sin(theta / 2) < s = r' / (2 rho); if s < 1, theta < pi and |v| < s / sqrt(1 - s^2) = t.
//
// SO(3) in R^9 (x row-major). R(y) = (y^T B(E_ij) y)_ij with Davenport's B (intrinsic_engines.hpp):
// the rotation of the quaternion y times |y|^2. y~ is an integer quaternion along the top eigenvector
// of B(p) (any nonzero one is correct), (a, b, c, d) = y~ and E = [e1 e2 e3] with
// e1 = (-b, a, -d, c), e2 = (-c, d, a, -b), e3 = (-d, -c, b, a): y~, e1, e2, e3 are pairwise
// orthogonal, each of squared norm |y~|^2. phi(v) = R(y~ + E v) / (|y~|^2 (1 + |v|^2)). (a): the
// polynomial identity R(y) R(y)^T = |y|^4 I in y (checked once) and the orthogonality relations of
// y~, e1, e2, e3 (checked per chart) give X X^T = D^2 I, so phi(v) is orthogonal; det phi(v),
// continuous on the connected R^3 with values in {1, -1}, is its value at 0 (checked exactly). Lemma (b): for unit quaternions y, z,
// |R(y) - R(z)|^2 = 8 (1 - (y.z)^2). Let p~ = phi(0). Every x in SO(3) is R(y) for a unit y with
// y.y~ >= 0; if x is in B(p, r) then |x - p~| < r + |p - p~| =: r', so the angle alpha between y
// and y~ has sin alpha < s = r' / sqrt(8); if s < 1, y.y~ > 0 and y is proportional to y~ + E v
// with |v| = |E v| / |y~| = tan alpha < s / sqrt(1 - s^2) = t.
//
// PRODUCT OF CIRCLES (a flat torus in R^2m, circle i of rational radius r_i on (x_2i, x_2i+1),
// centred at 0): one circle chart per pair, phi(v) = (phi_1(v_1), ..., phi_m(v_m)),
// phi_i(t) = r_i ((1 - t^2) n_i + 2 t n_i') / (1 + t^2), n_i a rational unit vector near p's pair
// (built as for the sphere, N = 2) and n_i' = (-n_i2, n_i1). (a): n_i' is orthogonal to n_i with
// the same norm, so |(1 - t^2) n_i + 2 t n_i'|^2 = (1 - t^2)^2 + 4 t^2 = (1 + t^2)^2 once |n_i|^2 = 1
// (checked exactly): phi(v) is on every circle, so in M. Lemma (b) per circle, as for the sphere
// with rho = r_i: x in B(p, r) has |x_i - p_i| < r, so |v_i| < t_i from r'_i = r + |p_i - r_i n_i|.
// As one RationalChart, D = prod (1 + v_i^2) (degree 2 in each variable); the cell analysis uses
// the separable form instead (param_cell.cpp, TorusModel).
//
// When s >= 1 (a ball too large for one chart) there is no rational chart: the caller uses the
// implicit engine (rvd.cpp).
#pragma once

#include <gmpxx.h>

#include <array>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "certify/detail/grid.hpp"
#include "certify/restricted/rvd.hpp"
#include "exact/polynomial.hpp"
#include "io/points.hpp"
#include "io/spec.hpp"

namespace delcert::certify::detail {

// phi = X / D over V0 = [-t, t]^m, as above: X has N polynomials in m variables, all of X and D
// of degree <= 2 (spheres, SO(3)) or of degree <= 2 in each variable (products of circles).
// M lies on the sphere |x - centre|^2 = radius2 (a round sphere: its own; SO(3): centre 0,
// radius2 = 3 = |x|^2 for an orthogonal x), which (a) makes exact on phi: |x - p|^2 is then affine
// in x on M, and |phi(v) - p|^2 D(v) = (radius2 - |p - centre|^2) D(v) - 2 (p - centre).Y(v) with
// Y = X - p D, one quadratic (rvd_param's distance enclosures).
struct RationalChart {
  std::vector<exact::Polynomial> X;
  exact::Polynomial D;
  double t = 0;
  std::vector<mpq_class> centre;
  mpq_class radius2;
};

// A product of circles' chart at p: per circle, r_i, n_i and the half-width t_i (V0 = prod [-t_i, t_i]).
struct TorusChart {
  std::vector<mpq_class> r;
  std::vector<std::array<mpq_class, 2>> n;
  std::vector<double> t;
};
std::optional<TorusChart> torus_chart(const io::ShapeSpec& shape, std::span<const double> p, double r);

// The chart at p for the ball B(p, r) (identities (a) checked), or none: another shape, or s >= 1.
// Throws std::logic_error when the identities fail.
std::optional<RationalChart> rational_chart(const io::ShapeSpec& shape, std::span<const double> p, double r);

class ParamCell {
 public:
  // nullptr when `shape` (verified, see above) has no rational chart of M ∩ B(p, graph_radius).
  // Throws std::logic_error when a chart fails its identities (a bug, never an input's fault).
  static std::unique_ptr<ParamCell> make(const io::ShapeSpec& shape, const io::PointSet& points, const PointGrid& grid,
                                         int p, const RestrictedCellOptions& options);
  virtual ~ParamCell() = default;
  // As RestrictedCell::first_pass / second_pass.
  virtual double first_pass() = 0;
  virtual RestrictedCellReport second_pass(double covering_target) = 0;
};

}  // namespace delcert::certify::detail
