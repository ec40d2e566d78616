#include "certify/certify.hpp"

#include <algorithm>
#include <chrono>
#include <ctime>
#include <cmath>
#include <map>
#include <set>

#include "certify/claims.hpp"
#include "certify/grid.hpp"
#include "certify/parallel.hpp"
#include "certify/sanity.hpp"
#include "certify/sha256.hpp"
#include "certify/star.hpp"
#include "certify/theorem.hpp"
#include "certify/thickness.hpp"
#include "certify/topology.hpp"
#include "exact/number_types.hpp"
#include "exact/tangent_predicates.hpp"
#include "io/atomic_file.hpp"
#include "io/complex.hpp"
#include "io/input_error.hpp"
#include "io/spec.hpp"

namespace delcert::certify {

using nlohmann::json;

namespace {

enum class Member { no, yes, unknown };

// Is s in star(v)? Proven yes, proven no, or unknown, from the analysis of v.
// (s is an m-simplex containing r.p; in verify mode it is one of the claimed simplices at r.p.)
Member member(const StarReport& r, const Simplex& s) {
  if (r.claimed_verified) return Member::yes;
  for (const auto& c : r.claimed)
    if (c.simplex == s && (c.degenerate || c.conflict >= 0)) return Member::no;  // a point in its ball
  if (r.state != StarReport::State::proven) return Member::unknown;
  for (const auto& c : r.star)
    if (c.simplex == s) return Member::yes;
  return Member::no;
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

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

// Wall-clock and process CPU seconds of a phase (CPU time is what a loaded machine cannot inflate).
struct Stopwatch {
  std::chrono::steady_clock::time_point wall = std::chrono::steady_clock::now();
  std::clock_t cpu = std::clock();
  void record(Certificate& C, const std::string& name) {
    C.times.emplace_back(name, seconds_since(wall));
    C.times.emplace_back(name + "_cpu", double(std::clock() - cpu) / CLOCKS_PER_SEC);
    wall = std::chrono::steady_clock::now();
    cpu = std::clock();
  }
};

}  // namespace

Certificate run_certify(const CertifyOptions& o) {
  using clock = std::chrono::steady_clock;
  const auto t_start = clock::now();
  const std::clock_t cpu_start = std::clock();
  Certificate C;
  const int threads = std::max(1, o.threads);

  // ---- Inputs ------------------------------------------------------------------------------
  // Each input is read once: the bytes parsed are the bytes hashed into the certificate.
  const std::string spec_text = io::read_spec_text(o.manifold);
  io::ManifoldSpec spec = io::parse_spec(spec_text, o.manifold);
  const int N = spec.ambient_dimension, m = spec.intrinsic_dimension;
  if (m > exact::kMaxTangentDimension)
    throw io::InputError(o.manifold, 0, "intrinsic dimension " + std::to_string(m) + " is above the supported maximum " +
                                            std::to_string(exact::kMaxTangentDimension));
  std::string points_text = io::read_file(o.points);
  io::PointsFile points = io::parse_points_file(points_text, o.points, io::PointReadOptions{N, true});
  const io::PointSet& P = points.points;
  if (P.size() < static_cast<std::size_t>(m + 2))
    throw io::InputError(o.points, 0, "only " + std::to_string(P.size()) + " points: a closed " + std::to_string(m) +
                                          "-manifold needs at least m + 2 = " + std::to_string(m + 2));
  std::optional<io::Complex> given;
  std::string complex_text;
  if (!o.complex.empty()) {
    complex_text = io::read_file(o.complex);
    io::ComplexFile cf = io::parse_complex(complex_text, o.complex);
    if (cf.complex.num_vertices != P.size())
      throw io::InputError(o.complex, cf.counts_line,
                           "the complex has " + std::to_string(cf.complex.num_vertices) + " vertices but " + o.points +
                               " has " + std::to_string(P.size()) + " points; they must describe the same vertex set");
    if (cf.embedded_points)
      for (std::size_t i = 0; i < P.size(); ++i)
        if (!std::equal(P.point(i).begin(), P.point(i).end(), cf.embedded_points->point(i).begin()))
          throw io::InputError(o.complex, cf.embedded_point_lines[i],
                               "vertex " + std::to_string(i) + " differs from point " + std::to_string(i) + " of " +
                                   o.points + "; pass the same points to --points");
    given = cf.complex;
  }
  Claims claims;
  std::string claims_text;
  if (!o.claims.empty()) {
    claims_text = io::read_file(o.claims);
    claims = parse_claims(claims_text, o.claims);
  }
  C.inputs["manifold"] = {{"source", o.manifold}, {"name", spec.name}, {"sha256", Sha256::hex(spec_text)},
                          {"intrinsic_dimension", m}, {"ambient_dimension", N}};
  C.inputs["points"] = {{"path", o.points}, {"sha256", Sha256::hex(points_text)}, {"count", P.size()}};
  C.inputs["complex"] = given ? json{{"path", o.complex}, {"sha256", Sha256::hex(complex_text)},
                                     {"simplices", given->simplices.size()}}
                              : json(nullptr);
  C.inputs["claims"] = o.claims.empty() ? json(nullptr) : json{{"path", o.claims}, {"sha256", Sha256::hex(claims_text)}};
  C.conventions = {
      {"coordinates", "every input double is the exact rational it represents"},
      {"tangent_space", "T_p = p + ker J_F(p) evaluated at p's exact coordinates, with an exact rational basis"},
      {"star", "s is in star(p) iff the ambient ball centred on T_p through the vertices of s contains no sample point "
               "(regular triangulation of the projections with weights -|q - pi_p(q)|^2)"},
      {"power_margin", "|c_p(s) - q|^2 - R_p(s)^2 for q not in s, in squared-distance units"},
      {"decisions", "every sign by an interval filter, then exactly (GMP / Mpzf) when the interval contains 0; no tolerance"},
      {"ties", "a point exactly on a sphere (an exact zero) is not protected; never resolved by perturbation"},
      {"margins", "a reported bound is the lower end of an interval enclosure (a double printed exactly): "
                  "certified_lower_bound <= true value; enclosures are [lo, hi]"},
      {"sparsity", "P is lambda-sparse iff every two points are at distance > lambda"},
      {"thickness", "Upsilon(t) = min_v D(v, t) / (j Delta(t)) for a j-simplex; gamma0-good: every j-face has Upsilon >= gamma0^j"},
      {"search", "every point within r of p is tested, with r >= 2.25 R_p(s) for every cell at p (a point in the ball is within 2R of p)"}};
  json params = json::object();
  if (claims.eps) params["eps"] = rational_to_string(*claims.eps);
  if (claims.sparsity) params["sparsity"] = rational_to_string(*claims.sparsity);
  if (claims.gamma0) params["gamma0"] = rational_to_string(*claims.gamma0);
  if (claims.power_protection) params["power_protection"] = rational_to_string(*claims.power_protection);
  C.parameters = {{"mode", given ? "verify the given complex" : "audit: compute Del_TM(P)"}, {"claims", params}};

  // ---- Checks 1 and 2 ------------------------------------------------------------------------
  Stopwatch watch;
  C.checks.push_back(check_input_sanity(spec, P, points.lines, o.points, threads));
  watch.record(C, "input_sanity");
  exact::ImplicitSystem system(spec.equations, N);
  PointGrid grid(P, m);
  exact::FilterContext ctx0;
  ctx0.force_exact = o.force_exact;
  SparsityResult sparsity = check_sparsity(P, grid, claims.sparsity ? &*claims.sparsity : nullptr, ctx0);
  watch.record(C, "sparsity");

  // ---- Stars (checks 3, 4, 6, 10) --------------------------------------------------------------
  const std::size_t n = P.size();
  StarSettings S{&P, &system, &grid, m, claims.power_protection, claims.eps};
  std::vector<std::vector<Simplex>> claimed(n);
  std::vector<Simplex> wrong_dimension;
  if (given)
    for (const auto& s0 : given->simplices) {
      Simplex s = s0;
      std::sort(s.begin(), s.end());
      if (static_cast<int>(s.size()) != m + 1) {
        wrong_dimension.push_back(s);
        continue;
      }
      for (int v : s) claimed[v].push_back(s);
    }
  std::vector<StarReport> reports(n);
  std::vector<exact::FilterContext> ctx(threads);
  for (auto& c : ctx) c.force_exact = o.force_exact;
  parallel_for(n, threads, [&](std::size_t p, int w) {
    reports[p] = analyse_star(S, static_cast<int>(p), given ? &claimed[p] : nullptr, ctx[w]);
  });
  watch.record(C, "stars");

  // The complex the global checks look at: the given one, or the union of the computed stars.
  io::Complex K;
  K.num_vertices = n;
  std::vector<Simplex> tops;  // its m-simplices, sorted and unique
  if (given) {
    K = *given;
    for (const auto& s0 : given->simplices)
      if (static_cast<int>(s0.size()) == m + 1) {
        Simplex s = s0;
        std::sort(s.begin(), s.end());
        tops.push_back(s);
      }
  } else {
    for (const auto& r : reports)
      for (const auto& c : r.star) tops.push_back(c.simplex);
    std::sort(tops.begin(), tops.end());
    tops.erase(std::unique(tops.begin(), tops.end()), tops.end());
    K.simplices = tops;
  }

  // Check 3: the complex is Del_TM(P).
  CheckEntry stars;
  stars.id = 3;
  stars.name = "stars";
  long undetermined = 0, missing = 0, extra = 0, verified = 0;
  json undetermined_examples = json::array();
  for (const auto& s : wrong_dimension)
    stars.add_witness({{"kind", "wrong_dimension"}, {"simplex", s}, {"dimension", s.size() - 1}, {"expected", m}}),
        stars.refute("a maximal simplex does not have dimension m");
  for (const auto& r : reports) {
    if (r.claimed_verified) ++verified;
    if (r.state != StarReport::State::proven) {
      ++undetermined;
      if (undetermined_examples.size() < 10) undetermined_examples.push_back({{"point", r.p}, {"reason", r.reason}});
      continue;
    }
    if (!given || r.claimed_verified) continue;
    std::set<Simplex> have(claimed[r.p].begin(), claimed[r.p].end());
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
  if (given) {
    for (const auto& s : tops) {
      bool yes = false, unknown = false;
      for (int v : s) {
        Member mv = member(reports[v], s);
        yes = yes || mv == Member::yes;
        unknown = unknown || mv == Member::unknown;
      }
      if (yes) continue;
      if (unknown) {
        stars.undecide("some stars could not be determined exactly");
        continue;
      }
      ++extra;
      stars.refute("a simplex of the complex is in no star of its vertices");
      const CellReport* c = find_cell(reports[s[0]].claimed, s);
      stars.add_witness(c ? not_in_star_witness(*c, s[0]) : json{{"kind", "not_in_star"}, {"simplex", s}});
    }
  }
  if (undetermined) stars.undecide(std::to_string(undetermined) + " star(s) not determined exactly (see details)");
  stars.details["points"] = n;
  stars.details["stars_undetermined"] = undetermined;
  stars.details["undetermined_examples"] = undetermined_examples;
  if (given) {
    stars.details["claimed_stars_verified"] = verified;
    stars.details["missing_simplices"] = missing;
    stars.details["extra_simplices"] = extra;
    stars.details["wrong_dimension_simplices"] = wrong_dimension.size();
  }
  stars.summary = given ? std::to_string(verified) + " of " + std::to_string(n) + " stars verified; " +
                              std::to_string(missing) + " missing, " + std::to_string(extra) + " extra, " +
                              std::to_string(wrong_dimension.size()) + " wrong-dimension simplices; " +
                              std::to_string(undetermined) + " stars undetermined"
                        : "star(p) computed exactly for " + std::to_string(n - undetermined) + " of " + std::to_string(n) +
                              " points (" + std::to_string(tops.size()) + " m-simplices)";

  // Check 4: consistency.
  CheckEntry cons;
  cons.id = 4;
  cons.name = "consistency";
  long inconsistent = 0;
  exact::FilterContext ctx_w;
  ctx_w.force_exact = o.force_exact;
  for (const auto& s : tops) {
    bool bad = false;
    for (int v : s) {
      Member mv = member(reports[v], s);
      if (mv == Member::unknown) cons.undecide("some stars could not be determined exactly");
      if (mv != Member::no) continue;
      if (!bad) ++inconsistent;
      bad = true;
      cons.refute("a simplex is not in the star of one of its vertices");
      if (cons.witnesses.size() < 20) {
        const CellReport* c = find_cell(reports[v].claimed, s);
        CellReport tested = c ? *c : test_cell(S, v, s, ctx_w);
        json w = not_in_star_witness(tested, v);
        if (tested.empty() && tested.tie < 0) w["kind"] = "not_in_star", w["detail"] = "empty ball but not a cell of star(v)";
        cons.add_witness(w);
      } else {
        cons.add_witness(json{{"simplex", s}, {"at_vertex", v}});
      }
    }
  }
  cons.details["m_simplices"] = tops.size();
  cons.details["inconsistent_simplices"] = inconsistent;
  cons.summary = std::to_string(tops.size() - inconsistent) + " of " + std::to_string(tops.size()) +
                 " m-simplices are in the star of every vertex";

  // Checks 6 and 10: protection and radius of the star simplices.
  CheckEntry prot, radius;
  prot.id = 6;
  prot.name = "power_protection";
  radius.id = 10;
  radius.name = "star_radius";
  exact::Interval min_margin{INFINITY, INFINITY}, max_r2{-INFINITY, -INFINITY};
  json margin_at, radius_at;
  long cells = 0, ties = 0, below_claim = 0, too_big = 0;
  for (const auto& r : reports) {
    if (r.state == StarReport::State::incomplete) {
      prot.undecide("some stars could not be determined");
      radius.undecide("some stars could not be determined");
      continue;
    }
    for (const auto& c : r.star) {
      ++cells;
      if (c.degenerate || c.conflict >= 0) {
        prot.undecide("a star cell could not be certified");
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
      if (c.margin.lo < min_margin.lo) margin_at = {{"simplex", c.simplex}, {"at_vertex", r.p}, {"point", c.margin_point}};
      min_margin.lo = std::min(min_margin.lo, c.margin.lo);
      min_margin.hi = std::min(min_margin.hi, c.margin.hi);
      if (c.radius2.hi > max_r2.hi) radius_at = {{"simplex", c.simplex}, {"at_vertex", r.p}};
      max_r2.lo = std::max(max_r2.lo, c.radius2.lo);
      max_r2.hi = std::max(max_r2.hi, c.radius2.hi);
      if (claims.eps && c.eps_sign >= 0) {
        ++too_big;
        radius.refute("a star simplex has R_p(s) >= eps");
        radius.add_witness({{"kind", "radius_not_below_eps"}, {"simplex", c.simplex}, {"at_vertex", r.p},
                            {"radius_squared", enclosure_json(c.radius2)}, {"eps_squared", rational_json(*claims.eps * *claims.eps)},
                            {"exact_sign", c.eps_sign}});
      }
    }
  }
  if (cells) {
    // What the verdicts imply about the printed bounds (the consistency guard, certificate.hpp).
    prot.require_at_least("min_power_margin", min_margin.lo, 0);
    if (claims.power_protection) prot.require_at_least("min_power_margin", min_margin.lo, *claims.power_protection);
    if (claims.eps) radius.require_at_most("max_radius_squared", max_r2.hi, *claims.eps * *claims.eps);
    prot.margin = {{"min_power_margin", lower_bound_json(min_margin)}, {"attained_near", margin_at}};
    radius.margin = {{"max_radius_squared", {{"certified_upper_bound", num(max_r2.hi)}, {"enclosure", enclosure_json(max_r2)}}},
                     {"attained_at", radius_at}};
  }
  prot.details = {{"star_cells", cells}, {"exact_ties", ties}, {"below_claim", below_claim}};
  radius.details = {{"star_cells", cells}, {"not_below_eps", too_big}};
  if (claims.power_protection)
    prot.claim = {{"power_protection", rational_to_string(*claims.power_protection)},
                  {"meaning", "|c_p(s) - q|^2 - R_p(s)^2 > power_protection for every star simplex s at p and q not in s"}};
  prot.summary = "min power margin >= " + num(min_margin.lo) + " (enclosure [" + num(min_margin.lo) + ", " + num(min_margin.hi) +
                 "]) over " + std::to_string(cells) + " star cells; " + std::to_string(ties) + " exact ties" +
                 (claims.power_protection ? "; " + std::to_string(below_claim) + " not above the claim " +
                                                rational_to_string(*claims.power_protection)
                                          : "");
  if (claims.eps) {
    radius.claim = {{"eps", rational_to_string(*claims.eps)}, {"meaning", "R_p(s) < eps for every star simplex"}};
  } else if (radius.verdict == Verdict::certified) {
    radius.verdict = Verdict::report;
  }
  radius.summary = "max R_p(s)^2 <= " + num(max_r2.hi) +
                   (claims.eps ? "; " + std::to_string(too_big) + " star cells with R_p(s) >= eps = " + rational_to_string(*claims.eps)
                               : " (no eps claim)");

  watch.record(C, "assemble_checks_3_4_6_10");

  // Check 5: thickness.
  // One face lattice for checks 5 and 8.
  // Simplices with more than m + 1 vertices are refuted by check 3 (wrong dimension, with the
  // simplex as witness); their 2^n faces are never enumerated (a 32-vertex simplex would hang).
  std::vector<Simplex> lattice_simplices;
  for (const auto& s : K.simplices)
    if (static_cast<int>(s.size()) <= m + 1) lattice_simplices.push_back(s);
  const FaceLattice lattice = face_lattice(lattice_simplices);
  ThicknessResult thick = check_thickness(P, lattice, m, claims.gamma0 ? &*claims.gamma0 : nullptr, threads, C.filter,
                                         o.force_exact);
  watch.record(C, "thickness");

  // Check 8: topology.
  CheckEntry topo;
  topo.id = 8;
  topo.name = "topology";
  TopologyReport T = analyse_topology(K, m, &lattice);
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
  if (spec.expected.euler_characteristic && !T.f.empty() && *spec.expected.euler_characteristic != T.euler)
    topo.refute("Euler characteristic differs from the spec's expected value");
  if (!spec.expected.betti_z2.empty() && spec.expected.betti_z2 != T.betti_z2)
    topo.refute("Betti numbers over Z/2 differ from the spec's expected values");
  if (!spec.expected.betti_z3.empty() && spec.expected.betti_z3 != T.betti_z3)
    topo.refute("Betti numbers over Z/3 differ from the spec's expected values");
  topo.details = {{"pure", T.pure}, {"boundary_ridges", T.boundary_ridges}, {"singular_ridges", T.singular_ridges},
                  {"strongly_connected_components", T.strong_components}, {"uncovered_vertices", T.uncovered_vertices},
                  {"links_not_spheres", T.bad_links}, {"links_unrecognised", T.unknown_links}, {"face_counts", T.f},
                  {"euler_characteristic", T.euler}, {"betti_z2", T.betti_z2}, {"betti_z3", T.betti_z3}};
  json expected = json::object();
  if (spec.expected.euler_characteristic) expected["euler_characteristic"] = *spec.expected.euler_characteristic;
  if (!spec.expected.betti_z2.empty()) expected["betti_z2"] = spec.expected.betti_z2;
  if (!spec.expected.betti_z3.empty()) expected["betti_z3"] = spec.expected.betti_z3;
  topo.claim = expected.empty() ? json(nullptr) : expected;
  auto vec = [](const std::vector<long>& v) {
    std::string s = "(";
    for (std::size_t i = 0; i < v.size(); ++i) s += (i ? "," : "") + std::to_string(v[i]);
    return s + ")";
  };
  topo.summary = "chi = " + std::to_string(T.euler) + ", Betti Z/2 " + vec(T.betti_z2) + ", Z/3 " + vec(T.betti_z3) +
                 (expected.empty() ? " (no expected values in the spec)" : "");
  watch.record(C, "topology");

  // Checks 7 and 9: the paper's hypotheses, measured.
  Measured meas;
  meas.min_distance = sqrt_lower(sparsity.min_squared);
  meas.min_thickness = thick.min_top.lo;
  meas.min_margin = cells ? min_margin.lo : -INFINITY;
  meas.max_radius_squared = cells ? max_r2.hi : INFINITY;
  meas.eps = claims.eps && radius.verdict == Verdict::certified ? std::optional<mpq_class>(*claims.eps) : std::nullopt;
  TheoremParams tp = theorem_parameters(meas, spec);
  CheckEntry secure;
  secure.id = 7;
  secure.name = "secure_simplices";
  secure.verdict = Verdict::report;
  if (!tp.usable) {
    secure.summary = "not evaluated: " + tp.why;
  } else {
    SecureParams sp{tp.eps, tp.delta, tp.upsilon0, tp.shortest, {}, {}, {}, {}};
    sp.prepare();
    std::vector<SecureReport> sr(n);
    parallel_for(n, threads, [&](std::size_t p, int w) {
      if (reports[p].state != StarReport::State::proven) return;
      std::vector<Simplex> st;
      for (const auto& c : reports[p].star) st.push_back(c.simplex);
      sr[p] = analyse_secure(S, static_cast<int>(p), st, sp, ctx[w], &reports[p]);
    });
    long ok = 0, bad = 0, fallbacks = 0, skipped = 0;
    std::map<std::string, long> reasons;
    for (std::size_t p = 0; p < n; ++p) {
      ok += sr[p].secure, bad += sr[p].insecure, fallbacks += sr[p].exact_fallbacks, skipped += sr[p].undecided;
      for (const auto& [s, why] : sr[p].failures) {
        std::string key = why.substr(0, why.find(" ("));
        ++reasons[key];
        if (secure.witnesses.size() < 20) secure.add_witness({{"simplex", s}, {"at_vertex", p}, {"failed", why}});
      }
    }
    secure.details = {{"parameters", tp.json_parameters()}, {"secure", ok}, {"not_secure", bad},
                      {"first_failed_condition_counts", reasons}, {"exact_fallbacks", fallbacks},
                      {"not_evaluated", skipped},
                      {"neighbourhood", "the points within 5 eps of p (ambient), projected orthogonally onto T_p"}};
    secure.summary = std::to_string(ok) + " of " + std::to_string(ok + bad + skipped) + " star simplices secure (Definition 3.1)" +
                     (skipped ? "; " + std::to_string(skipped) + " not evaluated (more than 4000 points within 5 eps)" : "");
  }
  CheckEntry theorem = theorem_report(meas, tp, spec);
  watch.record(C, "secure_and_theorem");

  for (auto& c : ctx) C.filter.merge(c.stats);
  C.filter.merge(ctx0.stats);
  C.filter.merge(ctx_w.stats);
  C.checks.push_back(sparsity.entry);
  C.checks.push_back(stars);
  C.checks.push_back(cons);
  C.checks.push_back(thick.entry);
  C.checks.push_back(prot);
  C.checks.push_back(secure);
  C.checks.push_back(topo);
  C.checks.push_back(theorem);
  C.checks.push_back(radius);
  C.times.emplace_back("total", seconds_since(t_start));
  C.times.emplace_back("total_cpu", double(std::clock() - cpu_start) / CLOCKS_PER_SEC);
  enforce_self_consistency(C);  // a certificate that contradicts itself is an internal error
  return C;
}

}  // namespace delcert::certify
