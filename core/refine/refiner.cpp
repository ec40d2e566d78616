#include "core/refine/refiner.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <numeric>
#include <set>
#include <stdexcept>
#include <unordered_map>

#include "core/refine/cospherical.hpp"
#include "core/refine/hitting_sets.hpp"
#include "core/refine/intrinsic_repair.hpp"
#include "core/refine/picking_region.hpp"
#include "core/spatial/neighbour_index.hpp"
#include "core/refine/simplex_measures.hpp"
#include "core/sampling/random.hpp"
#include "core/spatial/neighbour_index.hpp"
#include "core/support/parallel.hpp"
#include "core/tangential/star.hpp"
#include "core/tangential/tangent_planes.hpp"
#include "core/tangential/tangential_complex.hpp"
#include "core/spatial/distance.hpp"

namespace delcert::refine {

const char* to_string(RefineMode m) { return m == RefineMode::paper ? "paper" : "practical"; }

const char* to_string(Rule r) {
  switch (r) {
    case Rule::big: return "big";
    case Rule::bad_star: return "bad_star";
    case Rule::bad_cosph: return "bad_cosph";
    case Rule::unprotected: return "unprotected";
    case Rule::inconsistent: return "inconsistent";
    case Rule::not_restricted: return "not_restricted";
    case Rule::not_intrinsic: return "not_intrinsic";
  }
  return "?";
}

const char* to_string(StopReason s) {
  switch (s) {
    case StopReason::converged: return "converged";
    case StopReason::max_inserted: return "max_inserted";
    case StopReason::max_rounds: return "max_rounds";
    case StopReason::stalled: return "stalled";
    case StopReason::time_limit: return "time_limit";
    case StopReason::max_points: return "max_points";
    case StopReason::max_repair_rounds: return "max_repair_rounds";
  }
  return "?";
}

const char* advice(StopReason s) {
  switch (s) {
    case StopReason::converged: return "";
    case StopReason::max_inserted:
      return "the cap on inserted points was hit: raise --max-inserted, or refine with a larger --eps (fewer points)";
    case StopReason::max_rounds:
      return "the cap on rounds was hit: raise --max-rounds";
    case StopReason::max_points:
      return "the cap on the number of points was hit (partial output written): raise --max-points (default 1000000), "
             "or refine with a larger --eps; report.json's local_eps says where the curvature forced a smaller eps";
    case StopReason::stalled:
      return "the refinement stalled (a round inserted nothing, or stars stay open with no rule left to apply; in "
             "practical mode only when even a local eps below 2^-52 eps gives no point, which a smooth spec should "
             "not do): try another --seed or a smaller --gamma0, and report it; report.json says what was left pending";
    case StopReason::time_limit:
      return "the time limit was hit (benchmarks only): raise it";
    case StopReason::max_repair_rounds:
      return "Del_TM, Del_RM and Del_M were still not proven equal after the last Del_M repair round (rule "
             "not_intrinsic): raise --max-repair-rounds; report.json's stall says where";
  }
  return "";
}

std::string describe_stall(const Stall& s) {
  auto coords = [](const std::vector<double>& x) {
    std::string t = "(";
    char buf[32];
    for (std::size_t i = 0; i < x.size(); ++i) {
      std::snprintf(buf, sizeof buf, "%.6g", x[i]);
      t += (i ? ", " : "") + std::string(buf);
    }
    return t + ")";
  };
  std::string t = std::string("rule ") + to_string(s.rule) + " stalled";
  if (!s.simplex.empty()) {
    t += " at simplex [";
    for (std::size_t i = 0; i < s.simplex.size(); ++i) t += (i ? ", " : "") + std::to_string(s.simplex[i]);
    t += "]";
  }
  if (s.point >= 0) t += " (star of point " + std::to_string(s.point) + ")";
  if (!s.what.empty()) t += ": " + s.what;
  if (!s.location.empty()) t += "; location " + coords(s.location);
  return t;
}

namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

constexpr double kMargin = 1e-9;  // relative safety margin of practical-mode decisions
constexpr int kMaxCell = 5;       // m + 1 <= 5
constexpr std::size_t kNoCap = std::numeric_limits<std::size_t>::max();
constexpr int kMaxEpsLevel = 52;  // local ε down to ε / 2^52

struct CellKey {
  std::array<int, kMaxCell> v{-1, -1, -1, -1, -1};
  auto operator<=>(const CellKey&) const = default;
  bool operator==(const CellKey&) const = default;
};
struct CellKeyHash {
  std::size_t operator()(const CellKey& k) const {
    std::uint64_t h = 0x9e3779b97f4a7c15ull;
    for (int x : k.v) {
      h ^= static_cast<std::uint64_t>(static_cast<std::uint32_t>(x)) + 0x9e3779b97f4a7c15ull + (h << 6) + (h >> 2);
    }
    return static_cast<std::size_t>(h);
  }
};

CellKey make_key(std::span<const int> cell) {
  CellKey k;
  for (std::size_t i = 0; i < cell.size(); ++i) k.v[i] = cell[i];
  return k;
}

struct Configuration {
  Rule rule = Rule::big;
  int p = 0;
  CellKey cell;
  int q = -1;  // cosph apex
  double radius2 = 0;
  std::vector<double> centre;
  bool open = false;  // practical mode: p's star is open (an unbounded power cell, R = ∞); no cell
  std::vector<double> target;  // not_restricted: the point of M equidistant from the cell's vertices (empty: none found);
                               // not_intrinsic: the point of M where the Del_M check found the complexes differ
  std::vector<int> simplex;    // not_intrinsic: the simplex (or the candidates of an undecided place) named by the check
  std::string what;            // not_intrinsic: what is wrong there
};

bool canonical_less(const Configuration& a, const Configuration& b) {
  if (a.rule != b.rule) return a.rule < b.rule;
  if (a.p != b.p) return a.p < b.p;
  if (a.cell != b.cell) return a.cell < b.cell;
  return a.q < b.q;
}

class Refiner {
 public:
  Refiner(const manifold::Manifold& manifold, const io::PointSet& input, const RefineParameters& params)
      : M_(manifold), P_(params), m_(manifold.intrinsic_dimension()), N_(manifold.ambient_dimension()) {
    validate(input);
    resolve_delta0(P_.constants, m_);
    refine::validate(P_.constants);
    paper_ = P_.mode == RefineMode::paper;
    curvature_ = P_.sizing.kind == SizingKind::curvature;
    // The paper's Algorithm 1 has one ε; the local ε machinery the field rides on is the practical mode's.
    if (curvature_ && paper_)
      throw ParameterError("--sizing", "curvature sizing needs --mode practical (the paper's Algorithm 1 uses one eps)");
    if (P_.max_points == 0) P_.max_points = kDefaultMaxPoints;
    // Paper mode keeps the former default caps; in practical mode 0 is no cap of that kind (the
    // points cap bounds everything, as every round inserts a point).
    if (P_.max_inserted == 0) P_.max_inserted = paper_ ? 20 * input.size() + 20000 : kNoCap;
    if (P_.max_rounds == 0) P_.max_rounds = paper_ ? 2000 : kNoCap;
    if (P_.pick_attempts <= 0) P_.pick_attempts = paper_ ? 2000 : 200;
    if (!P_.intrinsic_check) P_.intrinsic_check = !paper_;
    R_.points = input;
    R_.input_size = input.size();
    rng_.emplace(P_.seed);
  }

  RefineResult run();

 private:
  void validate(const io::PointSet& input) const;
  void setup_eps();
  double gamma_check() const { return paper_ ? d_.gamma0 : d_.gamma0 * (1 + kMargin); }
  CosphOptions cosph_options(std::size_t p, double radius2) const {
    CosphOptions o;
    o.delta0 = d_.delta0;
    if (!paper_) {
      o.length_floor = mu0_times(leps_[p]);
      o.lower = -std::numeric_limits<double>::infinity();
      o.slack = kMargin * radius2;
    }
    return o;
  }
  bool is_big(double radius2) const { return radius2 >= (paper_ ? eps2_ : eps2_ * (1 - 2 * kMargin)); }
  // Practical mode: against a local ε (ε(p) = ε without sites).
  static bool is_big_local(double local_eps, double radius2) {
    return radius2 >= local_eps * local_eps * (1 - 2 * kMargin);
  }
  bool is_big_at(std::size_t p, double radius2) const { return paper_ ? is_big(radius2) : is_big_local(leps_[p], radius2); }
  // 0, 1, ..., n - 1 for the n points.
  std::vector<std::size_t> every_point() const {
    std::vector<std::size_t> all(R_.points.size());
    std::iota(all.begin(), all.end(), std::size_t{0});
    return all;
  }
  double local_eps_at(std::span<const double> x) const;
  // The sizing field before any site: ε (uniform) or min(ε, max(floor, c / κ_max(x))) (curvature).
  double field_eps(std::span<const double> x) const;
  void add_eps_site(const Configuration& c, int level);
  std::optional<Eigen::VectorXd> shrink(const Configuration& c, RuleStats& st);
  Eigen::VectorXd open_direction(std::size_t p, const manifold::Frame& frame);
  bool applies(const Configuration& c, const Eigen::VectorXd& x) const;

  std::vector<Configuration> configurations_of(std::size_t p) const;
  bool restricted_with_margin(std::size_t p, std::span<const int> cell, std::span<const double> centre, double radius2,
                              std::vector<double>& target) const;
  void recompute_configurations(const std::vector<std::size_t>& which);
  void update_consistency(const std::vector<std::size_t>& changed);
  void set_mask(const CellKey& key, int bit, bool on);
  std::vector<Configuration> inconsistent_configurations() const;
  PerRule<std::size_t> pending() const;
  bool stale(const Configuration& c, std::size_t round_start) const;
  std::optional<Eigen::VectorXd> produce(const Configuration& c, RuleStats& st);
  std::optional<Eigen::VectorXd> pick_valid(const Configuration& c, RuleStats& st);
  bool look_ahead_ok(const Eigen::VectorXd& x) const;
  bool insert(const Eigen::VectorXd& x, Rule rule);
  bool new_star_is_big(std::size_t x);
  std::vector<std::size_t> cosph_affected(std::size_t round_start) const;
  bool check_del_m();
  void report_progress(const PerRule<std::size_t>& pending, bool checking_del_m) const {
    if (!P_.progress) return;
    RefineProgress pr;
    pr.round = R_.rounds;
    pr.points = R_.points.size();
    pr.inserted = R_.points.size() - R_.input_size;
    pr.pending = pending;
    pr.checking_del_m = checking_del_m;
    P_.progress(pr);
  }
  std::optional<Eigen::VectorXd> produce_not_intrinsic(const Configuration& c, RuleStats& st);
  Stall first_pending() const;
  void measure();

  const manifold::Manifold& M_;
  RefineParameters P_;
  ConstantsAsDoubles d_;  // of P_.constants, once ε is set (setup_eps)
  int m_, N_;
  bool paper_ = false;
  bool curvature_ = false;
  double eps2_ = 0, mu0_eps_ = 0;
  double sizing_c_ = 0, sizing_floor_ = 0;  // the curvature field's c and floor, as doubles
  RefineResult R_;
  std::optional<sampling::Random> rng_;
  tangential::TangentPlanes planes_;
  tangential::TangentialComplex tc_;
  tangential::StarOptions star_options_;
  spatial::NeighbourIndex index_;  // exactly R_.points, kept in step with every insertion
  std::vector<std::vector<Configuration>> configs_;
  std::vector<std::vector<int>> cells_copy_;  // per point: its star's cells as last seen (for consistency)
  std::unordered_map<CellKey, std::uint8_t, CellKeyHash> masks_;
  std::set<CellKey> inconsistent_;
  double max_radius2_ = 0;
  std::size_t open_stars_ = 0;
  // Practical mode, the not_restricted rule: 0 while it is off (until nothing else applies), then
  // the number of points at the last restricted check of every star.
  std::size_t restricted_full_at_ = 0;
  // The not_intrinsic rule: the configurations of the last Del_M check, applied in the next round.
  std::vector<Configuration> intrinsic_configs_;
  // The sizing field (practical mode): sites and the local ε of every point.
  struct Site {
    std::vector<double> x;
    double eps = 0;
  };
  std::vector<Site> sites_;
  std::vector<double> leps_;
  std::vector<std::size_t> leps_changed_;  // points whose ε(p) dropped this round
};

void Refiner::validate(const io::PointSet& input) const {
  if (m_ < 2 || m_ > 4)
    throw std::invalid_argument("refine: the tangential complex supports intrinsic dimension 2, 3 or 4; the manifold has " +
                                std::to_string(m_));
  if (input.dimension != N_)
    throw std::invalid_argument("refine: the points have dimension " + std::to_string(input.dimension) +
                                ", the manifold's ambient dimension is " + std::to_string(N_));
  if (input.size() < static_cast<std::size_t>(m_ + 2))
    throw std::invalid_argument("refine: needs at least m + 2 = " + std::to_string(m_ + 2) + " points");
}

void Refiner::setup_eps() {
  if (!P_.constants.eps) {
    double max2 = 0;
    for (std::size_t p = 0; p < tc_.size(); ++p)
      if (tc_.star(p).closed) max2 = std::max(max2, tc_.star(p).max_radius2);
    if (!(max2 > 0)) throw std::invalid_argument("refine: cannot derive eps: no closed star; give --eps");
    P_.constants.eps = ExactParameter(decimal_above(std::sqrt(max2)));
    R_.eps_derived = true;
  }
  d_ = as_doubles(P_.constants);
  eps2_ = d_.eps * d_.eps;
  mu0_eps_ = mu0_times(d_.eps);
  if (curvature_) {
    resolve_sizing(P_.sizing, *P_.constants.eps);
    sizing_c_ = P_.sizing.c.value.get_d();
    sizing_floor_ = P_.sizing.floor->value.get_d();
  }
}

double Refiner::field_eps(std::span<const double> x) const {
  if (!curvature_) return d_.eps;
  const auto kappa = M_.max_normal_curvature(x);
  if (!kappa) return sizing_floor_;  // not a regular point: the finest the field allows
  // c / κ in double: κ = 0 (flat) gives +inf, capped by ε.
  return std::min(d_.eps, std::max(sizing_floor_, sizing_c_ / *kappa));
}

std::vector<Configuration> Refiner::configurations_of(std::size_t p) const {
  std::vector<Configuration> out;
  const tangential::Star& st = tc_.star(p);
  if (!st.closed) {
    // Practical mode: an open star is a configuration of Rule 1 with R = ∞ (the unbounded power
    // cell has a Voronoi vertex at infinity); shrink() inserts a point in the empty direction.
    if (!paper_) {
      Configuration cf;
      cf.rule = Rule::big;
      cf.p = static_cast<int>(p);
      cf.radius2 = std::numeric_limits<double>::infinity();
      cf.open = true;
      out.push_back(std::move(cf));
    }
    return out;
  }
  const double g = gamma_check();
  for (std::size_t c = 0; c < st.size(); ++c) {
    const auto cell = st.cell(c);
    const double r2 = st.radii2[c];
    auto make = [&](Rule rule, int q) {
      Configuration cf;
      cf.rule = rule;
      cf.p = static_cast<int>(p);
      cf.cell = make_key(cell);
      cf.q = q;
      cf.radius2 = r2;
      cf.centre.assign(st.centre(c).begin(), st.centre(c).end());
      out.push_back(std::move(cf));
    };
    if (is_big_at(p, r2)) {
      make(Rule::big, -1);
      continue;
    }
    if (!make_simplex(R_.points, cell).is_good(g)) {
      make(Rule::bad_star, -1);
      continue;
    }
    const std::size_t before = out.size();
    for (const CosphMember& mem : cosph_members(R_.points, index_, cell, st.centre(c), r2, cosph_options(p, r2))) {
      std::array<int, kMaxCell + 1> v;
      std::copy(cell.begin(), cell.end(), v.begin());
      v[cell.size()] = static_cast<int>(mem.q);
      const bool good = make_simplex(R_.points, std::span<const int>(v.data(), cell.size() + 1)).is_good(g);
      make(good ? Rule::unprotected : Rule::bad_cosph, static_cast<int>(mem.q));
    }
    // The restricted check, once on: a clean cell, tested once (at its smallest vertex; cells are
    // sorted vertex lists, and a clean complex is consistent, so that vertex's star holds it).
    if (restricted_full_at_ > 0 && out.size() == before && cell[0] == static_cast<int>(p)) {
      std::vector<double> target;
      if (!restricted_with_margin(p, cell, st.centre(c), r2, target)) {
        make(Rule::not_restricted, -1);
        out.back().target = std::move(target);
      }
    }
  }
  return out;
}

void Refiner::recompute_configurations(const std::vector<std::size_t>& which) {
  configs_.resize(R_.points.size());
  support::parallel_chunks(which.size(), P_.threads, 16, [&](int) {
    return [&](std::size_t b, std::size_t e) {
      for (std::size_t i = b; i < e; ++i) configs_[which[i]] = configurations_of(which[i]);
    };
  });
}

void Refiner::set_mask(const CellKey& key, int bit, bool on) {
  const std::uint8_t full = static_cast<std::uint8_t>((1u << (m_ + 1)) - 1);
  auto it = masks_.find(key);
  std::uint8_t mask = it == masks_.end() ? 0 : it->second;
  if (on)
    mask = static_cast<std::uint8_t>(mask | (1u << bit));
  else
    mask = static_cast<std::uint8_t>(mask & ~(1u << bit));
  if (mask == 0) {
    if (it != masks_.end()) masks_.erase(it);
    inconsistent_.erase(key);
    return;
  }
  if (it == masks_.end())
    masks_.emplace(key, mask);
  else
    it->second = mask;
  if (mask == full)
    inconsistent_.erase(key);
  else
    inconsistent_.insert(key);
}

void Refiner::update_consistency(const std::vector<std::size_t>& changed) {
  const int k = m_ + 1;
  cells_copy_.resize(R_.points.size());
  for (std::size_t p : changed) {
    auto position = [&](const CellKey& key) {
      for (int i = 0; i < k; ++i)
        if (key.v[i] == static_cast<int>(p)) return i;
      return -1;
    };
    const auto& old = cells_copy_[p];
    for (std::size_t c = 0; c + k <= old.size(); c += k) {
      CellKey key = make_key(std::span<const int>(old.data() + c, k));
      set_mask(key, position(key), false);
    }
    const tangential::Star& st = tc_.star(p);
    cells_copy_[p] = st.cells;
    for (std::size_t c = 0; c < st.size(); ++c) {
      CellKey key = make_key(st.cell(c));
      set_mask(key, position(key), true);
    }
  }
}

// Whether the cell (an m-simplex of star(p) with centre c_p(σ) and radius² R², nothing else wrong
// with it) is restricted Delaunay with a margin: Newton from c_p(σ) finds x ∈ M equidistant from
// its vertices within 2R of c_p(σ) (`Manifold::equidistant_point`), on the selected component, and
// every other point q has |x - q|² > r² (1 + 10⁻⁹) + δ0² (μ0 ε(p))², r = max_i |x - v_i|: the
// restricted Voronoi vertex dual to σ exists and is protected like the tangential stars (the
// protection the claims state). `target` is x when found. A simplex failing this is not in
// Del_RM(P), or barely: its Delaunay ball on M holds another point (a flip of the tangential
// complex at a curvature the tangent-space protection does not see), or its flat meets M far from
// it or not at all. The certifier decides Del_TM = Del_RM exactly (check 13); this is the
// producer's expectation, in doubles.
bool Refiner::restricted_with_margin(std::size_t p, std::span<const int> cell, std::span<const double> centre,
                                     double radius2, std::vector<double>& target) const {
  Eigen::MatrixXd V(N_, static_cast<Eigen::Index>(cell.size()));
  for (std::size_t i = 0; i < cell.size(); ++i)
    V.col(static_cast<Eigen::Index>(i)) = Eigen::Map<const Eigen::VectorXd>(R_.points.point(cell[i]).data(), N_);
  const Eigen::VectorXd start = Eigen::Map<const Eigen::VectorXd>(centre.data(), N_);
  manifold::NewtonOptions options;
  options.max_distance = 2 * std::sqrt(radius2);
  const auto x = M_.equidistant_point(V, start, options);
  if (!x || !M_.on_selected_component(manifold::as_span(*x))) return false;
  target.assign(x->data(), x->data() + N_);
  double r2 = 0;
  for (Eigen::Index i = 0; i < V.cols(); ++i) r2 = std::max(r2, (*x - V.col(i)).squaredNorm());
  const double floor = d_.delta0 * mu0_times(leps_[p]);
  bool empty = true;
  index_.for_each_in_ball(target, r2 * (1 + kMargin) + floor * floor, [&](std::size_t q, double) {
    if (std::find(cell.begin(), cell.end(), static_cast<int>(q)) == cell.end()) empty = false;
  });
  return empty;
}

std::vector<Configuration> Refiner::inconsistent_configurations() const {
  std::vector<Configuration> out;
  const int k = m_ + 1;
  for (const CellKey& key : inconsistent_) {
    const auto it = masks_.find(key);
    if (it == masks_.end()) continue;
    int best_p = -1;
    long best_c = -1;
    double best_r2 = -1;
    for (int i = 0; i < k; ++i) {
      if (!(it->second & (1u << i))) continue;
      const tangential::Star& st = tc_.star(key.v[i]);
      long c = st.find(std::span<const int>(key.v.data(), k));
      if (c < 0) continue;
      if (st.radii2[c] > best_r2) best_r2 = st.radii2[c], best_p = key.v[i], best_c = c;
    }
    if (best_p < 0) continue;
    const tangential::Star& st = tc_.star(best_p);
    Configuration cf;
    cf.rule = Rule::inconsistent;
    cf.p = best_p;
    cf.cell = key;
    cf.radius2 = best_r2;
    cf.centre.assign(st.centre(best_c).begin(), st.centre(best_c).end());
    out.push_back(std::move(cf));
  }
  return out;
}

PerRule<std::size_t> Refiner::pending() const {
  PerRule<std::size_t> n{};
  for (const auto& v : configs_)
    for (const auto& c : v) ++n[c.rule];
  n[Rule::inconsistent] = inconsistent_.size();
  n[Rule::not_intrinsic] += intrinsic_configs_.size();
  return n;
}

bool Refiner::stale(const Configuration& c, std::size_t round_start) const {
  if (c.open) return false;
  bool hit = false;
  index_.for_each_in_ball(c.centre, c.radius2 * (1 + kMargin), [&](std::size_t i, double) {
    if (i >= round_start) hit = true;
  });
  return hit;
}

std::optional<Eigen::VectorXd> Refiner::produce(const Configuration& c, RuleStats& st) {
  if (c.open) return std::nullopt;  // no cell: shrink() aims at the open direction
  if (c.rule == Rule::not_intrinsic) return produce_not_intrinsic(c, st);
  if (c.rule == Rule::not_restricted) {
    // The restricted Voronoi vertex itself (Chew's rule on M: it lies in σ's Delaunay ball on M, and
    // near c_p(σ) in σ's tangential one), else a point of σ's picking region as for the other rules.
    if (!c.target.empty()) {
      Eigen::VectorXd x = Eigen::Map<const Eigen::VectorXd>(c.target.data(), N_);
      if (applies(c, x)) return x;
    }
    return pick_valid(c, st);
  }
  if (c.rule != Rule::big) return pick_valid(c, st);
  // Rule 1: ψ_p(c_p(σ)).
  const auto p = R_.points.point(c.p);
  auto frame = M_.frame(p);
  if (!frame) return std::nullopt;
  Eigen::Map<const Eigen::VectorXd> centre(c.centre.data(), N_);
  auto x = M_.psi(p, *frame, centre);
  if (x && (*x - centre).norm() <= std::sqrt(c.radius2) && M_.on_selected_component(manifold::as_span(*x))) return x;
  ++st.psi_failures;
  auto y = M_.project(c.centre);
  if (y && M_.on_selected_component(manifold::as_span(*y))) return y;
  return std::nullopt;
}

std::optional<Eigen::VectorXd> Refiner::pick_valid(const Configuration& c, RuleStats& st) {
  const auto p = R_.points.point(c.p);
  auto frame = M_.frame(p);
  if (!frame) return std::nullopt;
  PickingRegion region;
  region.centre = Eigen::Map<const Eigen::VectorXd>(c.centre.data(), N_);
  const double Rp = std::sqrt(c.radius2);
  region.radius = d_.alpha * Rp;
  region.tangent = planes_.matrix(c.p);
  HittingQuery hq;
  hq.radius_bound = d_.beta * Rp;
  hq.gamma0 = d_.gamma0;
  hq.delta0 = d_.delta0;
  hq.max_set_size = m_ + 1;
  const double sparse_eps = paper_ ? mu0_eps_ : mu0_times(leps_[c.p]);
  const double sparse2 = sparse_eps * sparse_eps;
  // Practical fallback when every candidate is rejected: the best one seen, preferring those
  // farther than μ0 ε (rejected for a hitting set only), then the farthest from the points.
  std::optional<Eigen::VectorXd> best;
  double best_d2 = -1;
  bool best_sparse = false;
  // The candidates are drawn one after another, as a one-at-a-time search draws them, keeping the
  // generator's state after each; their hitting-set searches (the cost: about 99% of candidates are
  // rejected at Γ0 = 0.3) run in parallel in batches of 1, 2, 4, ... 32, sizes that do not depend
  // on the thread count. The first good candidate in drawing order is taken and the generator set
  // to the state drawing it left: the point, the statistics and every later draw are those of the
  // sequential search, whatever the thread count. (A first batch of one: at Γ0 = 0.1 the first
  // candidate is nearly always good, and nothing is searched in vain.)
  struct Drawn {
    std::optional<Eigen::VectorXd> x;
    double d2 = 0;
    bool sparse_ok = false, hit = false, ahead_bad = false;
    sampling::Random after;
  };
  std::vector<Drawn> batch;
  const bool look_ahead = P_.look_ahead && !paper_;
  for (int attempt = 0, size = 1; attempt < P_.pick_attempts; attempt += size, size = std::min(2 * size, 32)) {
    size = std::min(size, P_.pick_attempts - attempt);
    batch.clear();
    sampling::Random gen = *rng_;
    for (int j = 0; j < size; ++j) {
      Drawn d{pick_in_region(M_, p, *frame, region, gen, Rp), 0, false, false, false, gen};  // (braces: in order, so `after` is the state after the draw)
      if (d.x) d.d2 = index_.nearest_distance2(manifold::as_span(*d.x)), d.sparse_ok = paper_ || d.d2 > sparse2;
      batch.push_back(std::move(d));
    }
    support::parallel_chunks(batch.size(), P_.threads, 1, [&](int) {
      return [&](std::size_t b, std::size_t e) {
        for (std::size_t j = b; j < e; ++j)
          if (batch[j].x && batch[j].d2 > 0 && batch[j].sparse_ok) {
            batch[j].hit = find_hitting_set(manifold::as_span(*batch[j].x), R_.points, index_, hq).has_value();
            if (!batch[j].hit && look_ahead) batch[j].ahead_bad = !look_ahead_ok(*batch[j].x);
          }
      };
    });
    for (Drawn& d : batch) {
      ++st.candidates;
      if (!d.x) {
        ++st.psi_failures;
        continue;
      }
      if (!(d.d2 > 0)) continue;  // on an existing point
      if (d.sparse_ok) {
        if (!d.hit && !d.ahead_bad) {  // a good point
          *rng_ = d.after;
          return std::move(d.x);
        }
        if (d.hit)
          ++st.rejected_hit;
        else
          ++st.rejected_look_ahead;
      } else {
        ++st.rejected_sparse;
      }
      if (!paper_ && (!best || (d.sparse_ok && !best_sparse) || (d.sparse_ok == best_sparse && d.d2 > best_d2))) {
        best = d.x;
        best_d2 = d.d2;
        best_sparse = d.sparse_ok;
      }
    }
    *rng_ = batch.back().after;
  }
  if (best) ++st.fallbacks;
  return best;
}

// The look-ahead (practical mode, RefineParameters::look_ahead): x's own star as it would be after
// inserting x (tangential::tentative_star, with x's frame) is closed, and every cell is small at the
// local ε(x) and Γ0-good, so that x brings no Rule 1 or bad_star configuration of its own.
bool Refiner::look_ahead_ok(const Eigen::VectorXd& x) const {
  const auto xs = manifold::as_span(x);
  const auto frame = M_.frame(xs);
  if (!frame) return false;
  const tangential::Star st = tangential::tentative_star(
      R_.points, planes_, index_, xs, std::span<const double>(frame->tangent.data(), static_cast<std::size_t>(N_ * m_)));
  if (!st.closed) return false;
  const double le = local_eps_at(xs);
  const double g = gamma_check();
  const int self = static_cast<int>(R_.points.size());
  for (std::size_t c = 0; c < st.size(); ++c) {
    if (is_big_local(le, st.radii2[c])) return false;
    std::array<int, kMaxCell> others{};
    int k = 0;
    for (int v : st.cell(c))
      if (v != self) others[k++] = v;
    if (!make_simplex(xs, R_.points, std::span<const int>(others.data(), k)).is_good(g)) return false;
  }
  return true;
}

bool Refiner::insert(const Eigen::VectorXd& x, Rule rule) {
  std::size_t nn = 0;
  const double d2 = index_.nearest_distance2(manifold::as_span(x), &nn);
  if (!(d2 > 0)) return false;  // never insert a duplicate point
  const std::size_t id = R_.points.size();
  const double d = std::sqrt(d2);
  const double leps = paper_ ? d_.eps : local_eps_at(manifold::as_span(x));
  if (d < mu0_times(leps)) R_.sparsity_violations.push_back({id, nn, d, rule});
  leps_.push_back(leps);
  if (R_.inserted_by.empty() || d < R_.final.min_inserted_distance) R_.final.min_inserted_distance = d;
  R_.points.push_back(manifold::as_span(x));
  index_.push_back(manifold::as_span(x));
  R_.inserted_by.push_back(rule);
  R_.rules[rule].inserted++;
  return true;
}

double Refiner::local_eps_at(std::span<const double> x) const {
  double e = field_eps(x);
  for (const Site& s : sites_) e = std::min(e, s.eps + kSizingSlope * std::sqrt(spatial::squared_distance(x, s.x)));
  return e;
}

void Refiner::add_eps_site(const Configuration& c, int level) {
  Site site;
  const auto p = R_.points.point(c.p);
  site.x.assign(p.begin(), p.end());
  site.eps = std::ldexp(d_.eps, -level);
  for (std::size_t q = 0; q < leps_.size(); ++q) {
    const double e = site.eps + kSizingSlope * std::sqrt(spatial::squared_distance(R_.points.point(q), site.x));
    if (e < leps_[q]) {
      leps_[q] = e;
      leps_changed_.push_back(q);
    }
  }
  sites_.push_back(std::move(site));
  R_.eps_sites.push_back({static_cast<std::size_t>(c.p), level, c.rule, c.open});
  R_.eps_level = std::max(R_.eps_level, level);
}

// Whether x, produced for c, applies it: not on a point and, for a cell, inside its Delaunay ball
// B(c_p(σ), R_p(σ)), so that σ leaves star(p) and c is gone (a point of the picking region is
// there unless the lift by ψ_p adds more than the ball's slack, at a coarse ε). Practical mode only.
bool Refiner::applies(const Configuration& c, const Eigen::VectorXd& x) const {
  if (!x.allFinite() || !(index_.nearest_distance2(manifold::as_span(x)) > 0)) return false;
  if (c.open) return true;
  Eigen::Map<const Eigen::VectorXd> centre(c.centre.data(), N_);
  return (x - centre).squaredNorm() < c.radius2 * (1 - kMargin);
}

// A unit tangent direction at p in which p's power cell is (nearly) unbounded: among the 2m frame
// axes and 32 seeded random directions, the one that maximises min_q -<u_q, d> / |u_q| over the
// 64 nearest points q (u_q = T^T (q - p)).
Eigen::VectorXd Refiner::open_direction(std::size_t p, const manifold::Frame& frame) {
  const auto pp = R_.points.point(p);
  Eigen::Map<const Eigen::VectorXd> pv(pp.data(), N_);
  std::vector<std::pair<double, std::size_t>> nn;
  index_.nearest(pp, 65, nn);
  std::vector<Eigen::VectorXd> us;
  for (const auto& [d2, q] : nn) {
    if (q == p || !(d2 > 0)) continue;
    Eigen::VectorXd u = frame.tangent.transpose() * (Eigen::Map<const Eigen::VectorXd>(R_.points.point(q).data(), N_) - pv);
    const double n = u.norm();
    if (n > 0) us.push_back(u / n);
  }
  std::vector<Eigen::VectorXd> candidates;
  for (int i = 0; i < m_; ++i)
    for (double sg : {1.0, -1.0}) {
      Eigen::VectorXd d = Eigen::VectorXd::Zero(m_);
      d[i] = sg;
      candidates.push_back(d);
    }
  for (int k = 0; k < 32; ++k) {
    Eigen::VectorXd d(m_);
    for (int i = 0; i < m_; ++i) d[i] = rng_->normal();
    if (d.norm() > 1e-12) candidates.push_back(d / d.norm());
  }
  Eigen::VectorXd best = candidates.front();
  double best_score = -std::numeric_limits<double>::infinity();
  for (const auto& d : candidates) {
    double score = std::numeric_limits<double>::infinity();
    for (const auto& u : us) score = std::min(score, -u.dot(d));
    if (score > best_score) best_score = score, best = d;
  }
  return frame.tangent * best;
}

// Practical mode, when c cannot be applied at the local ε (ψ_p and the closest point fail or miss
// the Delaunay ball, Pick_valid finds nothing, or the star is open): the point ψ_p(p + s d) for the
// unit tangent d towards c_p(σ) (or the open direction), with s = ε / 2^level for the smallest
// level such that s <= ε(p) / 2, s < R_p(σ), and ψ_p succeeds within distance s of the tangent
// point and lands inside the Delaunay ball; each failure halves s. The point's site (p, s) joins
// the sizing field, so ε shrinks around p.
std::optional<Eigen::VectorXd> Refiner::shrink(const Configuration& c, RuleStats& st) {
  const auto p = R_.points.point(c.p);
  auto frame = M_.frame(p);
  if (!frame) return std::nullopt;
  Eigen::Map<const Eigen::VectorXd> pv(p.data(), N_);
  Eigen::VectorXd dir;
  if (c.open) {
    dir = open_direction(c.p, *frame);
  } else {
    Eigen::Map<const Eigen::VectorXd> centre(c.centre.data(), N_);
    dir = frame->tangent * (frame->tangent.transpose() * (centre - pv));
    if (!(dir.norm() > 0)) return std::nullopt;
    dir /= dir.norm();
  }
  const double R = std::sqrt(c.radius2);
  int level = 1;
  while (level < kMaxEpsLevel && std::ldexp(d_.eps, -level) > leps_[c.p] / 2) ++level;
  for (; level <= kMaxEpsLevel; ++level) {
    const double s = std::ldexp(d_.eps, -level);
    if (!(s < R)) continue;
    const Eigen::VectorXd y = pv + s * dir;
    manifold::NewtonOptions options;
    options.max_distance = s;
    auto x = M_.psi(p, *frame, y, options);
    if (!x || !M_.on_selected_component(manifold::as_span(*x))) {
      ++st.psi_failures;
      continue;
    }
    if (!applies(c, *x)) continue;
    add_eps_site(c, level);
    ++st.shrinks;
    return x;
  }
  return std::nullopt;
}

bool Refiner::new_star_is_big(std::size_t x) {
  tangential::extend_tangent_planes(M_, R_.points, planes_);
  std::vector<tangential::Star> tmp;
  std::vector<std::size_t> which{x};
  tangential::compute_stars(R_.points, planes_, index_, which, tmp, {});
  const auto& st = tmp[x];
  if (!st.closed) return true;
  for (double r2 : st.radii2)
    if (is_big(r2)) return true;
  return false;
}

std::vector<std::size_t> Refiner::cosph_affected(std::size_t round_start) const {
  std::vector<char> mark(R_.points.size(), 0);
  const double d2 = d_.delta0 * d_.delta0;
  const double floor2 = paper_ ? 0.0 : mu0_eps_ * mu0_eps_;
  const double R2 = max_radius2_;
  const double reach = std::sqrt(R2) + std::sqrt(R2 * (1 + 4 * d2) + d2 * floor2 + kMargin * R2) * (1 + kMargin);
  for (std::size_t x = round_start; x < R_.points.size(); ++x) {
    const auto px = R_.points.point(x);
    index_.for_each_in_ball(px, reach * reach, [&](std::size_t p, double) {
      if (p >= round_start || mark[p]) return;
      const tangential::Star& st = tc_.star(p);
      for (std::size_t c = 0; c < st.size(); ++c) {
        const double r2 = st.radii2[c];
        const double bound = r2 + d2 * std::max(4 * r2, floor2);
        if (spatial::squared_distance(px, st.centre(c)) <= bound * (1 + kMargin) + kMargin * r2) {
          mark[p] = 1;
          break;
        }
      }
    });
  }
  std::vector<std::size_t> out;
  for (std::size_t p = 0; p < mark.size(); ++p)
    if (mark[p]) out.push_back(p);
  return out;
}

// The Del_M check (rule not_intrinsic; docs/refinement.md, "Del_M check"), run when every other
// rule is satisfied: Del_TM (the stars' cells; consistent by now) against Del_RM and Del_M from the
// certifier's engines (compare_with_del_m). Returns true when it made configurations for the next
// round; false when the run ends here: converged (nothing found), or stopped (the repair cap, or
// nowhere to insert), with R_.stall the first break.
bool Refiner::check_del_m() {
  std::set<std::vector<int>> cells;
  for (std::size_t p = 0; p < tc_.size(); ++p) {
    const tangential::Star& st = tc_.star(p);
    for (std::size_t c = 0; c < st.size(); ++c) {
      const auto cell = st.cell(c);
      cells.emplace(cell.begin(), cell.end());
    }
  }
  report_progress({}, true);
  const DelMComparison cmp =
      compare_with_del_m(M_.spec(), R_.points, std::vector<std::vector<int>>(cells.begin(), cells.end()), P_.threads);
  DelMSummary& d = R_.del_m;
  d.checked = true;
  d.restricted_computed = cmp.restricted_computed;
  d.intrinsic_computed = cmp.intrinsic_computed;
  d.intrinsic_reason = cmp.intrinsic_reason;
  d.tangential = cmp.tangential, d.restricted = cmp.restricted, d.intrinsic = cmp.intrinsic;
  d.breaks = cmp.breaks.size();
  d.seconds += cmp.seconds;
  if (cmp.equal()) return false;
  auto stall_of = [&](const DelMBreak& b) {
    Stall s;
    s.rule = Rule::not_intrinsic;
    s.simplex = b.simplex;
    s.location = b.location;
    s.what = b.what + " (" + std::to_string(cmp.breaks.size()) + " places in all)";
    return s;
  };
  if (R_.repair_rounds >= P_.max_repair_rounds) {
    R_.stop_reason = StopReason::max_repair_rounds;
    R_.stall = stall_of(cmp.breaks.front());
    return false;
  }
  std::vector<Configuration> out;
  for (const DelMBreak& b : cmp.breaks) {
    std::vector<double> at = b.location;
    if (at.empty() && static_cast<int>(b.simplex.size()) == m_ + 1) {
      // No vertex given (a simplex of Del_TM alone): the point of M equidistant from its vertices
      // (its restricted Voronoi vertex, whose ball holds another point), from its cell's centre.
      Eigen::MatrixXd V(N_, m_ + 1);
      Eigen::VectorXd start = Eigen::VectorXd::Zero(N_);
      for (int i = 0; i <= m_; ++i) {
        V.col(i) = Eigen::Map<const Eigen::VectorXd>(R_.points.point(b.simplex[i]).data(), N_);
        start += V.col(i) / (m_ + 1);
      }
      const tangential::Star& st = tc_.star(b.simplex[0]);
      const long c = st.find(std::span<const int>(b.simplex.data(), b.simplex.size()));
      if (c >= 0) start = Eigen::Map<const Eigen::VectorXd>(st.centre(c).data(), N_);
      manifold::NewtonOptions options;
      if (c >= 0) options.max_distance = 2 * std::sqrt(st.radii2[c]);
      if (auto x = M_.equidistant_point(V, start, options)) at.assign(x->data(), x->data() + N_);
      else if (c >= 0) at.assign(start.data(), start.data() + N_);
    }
    if (static_cast<int>(at.size()) != N_) continue;
    // Onto M with the refiner's own projection.
    auto x = M_.project(at);
    if (!x || !M_.on_selected_component(manifold::as_span(*x))) continue;
    std::size_t nn = 0;
    const double d2 = index_.nearest_distance2(manifold::as_span(*x), &nn);
    if (!(d2 > 0)) continue;
    Configuration cf;
    cf.rule = Rule::not_intrinsic;
    cf.p = static_cast<int>(nn);
    for (std::size_t i = 0; i < b.simplex.size() && i < static_cast<std::size_t>(kMaxCell); ++i) cf.cell.v[i] = b.simplex[i];
    cf.centre.assign(x->data(), x->data() + N_);
    cf.radius2 = d2;  // the empty ball around x: a point inserted there earlier in the round makes it stale
    cf.target = cf.centre;
    cf.simplex = b.simplex;
    cf.what = b.what;
    out.push_back(std::move(cf));
  }
  if (out.empty()) {
    R_.stop_reason = StopReason::stalled;
    R_.stall = stall_of(cmp.breaks.front());
    R_.stall->what += "; no point of M to insert for any of them";
    return false;
  }
  ++R_.repair_rounds;
  intrinsic_configs_ = std::move(out);
  return true;
}

// The point for a not_intrinsic configuration: its target (on M). In paper mode only inside the
// paper's picking region: among the cells of star(p), p the nearest point, whose Delaunay ball holds
// the target, the one where its tangent offset from c_p(σ) is smallest relative to R_p(σ); the
// target if that offset is at most α R_p(σ), else Pick_valid(σ, p).
std::optional<Eigen::VectorXd> Refiner::produce_not_intrinsic(const Configuration& c, RuleStats& st) {
  Eigen::VectorXd x = Eigen::Map<const Eigen::VectorXd>(c.target.data(), N_);
  if (!(index_.nearest_distance2(manifold::as_span(x)) > 0)) return std::nullopt;
  if (!paper_) return x;
  const tangential::Star& star = tc_.star(c.p);
  if (!star.closed) return std::nullopt;
  const auto T = planes_.matrix(c.p);
  long best = -1;
  double best_ratio = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < star.size(); ++k) {
    Eigen::Map<const Eigen::VectorXd> centre(star.centre(k).data(), N_);
    if (!((x - centre).squaredNorm() < star.radii2[k])) continue;
    const double ratio = (T.transpose() * (x - centre)).norm() / std::sqrt(star.radii2[k]);
    if (ratio < best_ratio) best_ratio = ratio, best = static_cast<long>(k);
  }
  if (best < 0) return std::nullopt;
  if (best_ratio <= d_.alpha) return x;
  Configuration pc = c;
  pc.cell = make_key(star.cell(best));
  pc.centre.assign(star.centre(best).begin(), star.centre(best).end());
  pc.radius2 = star.radii2[best];
  return pick_valid(pc, st);
}

// The first configuration left, in canonical order (a run stopped by a cap), as a stall.
Stall Refiner::first_pending() const {
  std::vector<Configuration> all;
  for (const auto& v : configs_) all.insert(all.end(), v.begin(), v.end());
  auto inc = inconsistent_configurations();
  all.insert(all.end(), inc.begin(), inc.end());
  all.insert(all.end(), intrinsic_configs_.begin(), intrinsic_configs_.end());
  Stall s;
  if (all.empty()) {
    s.what = "no configuration left";
    return s;
  }
  const Configuration& c = *std::min_element(all.begin(), all.end(), canonical_less);
  s.rule = c.rule;
  s.point = c.p;
  if (c.rule == Rule::not_intrinsic) {
    s.simplex = c.simplex, s.what = c.what, s.point = -1;
  } else if (c.open) {
    s.what = "open star";
  } else {
    for (int v : c.cell.v)
      if (v >= 0) s.simplex.push_back(v);
    if (c.q >= 0) s.what = "with point " + std::to_string(c.q) + " in cosph";
  }
  if (!c.open) s.location = c.centre;
  return s;
}

RefineResult Refiner::run() {
  const auto t_start = Clock::now();
  star_options_.threads = P_.threads;
  star_options_.progress = P_.star_progress;
  {
    const auto t = Clock::now();
    planes_ = tangential::compute_tangent_planes(M_, R_.points, P_.threads);
    tc_ = tangential::TangentialComplex(R_.points, planes_, star_options_);
    R_.star_seconds += seconds_since(t);
  }
  setup_eps();
  leps_.resize(R_.points.size());
  for (std::size_t p = 0; p < leps_.size(); ++p) leps_[p] = field_eps(R_.points.point(p));
  {
    HypothesesInput hi;
    hi.m = m_;
    hi.constants = P_.constants;
    if (M_.spec().reach) {
      hi.reach = std::sqrt(M_.spec().reach->squared.get_d());
      hi.reach_is_lower_bound = !M_.spec().reach->exact;
    }
    R_.hypotheses = evaluate_hypotheses(hi);
  }
  index_ = spatial::NeighbourIndex(R_.points);
  {
    const auto t = Clock::now();
    const std::vector<std::size_t> all = every_point();
    update_consistency(all);
    recompute_configurations(all);
    R_.configuration_seconds += seconds_since(t);
    R_.initial_inconsistent_simplices = inconsistent_.size();
    std::vector<char> touched(R_.points.size(), 0);
    for (const CellKey& key : inconsistent_) {
      const auto it = masks_.find(key);
      for (int i = 0; i <= m_; ++i)
        if (it != masks_.end() && (it->second & (1u << i))) touched[key.v[i]] = 1;
    }
    R_.initial_inconsistent_stars = static_cast<std::size_t>(std::count(touched.begin(), touched.end(), 1));
    R_.initial_configurations = pending();
  }
  R_.stop_reason = StopReason::converged;
  for (;;) {
    max_radius2_ = 0;
    open_stars_ = 0;
    for (std::size_t p = 0; p < tc_.size(); ++p) {
      max_radius2_ = std::max(max_radius2_, tc_.star(p).max_radius2);
      if (!tc_.star(p).closed) ++open_stars_;
    }
    const auto counts = pending();
    report_progress(counts, false);
    const bool big = counts[Rule::big] > 0;
    const bool rule2 = counts[Rule::bad_star] + counts[Rule::bad_cosph] > 0;
    const bool practical_more =
        (!paper_ && (counts[Rule::unprotected] + counts[Rule::inconsistent] + counts[Rule::not_restricted] > 0)) ||
        !intrinsic_configs_.empty();
    if (!big && !rule2 && !practical_more) {
      if (!paper_ && P_.restricted_check && open_stars_ == 0 && restricted_full_at_ != R_.points.size()) {
        // Nothing else to do: turn the restricted check on, for every star now and for the stars
        // each later round changes (configurations_of), and go on. A point can enter a simplex's
        // Delaunay ball on M without changing any star or cosph (a thin shell between that ball and
        // the tangential one), so the run ends only after a check of every star finds nothing.
        const auto t = Clock::now();
        restricted_full_at_ = R_.points.size();
        recompute_configurations(every_point());
        R_.configuration_seconds += seconds_since(t);
        continue;
      }
      if (open_stars_ > 0) {
        R_.stop_reason = StopReason::stalled;
        break;
      }
      // Every other rule is satisfied: the Del_M check (rule not_intrinsic), which either finds
      // places to repair (the next round inserts there) or ends the run.
      if (*P_.intrinsic_check && check_del_m()) continue;
      break;
    }
    if (R_.rounds >= P_.max_rounds) {
      R_.stop_reason = StopReason::max_rounds;
      break;
    }
    if (P_.time_limit > 0 && seconds_since(t_start) > P_.time_limit) {
      R_.stop_reason = StopReason::time_limit;
      break;
    }
    ++R_.rounds;
    // The round's configurations, in canonical order.
    std::vector<Configuration> batch;
    auto take = [&](Rule r) {
      for (const auto& v : configs_)
        for (const auto& c : v)
          if (c.rule == r) batch.push_back(c);
    };
    if (big) {
      take(Rule::big);
    } else {
      take(Rule::bad_star);
      take(Rule::bad_cosph);
      if (!paper_) {
        take(Rule::unprotected);
        take(Rule::not_restricted);
        auto inc = inconsistent_configurations();
        batch.insert(batch.end(), std::make_move_iterator(inc.begin()), std::make_move_iterator(inc.end()));
      }
      batch.insert(batch.end(), std::make_move_iterator(intrinsic_configs_.begin()),
                   std::make_move_iterator(intrinsic_configs_.end()));
      intrinsic_configs_.clear();
    }
    std::sort(batch.begin(), batch.end(), canonical_less);
    const std::size_t round_start = R_.points.size();
    bool capped = false, points_capped = false;
    leps_changed_.clear();
    for (const Configuration& c : batch) {
      RuleStats& st = R_.rules[c.rule];
      if (R_.points.size() - R_.input_size >= P_.max_inserted) {
        capped = true;
        break;
      }
      if (R_.points.size() >= P_.max_points) {
        points_capped = true;
        break;
      }
      if (stale(c, round_start)) {
        ++st.skipped_stale;
        continue;
      }
      const auto t = Clock::now();
      auto x = produce(c, st);
      if (!paper_ && c.rule != Rule::not_intrinsic && (!x || !applies(c, *x))) x = shrink(c, st);
      bool ok = x && insert(*x, c.rule);
      if (ok)
        ++st.applied;
      else
        ++st.failures;
      bool stop = false;
      if (ok && paper_ && c.rule != Rule::big) stop = new_star_is_big(R_.points.size() - 1);
      st.seconds += seconds_since(t);
      if (stop) break;
      if (P_.time_limit > 0 && seconds_since(t_start) > P_.time_limit) break;
    }
    const std::size_t added = R_.points.size() - round_start;
    if (added == 0) {
      R_.stop_reason = points_capped ? StopReason::max_points : capped ? StopReason::max_inserted : StopReason::stalled;
      break;
    }
    {
      const auto t = Clock::now();
      tangential::extend_tangent_planes(M_, R_.points, planes_);
      std::vector<std::size_t> changed = tc_.insert(R_.points, planes_, star_options_);
      R_.star_seconds += seconds_since(t);
      const auto t2 = Clock::now();
      update_consistency(changed);
      std::vector<std::size_t> affected = cosph_affected(round_start);
      std::vector<std::size_t> dirty;
      std::set_union(changed.begin(), changed.end(), affected.begin(), affected.end(), std::back_inserter(dirty));
      if (!leps_changed_.empty()) {  // a local ε dropped: those stars' configurations change too
        std::sort(leps_changed_.begin(), leps_changed_.end());
        std::vector<std::size_t> merged;
        std::set_union(dirty.begin(), dirty.end(), leps_changed_.begin(), leps_changed_.end(), std::back_inserter(merged));
        merged.erase(std::unique(merged.begin(), merged.end()), merged.end());
        dirty = std::move(merged);
      }
      recompute_configurations(dirty);
      R_.configuration_seconds += seconds_since(t2);
    }
    if (points_capped || capped) {
      R_.stop_reason = points_capped ? StopReason::max_points : StopReason::max_inserted;
      break;
    }
  }
  R_.converged = R_.stop_reason == StopReason::converged;
  if (!R_.converged && !R_.stall) R_.stall = first_pending();
  R_.local_eps = leps_;
  measure();
  R_.parameters = P_;
  R_.parameters.progress = nullptr;
  R_.parameters.star_progress = nullptr;
  R_.total_seconds = seconds_since(t_start);
  return std::move(R_);
}

void Refiner::measure() {
  FinalMeasures& f = R_.final;
  const double min_inserted = f.min_inserted_distance;
  f = FinalMeasures{};
  f.min_inserted_distance = R_.inserted_by.empty() ? 0.0 : min_inserted;
  auto assembly = tc_.assemble(P_.threads);
  R_.complex = std::move(assembly.complex);
  f.stars = tc_.size();
  f.star_cells = assembly.star_cells;
  f.complex_simplices = R_.complex.simplices.size();
  f.inconsistent_simplices = assembly.inconsistent.size();
  f.remaining = pending();
  f.remaining[Rule::inconsistent] = assembly.inconsistent.size();
  f.remaining[Rule::not_intrinsic] = R_.converged ? 0 : R_.del_m.breaks;
  const int k = m_ + 1;
  f.min_local_eps = leps_.empty() ? d_.eps : *std::min_element(leps_.begin(), leps_.end());
  // The smallest local ε: ε / 2^eps_level (the sites), and the field's minimum under curvature sizing.
  const double eps_min = curvature_ ? std::min(std::ldexp(d_.eps, -R_.eps_level), f.min_local_eps)
                                    : std::ldexp(d_.eps, -R_.eps_level);
  const double mu0_min = mu0_times(eps_min);
  const double dcheck2 = d_.delta0 * d_.delta0 * mu0_min * mu0_min;
  std::set<CellKey> inconsistent;
  for (const auto& s : assembly.inconsistent) inconsistent.insert(make_key(s));
  f.min_thickness = 1;
  f.min_face_thickness_ratio = std::numeric_limits<double>::infinity();
  f.min_protection = std::numeric_limits<double>::infinity();
  double max_r2 = 0;
  bool small_local = true;
  const spatial::NeighbourIndex& nidx = tc_.index();
  std::vector<std::pair<double, std::size_t>> nn;
  for (std::size_t p = 0; p < tc_.size(); ++p) {
    const tangential::Star& st = tc_.star(p);
    if (!st.closed) ++f.open_stars;
    bool inc = false;
    for (std::size_t c = 0; c < st.size(); ++c) {
      const auto cell = st.cell(c);
      if (!inconsistent.empty() && inconsistent.count(make_key(cell))) inc = true;
      max_r2 = std::max(max_r2, st.radii2[c]);
      if (!(st.radii2[c] < leps_[p] * leps_[p] * (1 - 2 * kMargin))) small_local = false;
      auto g = make_simplex(R_.points, cell);
      f.min_thickness = std::min(f.min_thickness, g.thickness());
      f.min_face_thickness_ratio = std::min(f.min_face_thickness_ratio, g.goodness_ratio(d_.gamma0));
      nidx.nearest(st.centre(c), static_cast<std::size_t>(k + 4), nn);
      for (const auto& [d2, q] : nn)
        if (std::find(cell.begin(), cell.end(), static_cast<int>(q)) == cell.end()) {
          f.min_protection = std::min(f.min_protection, d2 - st.radii2[c]);
          break;
        }
    }
    if (inc) ++f.inconsistent_stars;
  }
  f.max_radius = std::sqrt(max_r2);
  f.min_protection_ratio = dcheck2 > 0 ? f.min_protection / dcheck2 : std::numeric_limits<double>::infinity();
  double md2 = std::numeric_limits<double>::infinity(), in2 = md2;
  for (std::size_t p = 0; p < R_.points.size(); ++p) {
    nidx.nearest(R_.points.point(p), 2, nn);
    for (const auto& [d2, q] : nn)
      if (q != p) {
        md2 = std::min(md2, d2);
        break;
      }
  }
  {  // the input alone
    io::PointSet in;
    in.dimension = R_.points.dimension;
    in.coordinates.assign(R_.points.coordinates.begin(), R_.points.coordinates.begin() + R_.input_size * R_.points.dimension);
    spatial::NeighbourIndex ii(in);
    for (std::size_t p = 0; p < in.size(); ++p) {
      ii.nearest(in.point(p), 2, nn);
      for (const auto& [d2, q] : nn)
        if (q != p) {
          in2 = std::min(in2, d2);
          break;
        }
    }
  }
  f.min_distance = std::sqrt(md2);
  f.input_min_distance = std::sqrt(in2);
  f.consistent = f.inconsistent_simplices == 0 && f.open_stars == 0;
  f.all_good = std::isinf(f.min_face_thickness_ratio) || f.min_face_thickness_ratio >= 1;
  f.all_small = f.max_radius < d_.eps * (1 - kMargin) && f.open_stars == 0;
  f.all_small_local = small_local && f.open_stars == 0;
  f.protected_claim = f.min_protection > dcheck2 * (1 + kMargin);
}

}  // namespace

RefineResult refine(const manifold::Manifold& manifold, const io::PointSet& input, const RefineParameters& parameters) {
  Refiner r(manifold, input, parameters);
  return r.run();
}

}  // namespace delcert::refine
