#include "certify/tangential/checks.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <optional>
#include <set>

#include "exact/tangent_predicates.hpp"
#include "topology/three_sphere.hpp"

namespace delcert::certify::detail {

using nlohmann::json;
using exact::Tri;

namespace {

Simplex to_simplex(std::span<const int> s) { return {s.begin(), s.end()}; }  // a StarReport's cell, for a witness

// Is s in star(v)? Proven yes, proven no, or unknown, from the analysis of v.
// (s is an m-simplex containing r.p; in verify mode it is one of the claimed simplices at r.p.)
Tri member(const StarReport& r, const Simplex& s) {
  if (r.claimed_verified) return Tri::yes;
  for (const auto& c : r.claimed)
    if (c.simplex == s && (c.degenerate || c.conflict >= 0)) return Tri::no;  // a point in its ball
  if (r.state != StarReport::State::proven) return Tri::unknown;
  for (int i = 0; i < r.cells; ++i)
    if (std::ranges::equal(r.simplex(i), s)) return Tri::yes;
  return Tri::no;
}


const CellReport* find_cell(const std::vector<CellReport>& cells, const Simplex& s) {
  for (const auto& c : cells)
    if (c.simplex == s) return &c;
  return nullptr;
}

// Why s is not a cell at v: the point inside its ball, or its degeneracy.
json not_in_star_witness(const CellReport& c, int v) {
  json w = {{"simplex", c.simplex}, {"at_vertex", v}};
  if (c.degenerate) {
    w["kind"] = "degenerate_in_tangent_space";
    w["detail"] = "the projection of the simplex to T_v is affinely dependent: no centre on T_v (exact orientation 0)";
  } else if (c.conflict >= 0) {
    w["kind"] = "point_in_ball";
    w["point"] = c.conflict;
    w["exact_sign"] = -1;
    w["power"] = enclosure_json(c.conflict_power);
    w["detail"] = "|c - q|^2 - R^2 < 0 for the centre c on T_v: q lies strictly inside the simplex's ball";
  } else if (c.tie >= 0) {
    w["kind"] = "point_on_sphere";
    w["point"] = c.tie;
    w["exact_sign"] = 0;
  } else {
    w["kind"] = "not_a_cell";
  }
  return w;
}

}  // namespace

// Check 3: the complex is Del_TM(P).
CheckEntry check_stars(const Stars& st, int m) {
  CheckEntry stars(CheckId::stars);
  const std::size_t n = st.reports.size();
  long undetermined = 0, missing = 0, extra = 0, verified = 0;
  json undetermined_examples = json::array();
  for (const auto& s : st.wrong_dimension)
    stars.add_witness({{"kind", "wrong_dimension"}, {"simplex", s}, {"dimension", s.size() - 1}, {"expected", m}}),
        stars.refute("a maximal simplex does not have dimension m");
  for (const auto& r : st.reports) {
    if (r.claimed_verified) ++verified;
    if (r.state != StarReport::State::proven) {
      ++undetermined;
      if (undetermined_examples.size() < 10) undetermined_examples.push_back({{"point", r.p}, {"reason", r.reason}});
      continue;
    }
    if (!st.verify || r.claimed_verified) continue;
    std::set<Simplex> have;
    for (auto& s : st.claimed(r.p)) have.insert(std::move(s));
    for (const auto& c : r.star)
      if (!have.count(c.simplex)) {
        ++missing;
        stars.refute("a simplex of the tangential complex is missing from the complex");
        stars.add_witness({{"kind", "missing_simplex"},
                           {"simplex", c.simplex},
                           {"at_vertex", r.p},
                           {"radius_squared", enclosure_json(c.radius2)},
                           {"min_power_margin", lower_bound_json(c.margin)},
                           {"detail", "its ball centred on T_p contains no sample point (all exact signs > 0), so it is in "
                                      "star(p); the complex does not contain it"}});
      }
  }
  if (st.verify) {
    for (const auto& s : st.tops()) {
      Tri in_a_star = Tri::no;
      for (int v : s) in_a_star = either(in_a_star, member(st.reports[v], s));
      if (in_a_star == Tri::yes) continue;
      if (in_a_star == Tri::unknown) {
        stars.undecide("some stars could not be determined exactly");
        continue;
      }
      ++extra;
      stars.refute("a simplex of the complex is in no star of its vertices");
      const CellReport* c = find_cell(st.reports[s[0]].claimed, s);
      stars.add_witness(c ? not_in_star_witness(*c, s[0]) : json{{"kind", "not_in_star"}, {"simplex", s}});
    }
  }
  if (undetermined) stars.undecide(std::to_string(undetermined) + " star(s) not determined exactly (see details)");
  stars.details["points"] = n;
  stars.details["stars_undetermined"] = undetermined;
  stars.details["undetermined_examples"] = undetermined_examples;
  if (st.verify) {
    stars.details["claimed_stars_verified"] = verified;
    stars.details["missing_simplices"] = missing;
    stars.details["extra_simplices"] = extra;
    stars.details["wrong_dimension_simplices"] = st.wrong_dimension.size();
  }
  stars.summary = st.verify ? std::to_string(verified) + " of " + std::to_string(n) + " stars verified; " +
                                  std::to_string(missing) + " missing, " + std::to_string(extra) + " extra, " +
                                  std::to_string(st.wrong_dimension.size()) + " wrong-dimension simplices; " +
                                  std::to_string(undetermined) + " stars undetermined"
                            : "star(p) computed exactly for " + std::to_string(n - undetermined) + " of " +
                                  std::to_string(n) + " points (" + std::to_string(st.tops().size()) + " m-simplices)";
  return stars;
}

// Check 4: every m-simplex is in the star of each of its vertices. A simplex that the star
// analyses did not test at a vertex is tested there (test_cell) to name the witness.
CheckEntry check_consistency(const Stars& st, const StarSettings& S, exact::FilterContext& ctx) {
  CheckEntry cons(CheckId::consistency);
  long inconsistent = 0;
  for (const auto& s : st.tops()) {
    bool bad = false;
    for (int v : s) {
      const Tri mv = member(st.reports[v], s);
      if (mv == Tri::unknown) cons.undecide("some stars could not be determined exactly");
      if (mv != Tri::no) continue;
      if (!bad) ++inconsistent;
      bad = true;
      cons.refute("a simplex is not in the star of one of its vertices");
      if (cons.witnesses.size() < 20) {
        const CellReport* c = find_cell(st.reports[v].claimed, s);
        CellReport tested = c ? *c : test_cell(S, v, s, ctx);
        json w = not_in_star_witness(tested, v);
        if (tested.empty() && tested.tie < 0) w["kind"] = "not_in_star", w["detail"] = "empty ball but not a cell of star(v)";
        cons.add_witness(w);
      } else {
        cons.add_witness(json{{"simplex", s}, {"at_vertex", v}});
      }
    }
  }
  cons.details["m_simplices"] = st.tops().size();
  cons.details["inconsistent_simplices"] = inconsistent;
  cons.summary = std::to_string(st.tops().size() - inconsistent) + " of " + std::to_string(st.tops().size()) +
                 " m-simplices are in the star of every vertex";
  return cons;
}

// Check 6: every star simplex power-protected (beyond the claim, when given); exact ties refuted.
ProtectionResult check_power_protection(const Stars& st, const std::optional<mpq_class>& claim) {
  ProtectionResult R;
  CheckEntry& prot = R.entry;
  exact::Interval& min_margin = R.min_margin;
  json margin_at;
  long ties = 0, below_claim = 0;
  bool& all_determined = R.all_determined;  // else min_margin is a minimum over some cells only, not a bound over all
  for (const auto& r : st.reports) {
    if (r.state == StarReport::State::incomplete) {
      prot.undecide("some stars could not be determined"), all_determined = false;
      continue;
    }
    R.cells += r.cells;
    if (r.min_margin.lo < min_margin.lo)
      margin_at = {{"simplex", to_simplex(r.simplex(r.min_margin_cell))}, {"at_vertex", r.p}, {"point", r.min_margin_point}};
    min_margin = {std::min(min_margin.lo, r.min_margin.lo), std::min(min_margin.hi, r.min_margin.hi)};
    for (const auto& c : r.star) {  // (kept when a cell is a witness)
      if (c.degenerate || c.conflict >= 0) {
        prot.undecide("a star cell could not be certified"), all_determined = false;
        continue;
      }
      if (c.tie >= 0) {
        ++ties;
        prot.refute("exact tie: a sample point lies exactly on the sphere of a star simplex, which is not protected");
        prot.add_witness({{"kind", "point_on_sphere"}, {"simplex", c.simplex}, {"at_vertex", r.p}, {"point", c.tie},
                          {"exact_sign", 0}, {"detail", "|c - q|^2 - R^2 = 0 exactly"}});
      }
      if (c.protection_point >= 0) {
        ++below_claim;
        prot.refute("a star simplex is not power-protected by more than the claim");
        prot.add_witness({{"kind", "not_protected"}, {"simplex", c.simplex}, {"at_vertex", r.p}, {"point", c.protection_point},
                          {"exact_sign", c.protection_sign}, {"power", enclosure_json(c.protection_power)},
                          {"detail", "sign(|c - q|^2 - R^2 - claim) <= 0"}});
      }
    }
  }
  if (R.cells) {
    // What the verdict implies about the printed bound (the consistency guard, certificate.hpp).
    prot.require_at_least("min_power_margin", min_margin.lo, 0);
    if (claim) prot.require_at_least("min_power_margin", min_margin.lo, *claim);
    prot.margin = {{"min_power_margin", all_determined ? lower_bound_json(min_margin) : over_determined_json(min_margin)},
                   {"attained_near", margin_at}};
  }
  prot.details = {{"star_cells", R.cells}, {"exact_ties", ties}, {"below_claim", below_claim}};
  if (claim)
    prot.claim = {{"power_protection", exact::rational_to_string(*claim)},
                  {"meaning", "|c_p(s) - q|^2 - R_p(s)^2 > power_protection for every star simplex s at p and q not in s"}};
  prot.summary = (all_determined ? "min power margin >= " : "min power margin over the determined cells only (no bound) ") +
                 num(min_margin.lo) + " (enclosure [" + num(min_margin.lo) + ", " +
                 num(min_margin.hi) + "]) over " + std::to_string(R.cells) + " star cells; " + std::to_string(ties) +
                 " exact ties" +
                 (claim ? "; " + std::to_string(below_claim) + " not above the claim " + exact::rational_to_string(*claim) : "");
  return R;
}

// Check 10: every star simplex has R_p(s) < eps (the star_radius claim); without a claim, a report.
// With a per-point claim (claims v3), eps is eps(p) at each star's point p: `per_point` holds them
// (one per point) and `per_point_file` names the file; `eps` is then absent.
RadiusResult check_star_radius(const Stars& st, const std::optional<mpq_class>& eps,
                               const std::vector<mpq_class>* per_point, const std::string& per_point_file) {
  RadiusResult R;
  const bool claimed = eps || per_point;
  // The largest claimed bound: what a CERTIFIED verdict implies about the printed max (the guard).
  mpq_class eps_max = eps ? *eps : mpq_class(0);
  if (per_point)
    for (const auto& e : *per_point) eps_max = std::max(eps_max, e);
  CheckEntry& radius = R.entry;
  exact::Interval& max_r2 = R.max_r2;
  json radius_at;
  long too_big = 0;
  bool& all_determined = R.all_determined;  // else max_r2 is a maximum over some stars only, not a bound over all
  for (const auto& r : st.reports) {
    if (r.state == StarReport::State::incomplete) {
      radius.undecide("some stars could not be determined"), all_determined = false;
      continue;
    }
    R.cells += r.cells;
    if (r.max_radius2.hi > max_r2.hi) radius_at = {{"simplex", to_simplex(r.simplex(r.max_radius_cell))}, {"at_vertex", r.p}};
    max_r2 = {std::max(max_r2.lo, r.max_radius2.lo), std::max(max_r2.hi, r.max_radius2.hi)};
    for (const auto& c : r.star) {  // (kept when a cell is a witness)
      if (c.degenerate || c.conflict >= 0) continue;  // not a cell: check 6 is undecided
      if (claimed && c.eps_sign >= 0) {
        ++too_big;
        const mpq_class& e = eps ? *eps : (*per_point)[r.p];
        radius.refute(eps ? "a star simplex has R_p(s) >= eps" : "a star simplex at p has R_p(s) >= eps(p)");
        json w = {{"kind", "radius_not_below_eps"}, {"simplex", c.simplex}, {"at_vertex", r.p},
                  {"radius_squared", enclosure_json(c.radius2)}, {"eps_squared", rational_json(e * e)},
                  {"exact_sign", c.eps_sign}};
        if (!eps) w["eps_at_vertex"] = exact::rational_to_string(e);
        radius.add_witness(w);
      }
    }
  }
  if (R.cells) {
    // What the verdict implies about the printed bound (the consistency guard, certificate.hpp).
    if (claimed) radius.require_at_most("max_radius_squared", max_r2.hi, eps_max * eps_max);
    radius.margin = {{"max_radius_squared", all_determined ? json{{"certified_upper_bound", num(max_r2.hi)},
                                                                  {"enclosure", enclosure_json(max_r2)}}
                                                            : over_determined_json(max_r2)},
                     {"attained_at", radius_at}};
  }
  radius.details = {{"star_cells", R.cells}, {"not_below_eps", too_big}};
  if (eps) {
    radius.claim = {{"star_radius", exact::rational_to_string(*eps)},
                    {"meaning", "R_p(s) < star_radius for every star simplex"}};
  } else if (per_point) {
    radius.claim = {{"star_radius_per_point", per_point_file},
                    {"meaning", "R_p(s) < eps(p) for every star simplex s at every point p (eps(p) from the file)"},
                    {"max_eps", exact::rational_to_string(eps_max)}};
  } else if (radius.verdict == Verdict::certified) {
    radius.verdict = Verdict::report;
  }
  radius.summary = (all_determined ? "max R_p(s)^2 <= " : "max R_p(s)^2 over the determined stars only (no bound) ") +
                   num(max_r2.hi) +
                   (eps         ? "; " + std::to_string(too_big) + " star cells with R_p(s) >= star_radius = " +
                                      exact::rational_to_string(*eps)
                    : per_point ? "; " + std::to_string(too_big) + " star cells at p with R_p(s) >= eps(p) (" +
                                      per_point_file + ")"
                                : " (no star_radius claim)");
  return R;
}

// Check 8: the complex is a closed pseudomanifold with sphere links, and the topology the spec expects.
CheckEntry check_topology(const io::Complex& K, int m, const FaceLattice& lattice, const io::ExpectedTopology& expect, int threads) {
  CheckEntry topo(CheckId::topology);
  TopologyReport T = analyse_topology(K, m, &lattice, threads);
  if (!T.pure) topo.refute("not pure"), topo.add_witness({{"kind", "not_pure"}, {"simplex", T.impure_example}});
  if (T.boundary_ridges || T.singular_ridges) {
    topo.refute("not a closed pseudomanifold");
    topo.add_witness({{"kind", "ridge"}, {"simplex", T.ridge_example}, {"in_m_simplices", T.ridge_example_count}});
  }
  if (T.uncovered_vertices) topo.refute("some points are in no simplex");
  if (T.bad_links) {
    topo.refute("a vertex link is not an (m-1)-sphere");
    topo.add_witness({{"kind", "vertex_link"}, {"vertex", T.bad_link_example}, {"reason", T.bad_link_reason}});
  }
  if (T.unknown_links) topo.undecide("vertex links not recognised as spheres: " + T.bad_link_reason);
  if (expect.euler_characteristic && !T.f.empty() && *expect.euler_characteristic != T.euler)
    topo.refute("Euler characteristic differs from the spec's expected value");
  if (!expect.betti_z2.empty() && expect.betti_z2 != T.betti_z2)
    topo.refute("Betti numbers over Z/2 differ from the spec's expected values");
  if (!expect.betti_z3.empty() && expect.betti_z3 != T.betti_z3)
    topo.refute("Betti numbers over Z/3 differ from the spec's expected values");
  topo.details = {{"pure", T.pure}, {"boundary_ridges", T.boundary_ridges}, {"singular_ridges", T.singular_ridges},
                  {"strongly_connected_components", T.strong_components}, {"uncovered_vertices", T.uncovered_vertices},
                  {"links_not_spheres", T.bad_links}, {"links_unrecognised", T.unknown_links}, {"face_counts", T.f},
                  {"euler_characteristic", T.euler}, {"betti_z2", T.betti_z2}, {"betti_z3", T.betti_z3}};
  if (m >= 4) topo.details["link_recognition"] = topology::recogniser();  // decides 3-dimensional links
  json expected = json::object();
  if (expect.euler_characteristic) expected["euler_characteristic"] = *expect.euler_characteristic;
  if (!expect.betti_z2.empty()) expected["betti_z2"] = expect.betti_z2;
  if (!expect.betti_z3.empty()) expected["betti_z3"] = expect.betti_z3;
  topo.claim = expected.empty() ? json(nullptr) : expected;
  auto vec = [](const std::vector<long>& v) {
    std::string s = "(";
    for (std::size_t i = 0; i < v.size(); ++i) s += (i ? "," : "") + std::to_string(v[i]);
    return s + ")";
  };
  topo.summary = "chi = " + std::to_string(T.euler) + ", Betti Z/2 " + vec(T.betti_z2) + ", Z/3 " + vec(T.betti_z3) +
                 (expected.empty() ? " (no expected values in the spec)" : "");
  return topo;
}

}  // namespace delcert::certify::detail
