// The intrinsic Delaunay complex Del_M(P): the nerve of the Voronoi diagram of P on M for the
// geodesic distance d_M (docs/design.md §3.9; checks 14 and 15, issue 12). Computed only where
// the spec declares a closed-form metric (io::ShapeSpec in `metric`):
//   * sphere (M a round hypersphere, m = N - 1): certify/intrinsic_sphere.cpp;
//   * product_of_circles (a flat torus, N = 2m): certify/intrinsic_torus.cpp;
//   * so3 (SO(3) in R^9, the Frobenius metric): certify/intrinsic_so3.cpp;
//   * product (any other product of round spheres, m <= 3, e.g. S^2 x S^1): geodesic Voronoi
//     cells, certify/intrinsic_product.cpp;
//   * anything else, m <= 3: bounds of the geodesic distance (certify/intrinsic/general.hpp), from
//     check 12's certified Del_RM(P); without those, not computed, with the reason.
//
// POINTS NEAR M. d_M(x, p) is defined for x, p in M; the sample's points are doubles, only near
// M. Convention (stated in the certificate): d_M(x, p) := d_M(x, pi(p)), pi the nearest-point
// projection onto M in closed form for the supported metrics (sphere: the radial projection
// from the centre; product of circles: the radial projection within each coordinate plane;
// SO(3): the nearest rotation, certified as an eigenvector; product: the radial projection
// within each factor's block).
// So Del_M(P) := Del_M(pi(P)). The projections are irrational; every predicate on them is
// evaluated in certified arithmetic (exact rationals where possible, MPFI enclosures otherwise)
// and a sign that the enclosure cannot decide leaves the simplex UNDECIDED: ties are "not
// protected", never guessed.
//
// CANDIDATES. The caller passes candidate m-simplices (the Del_RM and Del_TM simplices found by
// checks 3 and 12). Each is decided on its own: certified in Del_M (with its intrinsic Voronoi
// vertex as witness), proven not in Del_M (with a witness), or undecided. COMPLETENESS is proven
// without trusting the candidates: the certified simplices form a closed pseudomanifold (every
// (m-1)-face in exactly two of them), and each engine proves why that forces them to be all of
// Del_M (see its .cpp).
#pragma once

#include <nlohmann/json.hpp>

#include <optional>
#include <string>
#include <vector>

#include "certify/detail/grid.hpp"
#include "io/points.hpp"
#include "io/spec.hpp"

namespace delcert::certify {

struct IntrinsicSimplex {
  std::vector<int> simplex;  // sorted point indices, m + 1 of them
  nlohmann::json witness;    // why it is in Del_M (kind "intrinsic_voronoi_vertex": the vertex, radius, margin)
};

struct IntrinsicRejection {
  std::vector<int> simplex;
  nlohmann::json witness;  // why it is not in Del_M (kind "not_intrinsic": the point(s) proven closer)
};

struct IntrinsicUndecided {
  std::vector<int> simplex;
  std::string reason;  // e.g. "a point is on the boundary of its empty geodesic ball (not protected)"
};

// Where the completeness argument fails (the general engine; the refiner inserts points there).
struct IntrinsicUndecidedPlace {
  std::vector<int> points;        // the point whose cell fails, or an undecided box's candidates
  std::string reason;
  std::vector<double> location;   // ambient, near M; empty: none known
};
struct IntrinsicDelaunay {
  bool computed = false;          // a supported closed-form metric; otherwise `reason` says why not
  std::string metric;             // "sphere", "product_of_circles", "so3", or "" (none declared)
  std::string convention;         // how d_M(x, p) is defined for p near M (see above), for the certificate
  std::string completeness;       // the completeness argument used, for the certificate
  std::vector<IntrinsicSimplex> simplices;   // certified m-simplices of Del_M(P), sorted by simplex, unique
  std::vector<IntrinsicRejection> rejected;  // candidates proven not in Del_M, sorted by simplex
  std::vector<IntrinsicUndecided> undecided; // candidates neither, sorted by simplex
  bool complete = false;          // `simplices` are ALL the m-simplices of Del_M(P), and Del_M is pure
  std::string reason;             // why not computed / not complete ("" when complete)
  std::vector<IntrinsicUndecidedPlace> undecided_places;  // every failing cell's first place (general engine)
};

// The spec's declared metric, normalised (a product of one sphere, of one SO(3), or of circles on
// (x1, x2), (x3, x4), ... in order, becomes that shape; any other product of spheres with m <= 3
// stays a product) and used only when the spec's equations
// are exactly the shape's (up to nonzero rational factors and order; for SO(3) the selector a
// positive multiple of det): then M IS that shape. `shape` is set only then (a round sphere with
// N = m + 1, circles with N = 2m, SO(3)); otherwise `metric` names what was declared ("" for
// none) and `reason` says why it is not used. Del_M (below) and the restricted cells' rational
// charts (certify/rvd_param.hpp) both rest on it.
struct VerifiedShape {
  std::optional<io::ShapeSpec> shape;
  std::string metric, reason;
};
VerifiedShape verify_declared_shape(const io::ManifoldSpec& spec);

struct GeneralMetricInput;  // certify/intrinsic/general.hpp

// `candidates`: sorted vertex sets with m + 1 entries (duplicates allowed). Never throws on
// geometric input; throws std::invalid_argument on a malformed candidate (wrong size, index out
// of range). Without a verified closed-form metric, `general` (when given, m <= 3) selects the
// general engine (certify/intrinsic/general.hpp: geodesic distance bounds, no closed form).
IntrinsicDelaunay compute_intrinsic_delaunay(const io::ManifoldSpec& spec, const io::PointSet& points,
                                             const detail::PointGrid& grid,
                                             const std::vector<std::vector<int>>& candidates, int threads,
                                             const GeneralMetricInput* general = nullptr);

}  // namespace delcert::certify
