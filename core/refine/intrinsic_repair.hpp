// The refiner's view of Del_M (rule not_intrinsic; docs/refinement.md, "Del_M check"): the
// certifier's own engines, called in-process on the current points, decide whether the output
// complex Del_TM(P) equals the restricted Delaunay complex Del_RM(P) (certify/restricted.hpp, the
// engine of check 12) and the intrinsic Delaunay complex Del_M(P) (certify/intrinsic.hpp, checks
// 14-15), and say where they break: the places the rule inserts a point. And, at the end of
// `delcert refine`, whether the certificate of the output certifies it whole.
//
// core -> certify is allowed (the refiner uses the certifier's engines); certify never includes core.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "io/points.hpp"
#include "io/spec.hpp"

namespace delcert::certify {
struct Certificate;
}

namespace delcert::refine {

// One m-simplex (or place) where Del_TM, Del_RM and Del_M are not proven equal.
struct DelMBreak {
  std::vector<int> simplex;      // sorted point indices; for an undecided place of the restricted engine, its candidates
  std::string what;              // e.g. "only in Del_RM", "in Del_TM and Del_RM, not proven in Del_M: <reason>"
  std::vector<double> location;  // where it breaks (ambient, near M, not projected yet); empty: none known
};

struct DelMComparison {
  bool restricted_computed = false;  // the restricted engine ran (m <= 3)
  bool intrinsic_computed = false;   // the intrinsic engine had a closed-form metric (intrinsic_applies)
  std::string intrinsic_reason;      // why Del_M was not computed, when not
  std::size_t tangential = 0, restricted = 0, intrinsic = 0;  // m-simplices of each complex found
  // Sorted by simplex (places without one last). Empty: Del_TM = Del_RM = Del_M as far as the engines
  // decide (Del_M only where intrinsic_computed, Del_RM only where restricted_computed).
  std::vector<DelMBreak> breaks;
  double seconds = 0;
  bool equal() const { return breaks.empty(); }
};

// Del_TM(P) (the m-simplices given, each sorted) against Del_RM(P) and Del_M(P), computed by the
// certifier's engines exactly as delcert-certify computes checks 12-15 (the same options; Del_M's
// candidates are Del_TM's and Del_RM's simplices). A break is every m-simplex that is not in all
// three complexes, or that either engine rejects or leaves undecided, every lower-dimensional
// simplex of Del_RM (Del_RM not pure), every undecided box and unresolved face of an incomplete
// restricted cell (its candidates, at the box's centre), and, when nothing else is found, a
// restricted covering argument that does not hold (at the farthest point of the cell attaining the
// covering bound) or an incomplete Del_M (no location). Locations: the restricted Voronoi vertex
// (the enclosure's midpoint) for a simplex in Del_RM, else the intrinsic Voronoi vertex of its
// witness for a simplex in Del_M, else none (the caller picks one).
//
// What cannot be decided does not apply: without a closed-form metric (see intrinsic_applies)
// Del_M is left out, and for m > 3 Del_RM is.
DelMComparison compare_with_del_m(const io::ManifoldSpec& spec, const io::PointSet& points,
                                  const std::vector<std::vector<int>>& tangential_simplices, int threads);

// Whether the certificate of a refined output certifies it whole, as far as the certifier can
// decide: every claimed check (and every check decided but only reported) CERTIFIED, except the
// checks that could not be computed for a reason the engines state about the manifold, not about
// the output: Del_M (checks 14-15) without a closed-form geodesic distance, Del_RM (checks 11-13)
// for m > 3. This is the ONE place where "not computed" is forgiven; when the general Del_M engine
// computes Del_M for every manifold, check 14's "not computed" no longer occurs and nothing else
// changes. `failing` names each check that prevents it ("check 15 restricted_equals_intrinsic
// REFUTED: <summary>"), `not_decidable` each check forgiven.
struct WholeVerdict {
  bool certified = false;
  std::vector<std::string> failing;
  std::vector<std::string> not_decidable;
};
WholeVerdict certifies_whole(const certify::Certificate& certificate);

}  // namespace delcert::refine
