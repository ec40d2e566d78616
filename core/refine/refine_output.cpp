#include "core/refine/refine_output.hpp"

#include <gmpxx.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>

#include "io/atomic_file.hpp"
#include "io/claims.hpp"
#include "io/complex.hpp"
#include "io/input_error.hpp"
#include "io/points.hpp"

namespace delcert::refine {

namespace {

using json = nlohmann::ordered_json;

json number(double x) { return std::isfinite(x) ? json(x) : json(nullptr); }
// A cap, null when there is none.
json cap(std::size_t n) { return n == std::numeric_limits<std::size_t>::max() ? json(nullptr) : json(n); }

// The decimal with `digits` significant digits strictly below x > 0 (up = false: a safe rational
// lower bound of a double that was itself rounded), or at or above it (up = true: a safe upper
// bound); the relative margin 1e-9 covers the decimal conversion.
mpq_class decimal_rounded(double x, int digits, bool up) {
  const double y = x * (up ? 1 + 1e-9 : 1 - 1e-9);
  int e = static_cast<int>(std::floor(std::log10(y))) - (digits - 1);
  const double scale = std::pow(10.0, e);
  const long k = static_cast<long>(up ? std::ceil(y / scale) : std::floor(y / scale));
  if (k <= 0) return mpq_class(0);
  mpq_class q(k);
  mpz_class p10;
  mpz_ui_pow_ui(p10.get_mpz_t(), 10, static_cast<unsigned long>(std::abs(e)));
  if (e >= 0)
    q *= p10;
  else
    q /= p10;
  q.canonicalize();
  return q;
}
mpq_class decimal_below(double x, int digits) { return decimal_rounded(x, digits, false); }

const char* kPracticalRules[] = {
    "unprotected: a Gamma0-good (m+1)-simplex q*s in cosph(p) leaves s unprotected; the paper shows none exist under "
    "H0-H5, at realistic eps they do: insert Pick_valid in the picking region of s at p (the point lands in s's "
    "Delaunay ball and kills s)",
    "inconsistent: s in star(p) but not in star(q) for a vertex q; the paper's theorem rules this out only for tiny eps: "
    "insert Pick_valid in the picking region of s at the vertex p* whose star holds s with the largest R_p*(s) (as "
    "Boissonnat-Ghosh refine inconsistent configurations through their picking regions)",
    "not_restricted (unless restricted_check is false): once no other rule applies, every m-simplex s of the complex "
    "must have a point x of M equidistant from its vertices (Newton from c_p(s)) with every other point farther than "
    "r^2 (1 + 1e-9) + delta0^2 (eps(p)/9)^2: otherwise insert x (if it lies in s's Delaunay ball at p) or Pick_valid "
    "for s at p, so that Del_TM equals the restricted Delaunay complex",
    "not_intrinsic (unless intrinsic_check is false): once no other rule applies, Del_TM is compared with Del_RM and Del_M "
    "computed in-process by the certifier's engines (checks 12 and 14); at every m-simplex not proven in all three (or "
    "undecided place of the restricted engine) insert its restricted Voronoi vertex, else its intrinsic Voronoi vertex, "
    "projected onto M; then the other rules again, at most max_repair_rounds times",
    "cosph uses the bound delta0^2 max(L(q*s), eps/9)^2 and counts points on or inside the ball: an empty cosph then "
    "implies the claimed delta-check^2 = delta0^2 (eps/9)^2 even where the input is denser than eps/9",
    "Pick_valid rejects candidates closer than eps/9 to a point (the sparsity invariant is enforced, not inferred) and "
    "after pick_attempts rejections takes the best candidate seen (farther than eps/9 if any, then the farthest); a "
    "fallback closer than eps/9 is reported as a sparsity violation",
    "decisions carry a relative safety margin of 1e-9 towards refining more (thickness, R_p < eps, protection), so "
    "that the exact certifier agrees with the double-precision producer",
    "a round applies Rule 1 alone while big cells exist, otherwise every other configuration in canonical order "
    "(rule, point, cell, apex), skipping those whose Delaunay ball received a point earlier in the round"};

mpq_class decimal_at_or_above(double x, int digits) { return decimal_rounded(x, digits, true); }

bool curvature_sizing(const RefineResult& r) { return r.parameters.sizing.kind == SizingKind::curvature; }

// ε_min, exact: ε / 2^eps_level, and under curvature sizing at most the field's smallest value
// (three significant digits below it): every sparsity and protection decision used a local ε >= it.
mpq_class exact_eps_min(const RefineResult& r) {
  mpq_class eps_min = r.parameters.constants.eps.value().value;
  if (r.eps_level > 0) {
    mpz_class two_k;
    mpz_ui_pow_ui(two_k.get_mpz_t(), 2, static_cast<unsigned long>(r.eps_level));
    eps_min /= two_k;
    eps_min.canonicalize();
  }
  if (curvature_sizing(r) && r.final.min_local_eps > 0) {
    const mpq_class field_min = decimal_below(r.final.min_local_eps, 3);
    if (field_min < eps_min) eps_min = field_min;
  }
  return eps_min;
}

const char* kPerPointFile = "eps.txt";

}  // namespace

ClaimsOutcome make_claims(const RefineResult& r) {
  ClaimsOutcome out;
  const FinalMeasures& f = r.final;
  const Constants& k = r.parameters.constants;
  io::Claims claims;
  const mpq_class& eps = k.eps.value().value;
  if (curvature_sizing(r)) {
    // Version 3: the star radius and the covering radius against ε(p), per point (eps.txt). ε(p)
    // is written as the 6-digit decimal at or above the double the refiner used (at most ε): the
    // refiner kept R_p(σ) < ε(p) with a relative margin, so the claim is the refiner's own.
    // The covering claim is the refiner's expectation (each restricted Voronoi cell lies near the
    // union of its star's Delaunay balls), not something it measured: the certifier decides it.
    if (f.all_small_local) {
      out.per_point.reserve(r.local_eps.size());
      for (double e : r.local_eps) {
        mpq_class q = decimal_at_or_above(e, 6);
        out.per_point.push_back(q < eps ? q : eps);
      }
      claims.star_radius_per_point_file = kPerPointFile;
      claims.covering_per_point_file = kPerPointFile;
    } else {
      out.omitted.emplace_back("star_radius_per_point", "some star simplex at p has R_p >= eps(p), or a star is not closed");
    }
  } else if (f.all_small) {
    claims.star_radius = eps;
  } else {
    out.omitted.emplace_back("star_radius", "some star simplex has R_p >= eps, or a star is not closed");
  }
  // Sparsity and protection hold with the smallest local ε, ε / 2^eps_level (docs/refinement.md,
  // "Local ε"), and the field's smallest value under curvature sizing; the star radius with ε
  // itself, the largest local ε (uniform sizing).
  const mpq_class eps_min = exact_eps_min(r);
  const mpq_class mu0eps = mu0_times(eps_min);
  if (f.min_distance > mu0eps.get_d() * (1 + 1e-9)) {
    claims.sparsity = mu0eps;
  } else if (f.min_distance > 0) {
    claims.sparsity = decimal_below(f.min_distance, 3);
    out.omitted.emplace_back("sparsity eps/9", "the smallest distance is below eps_min/9 (the input is denser, or a "
                                               "sparsity violation was reported): the claim is a bound just below it");
  }
  if (f.all_good)
    claims.gamma0 = k.gamma0.value;
  else
    out.omitted.emplace_back("gamma0", "some star simplex is Gamma0-bad");
  const mpq_class& d0 = k.delta0.value().value;
  mpq_class dcheck2 = d0 * d0 * mu0eps * mu0eps;
  dcheck2.canonicalize();
  if (f.protected_claim)
    claims.power_protection = dcheck2;
  else
    out.omitted.emplace_back("power_protection", "some star simplex is not delta-check^2-power-protected");
  out.json = io::format_claims(claims);
  return out;
}

std::string paper_mode_assessment(const RefineResult& r) {
  if (r.parameters.mode != RefineMode::paper) return {};
  const FinalMeasures& f = r.final;
  const std::size_t inserted = r.points.size() - r.input_size;
  std::string done = inserted == 0 ? "Algorithm 1 inserted nothing"
                                   : "Algorithm 1 inserted " + std::to_string(inserted) + " point" + (inserted == 1 ? "" : "s");
  if (!r.converged) return done + " and stopped on " + to_string(r.stop_reason) + " before its rules ran out";
  std::vector<std::string> wrong;
  if (f.open_stars > 0) wrong.push_back(std::to_string(f.open_stars) + " open stars");
  if (f.inconsistent_simplices > 0)
    wrong.push_back(std::to_string(f.inconsistent_simplices) + " inconsistent simplices in " +
                    std::to_string(f.inconsistent_stars) + " stars");
  if (!f.protected_claim) wrong.push_back("star simplices not protected by delta-check");
  if (!f.all_good) wrong.push_back("Gamma0-bad faces");
  if (wrong.empty()) return done + ": every rule ran out, and the complex is consistent, Gamma0-good and protected";
  std::string list;
  for (std::size_t i = 0; i < wrong.size(); ++i) list += (i ? (i + 1 == wrong.size() ? " and " : ", ") : "") + wrong[i];
  std::string bound;
  if (r.hypotheses.max_eps) {
    char text[64];
    std::snprintf(text, sizeof text, "%.3g", *r.hypotheses.max_eps);
    bound = std::string(" (the paper's hypotheses ask eps <= ") + text + ")";
  }
  else if (r.hypotheses.any_fails)
    bound = " (some of the paper's hypotheses H0-H5 fail at these parameters)";
  return done + " and has no rule left to apply, but the complex is not what the paper's theorem promises: " + list +
         ". Its rules only see big cells and Gamma0-bad simplices; the theorem needs eps far smaller" + bound +
         ". Use --mode practical, which also refines inconsistent and unprotected simplices";
}

std::string make_report(const RefineResult& r, const OutputContext& c, const ClaimsOutcome& claims) {
  const RefineParameters& p = r.parameters;  // as used
  const Constants& k = p.constants;
  const ConstantsAsDoubles dbl = as_doubles(k);
  const FinalMeasures& f = r.final;
  json j;
  j["format"] = "delcert-refine-report v1";
  j["manifold"] = c.manifold;
  j["manifold_source"] = c.manifold_source;
  j["mode"] = to_string(p.mode);
  j["input"] = {{"source", c.input}, {"points", r.input_size}, {"min_distance", number(f.input_min_distance)}};
  j["parameters"] = {{"eps", k.eps.value().text},
                     {"eps_source", r.eps_derived ? "derived: two significant digits above the input's largest R_p"
                                                  : "given"},
                     {"gamma0", k.gamma0.text},
                     {"alpha", k.alpha.text},
                     {"beta", k.beta.text},
                     {"delta0", k.delta0.value().text},
                     {"mu0", "1/" + std::to_string(kMu0Reciprocal)},
                     {"seed", p.seed},
                     {"max_points", p.max_points},
                     {"max_inserted", cap(p.max_inserted)},
                     {"max_rounds", cap(p.max_rounds)},
                     {"pick_attempts", p.pick_attempts},
                     {"restricted_check", p.mode == RefineMode::practical && p.restricted_check},
                     {"look_ahead", p.mode == RefineMode::practical && p.look_ahead},
                     {"intrinsic_check", p.intrinsic_check.value_or(p.mode == RefineMode::practical)},
                     {"max_repair_rounds", p.max_repair_rounds}};
  {
    const HypothesesReport& h = r.hypotheses;
    json hs = json::array();
    for (const auto& ch : h.checks)
      hs.push_back({{"name", ch.name},
                    {"statement", ch.statement},
                    {"status", status_name(ch.status)},
                    {"lhs", ch.lhs ? number(*ch.lhs) : json(nullptr)},
                    {"rhs", ch.rhs ? number(*ch.rhs) : json(nullptr)},
                    {"detail", ch.detail}});
    j["hypotheses"] = {{"checks", hs},
                       {"eps0_tilde", h.eps0_tilde},
                       {"sparsity_lemma", {{"statement", "(1 - delta0^2)(1 - alpha - 4.5 eps0~) / 4 > 1/9"},
                                           {"lhs", h.sparsity_lemma_lhs},
                                           {"holds", h.sparsity_lemma_holds}}},
                       {"max_eps", h.max_eps ? number(*h.max_eps) : json(nullptr)},
                       {"max_eps_note", h.max_eps_note},
                       {"unspecified_constants", h.unspecified},
                       {"any_fails", h.any_fails},
                       {"all_hold", h.all_hold}};
  }
  j["converged"] = r.converged;
  j["stop_reason"] = to_string(r.stop_reason);
  if (p.mode == RefineMode::paper) j["assessment"] = paper_mode_assessment(r);
  if (p.time_limit > 0) j["time_limit_seconds"] = p.time_limit;
  j["rounds"] = r.rounds;
  {
    std::size_t applied = 0;
    for (const auto& s : r.rules.values) applied += s.applied;
    j["iterations"] = applied;  // rule applications (Algorithm 1 iterations), one inserted point each
  }
  {
    json ic = json::object();
    for (Rule rule : kRules) ic[to_string(rule)] = r.initial_configurations[rule];
    j["initial"] = {{"inconsistent_simplices", r.initial_inconsistent_simplices},
                    {"inconsistent_stars", r.initial_inconsistent_stars},
                    {"configurations", ic}};
  }
  j["points"] = {{"input", r.input_size}, {"inserted", r.points.size() - r.input_size}, {"total", r.points.size()}};
  json rules = json::object();
  const bool paper = p.mode == RefineMode::paper;
  for (Rule rule : kRules) {
    if (paper && (rule == Rule::unprotected || rule == Rule::inconsistent || rule == Rule::not_restricted)) continue;
    if (rule == Rule::not_intrinsic && !p.intrinsic_check.value_or(!paper)) continue;
    const RuleStats& s = r.rules[rule];
    rules[to_string(rule)] = {{"inserted", s.inserted},
                              {"applied", s.applied},
                              {"skipped_stale", s.skipped_stale},
                              {"candidates", s.candidates},
                              {"rejected_hit", s.rejected_hit},
                              {"rejected_sparse", s.rejected_sparse},
                              {"rejected_look_ahead", s.rejected_look_ahead},
                              {"psi_failures", s.psi_failures},
                              {"fallbacks", s.fallbacks},
                              {"failures", s.failures},
                              {"shrinks", s.shrinks},
                              {"seconds", s.seconds}};
  }
  j["rules"] = rules;
  if (r.del_m.checked) {
    const DelMSummary& d = r.del_m;
    j["del_m_check"] = {{"statement", "rule not_intrinsic: once no other rule applies, Del_TM is compared with Del_RM and "
                                      "Del_M computed by the certifier's engines, and a point is inserted where they are not "
                                      "proven equal (docs/refinement.md, \"Del_M check\")"},
                        {"repair_rounds", r.repair_rounds},
                        {"restricted_computed", d.restricted_computed},
                        {"intrinsic_computed", d.intrinsic_computed},
                        {"intrinsic_not_computed_because", d.intrinsic_reason},
                        {"last_check", {{"tangential", d.tangential}, {"restricted", d.restricted},
                                        {"intrinsic", d.intrinsic}, {"breaks", d.breaks}}},
                        {"seconds", d.seconds}};
  }
  if (r.stall) {
    j["stall"] = {{"rule", to_string(r.stall->rule)},
                  {"simplex", r.stall->simplex},
                  {"point", r.stall->point},
                  {"location", r.stall->location},
                  {"what", r.stall->what},
                  {"message", describe_stall(*r.stall)}};
  }
  if (!paper) {
    json pr = json::array();
    for (const char* s : kPracticalRules) pr.push_back(s);
    j["practical_rules"] = pr;
  }
  if (curvature_sizing(r)) {
    const SizingField& sz = p.sizing;
    double lo = std::numeric_limits<double>::infinity(), hi = 0;
    for (double e : r.local_eps) lo = std::min(lo, e), hi = std::max(hi, e);
    j["sizing"] = {{"kind", to_string(sz.kind)},
                   {"statement", "eps(x) = min(eps, max(floor, c / kappa_max(x))), kappa_max the largest normal curvature "
                                 "(from F's exact Hessians; an estimate in codimension > 1); the local eps sites below "
                                 "can lower it further"},
                   {"c", sz.c.text},
                   {"floor", sz.floor ? sz.floor->text : std::string()},
                   {"per_point_file", f.all_small_local ? kPerPointFile : ""},
                   {"min_local_eps", number(lo)},
                   {"max_local_eps", number(hi)},
                   {"eps_min_claimed", exact_eps_min(r).get_str()}};
  }
  {
    // The sizing field (practical mode): ε(x) = min(ε, min over sites of ε_site + slope |x - site|).
    mpz_class two_k;
    mpz_ui_pow_ui(two_k.get_mpz_t(), 2, static_cast<unsigned long>(r.eps_level));
    mpq_class eps_min = k.eps.value().value / two_k;
    eps_min.canonicalize();
    std::size_t below = 0;
    for (double e : r.local_eps) below += e < dbl.eps;
    json sites = json::array();
    for (std::size_t i = 0; i < r.eps_sites.size() && i < 20; ++i) {
      const auto& st = r.eps_sites[i];
      sites.push_back({{"point", st.point}, {"level", st.level}, {"rule", to_string(st.rule)}, {"open_star", st.open}});
    }
    j["local_eps"] = {{"statement", "where a configuration could not be applied at the local eps, a site (p, eps/2^level) "
                                    "was added: eps(x) = min(eps, min over sites of eps_site + slope |x - site|)"},
                      {"slope", kSizingSlope},
                      {"sites", r.eps_sites.size()},
                      {"first_sites", sites},
                      {"max_level", r.eps_level},
                      {"min_eps", eps_min.get_str()},
                      {"min_eps_double", number(std::ldexp(dbl.eps, -r.eps_level))},
                      {"points_below_eps", below}};
  }
  j["time_seconds"] = {{"stars", r.star_seconds}, {"configurations", r.configuration_seconds}, {"total", r.total_seconds}};
  json remaining = json::object();
  for (Rule rule : kRules) remaining[to_string(rule)] = f.remaining[rule];
  const double mu0eps = curvature_sizing(r) ? mu0_times(exact_eps_min(r).get_d())
                                            : mu0_times(std::ldexp(dbl.eps, -r.eps_level));  // the smallest local ε
  j["final"] = {{"stars", f.stars},
                {"star_cells", f.star_cells},
                {"complex_simplices", f.complex_simplices},
                {"open_stars", f.open_stars},
                {"inconsistent_simplices", f.inconsistent_simplices},
                {"inconsistent_stars", f.inconsistent_stars},
                {"remaining_configurations", remaining},
                {"max_radius", number(f.max_radius)},
                {"min_thickness", number(f.min_thickness)},
                {"min_face_thickness_ratio", number(f.min_face_thickness_ratio)},
                {"min_protection", number(f.min_protection)},
                {"power_protection_bound", number(dbl.delta0 * dbl.delta0 * mu0eps * mu0eps)},
                {"min_protection_ratio", number(f.min_protection_ratio)},
                {"min_distance", number(f.min_distance)},
                {"min_inserted_distance", number(f.min_inserted_distance)},
                {"consistent", f.consistent},
                {"all_gamma0_good", f.all_good},
                {"all_radii_below_eps", f.all_small},
                {"protected", f.protected_claim}};
  json viol = json::array();
  for (std::size_t i = 0; i < r.sparsity_violations.size() && i < 20; ++i) {
    const auto& v = r.sparsity_violations[i];
    viol.push_back({{"point", v.point}, {"nearest", v.nearest}, {"distance", v.distance}, {"rule", to_string(v.rule)}});
  }
  j["sparsity"] = {{"bound", mu0eps},
                   {"statement", "every inserted point is farther than eps(x)/9 from the points before it (the bound "
                                 "is the smallest: eps_min/9)"},
                   {"violations", r.sparsity_violations.size()},
                   {"first_violations", viol}};
  json om = json::object();
  for (const auto& [k, why] : claims.omitted) om[k] = why;
  j["claims"] = {{"file", "claims.json"}, {"not_claimed", om}};
  return j.dump(2) + "\n";
}

void write_refine_output(const std::string& dir, const RefineResult& result, const OutputContext& context) {
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec || !fs::is_directory(dir))
    throw io::InputError(dir, 0, "cannot create the output directory: " + (ec ? ec.message() : std::string("not a directory")));
  const fs::path d(dir);
  ClaimsOutcome claims = make_claims(result);
  // All four (five with eps.txt) or none (each first complete in a temporary file, then renamed).
  std::vector<std::pair<std::string, std::string>> files{{(d / "points.txt").string(), io::format_points(result.points)},
                                                         {(d / "complex.txt").string(), io::format_complex(result.complex)}};
  if (!claims.per_point.empty()) files.emplace_back((d / kPerPointFile).string(), io::format_per_point(claims.per_point));
  files.emplace_back((d / "claims.json").string(), claims.json);
  files.emplace_back((d / "report.json").string(), make_report(result, context, claims));
  io::write_files_atomically(files);
}

}  // namespace delcert::refine
