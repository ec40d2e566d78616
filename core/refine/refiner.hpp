// The refiner: refine() runs the paper's Algorithm 1 (§4.2) on the tangential Delaunay complex
// (--mode paper) or the practical mode that adds the rules a realistic ε needs (the default).
// Declares the rules, RefineParameters, RefineResult with its statistics and final measures, and
// refine(). The rules, the two modes and the caps are described in docs/refinement.md.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/manifold/manifold.hpp"
#include "core/refine/hypotheses.hpp"
#include "core/refine/parameters.hpp"
#include "io/complex.hpp"
#include "io/points.hpp"

namespace delcert::refine {

enum class RefineMode { practical, paper };
const char* to_string(RefineMode m);

// not_restricted (practical mode): an m-simplex of the complex whose point of M equidistant from its
// vertices (its restricted Voronoi vertex) is missing or has another point nearer, so that it is not
// in the restricted Delaunay complex with a margin (docs/refinement.md, "Restricted check").
// not_intrinsic (practical mode by default): once every other rule is satisfied, an m-simplex (or a
// place) where the certifier's engines do not prove Del_TM = Del_RM = Del_M (docs/refinement.md,
// "Del_M check"; core/refine/intrinsic_repair.hpp).
enum class Rule : std::uint8_t {
  big = 0, bad_star = 1, bad_cosph = 2, unprotected = 3, inconsistent = 4, not_restricted = 5, not_intrinsic = 6
};
inline constexpr int kNumRules = 7;
// Lipschitz slope of the practical mode's local ε (the sizing field; docs/refinement.md).
inline constexpr double kSizingSlope = 0.5;
inline constexpr std::array<Rule, kNumRules> kRules = {Rule::big,         Rule::bad_star,     Rule::bad_cosph,
                                                       Rule::unprotected, Rule::inconsistent, Rule::not_restricted,
                                                       Rule::not_intrinsic};
const char* to_string(Rule r);

// One T per rule, indexed by the rule.
template <class T>
struct PerRule {
  std::array<T, kNumRules> values{};
  T& operator[](Rule r) { return values[static_cast<std::size_t>(r)]; }
  const T& operator[](Rule r) const { return values[static_cast<std::size_t>(r)]; }
};

// Why a run stopped; only `converged` is a success.
// max_repair_rounds: the Del_M check still found breaks after max_repair_rounds repair rounds.
enum class StopReason { converged, max_inserted, max_rounds, stalled, time_limit, max_points, max_repair_rounds };
const char* to_string(StopReason s);
// What to do about a run that stopped for `s` (not converged): one sentence for the user.
const char* advice(StopReason s);

// The default cap on the total number of points (input and inserted).
inline constexpr std::size_t kDefaultMaxPoints = 1000000;
// The default cap on Del_M repair rounds (rule not_intrinsic).
inline constexpr std::size_t kDefaultMaxRepairRounds = 20;

struct RefineProgress {
  std::size_t round = 0;
  std::size_t points = 0;
  std::size_t inserted = 0;
  PerRule<std::size_t> pending{};  // configurations per rule at the start of the round
  bool checking_del_m = false;      // the Del_M check (rule not_intrinsic) is running: the certifier's engines
};

struct RefineParameters {
  RefineMode mode = RefineMode::practical;
  Constants constants;  // ε, Γ0, α, β, δ0, exact
  // The sizing field (parameters.hpp): uniform (the default) or curvature (practical mode only);
  // ε above is its cap. RefineResult::parameters holds it resolved (the floor set).
  SizingField sizing;
  std::uint64_t seed = 1;
  int threads = 1;
  // Practical mode: once no other rule applies, also refine the m-simplices that are not restricted
  // Delaunay with a margin (Rule::not_restricted), so that the output's Del_TM equals its Del_RM.
  bool restricted_check = true;
  // Rule not_intrinsic: once every other rule is satisfied, compare the complex with Del_RM and Del_M
  // computed by the certifier's engines (core/refine/intrinsic_repair.hpp) and insert points where
  // they differ, until they are proven equal (as far as the engines decide). nullopt: on in
  // practical mode, off in paper mode (Algorithm 1 has no such rule). RefineResult::parameters
  // holds it resolved.
  std::optional<bool> intrinsic_check;
  // The rule's cap: at most this many repair rounds (Del_M checks that found something to repair,
  // each followed by the other rules); the check after the last one must find nothing, else the run
  // stops with StopReason::max_repair_rounds. 0: no repair at all (the check runs once).
  std::size_t max_repair_rounds = kDefaultMaxRepairRounds;
  // Practical mode: Pick_valid also rejects a candidate whose own star, computed before inserting
  // it (tangential::tentative_star), would be open, hold a cell with R >= ε(x) or a Γ0-bad cell
  // (docs/refinement.md, "Look-ahead"). Off by default: see there for what it measured.
  bool look_ahead = false;
  // Caps: the run stops (not converged) when it would hold more than max_points points in all
  // (0: kDefaultMaxPoints), insert more than max_inserted points or start round max_rounds + 1
  // (0: no cap of that kind; every round inserts a point, so max_points bounds the rounds too).
  std::size_t max_points = 0;
  std::size_t max_inserted = 0;
  std::size_t max_rounds = 0;
  // Pick_valid draws at most this many candidates per configuration (0: 200 in practical mode,
  // 2000 in paper mode, where a configuration without a good point found stays for a later round).
  int pick_attempts = 0;
  // Wall-clock limit in seconds (0: none). For benchmarks: a run stopped by it is not
  // reproducible and is marked so.
  double time_limit = 0;
  // Called after every round (from the calling thread).
  std::function<void(const RefineProgress&)> progress;
  // Called with (stars done, stars to compute) while stars are computed: all of them at the start,
  // then those a round's insertions changed (tangential::StarOptions::progress). For a progress line.
  std::function<void(std::size_t, std::size_t)> star_progress;
};

struct RuleStats {
  std::size_t inserted = 0;          // points inserted by the rule
  std::size_t applied = 0;           // configurations for which a point was produced
  std::size_t skipped_stale = 0;     // configurations killed earlier in the same round
  std::size_t candidates = 0;        // Pick_valid candidates drawn
  std::size_t rejected_hit = 0;      // ... rejected because a hitting set exists
  std::size_t rejected_sparse = 0;   // ... rejected because closer than μ0 ε to a point (practical)
  std::size_t rejected_look_ahead = 0;  // ... rejected because their tentative star is bad (look_ahead)
  std::size_t psi_failures = 0;      // ... where ψ_p failed
  std::size_t fallbacks = 0;         // configurations where Pick_valid gave up and took the best candidate
  std::size_t failures = 0;          // configurations where no point could be produced
  std::size_t shrinks = 0;           // configurations applied by shrinking ε locally (practical; docs/refinement.md)
  double seconds = 0;                // time spent producing the points of this rule
};

struct SparsityViolation {
  std::size_t point = 0;    // the inserted point
  std::size_t nearest = 0;  // its nearest point at insertion time
  double distance = 0;
  Rule rule = Rule::big;
};

struct FinalMeasures {
  std::size_t stars = 0, star_cells = 0, complex_simplices = 0;
  std::size_t open_stars = 0;                 // stars whose power cell is unbounded
  std::size_t inconsistent_simplices = 0;     // distinct simplices missing from a vertex's star
  std::size_t inconsistent_stars = 0;         // stars holding at least one inconsistent simplex
  PerRule<std::size_t> remaining{};           // configurations left, per rule (all five, any mode)
  double max_radius = 0;                      // max R_p(σ) over star cells
  double min_thickness = 1;                   // min Υ over star cells (m-simplices)
  double min_face_thickness_ratio = 0;        // min over faces t (dim >= 2) of star cells of Υ(t) / Γ0^dim(t)
  double min_protection = 0;                  // min over star cells and q ∉ σ of ||c_p(σ) - q||^2 - R_p(σ)^2
  double min_protection_ratio = 0;            // min_protection / δ̌^2
  double min_distance = 0;                    // smallest distance between two points
  double input_min_distance = 0;              // the same over the input points
  double min_inserted_distance = 0;           // smallest distance of an inserted point to the points before it
  bool consistent = false, all_good = false, all_small = false, protected_claim = false;
  bool all_small_local = false;               // every star cell at p has R_p(σ) < ε(p) (= all_small when uniform)
  double min_local_eps = 0;                   // min over points of ε(p) at the end
};

// Where a run that did not converge stopped: the first configuration left (in canonical order) or,
// for the Del_M check, the first break it found. For the stall message (describe_stall).
struct Stall {
  Rule rule = Rule::big;
  std::vector<int> simplex;      // the cell (sorted), or the simplex the Del_M check named; may be empty
  int point = -1;                // the star it is in (the nearest point for not_intrinsic), or -1
  std::vector<double> location;  // c_p(σ), or where the Del_M check found it breaks; may be empty
  std::string what;              // what is wrong, in words
};
// "rule not_intrinsic stalled at simplex [3, 17, 52, 90] (in Del_RM, Del_M, not in Del_TM), location (0.12, ...)".
std::string describe_stall(const Stall& s);

// The last Del_M check (rule not_intrinsic).
struct DelMSummary {
  bool checked = false;
  bool restricted_computed = false, intrinsic_computed = false;
  std::string intrinsic_reason;  // why Del_M was not computed (the rule then compares Del_TM with Del_RM only)
  std::size_t tangential = 0, restricted = 0, intrinsic = 0;  // m-simplices
  std::size_t breaks = 0;        // where the complexes were not proven equal (0 at convergence)
  double seconds = 0;            // all checks together
};

struct RefineResult {
  io::PointSet points;           // the input points first, in their order, then the inserted ones
  std::size_t input_size = 0;
  std::vector<Rule> inserted_by;  // per inserted point
  io::Complex complex;           // the union of the stars
  bool eps_derived = false;      // ε came from the input's largest R_p (decimal_above)
  bool converged = false;        // stop_reason == StopReason::converged
  StopReason stop_reason = StopReason::converged;
  std::size_t rounds = 0;
  PerRule<RuleStats> rules{};
  std::vector<SparsityViolation> sparsity_violations;
  std::size_t repair_rounds = 0;  // Del_M checks that found something to repair (rule not_intrinsic)
  DelMSummary del_m;
  std::optional<Stall> stall;     // set when the run did not converge
  // Local ε (practical mode; docs/refinement.md, "Local ε"): where a configuration could not be
  // applied at the local ε, a site (point, ε / 2^level) was added to the sizing field
  // ε(x) = min(ε, min over sites of ε_site + kSizingSlope |x - site|). eps_level is the largest
  // level (0: no site), so the smallest local ε is exactly ε / 2^eps_level.
  struct EpsSite {
    std::size_t point = 0;  // the point whose configuration was stuck
    int level = 0;
    Rule rule = Rule::big;
    bool open = false;      // the point's star was open (no cell to aim at)
  };
  std::vector<EpsSite> eps_sites;
  int eps_level = 0;
  std::vector<double> local_eps;  // per point, ε(p) at the end (= ε everywhere without sites)
  std::size_t initial_inconsistent_simplices = 0;  // in the input's complex
  std::size_t initial_inconsistent_stars = 0;      // stars of the input holding an inconsistent simplex
  PerRule<std::size_t> initial_configurations{};  // per rule, in the input's complex
  double star_seconds = 0;           // initial complex and incremental star updates
  double configuration_seconds = 0;  // finding configurations (cosph, thickness, consistency)
  double total_seconds = 0;
  FinalMeasures final;
  HypothesesReport hypotheses;
  RefineParameters parameters;   // as used: caps and attempts resolved, ε and δ0 set, no progress callbacks
};

// Refines `input` (points on M) with the given parameters. Throws std::invalid_argument on bad
// input (ParameterError, naming the option, for a constant out of range), std::domain_error when
// a point is not a regular point of M.
RefineResult refine(const manifold::Manifold& manifold, const io::PointSet& input, const RefineParameters& parameters);

}  // namespace delcert::refine
