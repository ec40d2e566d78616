#include "certify/certify.hpp"

#include <algorithm>
#include <chrono>
#include <ctime>
#include <cmath>
#include <map>
#include <numeric>
#include <optional>
#include <set>

#include "certify/restricted/coverage.hpp"
#include "certify/detail/grid.hpp"
#include "certify/detail/parallel.hpp"
#include "certify/detail/world.hpp"
#include "certify/distributed.hpp"
#include "certify/intrinsic/intrinsic.hpp"
#include "certify/restricted/restricted.hpp"
#include "certify/restricted/restricted_recheck.hpp"
#include "certify/tangential/sanity.hpp"
#include "certify/intrinsic/general.hpp"
#include "certify/tangential/reach_check.hpp"
#include "certify/detail/sha256.hpp"
#include "certify/tangential/star.hpp"
#include "certify/tangential/theorem.hpp"
#include "certify/tangential/thickness.hpp"
#include "certify/tangential/topology.hpp"
#include "certify/tangential/checks.hpp"
#include "certify/restricted/checks.hpp"
#include "certify/intrinsic/checks.hpp"
#include "exact/number_types.hpp"
#include "exact/tangent_predicates.hpp"
#include "io/atomic_file.hpp"
#include "io/claims.hpp"
#include "io/complex.hpp"
#include "io/input_error.hpp"
#include "io/spec.hpp"
#include "topology/three_sphere.hpp"

namespace delcert::certify {

using nlohmann::json;

namespace {

using exact::Tri;
using detail::check_consistency;
using detail::check_covering;
using detail::check_intrinsic;
using detail::check_power_protection;
using detail::ProtectionResult;
using detail::RadiusResult;
using detail::check_restricted;
using detail::check_restricted_equals_intrinsic;
using detail::check_star_radius;
using detail::check_stars;
using detail::check_tangential_equals_restricted;
using detail::check_topology;
using detail::either;
using detail::sharpen_per_point_cells;
using detail::Stars;


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

// ---- Inputs ----------------------------------------------------------------------------------

// The inputs, each read once: the bytes parsed are the bytes hashed into the certificate.
struct Inputs {
  std::string spec_text, points_text, complex_text, claims_text;
  std::string points_sha256, complex_sha256;  // of points_text and complex_text
  std::string per_point_sha256;      // claims v3: SHA-256 of each per-point file (star radius, covering), "" when absent
  std::string covering_per_point_sha256;
  io::ManifoldSpec spec;
  io::PointSet points;
  std::vector<long> point_lines;     // line of each point in the points file
  std::optional<io::Complex> given;  // the complex to verify; none in audit mode
  bool given_is_off = false;         // it came from a mesh file: OFF, OBJ, PLY, STL (a surface mesher's output)
  json complex_read;                 // the format read and what the reader changed (merged vertices, dropped faces)
  io::Claims claims;
};

Inputs read_inputs(const CertifyOptions& o, int threads) {
  Inputs in;
  in.spec_text = io::read_spec_text(o.manifold);
  in.spec = io::parse_spec(in.spec_text, o.manifold);
  if (!o.residual_tolerance.empty()) in.spec.residual_tolerance = io::parse_residual_tolerance(o.residual_tolerance);
  const int N = in.spec.ambient_dimension, m = in.spec.intrinsic_dimension;
  if (m > exact::kMaxTangentDimension)
    throw io::InputError(o.manifold, 0, "intrinsic dimension " + std::to_string(m) + " is above the supported maximum " +
                                            std::to_string(exact::kMaxTangentDimension));
  // The points and the complex are read, parsed and hashed on two threads when there are two:
  // the same results and the same first error as one after the other. A points error is thrown
  // first (task 0); a complex that failed, or is in the headerless gudhi format (whose reading
  // needs the number of points), is read again below exactly as before.
  const auto format = io::complex_format_from_name(o.complex_format).value_or(io::ComplexFormat::automatic);
  std::optional<io::PointsFile> pf;
  std::optional<io::ComplexFile> read_first;
  detail::parallel_for(o.complex.empty() ? 1 : 2, threads, [&](std::size_t task, int) {
    if (task == 0) {
      in.points_text = io::read_file(o.points);
      pf = io::parse_points_file(in.points_text, o.points, io::PointReadOptions{N, true});
      in.points_sha256 = detail::Sha256::hex(in.points_text);
      return;
    }
    try {
      in.complex_text = io::read_file(o.complex);
      in.complex_sha256 = detail::Sha256::hex(in.complex_text);
      read_first = io::parse_complex(in.complex_text, o.complex, {format, 0});
    } catch (const std::exception&) {  // thrown again below
    }
  });
  in.points = std::move(pf->points);
  in.point_lines = std::move(pf->lines);
  const io::PointSet& P = in.points;
  if (P.size() < static_cast<std::size_t>(m + 2))
    throw io::InputError(o.points, 0, "only " + std::to_string(P.size()) + " points: a closed " + std::to_string(m) +
                                          "-manifold needs at least m + 2 = " + std::to_string(m + 2));
  if (!o.complex.empty()) {
    if (!read_first || read_first->format == io::ComplexFormat::gudhi) {
      if (in.complex_sha256.empty()) {  // the first read failed: fails again here, or the file came back
        in.complex_text = io::read_file(o.complex);
        in.complex_sha256 = detail::Sha256::hex(in.complex_text);
      }
      read_first = io::parse_complex(in.complex_text, o.complex, {format, P.size()});
    }
    io::ComplexFile& cf = *read_first;
    in.complex_read = {{"format", io::to_string(cf.format)}, {"note", cf.note}};
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
    in.given_is_off = cf.embedded_points.has_value();
    in.given = std::move(cf.complex);
  }
  if (!o.claims.empty()) {
    in.claims_text = io::read_file(o.claims);
    in.claims = io::parse_claims(in.claims_text, o.claims);
    // Version 3: one eps(p) per point, in the order of the points.
    const std::pair<const std::string*, const std::vector<mpq_class>*> per_point[] = {
        {&in.claims.star_radius_per_point_path, &in.claims.star_radius_per_point},
        {&in.claims.covering_per_point_path, &in.claims.covering_per_point}};
    for (const auto& [path, values] : per_point)
      if (!path->empty() && values->size() != in.points.size())
        throw io::InputError(*path, 0, "holds " + std::to_string(values->size()) + " values but " + o.points + " has " +
                                           std::to_string(in.points.size()) +
                                           " points: write one eps(p) per point, in the order of the points");
    if (!in.claims.star_radius_per_point_path.empty())
      in.per_point_sha256 = detail::Sha256::hex(io::read_file(in.claims.star_radius_per_point_path));
    if (!in.claims.covering_per_point_path.empty())
      in.covering_per_point_sha256 = detail::Sha256::hex(io::read_file(in.claims.covering_per_point_path));
  }
  return in;
}

// The certificate's "inputs": what was read, with the SHA-256 of the bytes parsed.
json inputs_json(const Inputs& in, const CertifyOptions& o) {
  json j;
  j["manifold"] = {{"source", o.manifold}, {"name", in.spec.name}, {"sha256", detail::Sha256::hex(in.spec_text)},
                   {"intrinsic_dimension", in.spec.intrinsic_dimension}, {"ambient_dimension", in.spec.ambient_dimension}};
  j["points"] = {{"path", o.points}, {"sha256", in.points_sha256}, {"count", in.points.size()}};
  j["complex"] = in.given ? json{{"path", o.complex}, {"sha256", in.complex_sha256},
                                 {"simplices", in.given->simplices.size()}, {"read", in.complex_read}}
                          : json(nullptr);
  j["residual_tolerance"] = {{"value", exact::rational_to_string(in.spec.residual_tolerance)},
                             {"source", o.residual_tolerance.empty() ? "the manifold spec" : "--residual-tolerance"}};
  j["claims"] = o.claims.empty() ? json(nullptr) : json{{"path", o.claims}, {"sha256", detail::Sha256::hex(in.claims_text)}};
  if (!in.per_point_sha256.empty())
    j["claims"]["star_radius_per_point"] = {{"path", in.claims.star_radius_per_point_path}, {"sha256", in.per_point_sha256}};
  if (!in.covering_per_point_sha256.empty())
    j["claims"]["covering_per_point"] = {{"path", in.claims.covering_per_point_path}, {"sha256", in.covering_per_point_sha256}};
  return j;
}

json conventions_json() {
  return {
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
}

json parameters_json(const Inputs& in) {
  json params = json::object();
  const io::Claims& claims = in.claims;
  if (claims.star_radius) params["star_radius"] = exact::rational_to_string(*claims.star_radius);
  if (claims.covering) params["covering"] = exact::rational_to_string(*claims.covering);
  if (!claims.star_radius_per_point_file.empty()) params["star_radius_per_point"] = claims.star_radius_per_point_file;
  if (!claims.covering_per_point_file.empty()) params["covering_per_point"] = claims.covering_per_point_file;
  if (claims.sparsity) params["sparsity"] = exact::rational_to_string(*claims.sparsity);
  if (claims.gamma0) params["gamma0"] = exact::rational_to_string(*claims.gamma0);
  if (claims.power_protection) params["power_protection"] = exact::rational_to_string(*claims.power_protection);
  return {{"mode", in.given ? "verify the given complex" : "audit: compute Del_TM(P) and Del_RM(P)"}, {"claims", params}};
}

// ---- Stars (read by checks 3, 4, 6, 7 and 10; their checks in tangential/checks.hpp) ------------

// What checks 3-14 keep of star(p) (1M points: all cell reports would be 1.3 KB a point, most of the peak memory): the
// cells' simplices; the smallest margin and the largest R_p(s)^2 over the cells that are cells (degenerate or with a
// point inside are not), folded in cell order as checks 6 and 10 fold them; the reports only where one is a witness.
void keep_for_checks(StarReport& r, int m, bool verify) {
  bool witness = r.state != StarReport::State::proven || (verify && !r.claimed_verified);
  r.cells = static_cast<int>(r.star.size()), r.vertices.reserve(r.star.size() * (m + 1));
  for (int i = 0; i < r.cells; ++i) {
    const CellReport& c = r.star[i];
    r.vertices.insert(r.vertices.end(), c.simplex.begin(), c.simplex.end());
    witness = witness || !c.empty() || c.protection_point >= 0 || c.eps_sign >= 0;
    if (c.degenerate || c.conflict >= 0) continue;  // not a cell: neither check measures it
    if (c.margin.lo < r.min_margin.lo) r.min_margin_cell = i, r.min_margin_point = c.margin_point;
    if (c.radius2.hi > r.max_radius2.hi) r.max_radius_cell = i;
    r.min_margin = {std::min(r.min_margin.lo, c.margin.lo), std::min(r.min_margin.hi, c.margin.hi)};
    r.max_radius2 = {std::max(r.max_radius2.lo, c.radius2.lo), std::max(r.max_radius2.hi, c.radius2.hi)};
  }
  if (!witness) std::vector<CellReport>().swap(r.star);
}

// The ranks of the run and the points each analyses (blocks[r] for rank r; none in one process).
// Every rank but 0 searches its block in `part`: the grid of its block's slab plus a halo of
// cells on either side (detail/grid.hpp), not the whole point set. Each search proves that the
// slab held its ball (PointGrid::covers); a point whose search leaves it is reported with the
// radius it needed. With a fixed halo (--halo) such a point stays undetermined (UNDECIDED, with
// the reason); otherwise the slab is widened to that radius and the point redone,
// until every search is covered (at worst the slab is the whole grid, which covers everything).
struct Distribution {
  const detail::World* world = nullptr;
  std::vector<std::vector<int>> blocks;
  double halo = 0;  // the first halo's width (0: 16 spacings)
  bool fixed = false;  // never widened (--halo)
  const io::PointSet* points = nullptr;
  int m = 0;
  std::optional<detail::PointGrid> part;  // another rank's block plus halo; empty on rank 0 (the whole grid)
  double width = 0;                       // the halo `part` was cut for
  bool root() const { return world->rank() == 0; }
  const std::vector<int>& mine() const { return blocks[world->rank()]; }
  // Cuts `part` for a halo of width h (from a grid over every point, built for the cut and freed).
  void cut(double h) {
    const detail::PointGrid whole(*points, m);
    const auto [lo, hi] = whole.first_axis_range(mine());
    const std::int64_t k = whole.cells_for(h);
    part.emplace(whole, lo - k, hi + k);
    width = h;
  }
  // The slot of point p's result: p on rank 0 (every point's), its place in mine() elsewhere.
  std::size_t slot(std::size_t p) const {
    if (root()) return p;
    return static_cast<std::size_t>(std::lower_bound(mine().begin(), mine().end(), static_cast<int>(p)) - mine().begin());
  }
};

// results[slot(p)] = f(p, worker) for every point p this rank analyses (every point, in one
// process); then rank 0 receives the other ranks' results (certify/distributed.hpp). Rank 0's
// `results` has a slot per point, another rank's one per point of its block. Every slot of rank
// 0's `results` is then exactly what one process computes: f(p) depends only on p and the inputs
// (every rank holds all the points; another rank searches them in its part, and a result whose
// search left the part is redone in a wider one or reported as such: need(result) > 0).
// The filter statistics of a search that left the part are dropped (ctx[w] is restored): rank 0
// then sums exactly the single-process counts.
template <class R, class F, class Need>
void for_each_point(Distribution& D, std::size_t n, std::vector<R>& results, int threads,
                    std::vector<exact::FilterContext>& ctx, F&& f, Need&& need) {
  if (D.world->size() == 1) {
    results.assign(n, R{});
    return detail::parallel_for(n, threads, [&](std::size_t p, int w) { results[p] = f(p, w); });
  }
  const std::vector<int>& mine = D.mine();
  results.assign(D.root() ? n : mine.size(), R{});
  std::vector<std::size_t> todo(mine.size());
  std::iota(todo.begin(), todo.end(), std::size_t(0));
  for (;;) {
    detail::parallel_for(todo.size(), threads, [&](std::size_t k, int w) {
      const std::size_t p = static_cast<std::size_t>(mine[todo[k]]);
      const exact::FilterStats before = ctx[w].stats;
      R& r = results[D.root() ? p : todo[k]];
      r = f(p, w);
      if (need(r) > 0) ctx[w].stats = before;
    });
    if (D.root() || D.fixed) break;
    std::vector<std::size_t> again;
    double h = 0;
    for (std::size_t i : todo)
      if (const double r = need(results[i]); r > 0) again.push_back(i), h = std::max(h, r);
    if (again.empty()) break;
    D.cut(std::max(h * 1.25, D.width * 2));  // geometric growth: a few cuts at most
    todo = std::move(again);
  }
  std::vector<std::string> all = D.world->gather(D.root() ? std::string() : encode(results));
  for (std::size_t r = 1; r < all.size(); ++r) decode(all[r], D.blocks[r], results);
}

Stars analyse_stars(const io::Complex* given, const StarSettings& S, int threads,
                    std::vector<exact::FilterContext>& ctx, io::ProgressLine* progress, Distribution& D) {
  const std::size_t n = S.points->size();
  const int m = S.m;
  Stars st;
  st.verify = given != nullptr;
  st.first.assign(n + 1, 0);
  if (given) {  // (the global checks read *given itself)
    if (std::all_of(given->simplices.begin(), given->simplices.end(), [&](const Simplex& s) {
          return static_cast<int>(s.size()) == m + 1 && std::is_sorted(s.begin(), s.end()); }))
      st.given_tops = &given->simplices;  // no copy (1M points: 112 MB)
    else
      for (Simplex s : given->simplices) {
        std::sort(s.begin(), s.end());
        (static_cast<int>(s.size()) != m + 1 ? st.wrong_dimension : st.sorted).push_back(std::move(s));
      }
    for (const auto& s : st.tops())  // counting sort of the (simplex, vertex) incidences by vertex
      for (int v : s) ++st.first[v + 1];
    for (std::size_t p = 0; p < n; ++p) st.first[p + 1] += st.first[p];
    st.at.resize(st.first[n]);
    std::vector<long> next(st.first.begin(), st.first.end() - 1);
    for (std::size_t i = 0; i < st.tops().size(); ++i)
      for (int v : st.tops()[i]) st.at[next[v]++] = static_cast<int>(i);
  }
  for_each_point(D, n, st.reports, threads, ctx, [&](std::size_t p, int w) {
    const std::vector<Simplex> claimed = given ? st.claimed(p) : std::vector<Simplex>();
    StarReport r = analyse_star(S, static_cast<int>(p), given ? &claimed : nullptr, ctx[w]);
    keep_for_checks(r, m, given != nullptr);
    if (progress) progress->add();
    return r;
  }, [](const StarReport& r) { return r.halo_needed; });
  if (!given && D.root()) {
    auto& K = st.complex.simplices;
    for (const auto& r : st.reports)
      for (auto& s : r.simplices()) K.push_back(std::move(s));
    std::sort(K.begin(), K.end()), K.erase(std::unique(K.begin(), K.end()), K.end()), st.complex.num_vertices = n;
  }
  return st;
}

// A check that is not a claim of this input (is_claimed): its decision is reported (details.decision), not held
// against the input. Its requirements stay: the consistency guard still holds a reported CERTIFIED to its bounds.
void report_unclaimed(CheckEntry& e) {
  e.details["decision"] = to_string(e.verdict);
  e.verdict = Verdict::report;
}

// Check 7: are the star simplices secure (paper Definition 3.1), with the parameters that check 9 derives from the
// measured values? Decided only with eps a certified sampling radius; a claim only with "secure": true (is_claimed).
CheckEntry check_secure_simplices(const TheoremParams& tp, const StarSettings& S, const std::vector<StarReport>& reports,
                                  int threads, std::vector<exact::FilterContext>& ctx, bool claimed,
                                  bool stars_are_the_complex, io::ProgressLine* progress, Distribution& D) {
  CheckEntry secure(CheckId::secure_simplices);
  if (claimed)
    secure.claim = {{"secure", true},
                    {"meaning", "every m-simplex of the complex is secure (Definition 3.1) with eps the certified "
                                "covering radius"}};
  if (!tp.usable) {
    secure.undecide("not evaluated: " + tp.why);
    secure.summary = "not evaluated: " + tp.why;
    return secure;
  }
  const std::size_t n = reports.size();
  SecureParams sp{tp.eps, tp.delta, tp.upsilon0, tp.shortest, {}, {}, {}, {}};
  sp.prepare();
  std::vector<SecureReport> sr;
  for_each_point(D, n, sr, threads, ctx, [&](std::size_t p, int w) {
    const StarReport& star = reports[D.slot(p)];
    if (star.state != StarReport::State::proven) return SecureReport{};
    if (progress) progress->add();
    return analyse_secure(S, static_cast<int>(p), star.simplices(), sp, ctx[w], &star);
  }, [](const SecureReport& r) { return r.halo_needed; });
  if (!D.root()) return secure;  // another rank: its results are on rank 0
  long ok = 0, bad = 0, fallbacks = 0, skipped = 0, unproven = 0, no_halo = 0;
  std::map<std::string, long> reasons;
  for (std::size_t p = 0; p < n; ++p) {
    if (reports[p].state != StarReport::State::proven) ++unproven;
    ok += sr[p].secure, bad += sr[p].insecure, fallbacks += sr[p].exact_fallbacks;
    (sr[p].halo_needed > 0 ? no_halo : skipped) += sr[p].undecided;
    for (const auto& [s, why] : sr[p].failures) {
      std::string key = why.substr(0, why.find(" ("));
      ++reasons[key];
      if (secure.witnesses.size() < 20) secure.add_witness({{"simplex", s}, {"at_vertex", p}, {"failed", why}});
    }
  }
  // The decision: Definition 3.1 is about a sampling radius eps; with eps only a star-radius
  // bound (check 11 not certified) neither answer is the paper's.
  if (!stars_are_the_complex)
    secure.undecide("Definition 3.1 is evaluated on the stars of Del_TM(P), and the complex is given as another "
                    "complex (--kind restricted or intrinsic)");
  else if (!tp.eps_is_sampling_radius)
    secure.undecide("eps is not a certified sampling radius (check 11 not CERTIFIED): Definition 3.1 not decided");
  else if (bad)
    secure.refute("a simplex is not secure (Definition 3.1); the witnesses give the first failed condition");
  else if (skipped)
    secure.undecide(std::to_string(skipped) + " star simplices not evaluated (more than 50 000 points within 5 eps)");
  else if (no_halo)
    secure.undecide(std::to_string(no_halo) + " star simplices not evaluated: an MPI rank's halo does not hold the points "
                    "within 5 eps of their vertex (rerun with a larger --halo, or without --halo: automatic)");
  else if (unproven)
    secure.undecide(std::to_string(unproven) + " star(s) not determined exactly");
  secure.details.update(json{{"parameters", tp.json_parameters()}, {"secure", ok}, {"not_secure", bad},
                              {"first_failed_condition_counts", reasons}, {"exact_fallbacks", fallbacks},
                              {"not_evaluated", skipped},
                              {"neighbourhood", "the points within 5 eps of p (ambient), projected orthogonally onto T_p"}});
  secure.summary = std::to_string(ok) + " of " + std::to_string(ok + bad + skipped + no_halo) + " star simplices secure (Definition 3.1" +
                   (tp.eps_is_sampling_radius ? ", eps >= the certified covering radius)" : ", eps a star-radius bound only)") +
                   (skipped ? "; " + std::to_string(skipped) + " not evaluated (more than 50 000 points within 5 eps)" : "") +
                   (no_halo ? "; " + std::to_string(no_halo) + " not evaluated (an MPI rank's halo too small)" : "");
  if (no_halo) secure.details["not_evaluated_halo_too_small"] = no_halo;
  return secure;
}

// ---- Del_RM (checks 11, 12, 13 in restricted/checks.hpp) ---------------------------------------

// What checks 11-13 say when Del_RM was not computed: with --skip-restricted (`why` empty), a
// REPORT; where it cannot be computed, UNDECIDED with the reason.
CheckEntry not_computed(CheckId id, const std::string& why = "") {
  CheckEntry e(id);
  if (why.empty()) {
    e.verdict = Verdict::report;
    e.summary = "not computed (--skip-restricted): this certificate says nothing about Del_RM(P) or the covering radius";
  } else {
    e.undecide(why);
    e.summary = "not computed: " + why;
  }
  return e;
}

// The checks that need T_p M at every point (Del_TM and what is measured on it), when some point is off M: accepted
// only for a complex claimed to be restricted Delaunay (check 1), they are not computed: UNDECIDED, which counts
// only where the claims file makes a claim the check would have decided (is_claimed; else reported).
CheckEntry tangent_space_undefined(CheckId id, int point) {
  CheckEntry e(id);
  const std::string why = "point " + std::to_string(point) +
                          " is off M (residual above the spec's residual_tolerance), where T_p M is not defined, "
                          "so Del_TM(P) is not computed";
  e.undecide(why);
  e.summary = "not computed: " + why;
  return e;
}


}  // namespace

bool is_claimed(CheckId id, Mode mode, const io::Claims& claims) {
  switch (id) {
    case CheckId::input_sanity: return true;
    case CheckId::theorem: return false;  // the paper's hypotheses, measured
    case CheckId::secure_simplices: return claims.secure;
    default: break;
  }
  if (mode == Mode::audit || mode == Mode::tangential) return true;  // the refiner's promise: Del_TM = Del_RM = Del_M
  switch (id) {  // a complex claimed restricted or intrinsic: that, and the claims file
    case CheckId::sparsity: return claims.sparsity.has_value();
    case CheckId::thickness: return claims.gamma0.has_value();
    case CheckId::power_protection: return claims.power_protection.has_value();
    case CheckId::star_radius: return claims.star_radius || !claims.star_radius_per_point_file.empty();
    case CheckId::covering: return claims.covering || !claims.covering_per_point_file.empty();
    case CheckId::restricted_delaunay: return mode == Mode::restricted;  // its completeness is check 11's argument
    case CheckId::intrinsic_delaunay: return mode == Mode::intrinsic;
    default: return false;  // 3, 4, 13, 15: other complexes of P; 8: the spec's expected topology
  }
}

Certificate run_certify(const CertifyOptions& o) {
  using clock = std::chrono::steady_clock;
  const auto t_start = clock::now();
  const std::clock_t cpu_start = std::clock();
  Certificate C;
  const int threads = std::max(1, o.threads);
  const detail::World one_process;
  Distribution D;
  D.world = o.world ? o.world : &one_process, D.halo = o.halo, D.fixed = o.fixed_halo;
  const bool root = D.root();

  Inputs in = read_inputs(o, threads);
  const io::ManifoldSpec& spec = in.spec;
  const io::PointSet& P = in.points;
  const io::Claims& claims = in.claims;
  const int N = spec.ambient_dimension, m = spec.intrinsic_dimension;
  C.inputs = inputs_json(in, o);
  std::string().swap(in.points_text), std::string().swap(in.complex_text);  // hashed: not read again
  C.conventions = conventions_json();
  C.parameters = parameters_json(in);

  // Every filtered predicate records its statistics in a context: one per worker thread (checks
  // 3, 6, 7 and 10), one for check 2 and one for the cells that check 4 tests.
  std::vector<exact::FilterContext> ctx(threads);
  exact::FilterContext ctx_sparsity, ctx_consistency;
  for (auto& c : ctx) c.force_exact = o.force_exact;
  ctx_sparsity.force_exact = ctx_consistency.force_exact = o.force_exact;

  // The kind of the given complex: tangential (checks 3 and 4 compare it with Del_TM) or
  // restricted (check 12 compares it with Del_RM; the stars are computed as in audit mode).
  const bool restricted_kind =
      in.given && (o.kind == ComplexKind::restricted || (o.kind == ComplexKind::automatic && in.given_is_off));
  const bool intrinsic_kind = in.given && o.kind == ComplexKind::intrinsic;
  if ((restricted_kind || intrinsic_kind) && o.skip_restricted)
    throw io::InputError(o.complex, 0, std::string("the complex is claimed to be ") +
                                           (intrinsic_kind ? "intrinsic Delaunay (--kind intrinsic), which needs checks 14-15"
                                                           : "restricted Delaunay (--kind restricted, the default for "
                                                             "OFF), which needs checks 11-13") +
                                           ": drop --skip-restricted or pass --kind tangential");
  const bool tangential_kind = in.given && !restricted_kind && !intrinsic_kind;
  C.parameters["kind"] = !in.given ? "audit" : restricted_kind ? "restricted" : intrinsic_kind ? "intrinsic" : "tangential";

  const auto phase = [&](const char* label, std::size_t total = 0) { if (o.progress) o.progress->phase(label, total); };
  Stopwatch watch;
  phase("check 1 input_sanity");
  SanityResult sanity = check_input_sanity(spec, P, in.point_lines, o.points, restricted_kind, threads);
  watch.record(C, "input_sanity");
  // Points off M (accepted only for a restricted claim) have no tangent space: no Del_TM.
  const bool on_M = sanity.off_manifold.empty();
  const exact::ImplicitSystem system(spec.equations, N);
  std::optional<detail::PointGrid> whole(std::in_place, P, m);  // rank 0's (every point)
  if (D.world->size() > 1) {
    for (int r = 0; r < D.world->size(); ++r) D.blocks.push_back(owned_points(*whole, r, D.world->size()));
    D.points = &P, D.m = m;
    if (!root) {  // another rank keeps its part: its block and a halo (by default 16 typical spacings to start)
      const double spacing = whole->spacing();
      whole.reset();
      D.cut(D.halo > 0 ? D.halo : 16 * spacing);
    }
  }
  const detail::PointGrid& grid = root ? *whole : *D.part;
  SparsityResult sparsity;  // (rank 0's alone: the other ranks do not hold every point)
  if (root) {
    phase("check 2 sparsity");
    sparsity = check_sparsity(P, grid, claims.sparsity ? &*claims.sparsity : nullptr, ctx_sparsity, threads);
    watch.record(C, "sparsity");
  }
  // THE DECLARED REACH (certify/reach_check.hpp), an input the graph lemma trusts: two points of M violating
  // Federer's inequality refute it (check 1), among the pairs a cell's first ball would see (about 4 spacings).
  if (root && spec.reach)
    if (const auto w = refute_declared_reach(system, spec.selector ? &*spec.selector : nullptr, P, grid, *spec.reach,
                                             4 * grid.spacing(), threads))
      record_reach_refutation(sanity.entry, *w, *spec.reach);

  const auto* radius_per_point = claims.star_radius_per_point_file.empty() ? nullptr : &claims.star_radius_per_point;
  const auto* covering_per_point = claims.covering_per_point_file.empty() ? nullptr : &claims.covering_per_point;
  // (on another rank `grid` is D.part, which D.cut re-cuts in place: S.grid stays valid)
  const StarSettings S{&P, &system, &grid, m, claims.power_protection, claims.star_radius, radius_per_point};
  std::optional<Stars> stars;  // Del_TM(P): needs T_p M at every point
  std::optional<CheckEntry> stars_entry, consistency, protection_entry, radius_entry, secure, theorem;
  std::optional<ProtectionResult> protection;
  std::optional<RadiusResult> radius;
  if (on_M) {
    phase("check 3 stars", P.size());
    stars = analyse_stars(tangential_kind ? &*in.given : nullptr, S, threads, ctx, o.progress, D);
    watch.record(C, "stars");
  }
  if (!root) {  // another rank of an MPI job: its share of check 7, with the parameters rank 0 measured
    if (on_M) {
      const TheoremParams tp = theorem_parameters(decode_measured(D.world->broadcast({})));
      check_secure_simplices(tp, S, stars->reports, threads, ctx, claims.secure, !restricted_kind && !intrinsic_kind, nullptr, D);
    }
    exact::FilterStats mine;  // only the split loops' (rank 0 alone runs the rest)
    for (auto& c : ctx) mine.merge(c.stats);
    D.world->gather(encode_stats(mine));
    return Certificate{};
  }
  if (on_M) {
    stars_entry = check_stars(*stars, m);
    consistency = check_consistency(*stars, S, ctx_consistency);
    protection = check_power_protection(*stars, claims.power_protection);
    radius = check_star_radius(*stars, claims.star_radius, radius_per_point, claims.star_radius_per_point_file);
    protection_entry = protection->entry, radius_entry = radius->entry;
    watch.record(C, "assemble_checks_3_4_6_10");
  } else {
    const int first = sanity.off_manifold[0];
    stars_entry = tangent_space_undefined(CheckId::stars, first);
    consistency = tangent_space_undefined(CheckId::consistency, first);
    protection_entry = tangent_space_undefined(CheckId::power_protection, first);
    radius_entry = tangent_space_undefined(CheckId::star_radius, first);
    secure = tangent_space_undefined(CheckId::secure_simplices, first);
    theorem = tangent_space_undefined(CheckId::theorem, first);
  }

  // One face lattice for checks 5 and 8. Simplices with more than m + 1 vertices are refuted by check 3 (wrong
  // dimension, with the simplex as witness); their 2^n faces are never enumerated (a 32-vertex simplex would hang).
  const io::Complex& K = in.given ? *in.given : stars->complex;  // what checks 5 and 8 look at
  auto fits = [&](const Simplex& s) { return static_cast<int>(s.size()) <= m + 1; };
  const bool all_fit = std::all_of(K.simplices.begin(), K.simplices.end(), fits);
  std::vector<Simplex> fitting;  // a copy only when some simplex is too large
  if (!all_fit) std::copy_if(K.simplices.begin(), K.simplices.end(), std::back_inserter(fitting), fits);
  phase("check 5 thickness");
  const FaceLattice lattice = face_lattice(all_fit ? K.simplices : fitting, threads);
  ThicknessResult thick = check_thickness(P, lattice, m, claims.gamma0 ? &*claims.gamma0 : nullptr, threads, C.filter,
                                         o.force_exact);
  watch.record(C, "thickness");

  phase("check 8 topology");
  CheckEntry topology = check_topology(K, m, lattice, spec.expected, threads);
  watch.record(C, "topology");

  // Checks 11-13: the certified restricted Voronoi diagram.
  std::optional<CheckEntry> covering, restricted, equal, intrinsic, equal_mi;
  std::optional<RestrictedDelaunay> R;
  RestrictedCellOptions cell_options;  // check 12's, for the general Del_M engine (checks 14-15)
  const VerifiedShape shape = verify_declared_shape(spec);  // (Del_M below verifies it again: cheap)
  if (o.skip_restricted || m > 3) {
    const std::string why = o.skip_restricted ? "" : "the certified restricted Voronoi diagram is built for m <= 3 (here m = " +
                                                         std::to_string(m) + ")";
    covering = not_computed(CheckId::covering, why), restricted = not_computed(CheckId::restricted_delaunay, why);
    equal = not_computed(CheckId::tangential_equals_restricted, why);
  } else {
    RestrictedDelaunayOptions ro;
    ro.threads = threads;
    ro.expected = &K.simplices;
    ro.distance_to_M = &sanity.distance_to_M;
    // THE GRAPH LEMMA (rvd.cpp) in codimension >= 4 only, where excluding the other sheets box by box
    // (2k searches of a k-dimensional slab) never ends (SO(3)); below, it is as fast and assumes nothing.
    if (spec.reach && N - m >= 4) ro.cell.reach = sqrt_lower(spec.reach->squared);
    ro.cell.selector = spec.selector ? &*spec.selector : nullptr;
    // A verified SO(3) or flat torus: rational charts (certify/detail/param_cell.hpp; about 1000 times
    // faster than the codimension-6 implicit chart on SO(3), 2.2 times on the refined T^3, and
    // minutes against a second on coarse T^3 samples). Spheres keep the implicit chart: as fast on
    // them and its Lagrangian covering bound is tighter; the tests run both on spheres and T^2 and
    // require the same Del_RM.
    if (shape.shape && (shape.shape->kind == io::ShapeSpec::Kind::so3 || shape.shape->kind == io::ShapeSpec::Kind::product_of_circles))
      ro.cell.shape = &*shape.shape;
    phase("checks 11-13 restricted Voronoi cells");
    if (o.progress) ro.progress = [&o](std::size_t done, std::size_t total) { o.progress->update(done, total); };
    R = compute_restricted_delaunay(system, P, grid, ro);
    cell_options = ro.cell;
    if (covering_per_point && R->covering_certified) sharpen_per_point_cells(*R, *covering_per_point, system, P, grid, ro.cell, threads);
    // COVERAGE (certify/coverage.hpp): every point of M within c of P, or a far point of M refuting
    // the claim (without one: above c), found and stops the search.
    watch.record(C, "restricted_delaunay");
    double target = std::nextafter(R->covering, INFINITY);
    if (claims.covering) target = exact::enclose(*claims.covering).hi;
    if (covering_per_point)
      for (const auto& e : *covering_per_point) target = std::max(target, exact::enclose(e).hi);
    const CoverageProof coverage = prove_coverage(system, ro.cell.selector, spec.bounding_box,
                                                  shape.shape ? shape.metric : "", P, grid, *R, target);
    if (!coverage.proven) R->covering_certified = false, R->reason = coverage.reason;
    watch.record(C, "coverage");
    covering = check_covering(*R, coverage, claims.covering, spec, covering_per_point, claims.covering_per_point_file);
    const RecheckInput recheck{&spec.equations, spec.selector ? &*spec.selector : nullptr, &P};
    restricted = check_restricted(*R, in.given, restricted_kind, m, recheck);
    // Del_RM(P) known completely rests on check 11's covering argument, whether or not a covering radius is claimed.
    restricted->details["assumptions"] = covering->details["assumptions"];
    if (restricted->details["pure"] == true) for (const auto& s : R->simplices) C.restricted_complex.push_back(s.simplex);  // (--fix-out)
    equal = on_M ? check_tangential_equals_restricted(*stars, *R)
                 : tangent_space_undefined(CheckId::tangential_equals_restricted, sanity.off_manifold[0]);
  }
  watch.record(C, "checks_11_13");

  if (on_M) {
    // Checks 7 and 9: the paper's hypotheses, measured; eps is also a sampling radius when check
    // 11 certified one (the smallest double above its bound: the paper's eps-sample is strict).
    Measured meas;
    meas.min_distance = sqrt_lower(sparsity.min_squared);
    meas.min_thickness = thick.min_top.lo;
    // (bounds over all star cells only where every star was determined: check 9's factor is printed as certified)
    meas.min_margin = protection->cells && protection->all_determined ? protection->min_margin.lo : -INFINITY;
    meas.max_radius_squared = radius->cells && radius->all_determined ? radius->max_r2.hi : INFINITY;
    meas.eps = claims.star_radius && radius->entry.verdict == Verdict::certified
                   ? std::optional<mpq_class>(*claims.star_radius)
                   : std::nullopt;
    if (R && covering->verdict == Verdict::certified)
      meas.covering = exact::to_rational(std::nextafter(R->covering, INFINITY));
    if (D.world->size() > 1) D.world->broadcast(encode_measured(meas));  // the other ranks decode these very bits
    const TheoremParams tp = theorem_parameters(meas);
    phase("check 7 secure_simplices", P.size());
    secure = check_secure_simplices(tp, S, stars->reports, threads, ctx, claims.secure, !restricted_kind && !intrinsic_kind,
                                    o.progress, D);
    theorem = theorem_report(tp, spec);
    watch.record(C, "secure_and_theorem");
  }

  // Checks 14-15: Del_M, from the candidates of Del_RM, Del_TM and the given complex.
  if (o.skip_restricted) {
    intrinsic = not_computed(CheckId::intrinsic_delaunay), equal_mi = not_computed(CheckId::restricted_equals_intrinsic);
  } else {
    std::vector<Simplex> candidates;
    if (R)
      for (const auto& s : R->simplices) candidates.push_back(s.simplex);
    if (stars)
      for (const auto& r : stars->reports)
        if (r.state == StarReport::State::proven)
          for (auto& s : r.simplices()) candidates.push_back(std::move(s));
    if (in.given)
      for (Simplex s : in.given->simplices)
        if (static_cast<int>(s.size()) == m + 1) {
          std::sort(s.begin(), s.end());
          if (std::adjacent_find(s.begin(), s.end()) == s.end()) candidates.push_back(s);
        }
    phase("checks 14-15 intrinsic Delaunay");
    GeneralMetricInput general;
    general.system = &system, general.distance_to_M = &sanity.distance_to_M, general.cell = cell_options;
    general.restricted = R ? &*R : nullptr;
    const IntrinsicDelaunay D = compute_intrinsic_delaunay(spec, P, grid, candidates, threads, o.general_del_m ? &general : nullptr);
    intrinsic = check_intrinsic(D, in.given, intrinsic_kind, m);
    equal_mi = check_restricted_equals_intrinsic(R ? &*R : nullptr, D);
  }
  watch.record(C, "intrinsic_delaunay");
  if (o.progress) o.progress->clear();

  for (auto& c : ctx) C.filter.merge(c.stats);
  if (D.world->size() > 1) {
    const std::vector<std::string> others = D.world->gather(std::string());
    for (std::size_t r = 1; r < others.size(); ++r) C.filter.merge(decode_stats(others[r]));
  }
  C.filter.merge(ctx_sparsity.stats);
  C.filter.merge(ctx_consistency.stats);
  C.checks.push_back(std::move(sanity.entry));
  C.checks.push_back(std::move(sparsity.entry));
  C.checks.push_back(std::move(*stars_entry));
  C.checks.push_back(std::move(*consistency));
  C.checks.push_back(std::move(thick.entry));
  C.checks.push_back(std::move(*protection_entry));
  C.checks.push_back(std::move(*secure));
  C.checks.push_back(std::move(topology));
  C.checks.push_back(std::move(*theorem));
  C.checks.push_back(std::move(*radius_entry));
  C.checks.push_back(std::move(*covering));
  C.checks.push_back(std::move(*restricted));
  C.checks.push_back(std::move(*equal));
  C.checks.push_back(std::move(*intrinsic));
  C.checks.push_back(std::move(*equal_mi));
  // The verdict answers what was claimed, and only that: every other check is reported (is_claimed).
  const Mode mode = !in.given ? Mode::audit : restricted_kind ? Mode::restricted : intrinsic_kind ? Mode::intrinsic : Mode::tangential;
  for (CheckEntry& e : C.checks) {
    const bool claim = is_claimed(e.id, mode, claims);
    // The complex's own claim (12 or 14) is decided, never merely reported: else check 1 alone would certify it.
    const bool about_the_complex = claim && (mode == Mode::restricted || mode == Mode::intrinsic) &&
                                   (e.id == CheckId::restricted_delaunay || e.id == CheckId::intrinsic_delaunay);
    if (about_the_complex && e.verdict == Verdict::report) {
      e.verdict = Verdict::undecided;
      e.details["reason"] = "the complex's claim was not decided: " + e.summary;
    }
    if (e.verdict != Verdict::report && !claim) report_unclaimed(e);
    e.claimed = e.verdict != Verdict::report;
  }
  C.times.emplace_back("total", seconds_since(t_start));
  C.times.emplace_back("total_cpu", double(std::clock() - cpu_start) / CLOCKS_PER_SEC);
  enforce_self_consistency(C);  // a certificate that contradicts itself is an internal error
  return C;
}

}  // namespace delcert::certify
