#include "certify/restricted/checks.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <optional>
#include <set>

#include "certify/detail/parallel.hpp"

namespace delcert::certify::detail {

using nlohmann::json;
using exact::Tri;

namespace {

json box_json(const exact::Box& X) {
  json b = json::array();
  for (const auto& i : X) b.push_back(enclosure_json(i));
  return b;
}

}  // namespace

json vertex_witness(const RestrictedSimplex& s) {
  return {{"kind", "restricted_voronoi_vertex"},
          {"simplex", s.simplex},
          {"found_at", s.found_at},
          {"vertex_enclosure", box_json(s.vertex.x)},
          {"detail", "Krawczyk proves exactly one point of M in this box equidistant from the simplex's points, and "
                     "every other sample point is certainly farther from every point of the box: the simplex is in "
                     "Del_RM(P)"}};
}

// A simplex of Del_RM(P) of dimension < m that no m-simplex found contains (a face point, rvd.hpp).
namespace {

json face_witness(const RestrictedSimplex& s, bool complete) {
  return {{"kind", "face_point"},
          {"simplex", s.simplex},
          {"found_at", s.found_at},
          {"point_enclosure", box_json(s.vertex.x)},
          {"detail", std::string("Krawczyk proves a point of M in this box equidistant from the simplex's points, and "
                                 "every other sample point is certainly farther from every point of the box: the "
                                 "simplex is in Del_RM(P); ") +
                         (complete ? "Del_RM(P) is known completely and no m-simplex of it contains this simplex: "
                                     "Del_RM(P) is not pure"
                                   : "no m-simplex found contains it")}};
}

json location_json(const std::vector<double>& x) {
  json j = json::array();
  for (double v : x) j.push_back(num(v));
  return j;
}

}  // namespace

// Check 11: the certified covering radius (P is an eps-sample of M), against the covering claim.
// A per-point covering claim compares each cell's bound with eps(p), but the bounds are refined only
// against the largest vertex distance found anywhere (COVERING TARGET, restricted.hpp): a cell far
// smaller than the largest keeps a loose bound. Such a cell is analysed again on its own (both
// passes, same radius and options: the target is its own vertices), and its bound replaced by the
// new one when that is complete and smaller: both are certified upper bounds of max |x - p| over
// the same set M ∩ Vor(p) ∩ B(p, r_p), so the covering argument is unchanged. Work only.
void sharpen_per_point_cells(RestrictedDelaunay& R, const std::vector<mpq_class>& eps, const exact::ImplicitSystem& system,
                             const io::PointSet& P, const detail::PointGrid& grid, const RestrictedCellOptions& options,
                             int threads) {
  std::vector<int> loose;
  for (std::size_t p = 0; p < R.cells.size(); ++p)
    if (R.cells[p].complete && !(R.cells[p].covering_bound < exact::enclose(eps[p]).lo)) loose.push_back(static_cast<int>(p));
  detail::parallel_for(loose.size(), threads, [&](std::size_t i, int) {
    RestrictedCellReport& cell = R.cells[loose[i]];
    RestrictedCellOptions o = options;
    o.graph_radius = cell.graph_radius;
    o.covering_width = options.covering_width / 16;  // boxes 16 times narrower: the bound within ~1/2000 of r_p
    const RestrictedCellReport again = analyse_restricted_cell(system, P, grid, loose[i], o);
    if (again.complete && again.covering_bound < cell.covering_bound)
      cell.covering_bound = again.covering_bound, cell.covering_location = again.covering_location;
  });
}

// With a per-point claim (claims v3, covering_per_point): every x in M whose nearest sample point
// is p has |x - p| < eps(p). CERTIFIED when the covering argument holds (restricted.hpp: every x
// with nearest point p lies in p's kept boxes) and every cell's certified bound is below eps(p);
// REFUTED by a certified restricted Voronoi vertex at distance >= eps(q) from a point q of its
// simplex (the vertex is in Vor(q), at the same distance from every point of the simplex).
// COVERAGE (certify/coverage.hpp): R.covering_certified includes that all of M is within c of P;
// a certified point of M farther from P than the claim (than c without a claim) refutes it.
CheckEntry check_covering(const RestrictedDelaunay& R, const CoverageProof& coverage, const std::optional<mpq_class>& claim,
                          const io::ManifoldSpec& spec, const std::vector<mpq_class>* per_point,
                          const std::string& per_point_file) {
  CheckEntry cov(CheckId::covering);
  if (!R.covering_certified) cov.undecide(R.reason);
  // R.covering (and every cell's covering_bound) bounds d(x, P) only under the covering argument: when it
  // fails they are maxima over the decided boxes, below the truth as often as not (the 16 vertices of a
  // tesseract on S^3: 0.99253 where the covering radius is 1). They are printed as certified only then, and
  // only with all of M proven within reach of P (coverage.proven: no component of M left unsampled).
  const bool upper_proven = R.covering_certified && coverage.proven;
  if (R.covering_certified && !coverage.proven) cov.undecide(coverage.reason);
  // A point of M far from P (coverage.search->far) refutes a claimed covering radius it reaches; without a claim it
  // refutes nothing the input says: only c, the certifier's own bound, which is then not printed (UNDECIDED).
  const FarPoint* far = coverage.search && coverage.search->far ? &*coverage.search->far : nullptr;
  // A certified lower bound of max_x d(x, P), proven in every case: the farthest restricted Voronoi vertex found
  // (a point of M whose nearest sample points are its simplex's, each certified on its own), or the far point.
  const double lower = std::max(R.vertex_distance_lower, far ? far->distance_lower : 0.0);
  if (claim) {
    cov.claim = {{"covering", exact::rational_to_string(*claim)},
                 {"meaning", "P is an eps-sample of M: d(x, P) < covering for every x in M"}};
    const exact::Interval e = exact::enclose(*claim);
    if (lower >= e.hi) {  // a point of M (a certified vertex) at distance >= the claim from P
      cov.refute("a point of M is at distance >= the claimed covering radius from P");
      for (const auto& s : R.simplices)
        if (s.distance_lower >= e.hi) {
          json w = vertex_witness(s);
          w["distance_to_P"] = {{"certified_lower_bound", num(s.distance_lower)}};
          w["detail"] = "a point of M (a certified restricted Voronoi vertex) whose nearest sample points, the "
                        "simplex's, are at distance >= the claim";
          cov.add_witness(w, 5);
        }
    } else if (!(R.covering < e.lo) && cov.verdict == Verdict::certified) {
      cov.undecide("the certified covering bound is not below the claim");
    }
    if (far && far->distance_lower >= e.hi) cov.refute("a point of M is at distance >= the claimed covering radius from P");
    if (cov.verdict == Verdict::certified) cov.require_at_most("covering_radius", R.covering, *claim);
  }
  json worst_cell, per_point_details;
  if (per_point) {
    mpq_class eps_max(0);
    for (const auto& e : *per_point) eps_max = std::max(eps_max, e);
    cov.claim = {{"covering_per_point", per_point_file},
                 {"meaning", "every x in M whose nearest sample point is p has |x - p| < eps(p) (eps(p) from the file)"},
                 {"max_eps", exact::rational_to_string(eps_max)}};
    long refuting = 0;
    for (const auto& s : R.simplices)
      for (int q : s.simplex) {
        const mpq_class& e = (*per_point)[q];
        if (!(s.distance_lower >= exact::enclose(e).hi)) continue;
        ++refuting;
        cov.refute("a point of M in the restricted Voronoi cell of p is at distance >= eps(p) from p");
        json w = vertex_witness(s);
        w["point"] = q;
        w["eps_at_point"] = exact::rational_to_string(e);
        w["distance_to_point"] = {{"certified_lower_bound", num(s.distance_lower)}};
        w["detail"] = "a certified restricted Voronoi vertex: its nearest sample points are the simplex's, all at the "
                      "same distance, which is >= eps(point)";
        cov.add_witness(w, 5);
      }
    // The cells whose certified bound is not below eps(p), and the tightest one (largest bound / eps(p)).
    long not_below = 0;
    double worst = -1;
    for (std::size_t p = 0; upper_proven && p < R.cells.size() && p < per_point->size(); ++p) {
      const exact::Interval e = exact::enclose((*per_point)[p]);
      const double ratio = R.cells[p].covering_bound / e.lo;
      if (ratio > worst)
        worst = ratio, worst_cell = {{"point", p}, {"eps_at_point", exact::rational_to_string((*per_point)[p])},
                                     {"certified_upper_bound", num(R.cells[p].covering_bound)}};
      if (!(R.cells[p].covering_bound < e.lo)) ++not_below;
    }
    if (far && far->distance_lower >= exact::enclose(eps_max).hi)
      cov.refute("a point of M is at distance >= max eps(p) from P, so >= eps(q) from its nearest point q");
    if (not_below > 0 && cov.verdict == Verdict::certified)
      cov.undecide(std::to_string(not_below) + " cells' certified covering bound is not below their eps(p)");
    if (cov.verdict == Verdict::certified) cov.require_at_most("covering_radius", R.covering, eps_max);
    per_point_details = {{"cells_not_below_eps", upper_proven ? json(not_below) : json(nullptr)},
                         {"refuting_vertices", refuting},
                         {"tightest_cell", worst_cell}};
    if (!worst_cell.is_null())
      cov.bound_proven_whatever_the_verdict("/details/per_point/tightest_cell/certified_upper_bound",
                                            R.cells[worst_cell["point"].get<std::size_t>()].covering_bound,
                                            "the covering argument holds");
  }
  // Printed as certified only what is proven: the upper bound under the covering argument, the lower bound always.
  if (upper_proven) {
    cov.margin = {{"covering_radius", {{"certified_upper_bound", num(R.covering)}, {"certified_lower_bound", num(lower)}}},
                  {"attained_near", location_json(R.cells[R.covering_point].covering_location)},
                  {"in_the_cell_of", R.covering_point}};
    cov.bound_proven_whatever_the_verdict("/margin/covering_radius/certified_upper_bound", R.covering,
                                          "the covering argument holds");
  } else {
    cov.margin = {{"covering_radius",
                   {{"certified_lower_bound", num(lower)},
                    {"upper_bound", "not proven: " + (R.covering_certified ? coverage.reason
                                                                            : R.reason)}}}};
  }
  cov.bound_proven_whatever_the_verdict("/margin/covering_radius/certified_lower_bound", lower,
                                        "the farthest certified restricted Voronoi vertex or point of M far from P");
  cov.details = {{"assumptions",
                  {{"charts", R.reach_slabs == 0 && R.rational_chart_cells == 0
                                  ? "none: no reach and no graph property is assumed; the other sheets of "
                                    "M in each ball are excluded box by box (docs/design.md §3.8)"
                              : R.reach_slabs == 0
                                  ? "none: no reach and no graph property is assumed; " +
                                        std::to_string(R.rational_chart_cells) +
                                        " cells are analysed in a rational parametrisation of the verified shape "
                                        "(identities checked exactly), in the others the other sheets of M are "
                                        "excluded box by box (docs/design.md §3.8)"
                                                 : "the reach of M is at least " + spec.reach->text + " (the spec's, " +
                                                       "assumed): the graph lemma (docs/design.md §3.8) took " +
                                                       std::to_string(R.reach_slabs) + " chart slabs"},
                   {"components", coverage.argument}}},
                 {"min_analysed_radius", num(R.min_radius)},
                 {"rounds", R.rounds_used},
                 {"incomplete_cells", R.incomplete_points.size()},
                 {"boxes", R.boxes},
                 {"rational_chart_cells", R.rational_chart_cells},
                 {"krawczyk_calls", R.krawczyk_calls},
                 {"krawczyk_failures", R.krawczyk_failures}};
  if (per_point) cov.details["per_point"] = per_point_details;
  if (far) {
    json w = {{"kind", "point_of_M_far_from_P"},
              {"point_enclosure", box_json(far->x)},
              {"distance_to_P", {{"certified_lower_bound", num(far->distance_lower)}}},
              {"nearest_sample_point", far->nearest},
              {"detail", "Krawczyk proves exactly one point of M in this box (N - m coordinates free, the others "
                         "fixed); every sample point is at least distance_to_P from every point of the box"}};
    cov.bound_proven_whatever_the_verdict("/witnesses/" + std::to_string(cov.witnesses.size()) +
                                              "/distance_to_P/certified_lower_bound",
                                          far->distance_lower, "a point of M certified by Krawczyk, its distance to all of P");
    cov.add_witness(w);
  }
  if (const auto& S = coverage.search) {
    json u = json::array();
    for (const auto& x : S->undecided) u.push_back(location_json(x));
    cov.details["coverage_search"] = {{"boxes", S->boxes}, {"free_of_M", S->excluded}, {"inside_a_ball", S->inside_balls},
                                      {"krawczyk_calls", S->krawczyk_calls}, {"undecided_boxes", S->undecided_boxes},
                                      {"undecided_at", u}, {"size_limit", num(S->size_limit)}};
  }
  json undecided = json::array();
  for (int p : R.incomplete_points) {
    if (undecided.size() >= 10) break;
    const auto& c = R.cells[p];
    json u = {{"point", p}, {"reason", c.reason}};
    if (!c.undecided.empty())
      u["location"] = location_json(c.undecided[0].location), u["candidates"] = c.undecided[0].candidates,
      u["why"] = c.undecided[0].reason;
    undecided.push_back(u);
  }
  cov.details["undecided_examples"] = undecided;
  long undecided_boxes = 0;
  for (const auto& c : R.cells) undecided_boxes += static_cast<long>(c.undecided.size());
  cov.details["undecided_boxes"] = undecided_boxes;
  cov.summary = (upper_proven ? "P is an eps-sample of M with eps <= " + num(R.covering)
                              : "covering radius not certified (" + (R.covering_certified ? coverage.reason : R.reason) + ")") +
                (far && far->distance_lower >= R.vertex_distance_lower ? "; a point of M is at distance >= " : "; a restricted Voronoi vertex is at distance >= ") + num(lower) + " from P" +
                (claim ? "; claim " + exact::rational_to_string(*claim) : "") +
                (per_point ? "; claim eps(p) per point (" + per_point_file + "), tightest cell " +
                                 (worst_cell.is_null() ? std::string(upper_proven ? "none" : "not known") : worst_cell["point"].dump() + ": bound " +
                                                                                   worst_cell["certified_upper_bound"].dump() +
                                                                                   " vs eps(p) " + worst_cell["eps_at_point"].get<std::string>())
                           : "");
  return cov;
}

// The m-simplices of a complex, each sorted.
std::set<Simplex> top_simplices(const io::Complex& K, int m) {
  std::set<Simplex> tops;
  for (Simplex s : K.simplices)
    if (static_cast<int>(s.size()) == m + 1) std::sort(s.begin(), s.end()), tops.insert(std::move(s));
  return tops;
}

std::string equality(Verdict v, const std::string& a, const std::string& b) {
  return v == Verdict::certified ? a + " = " + b : v == Verdict::refuted ? a + " != " + b : a + " = " + b + " not decided";
}

// Check 12: Del_RM(P) computed (every m-simplex with a certified restricted Voronoi vertex; all
// of them when the covering argument holds; pure when no face is in doubt) and, with --kind
// restricted, compared with the given complex. Every REFUTED rests on witnesses re-checked by
// certify/restricted_recheck.hpp before they are printed: a simplex of Del_RM(P) by its nearest-set
// proof, a rejection by completeness by the covering argument's premises (a failure there is an
// internal error, never a verdict).
//
// When Del_RM(P) is known completely and not pure (a face point: a simplex of it of dimension < m in
// no m-simplex), the verdict is REFUTED: check 12 claims that Del_RM(P) is a pure m-complex (a
// triangulation candidate) equal to the complex, and the face point proves the first part false.
// If the complex's m-simplices are exactly Del_RM(P)'s, the complex is not what is wrong: the
// summary and reason say so ("Del_RM(P) is not pure: it triangulates nothing"), and the lower faces
// are not counted as missing from it (no pure m-complex could hold them as maximal simplices).
CheckEntry check_restricted(const RestrictedDelaunay& R, const std::optional<io::Complex>& given, bool claimed, int m,
                            const RecheckInput& recheck) {
  CheckEntry rd(CheckId::restricted_delaunay);
  if (!R.covering_certified) rd.undecide("Del_RM(P) not known completely: " + R.reason);
  long unresolved = 0;
  json impure = json::array();
  for (const auto& c : R.cells)
    for (const auto& f : c.unresolved_faces) {
      ++unresolved;
      if (impure.size() < 10) impure.push_back({{"face", f.candidates}, {"at_point", c.point},
                                               {"location", location_json(f.location)}, {"why", f.reason}});
    }
  // A refutation by completeness: its premise is re-checked once, before the first one is printed.
  bool premise_checked = false;
  auto by_completeness = [&](const std::string& why) {
    if (!premise_checked) require_completeness(recheck, R, "check 12 (restricted_delaunay): " + why);
    premise_checked = true;
    rd.refute(why);
  };
  // Witnesses printed (CheckEntry::add_witness's cap), each re-checked; the first of each refutation
  // (`first`) is re-checked even when the cap hides it: the verdict rests on it.
  constexpr std::size_t kShown = 20;
  auto proven = [&](const RestrictedSimplex& s, json w, const char* field, bool first) {
    if (first || rd.witnesses.size() < kShown)
      w[field] = box_json(require_nearest_set(recheck, s.simplex, s.vertex.x, "check 12 (restricted_delaunay)"));
    rd.add_witness(std::move(w), kShown);
  };
  // The m-simplices of the complex, and whether they are exactly Del_RM(P)'s (when it is complete).
  std::set<Simplex> tops, found;
  if (claimed && given) tops = top_simplices(*given, m);
  for (const auto& s : R.simplices) found.insert(s.simplex);
  const bool tops_equal = claimed && given && R.covering_certified && tops == found;
  const bool impure_known = !R.lower_faces.empty() && R.covering_certified;
  if (unresolved || (!R.lower_faces.empty() && !R.covering_certified))
    rd.undecide("Del_RM(P) may not be pure: a restricted Voronoi face of dimension > 0 may hold no vertex (see "
                "details.possibly_impure and the face_point witnesses)");
  if (impure_known)
    by_completeness(tops_equal ? "Del_RM(P) is not pure: it triangulates nothing (the complex's m-simplices are exactly "
                                 "Del_RM(P)'s; Del_RM(P) also holds a simplex of lower dimension in none of them, "
                                 "which no complex of m-simplices can be)"
                               : "Del_RM(P) is not pure: a simplex of it is in no m-simplex");
  for (const auto& f : R.lower_faces)
    impure_known ? proven(f, face_witness(f, true), "point_enclosure", &f == &R.lower_faces.front())
                 : rd.add_witness(face_witness(f, false), kShown);
  for (const auto& f : R.cross_check_failures)
    rd.add_witness({{"kind", "cross_check_failure"}, {"simplex", f.simplex}, {"found_at", f.found_at},
                    {"missed_at", f.missed_at}}, kShown);
  long missing = 0, extra = 0;
  if (claimed && given) {
    for (const auto& s : R.simplices) {
      if (tops.count(s.simplex)) continue;
      ++missing;  // certified without any assumption: refuted whatever else is undecided
      rd.refute("a simplex of Del_RM(P) is missing from the complex");
      proven(s, vertex_witness(s), "vertex_enclosure", missing == 1);
    }
    if (!tops_equal)
      for (const auto& f : R.lower_faces) {  // in Del_RM without any assumption: missing unless a face of the complex
        if (std::any_of(given->simplices.begin(), given->simplices.end(), [&](Simplex t) {
              std::sort(t.begin(), t.end());
              return std::includes(t.begin(), t.end(), f.simplex.begin(), f.simplex.end());
            }))
          continue;
        ++missing;
        rd.refute("a simplex of Del_RM(P) is missing from the complex");
        if (!impure_known) proven(f, face_witness(f, false), "point_enclosure", missing == 1);  // (else shown above)
      }
    // Simplices of other dimensions: Del_RM has none above m when it is known completely (a point of M equidistant
    // from m + 2 points never resolves), and when it is pure every lower one is a face of an m-simplex.
    for (Simplex s : given->simplices) {
      std::sort(s.begin(), s.end());
      if (static_cast<int>(s.size()) == m + 1) continue;
      bool face = false;
      for (const auto& t : tops)
        if (std::includes(t.begin(), t.end(), s.begin(), s.end())) {
          face = true;
          break;
        }
      for (const auto& f : R.lower_faces)  // a face of a proven lower simplex of Del_RM
        face = face || std::includes(f.simplex.begin(), f.simplex.end(), s.begin(), s.end());
      if (face && static_cast<int>(s.size()) < m + 1) continue;
      ++extra;
      if (!R.covering_certified || unresolved) continue;  // not proven absent
      by_completeness("a simplex of the complex is not in Del_RM(P)");
      rd.add_witness({{"kind", static_cast<int>(s.size()) > m + 1 ? "wrong_dimension" : "not_a_face_of_an_m_simplex"},
                      {"simplex", s},
                      {"detail", "Del_RM(P) is known completely, has no simplex of dimension above m, and is pure"}},
                     kShown);
    }
    for (const auto& s : tops) {
      if (found.count(s)) continue;
      ++extra;
      if (!R.covering_certified) continue;  // not proven absent
      by_completeness("a simplex of the complex is not in Del_RM(P)");
      rd.add_witness({{"kind", "not_restricted"}, {"simplex", s},
                      {"detail", "the restricted Voronoi cells of all points were computed completely (check 11) and "
                                 "no point of M is equidistant from these m + 1 points and closer to them than to every "
                                 "other point"}},
                     kShown);
    }
    rd.claim = {{"kind", "restricted"}, {"meaning", "the complex is the restricted Delaunay complex Del_RM(P)"}};
  }
  const bool known = R.covering_certified && !unresolved;
  rd.details.update(json{{"m_simplices", R.simplices.size()}, {"cross_check_failures", R.cross_check_failures.size()},
                         {"possibly_impure_faces", unresolved}, {"possibly_impure", impure},
                         {"lower_faces_in_no_m_simplex", R.lower_faces.size()},
                         {"pure", impure_known ? json(false) : known ? json(true) : json(nullptr)}});
  if (claimed && given) {
    rd.details["missing_simplices"] = missing, rd.details["extra_simplices"] = extra;
    if (R.covering_certified) rd.details["m_simplices_equal_to_the_complex"] = tops_equal;
  }
  rd.summary = "Del_RM of the points: " + std::to_string(R.simplices.size()) + " m-simplices certified" +
               (R.covering_certified ? " (all of them)" : " (maybe not all)") +
               (tops_equal ? ", exactly the given complex's" : given && !claimed ? "; the given complex is checked against another complex (check 3 or 14), not this one" : "") +
               (impure_known ? "; Del_RM(P) is not pure, so it triangulates nothing: " + std::to_string(R.lower_faces.size()) +
                                   " simplices of lower dimension in no m-simplex"
                : unresolved || !R.lower_faces.empty() ? "; purity not proven" : "") +
               (claimed && given && !tops_equal
                    ? (missing || R.covering_certified ? "; the given complex is not it: " + std::to_string(missing) + " simplices of Del_RM missing from it, "
                                                       : "; the given complex is not proven to be it: ") + std::to_string(extra) + " of its simplices " + (R.covering_certified ? "not in Del_RM" : "not proven in Del_RM")
                    : "");
  return rd;
}

// Check 13: Del_TM(P) = Del_RM(P) on m-simplices, decided either way with witnesses.
CheckEntry check_tangential_equals_restricted(const Stars& st, const RestrictedDelaunay& R) {
  CheckEntry eq(CheckId::tangential_equals_restricted);
  std::set<Simplex> tm;
  long unknown_stars = 0, given_differs = 0;  // (stars where the given complex, if any, is not Del_TM)
  for (const auto& r : st.reports) {
    if (r.state == StarReport::State::proven) {  // (claimed_verified: star holds the claimed cells)
      for (auto& s : r.simplices()) tm.insert(std::move(s));
      given_differs += st.verify && !r.claimed_verified;
    } else {
      ++unknown_stars;
    }
  }
  std::set<Simplex> rm;
  long only_rm = 0, only_tm = 0;
  for (const auto& s : R.simplices) {
    rm.insert(s.simplex);
    if (tm.count(s.simplex)) continue;
    if (unknown_stars) continue;
    ++only_rm;
    eq.refute("a simplex of Del_RM(P) is not in Del_TM(P)");
    json w = vertex_witness(s);
    w["not_in"] = "Del_TM(P)";
    eq.add_witness(w);
  }
  for (const auto& s : tm) {
    if (rm.count(s) || !R.covering_certified) continue;
    ++only_tm;
    eq.refute("a simplex of Del_TM(P) is not in Del_RM(P)");
    eq.add_witness({{"kind", "not_restricted"}, {"simplex", s}, {"in", "Del_TM(P)"},
                    {"detail", "it is in a tangential star, but the complete restricted Voronoi diagram (check 11) has "
                               "no vertex dual to it"}});
  }
  if (eq.verdict == Verdict::certified) {
    if (unknown_stars) eq.undecide(std::to_string(unknown_stars) + " star(s) not determined exactly");
    else if (!R.covering_certified) eq.undecide("Del_RM(P) not known completely: " + R.reason);
  }
  eq.details = {{"tangential_m_simplices", tm.size()}, {"restricted_m_simplices", rm.size()},
                {"only_in_restricted", only_rm}, {"only_in_tangential", only_tm}, {"stars_undetermined", unknown_stars}};
  eq.summary = equality(eq.verdict, "Del_TM of the points", "Del_RM of the points") + " (" + std::to_string(tm.size()) + " and " +
               std::to_string(rm.size()) + " m-simplices; " + std::to_string(only_tm) + " only tangential, " + std::to_string(only_rm) +
               " only restricted)" + (given_differs ? "; the given complex is not Del_TM: " + std::to_string(given_differs) + " of its stars differ (check 3)" : "");
  return eq;
}

}  // namespace delcert::certify::detail
