// The facets of the convex hull K of points y_i on a round sphere (centred at the origin of R^D),
// decided one candidate at a time in certified arithmetic, completed by gift wrapping and proven
// complete by counting ridges (docs/design.md §3.9). Shared by the Del_M engines whose geodesic
// balls lift to caps of a round sphere: the sphere itself (certify/intrinsic_sphere.cpp, y = the
// projected points) and SO(3) through its double cover S^3 (certify/intrinsic_so3.cpp, y = the
// unit quaternions +-q of the projected points).
//
// A FACET. An id set s (D ids) is certified when every other y lies STRICTLY on one side of the
// affine hyperplane H(s) through y_s: then conv(y_s) is a facet of K and the cap beyond H(s) on the
// other side is empty, its boundary holding y_s only. It is rejected when two y's lie strictly on
// opposite sides (no cap bounded by H(s) is empty). Ties and undecided signs leave it undecided.
// An engine may bound the ids worth testing: the ones that can lie in the closed cap on the side
// of H(s) away from the origin; every other id is then strictly on the origin's side.
//
// COMPLETENESS. If every ridge (D - 1 ids) of every certified facet lies in exactly two certified
// facets, the certified facets are all the facets of K (in a polytope every ridge lies in exactly
// two facets and the facet-ridge graph is connected). With a symmetric set (y_{antipode(i)} =
// -y_i), facets are counted modulo the antipodal map: the class of a ridge r holds as many
// certified classes as there are facets through r (no facet holds both y and -y: H(s) would pass
// through the origin, and y's antipodes would then lie on both sides).
#pragma once

#include <cmath>
#include <functional>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "exact/interval_arithmetic.hpp"

namespace delcert::certify::detail {

enum class HullSide { positive, negative, zero, unknown };

// det of the k x k matrix rows[0..k) (each a pointer to entries col .. col + k - 1), k <= 7, by
// Laplace expansion along the first column, its minors memoised by row subset (2^k k products
// instead of k!, no allocation). Each minor is expanded exactly as the plain recursion would
// (rows in increasing order, alternating signs, the sum started at 0), so the result is the same
// number, bit for bit, for intervals too. Division-free: exact for mpq_class, an enclosure for
// IntervalNumber (under UpwardRounding).
template <class T>
T laplace(const std::vector<const T*>& rows, int col, int k) {
  if (k < 1 || k > 7) throw std::invalid_argument("laplace: size outside 1..7");
  T minor[1 << 7];
  // minor[mask] = det of the rows in mask and the last popcount(mask) columns
  for (unsigned mask = 1; mask < (1u << k); ++mask) {
    const int c = __builtin_popcount(mask), column = col + k - c;
    if (c == 1) {
      minor[mask] = rows[__builtin_ctz(mask)][column];
      continue;
    }
    T sum(0);
    int position = 0;
    for (int j = 0; j < k; ++j) {
      if (!(mask >> j & 1u)) continue;
      T d = rows[j][column] * minor[mask & ~(1u << j)];
      if (position++ % 2) sum -= d;
      else sum += d;
    }
    minor[mask] = sum;
  }
  return minor[(1u << k) - 1];
}

inline int sign_of(const exact::IntervalNumber& x) { return x.inf() > 0 ? 1 : x.sup() < 0 ? -1 : 0; }

// A certified upper bound of the circumradius of the k + 1 points a[0..k] of R^D (each D
// enclosures, 1 <= k <= D), +inf when not bounded: the Gram system of the edge vectors solved by
// Cramer's rule in intervals (+inf when its determinant's enclosure is not > 0). Call under
// UpwardRounding.
double circumradius_upper(const std::vector<std::vector<exact::IntervalNumber>>& a);

struct LiftedSphere {
  int D = 0;
  std::size_t count = 0;  // ids 0 .. count - 1
  // Certified sign of det [[1, y_j]] over the D + 1 ids of `rows` (the last is the tested one).
  std::function<HullSide(const std::vector<int>& rows)> orient;
  // orient(s, origin) for a facet's D ids; 0 when H(s) passes through the origin or not decided.
  std::function<int(const std::vector<int>& facet)> centre_side;
  // Called when centre_side != 0: a superset `ids` (sorted) of the ids whose y may lie in the
  // closed cap beyond H(facet) away from the origin, found within `radius` (a certified bound the
  // witness reports); radius = +inf: no bound, every id is tested.
  struct Cap {
    std::vector<int> ids;
    double radius = INFINITY;
  };
  std::function<Cap(const std::vector<int>& facet)> cap;
  // Ids near ridge[0], about `chord` away on the unit sphere and more: gift wrapping's search
  // (proposals only, nothing trusted).
  std::function<std::vector<int>(const std::vector<int>& ridge, double chord)> near;
  std::vector<std::vector<double>> approx;  // #count by D: unit vectors near y_i, in doubles (proposals only)
  std::function<int(int)> antipode;         // y_{antipode(i)} = -y_i, or empty (no symmetry)
};

struct HullDecision {
  enum class Kind { certified, rejected, undecided } kind = Kind::undecided;
  int both_sides[2] = {-1, -1};  // rejected: an id strictly on the positive / negative side
  int untested = -1;             // an id not tested, strictly on the origin's side (or -1)
  int tie = -1, unknown = -1;    // undecided: an id exactly on H(s) / whose side was not decided
                                 // (neither: undecided because no other id decides the side)
  long tested = 0;               // ids tested
  int centre_side = 0;
  bool empty_cap_small = false;  // certified: the empty cap is the one not holding the origin
  double radius = INFINITY;      // the test radius used
};

// The sorted id set, or its antipodal image when that is lexicographically smaller.
std::vector<int> canonical(const LiftedSphere& S, const std::vector<int>& ids);

HullDecision decide_facet(const LiftedSphere& S, const std::vector<int>& facet);

// Decides the canonical forms of `batch` not yet in `decided`, in parallel (deterministic).
void decide_facets(const LiftedSphere& S, const std::vector<std::vector<int>>& batch,
                   std::map<std::vector<int>, HullDecision>& decided, int threads);

// Gift wrapping across every ridge that lies in one certified facet (rounds until no new
// candidate), then the ridge count: nullopt when the certified facets close up (all the facets of
// K), otherwise the first (canonical) ridge that does not lie in exactly two of them.
struct OpenRidge {
  std::vector<int> ridge;
  int facets = 0;
};
std::optional<OpenRidge> wrap_and_count(const LiftedSphere& S, std::map<std::vector<int>, HullDecision>& decided,
                                        int threads);

}  // namespace delcert::certify::detail
