#include "certify/certify.hpp"

#include <algorithm>
#include <chrono>
#include <ctime>
#include <cmath>
#include <map>
#include <numeric>
#include <optional>
#include <set>

#include "certify/coverage.hpp"
#include "certify/detail/grid.hpp"
#include "certify/detail/parallel.hpp"
#include "certify/detail/world.hpp"
#include "certify/distributed.hpp"
#include "certify/intrinsic.hpp"
#include "certify/intrinsic/general.hpp"
#include "certify/reach_check.hpp"
#include "certify/restricted.hpp"
#include "certify/restricted_recheck.hpp"
#include "certify/sanity.hpp"
#include "certify/detail/sha256.hpp"
#include "certify/star.hpp"
#include "certify/theorem.hpp"
#include "certify/thickness.hpp"
#include "certify/topology.hpp"
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

// Three-valued (Kleene) disjunction: yes if either is yes, no if both are no, else unknown.
Tri either(Tri a, Tri b) { return !(!a && !b); }

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

// ---- Stars (read by checks 3, 4, 6, 7 and 10) ------------------------------------------------

struct Stars {
  bool verify = false;                               // a complex was given (else: audit mode)
  std::vector<Simplex> wrong_dimension;              // given simplices of another dimension, sorted
  std::vector<StarReport> reports;                   // per point: star(p), exactly or why not
  io::Complex complex;                               // audit mode: the union of the stars, what the global checks look at
  std::vector<Simplex> sorted;                       // verify mode: the given m-simplices, each sorted, in file order,
  const std::vector<Simplex>* given_tops = nullptr;  // or the given simplices themselves when they are just that
  std::vector<long> first;                           // verify mode: tops()[at[i]], first[p] <= i < first[p + 1], contain p
  std::vector<int> at;
  // The m-simplices, each sorted (given: in file order; audit: sorted, unique)
  const std::vector<Simplex>& tops() const { return given_tops ? *given_tops : verify ? sorted : complex.simplices; }
  std::vector<Simplex> claimed(std::size_t p) const {  // the given m-simplices at p, in file order
    std::vector<Simplex> c;
    for (long i = first[p]; i < first[p + 1]; ++i) c.push_back(tops()[at[i]]);
    return c;
  }
};

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
struct ProtectionResult {
  CheckEntry entry{CheckId::power_protection};
  long cells = 0;                                 // star cells seen (certified or not)
  exact::Interval min_margin{INFINITY, INFINITY};  // over the certified cells
  bool all_determined = true;                      // every star and star cell determined: min_margin bounds them all
};

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
struct RadiusResult {
  CheckEntry entry{CheckId::star_radius};
  long cells = 0;                                 // star cells seen (certified or not)
  exact::Interval max_r2{-INFINITY, -INFINITY};   // of R_p(s)^2 over the certified cells
  bool all_determined = true;                     // every star determined: max_r2 bounds them all
};

// With a per-point claim (claims v3), eps is eps(p) at each star's point p: `per_point` holds them
// (one per point) and `per_point_file` names the file; `eps` is then absent.
RadiusResult check_star_radius(const Stars& st, const std::optional<mpq_class>& eps,
                               const std::vector<mpq_class>* per_point = nullptr, const std::string& per_point_file = {}) {
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

// ---- Del_RM (checks 11, 12, 13; certify/restricted.hpp) --------------------------------------

json box_json(const exact::Box& X) {
  json b = json::array();
  for (const auto& i : X) b.push_back(enclosure_json(i));
  return b;
}

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
                          const io::ManifoldSpec& spec, const std::vector<mpq_class>* per_point = nullptr,
                          const std::string& per_point_file = {}) {
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
  rd.summary = std::to_string(R.simplices.size()) + " m-simplices of Del_RM(P) certified" +
               (R.covering_certified ? " (all of them)" : " (maybe not all)") +
               (tops_equal ? ", exactly the complex's" : "") +
               (impure_known ? "; Del_RM(P) is not pure, so it triangulates nothing: " + std::to_string(R.lower_faces.size()) +
                                   " simplices of lower dimension in no m-simplex"
                : unresolved || !R.lower_faces.empty() ? "; purity not proven" : "") +
               (claimed && given && !tops_equal
                    ? "; " + std::to_string(missing) + " missing from the complex, " + std::to_string(extra) +
                          " not in Del_RM" + (R.covering_certified ? "" : " (not proven absent)")
                    : "");
  return rd;
}

// Check 13: Del_TM(P) = Del_RM(P) on m-simplices, decided either way with witnesses.
CheckEntry check_tangential_equals_restricted(const Stars& st, const RestrictedDelaunay& R) {
  CheckEntry eq(CheckId::tangential_equals_restricted);
  std::set<Simplex> tm;
  long unknown_stars = 0;
  for (const auto& r : st.reports) {
    if (r.state == StarReport::State::proven) {  // (claimed_verified: star holds the claimed cells)
      for (auto& s : r.simplices()) tm.insert(std::move(s));
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
  eq.summary = equality(eq.verdict, "Del_TM(P)", "Del_RM(P)") + " (" + std::to_string(tm.size()) + " and " + std::to_string(rm.size()) + " m-simplices; " +
               std::to_string(only_tm) + " only tangential, " + std::to_string(only_rm) + " only restricted)";
  return eq;
}

// Check 14: Del_M(P) computed (certify/intrinsic.hpp) and, with --kind intrinsic, compared with
// the given complex.
CheckEntry check_intrinsic(const IntrinsicDelaunay& D, const std::optional<io::Complex>& given, bool intrinsic_kind, int m) {
  CheckEntry im(CheckId::intrinsic_delaunay);
  im.details = {{"metric", D.metric.empty() ? json(nullptr) : json(D.metric)}};
  if (!D.computed) {
    im.undecide(D.reason);
    im.summary = "not computed: " + D.reason;
  } else {
    im.details["convention"] = D.convention;
    im.details["completeness"] = D.completeness;
    im.details["m_simplices"] = D.simplices.size();
    im.details["candidates_rejected"] = D.rejected.size();
    json und = json::array();
    for (const auto& u : D.undecided)
      if (und.size() < 10) und.push_back({{"simplex", u.simplex}, {"reason", u.reason}});
    im.details["candidates_undecided"] = D.undecided.size();
    im.details["undecided_examples"] = und;
    if (!D.complete) im.undecide("Del_M(P) not known completely: " + D.reason);
    long missing = 0, extra = 0;
    if (intrinsic_kind && given) {
      const std::set<Simplex> tops = top_simplices(*given, m);
      std::set<Simplex> certified;
      for (const auto& s : D.simplices) {
        certified.insert(s.simplex);
        if (tops.count(s.simplex)) continue;
        ++missing;
        im.refute("a simplex of Del_M(P) is missing from the complex");
        im.add_witness(s.witness);
      }
      for (const auto& r : D.rejected)
        if (tops.count(r.simplex)) {
          ++extra;
          im.refute("a simplex of the complex is not in Del_M(P)");
          im.add_witness(r.witness);
        }
      for (Simplex s : given->simplices) {
        std::sort(s.begin(), s.end());
        const bool top = static_cast<int>(s.size()) == m + 1;
        bool face = top;
        for (const auto& t : tops)
          if (!face && std::includes(t.begin(), t.end(), s.begin(), s.end())) face = static_cast<int>(s.size()) < m + 1;
        if (top ? certified.count(s) || !D.complete : face) continue;
        if (top && std::any_of(D.rejected.begin(), D.rejected.end(), [&](const auto& r) { return r.simplex == s; }))
          continue;  // already a witness
        ++extra;
        if (!D.complete) continue;
        im.refute("a simplex of the complex is not in Del_M(P)");
        im.add_witness({{"kind", top ? "not_intrinsic" : "not_a_face_of_an_m_simplex"},
                        {"simplex", s},
                        {"detail", "Del_M(P) is known completely (check 14) and does not contain it"}});
      }
      im.claim = {{"kind", "intrinsic"}, {"meaning", "the complex is the intrinsic Delaunay complex Del_M(P)"}};
      im.details["missing_simplices"] = missing, im.details["extra_simplices"] = extra;
    }
    im.summary = std::to_string(D.simplices.size()) + " m-simplices of Del_M(P) certified" +
                 (D.complete ? " (all of them)" : " (maybe not all)") +
                 (intrinsic_kind && given ? "; " + std::to_string(missing) + " missing from the complex, " +
                                                std::to_string(extra) + " not in Del_M"
                                          : "");
  }
  return im;
}

// Check 15: Del_RM(P) = Del_M(P) on m-simplices, decided either way with witnesses.
CheckEntry check_restricted_equals_intrinsic(const RestrictedDelaunay* R, const IntrinsicDelaunay& D) {
  CheckEntry eq(CheckId::restricted_equals_intrinsic);
  long only_rm = 0, only_m = 0;
  std::set<Simplex> rm, im, rejected;
  if (R)
    for (const auto& s : R->simplices) rm.insert(s.simplex);
  for (const auto& s : D.simplices) im.insert(s.simplex);
  for (const auto& r : D.rejected) rejected.insert(r.simplex);
  if (R && D.computed) {
    for (const auto& s : R->simplices) {
      const bool proven_out = rejected.count(s.simplex) || (D.complete && !im.count(s.simplex));
      if (!proven_out) continue;
      ++only_rm;
      eq.refute("a simplex of Del_RM(P) is not in Del_M(P)");
      json w = vertex_witness(s);
      w["not_in"] = "Del_M(P)";
      for (const auto& r : D.rejected)
        if (r.simplex == s.simplex) w["intrinsic_witness"] = r.witness;
      eq.add_witness(w);
    }
    for (const auto& s : D.simplices) {
      if (rm.count(s.simplex) || !R->covering_certified) continue;
      ++only_m;
      eq.refute("a simplex of Del_M(P) is not in Del_RM(P)");
      json w = s.witness;
      w["not_in"] = "Del_RM(P)";
      eq.add_witness(w);
    }
  }
  if (eq.verdict == Verdict::certified) {
    if (!R) eq.undecide("Del_RM(P) not computed");
    else if (!D.computed) eq.undecide("Del_M(P) not computed: " + D.reason);
    else if (!R->covering_certified) eq.undecide("Del_RM(P) not known completely: " + R->reason);
    else if (!D.complete) eq.undecide("Del_M(P) not known completely: " + D.reason);
  }
  eq.details = {{"restricted_m_simplices", rm.size()}, {"intrinsic_m_simplices", im.size()},
                {"only_in_restricted", only_rm}, {"only_in_intrinsic", only_m}};
  eq.summary = equality(eq.verdict, "Del_RM(P)", "Del_M(P)") + " (" + std::to_string(rm.size()) + " and " + std::to_string(im.size()) + " m-simplices; " +
               std::to_string(only_rm) + " only restricted, " + std::to_string(only_m) + " only intrinsic)";
  if (!D.computed) eq.summary = "not decided: Del_M(P) not computed: " + D.reason;
  return eq;
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
    const IntrinsicDelaunay D = compute_intrinsic_delaunay(spec, P, grid, candidates, threads, &general);
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
