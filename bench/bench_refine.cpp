// The refiner against GUDHI's perturbation fix (docs/design.md §11, issue 6), on the same starting points
// and the same tangent planes.
//
// For each case (a manifold and a number of points, sampled uniformly with respect to volume by
// the built-in parametrisation, seeded): the tangent planes from Manifold::frame, then
//   delcert: refine (practical mode, default parameters) -> points added, time per rule, rounds,
//            final inconsistent stars, minimum thickness and protection margin;
//   GUDHI:   Tangential_complex with set_tangent_planes, compute_tangential_complex, then
//            fix_inconsistencies_using_perturbation(max_perturb, time limit) -> inconsistent
//            stars before and after, time.
// Prints one JSON document on stdout.
//
//   bench_refine [--cases t3:10000,so3:10000] [--threads 2] [--gudhi-time-limit 120]
//                [--max-perturb 0.01] [--seed 1] [--reps 1] [--no-gudhi] [--out-dir DIR]
//                [--gamma0 0.1,0.15,0.2,0.3] [--time-limit S] [--no-restricted-check] [--look-ahead]
// With several Γ0 (issue 15: the thickness trade-off), delcert runs once per value ("gamma0_sweep":
// points added, time, and the distribution of the thickness Υ of the m-simplices); the first value
// is the one compared with GUDHI. --time-limit stops a run (marked, not reproducible).
// --no-restricted-check refines without the not_restricted rule (docs/refinement.md, "Restricted
// check"), to measure what the rule costs; --look-ahead turns on Pick_valid's look-ahead
// (docs/refinement.md, "Look-ahead"), to measure what it saves.
// With --reps R, delcert runs R times (the outputs are identical; the JSON gives the median
// total time and every run's); GUDHI runs once (its time is set by the limit).
//
// --certify runs delcert-certify's checks (in process, certify::run_certify, every check) on each
// delcert output with its own claims and adds "certificate": the overall verdict, each check's,
// and the time (issue 15: "the certifier's verdict on the output"). The outputs are written to
// --out-dir, or to a temporary directory removed at the end.
//
// --sizing SPEC:EPS[:FLOOR[:C]] (repeatable; issue 15 item 2) compares the curvature sizing field
// with the uniform ε that certifies the same spec: from the same ε-net of SPEC at EPS, delcert
// refine --sizing curvature (cap EPS, --eps-floor FLOOR, --sizing-c C, defaults EPS/10 and 1/2),
// then the uniform run at ε_u = the field's smallest value over the output (three significant
// digits below it: the finest ε the field asked for anywhere, which a uniform ε must match to give
// every point the same guarantee); prints both point counts, the ratio, and both certificates.
//
#include "bench/gudhi_input.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "core/manifold/manifold.hpp"
#include "core/refine/refine_output.hpp"
#include "core/refine/refiner.hpp"
#include "core/refine/simplex_measures.hpp"
#include "certify/certify.hpp"
#include "core/sampling/sampling.hpp"
#include "core/tangential/tangent_planes.hpp"
#include "io/points.hpp"
#include "io/spec.hpp"

namespace {

using json = nlohmann::ordered_json;
using namespace delcert;

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

struct Case {
  std::string manifold;  // built-in name
  std::size_t count = 0;
};

std::string builtin_of(const std::string& shorthand) {
  if (shorthand == "t3") return "clifford-torus-3";
  if (shorthand == "t2") return "clifford-torus-2";
  if (shorthand == "s2") return "sphere-2";
  if (shorthand == "s3") return "sphere-3";
  return shorthand;
}

std::vector<Case> parse_cases(const std::string& text) {
  std::vector<Case> out;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ',')) {
    auto colon = item.find(':');
    if (colon == std::string::npos) throw std::runtime_error("case '" + item + "': expected NAME:COUNT");
    out.push_back({builtin_of(item.substr(0, colon)), std::stoul(item.substr(colon + 1))});
  }
  return out;
}

template <int M>
json run_gudhi_m(const io::PointSet& ps, const tangential::TangentPlanes& planes, int threads, double max_perturb,
                 double time_limit) {
  using Input = bench::GudhiInput<M>;
  using TC = typename Input::TC;
  const Input in(ps, planes);
  json r;
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
  r["parallel"] = "TBB, " + std::to_string(threads) + " threads";
  auto t0 = std::chrono::steady_clock::now();
  TC tc(in.points, M, in.kernel);
  tc.set_tangent_planes(in.bases);
  tc.compute_tangential_complex();
  r["build_seconds"] = seconds_since(t0);
  auto before = tc.number_of_inconsistent_simplices();
  r["initial_inconsistent_stars"] = before.num_inconsistent_stars;
  r["initial_inconsistent_simplices"] = before.num_inconsistent_simplices;
  auto t1 = std::chrono::steady_clock::now();
  auto info = tc.fix_inconsistencies_using_perturbation(max_perturb, time_limit);
  r["fix_seconds"] = seconds_since(t1);
  auto after = tc.number_of_inconsistent_simplices();
  r["max_perturb"] = max_perturb;
  r["time_limit_seconds"] = time_limit;
  r["success"] = info.success;
  r["steps"] = info.num_steps;
  r["best_inconsistent_stars"] = info.best_num_inconsistent_stars;
  r["final_inconsistent_stars"] = after.num_inconsistent_stars;
  r["final_inconsistent_simplices"] = after.num_inconsistent_simplices;
  r["total_seconds"] = seconds_since(t0);
  return r;
}

json run_gudhi(const io::PointSet& ps, const tangential::TangentPlanes& planes, int m, int threads, double max_perturb,
               double time_limit) {
  switch (m) {
    case 2: return run_gudhi_m<2>(ps, planes, threads, max_perturb, time_limit);
    case 3: return run_gudhi_m<3>(ps, planes, threads, max_perturb, time_limit);
    default: return json{{"error", "GUDHI is run for m = 2 and 3 only"}};
  }
}

// Thickness Υ of the m-simplices of the complex: the smallest and percentiles (by rank).
json thickness_distribution(const refine::RefineResult& r, int m) {
  std::vector<double> t;
  for (const auto& s : r.complex.simplices)
    if (static_cast<int>(s.size()) == m + 1) t.push_back(refine::make_simplex(r.points, s).thickness());
  if (t.empty()) return nullptr;
  std::sort(t.begin(), t.end());
  json j = {{"m_simplices", t.size()}, {"min", t.front()}};
  for (const auto& [key, q] : {std::pair{"p0.1", 0.001}, {"p1", 0.01}, {"p5", 0.05}, {"p50", 0.5}})
    j[key] = t[static_cast<std::size_t>(q * static_cast<double>(t.size() - 1))];
  long below = 0;  // below 10 times today's smallest at Γ0 = 0.1 on T^3 from 10k (0.0028, issue 15)
  for (double x : t) below += x < 0.028;
  j["below_0.028"] = below;
  return j;
}

// delcert-certify on a refine output directory with its own claims: every check, in process.
json certify_output(const std::string& manifold_source, const std::string& dir, int threads) {
  certify::CertifyOptions o;
  o.manifold = manifold_source;
  o.points = dir + "/points.txt";
  o.complex = dir + "/complex.txt";
  o.claims = dir + "/claims.json";
  o.threads = threads;
  auto t0 = std::chrono::steady_clock::now();
  json j;
  try {
    const certify::Certificate c = certify::run_certify(o);
    j["verdict"] = certify::to_string(c.overall());
    json checks = json::object();
    for (const auto& e : c.checks) checks[e.name()] = certify::to_string(e.verdict);
    j["checks"] = checks;
  } catch (const std::exception& e) {
    j["verdict"] = "ERROR";
    j["error"] = e.what();
  }
  j["seconds"] = seconds_since(t0);
  return j;
}

json run_delcert(const manifold::Manifold& manifold, const io::PointSet& ps, int threads, std::uint64_t seed, const std::string& out_dir,
                 const std::string& name, const std::string& gamma0, double time_limit, bool certify_it,
                 const refine::SizingField* sizing = nullptr, const std::string& eps = {}, bool restricted_check = true,
                 bool look_ahead = false) {
  refine::RefineParameters p;
  p.restricted_check = restricted_check;
  p.look_ahead = look_ahead;
  if (sizing) p.sizing = *sizing;
  if (!eps.empty()) p.constants.eps = refine::ExactParameter::parse(eps);
  p.threads = threads;
  p.seed = seed;
  p.constants.gamma0 = refine::ExactParameter::parse(gamma0);
  p.time_limit = time_limit;
  auto t0 = std::chrono::steady_clock::now();
  refine::RefineResult r = refine::refine(manifold, ps, p);
  const double total = seconds_since(t0);
  json j;
  const refine::ConstantsAsDoubles used = refine::as_doubles(r.parameters.constants);
  j["parameters"] = {{"mode", "practical"},
                     {"eps", r.parameters.constants.eps.value().text},
                     {"sizing", refine::to_string(r.parameters.sizing.kind)},
                     {"restricted_check", r.parameters.restricted_check},
                     {"look_ahead", r.parameters.look_ahead},
                     {"gamma0", used.gamma0},
                     {"alpha", used.alpha},
                     {"beta", used.beta},
                     {"delta0", used.delta0}};
  j["initial_inconsistent_stars"] = r.initial_inconsistent_stars;
  j["initial_inconsistent_simplices"] = r.initial_inconsistent_simplices;
  j["converged"] = r.converged;
  j["stop_reason"] = refine::to_string(r.stop_reason);
  j["rounds"] = r.rounds;
  j["points_added"] = r.points.size() - r.input_size;
  j["points"] = r.points.size();
  if (!r.local_eps.empty())
    j["local_eps_min"] = *std::min_element(r.local_eps.begin(), r.local_eps.end()),
    j["local_eps_max"] = *std::max_element(r.local_eps.begin(), r.local_eps.end());
  json rules = json::object();
  for (refine::Rule rule : refine::kRules)
    rules[refine::to_string(rule)] = {{"inserted", r.rules[rule].inserted},
                                      {"seconds", r.rules[rule].seconds},
                                      {"candidates", r.rules[rule].candidates},
                                      {"rejected_hit", r.rules[rule].rejected_hit},
                                      {"rejected_look_ahead", r.rules[rule].rejected_look_ahead},
                                      {"fallbacks", r.rules[rule].fallbacks}};
  j["rules"] = rules;
  j["time_seconds"] = {{"stars", r.star_seconds},
                       {"configurations", r.configuration_seconds},
                       {"total", total}};
  const auto& f = r.final;
  j["final_inconsistent_stars"] = f.inconsistent_stars;
  j["final_inconsistent_simplices"] = f.inconsistent_simplices;
  j["final_min_thickness"] = f.min_thickness;
  j["final_min_face_thickness_ratio"] = f.min_face_thickness_ratio;
  j["final_min_protection"] = f.min_protection;
  j["final_min_protection_ratio"] = f.min_protection_ratio;
  j["final_max_radius"] = f.max_radius;
  j["sparsity_violations"] = r.sparsity_violations.size();
  j["claims_hold"] = f.consistent && f.all_good && f.all_small && f.protected_claim;
  j["thickness_of_m_simplices"] = thickness_distribution(r, manifold.intrinsic_dimension());
  if (!out_dir.empty()) {
    refine::OutputContext ctx;
    ctx.manifold = manifold.spec().name;
    ctx.manifold_source = manifold.spec().source;
    ctx.input = "bench_refine " + name;
    const std::string dir = out_dir + "/" + name;
    refine::write_refine_output(dir, r, ctx);
    {
      io::PointSet input;
      input.dimension = ps.dimension;
      input.coordinates = ps.coordinates;
      io::write_points(dir + "/input.txt", input);
    }
    j["output"] = dir;
    if (certify_it) j["certificate"] = certify_output(manifold.spec().source, dir, threads);
  }
  return j;
}

// One --sizing row: the curvature field against the uniform ε at the field's minimum, same ε-net.
json run_sizing(const std::string& item, int threads, std::uint64_t seed, const std::string& out_dir) {
  // SPEC:EPS[:FLOOR[:C]]; SPEC may be builtin:NAME (its colon is kept).
  std::vector<std::string> parts;
  {
    std::stringstream ss(item);
    std::string x;
    while (std::getline(ss, x, ':')) parts.push_back(x);
    if (parts.size() >= 2 && parts[0] == "builtin") parts[0] += ":" + parts[1], parts.erase(parts.begin() + 1);
  }
  if (parts.size() < 2 || parts.size() > 4) throw std::runtime_error("--sizing '" + item + "': expected SPEC:EPS[:FLOOR[:C]]");
  manifold::Manifold manifold(io::read_spec(parts[0]));
  const std::string eps = parts[1];
  refine::SizingField sizing;
  sizing.kind = refine::SizingKind::curvature;
  if (parts.size() >= 3 && !parts[2].empty()) sizing.floor = refine::ExactParameter::parse(parts[2]);
  if (parts.size() >= 4) sizing.c = refine::ExactParameter::parse(parts[3]);
  sampling::EpsNetOptions eo;
  eo.eps = refine::ExactParameter::parse(eps).value.get_d();
  eo.seed = seed;
  const io::PointSet net =
      sampling::eps_net_with_at_least(manifold, eo, static_cast<std::size_t>(manifold.intrinsic_dimension() + 2)).points;
  const std::string name = "sizing-" + manifold.spec().name;
  json e;
  e["manifold"] = parts[0];
  e["input"] = {{"eps_net", eps}, {"points", net.size()}, {"seed", seed}};
  std::cerr << "sizing " << parts[0] << ": curvature" << std::flush;
  json curv = run_delcert(manifold, net, threads, seed, out_dir, name + "-curvature", "0.15", 0, true, &sizing, eps);
  // The uniform ε at the field's minimum, three significant digits below it.
  const double lo = curv["local_eps_min"].get<double>();
  const int e10 = static_cast<int>(std::floor(std::log10(lo * (1 - 1e-9)))) - 2;
  const double scale = std::pow(10.0, e10);
  char text[64];
  std::snprintf(text, sizeof text, "%.*f", std::max(0, -e10), std::floor(lo * (1 - 1e-9) / scale) * scale);
  std::cerr << " (" << curv["points"] << " points), uniform eps " << text << std::flush;
  json uni = run_delcert(manifold, net, threads, seed, out_dir, name + "-uniform", "0.15", 0, true, nullptr, text);
  std::cerr << " (" << uni["points"] << " points)\n";
  e["curvature"] = curv;
  e["uniform"] = uni;
  e["uniform_eps"] = text;
  e["points_curvature"] = curv["points"];
  e["points_uniform"] = uni["points"];
  e["ratio_uniform_over_curvature"] = uni["points"].get<double>() / curv["points"].get<double>();
  return e;
}

}  // namespace

int main(int argc, char** argv) {
  std::string cases_text = "t3:10000,so3:10000";
  int threads = 2;
  double gudhi_limit = 120, max_perturb = 0.01;
  std::uint64_t seed = 1;
  int reps = 1;
  bool gudhi = true;
  std::string out_dir, gamma0_list = "0.1";
  double time_limit = 0;
  bool certify_outputs = false, restricted_check = true, look_ahead = false;
  std::vector<std::string> sizing_items;
  for (int i = 1; i < argc; ++i) {
    std::string a = argv[i];
    auto next = [&]() -> std::string {
      if (i + 1 >= argc) throw std::runtime_error(a + " needs a value");
      return argv[++i];
    };
    if (a == "--cases") cases_text = next();
    else if (a == "--threads") threads = std::stoi(next());
    else if (a == "--gudhi-time-limit") gudhi_limit = std::stod(next());
    else if (a == "--max-perturb") max_perturb = std::stod(next());
    else if (a == "--seed") seed = std::stoull(next());
    else if (a == "--reps") reps = std::max(1, std::stoi(next()));
    else if (a == "--no-gudhi") gudhi = false;
    else if (a == "--out-dir") out_dir = next();
    else if (a == "--gamma0") gamma0_list = next();
    else if (a == "--time-limit") time_limit = std::stod(next());
    else if (a == "--certify") certify_outputs = true;
    else if (a == "--no-restricted-check") restricted_check = false;
    else if (a == "--look-ahead") look_ahead = true;
    else if (a == "--sizing") sizing_items.push_back(next());
    else {
      std::cerr << "usage: bench_refine [--cases t3:10000,so3:10000] [--threads 2] [--gudhi-time-limit 120] "
                   "[--max-perturb 0.01] [--seed 1] [--no-gudhi] [--out-dir DIR] [--gamma0 0.1,0.15,...] "
                   "[--time-limit S] [--certify] [--no-restricted-check] [--look-ahead] [--sizing SPEC:EPS[:FLOOR[:C]]] ...\n";
      return 2;
    }
  }
  // --certify and --sizing certify files: without --out-dir, a temporary directory (removed at the end).
  std::string temp_dir;
  if (out_dir.empty() && (certify_outputs || !sizing_items.empty())) {
    temp_dir = (std::filesystem::temp_directory_path() / ("bench_refine-" + std::to_string(seed) + "-" +
                                                         std::to_string(std::chrono::steady_clock::now().time_since_epoch().count())))
                   .string();
    std::filesystem::create_directories(temp_dir);
    out_dir = temp_dir;
  }
  json doc;
  doc["benchmark"] = "refinement to a consistent tangential complex: delcert refine vs GUDHI's perturbation fix";
  doc["threads"] = threads;
  doc["seed"] = seed;
  json results = json::array();
  for (const Case& c : parse_cases(cases_text)) {
    manifold::Manifold manifold(io::read_spec("builtin:" + c.manifold));
    sampling::Random rng(seed);
    io::PointSet ps;
    sampling::sample_manifold(manifold, c.count, rng, ps);
    auto planes = tangential::compute_tangent_planes(manifold, ps, threads);
    json e;
    e["manifold"] = c.manifold;
    e["points"] = c.count;
    e["sampling"] = "uniform with respect to volume (built-in parametrisation), seed " + std::to_string(seed);
    std::cerr << c.manifold << " " << c.count << ": delcert" << std::flush;
    // One run per Γ0 (the first is "delcert", compared with GUDHI; all of them in "gamma0_sweep").
    json sweep = json::array();
    for (std::size_t begin = 0, end = 0; begin <= gamma0_list.size(); begin = end + 1) {
      end = gamma0_list.find(',', begin);
      if (end == std::string::npos) end = gamma0_list.size();
      const std::string g = gamma0_list.substr(begin, end - begin);
      std::vector<double> totals;
      json d;
      for (int r = 0; r < reps; ++r) {
        json one = run_delcert(manifold, ps, threads, seed, r == 0 ? out_dir : std::string(),
                               c.manifold + "-" + std::to_string(c.count) + (sweep.empty() ? "" : "-gamma0-" + g), g,
                               time_limit, certify_outputs && r == 0, nullptr, {}, restricted_check, look_ahead);
        totals.push_back(one["time_seconds"]["total"].get<double>());
        if (r == 0) d = one;
        else if (one["points_added"] != d["points_added"]) d["warning"] = "runs differ: the refiner is not deterministic";
      }
      std::vector<double> sorted = totals;
      std::sort(sorted.begin(), sorted.end());
      d["total_seconds_runs"] = totals;
      d["total_seconds_median"] = sorted[sorted.size() / 2];
      std::cerr << " [gamma0 " << g << ": +" << d["points_added"] << " points, " << d["total_seconds_median"] << " s]" << std::flush;
      if (sweep.empty()) e["delcert"] = d;
      sweep.push_back(d);
    }
    if (sweep.size() > 1) e["gamma0_sweep"] = sweep;
    if (gudhi) {
      std::cerr << ", gudhi" << std::flush;
      e["gudhi"] = run_gudhi(ps, planes, manifold.intrinsic_dimension(), threads, max_perturb, gudhi_limit);
      const json d = e["delcert"], g = e["gudhi"];
      if (g.contains("total_seconds"))
        e["time_ratio_gudhi_over_delcert"] = g["total_seconds"].get<double>() / d["total_seconds_median"].get<double>();
    }
    std::cerr << "\n";
    results.push_back(e);
    std::cerr << e.dump(2) << std::endl;  // each case as soon as it is done (stdout gets one document)
  }
  doc["results"] = results;
  if (!sizing_items.empty()) {
    json rows = json::array();
    for (const auto& item : sizing_items) {
      rows.push_back(run_sizing(item, threads, seed, out_dir));
      std::cerr << rows.back().dump(2) << std::endl;  // as soon as it is done, as the cases
    }
    doc["sizing"] = rows;
  }
  if (!temp_dir.empty()) std::filesystem::remove_all(temp_dir);
  std::cout << doc.dump(2) << std::endl;
  return 0;
}
