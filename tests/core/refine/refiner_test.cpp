// The refinement loop: each rule triggered by a constructed input, the sparsity invariant, and
// CI-sized runs whose outputs are checked against a fresh, independent recomputation.
#include "core/refine/refiner.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <numbers>
#include <string>
#include <vector>

#include "core/refine/simplex_measures.hpp"
#include "core/sampling/sampling.hpp"
#include "core/tangential/tangent_planes.hpp"
#include "core/tangential/tangential_complex.hpp"
#include "exact/polynomial.hpp"
#include "io/points.hpp"
#include "io/spec.hpp"
#include "tests/test_support.hpp"

namespace delcert::refine {
namespace {

manifold::Manifold builtin(const std::string& name) { return manifold::Manifold(io::read_spec("builtin:" + name)); }

ExactParameter exact(const char* text) { return ExactParameter::parse(text); }

io::PointSet net(const manifold::Manifold& M, double eps, std::uint64_t seed = 1) {
  sampling::EpsNetOptions o;
  o.eps = eps;
  o.seed = seed;
  return sampling::eps_net(M, o).points;
}

double dist(std::span<const double> a, std::span<const double> b) {
  double s = 0;
  for (std::size_t j = 0; j < a.size(); ++j) s += (a[j] - b[j]) * (a[j] - b[j]);
  return std::sqrt(s);
}

// What the output promises, recomputed from scratch: a fresh tangential complex of the output
// points (not the refiner's incrementally updated one) must equal the output complex and be
// consistent; every star cell has R_p < eps and is Γ0-good; every star cell is power-protected
// by more than δ0^2 (eps/9)^2 against every other point (brute force); every inserted point is
// farther than eps/9 from the points before it.
void expect_certified_by_own_measure(const manifold::Manifold& M, const RefineResult& r) {
  const ConstantsAsDoubles P = as_doubles(r.parameters.constants);
  auto planes = tangential::compute_tangent_planes(M, r.points);
  tangential::TangentialComplex tc(r.points, planes);
  auto a = tc.assemble();
  EXPECT_TRUE(a.inconsistent.empty()) << a.inconsistent.size() << " inconsistent simplices";
  EXPECT_EQ(a.complex.simplices, r.complex.simplices);
  const double dcheck2 = P.delta0 * P.delta0 * (P.eps / 9) * (P.eps / 9);
  std::size_t cells = 0;
  for (std::size_t p = 0; p < tc.size(); ++p) {
    const auto& st = tc.star(p);
    ASSERT_TRUE(st.closed);
    for (std::size_t c = 0; c < st.size(); ++c, ++cells) {
      const auto cell = st.cell(c);
      EXPECT_LT(std::sqrt(st.radii2[c]), P.eps);
      EXPECT_TRUE(make_simplex(r.points, cell).is_good(P.gamma0)) << "star " << p << " cell " << c;
      double worst = INFINITY;
      for (std::size_t q = 0; q < r.points.size(); ++q) {
        if (std::find(cell.begin(), cell.end(), static_cast<int>(q)) != cell.end()) continue;
        const double d = dist(st.centre(c), r.points.point(q));
        worst = std::min(worst, d * d - st.radii2[c]);
      }
      EXPECT_GT(worst, dcheck2) << "star " << p << " cell " << c;
    }
  }
  EXPECT_GT(cells, 0u);
  for (std::size_t i = r.input_size; i < r.points.size(); ++i) {
    double d = INFINITY;
    for (std::size_t j = 0; j < i; ++j) d = std::min(d, dist(r.points.point(i), r.points.point(j)));
    EXPECT_GT(d, P.eps / 9) << "inserted point " << i;
  }
  EXPECT_TRUE(r.sparsity_violations.empty());
  EXPECT_TRUE(r.final.consistent && r.final.all_good && r.final.all_small && r.final.protected_claim);
  for (std::size_t i = r.input_size; i < r.points.size(); ++i) EXPECT_LT(M.residual(r.points.point(i)), 1e-12);
}

std::size_t inserted(const RefineResult& r, Rule rule) { return r.rules[rule].inserted; }

TEST(Refiner, RuleOneInsertsAtTheCentresOfBigCells) {
  // The octahedron's vertices on S^2: every star cell has R_p ≈ 0.8, far above eps = 0.5.
  manifold::Manifold M = builtin("sphere-2");
  io::PointSet octa;
  octa.dimension = 3;
  for (int i = 0; i < 3; ++i)
    for (double s : {1.0, -1.0}) {
      std::vector<double> v(3, 0.0);
      v[i] = s;
      octa.push_back(v);
    }
  for (RefineMode mode : {RefineMode::practical, RefineMode::paper}) {
    RefineParameters p;
    p.mode = mode;
    p.constants.eps = exact("0.5");
    auto r = refine(M, octa, p);
    EXPECT_TRUE(r.converged) << to_string(r.stop_reason);
    EXPECT_GT(r.initial_configurations[Rule::big], 0u);
    EXPECT_GT(inserted(r, Rule::big), 0u);
    EXPECT_LT(r.final.max_radius, 0.5);
    EXPECT_EQ(r.input_size, 6u);
    for (std::size_t i = 0; i < 6 * 3; ++i) EXPECT_EQ(r.points.coordinates[i], octa.coordinates[i]);  // input first
    if (mode == RefineMode::practical) expect_certified_by_own_measure(M, r);
  }
}

TEST(Refiner, RuleTwoRefinesSliversInTheStars) {
  // An eps-net of S^3 has slivers: with Γ0 = 0.25 tetrahedra need thickness >= 0.0156.
  manifold::Manifold M = builtin("sphere-3");
  auto pts = net(M, 0.3);
  for (RefineMode mode : {RefineMode::practical, RefineMode::paper}) {
    RefineParameters p;
    p.mode = mode;
    p.constants.eps = exact("0.3");
    p.constants.gamma0 = exact("0.25");
    auto r = refine(M, pts, p);
    EXPECT_TRUE(r.converged) << to_string(r.stop_reason);
    EXPECT_GT(r.initial_configurations[Rule::bad_star], 0u);
    EXPECT_GT(inserted(r, Rule::bad_star), 0u);
    EXPECT_TRUE(r.final.all_good);
    EXPECT_GE(r.final.min_face_thickness_ratio, 1.0);
    if (mode == RefineMode::practical) expect_certified_by_own_measure(M, r);
  }
}

// A square grid of angles on the flat torus: every grid square is a rectangle in R^4, four
// cocircular and coplanar points, so q * σ is a flat (Γ0-bad) quasi-cospherical 3-simplex with
// power exactly 0 (up to rounding): Rule 2 on cosph.
io::PointSet torus_grid(int n) {
  io::PointSet ps;
  ps.dimension = 4;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const double a = 2 * std::numbers::pi * i / n, b = 2 * std::numbers::pi * j / n;
      ps.push_back(std::vector<double>{std::cos(a), std::sin(a), std::cos(b), std::sin(b)});
    }
  return ps;
}

TEST(Refiner, RuleTwoBreaksQuasiCosphericalSimplices) {
  manifold::Manifold M = builtin("clifford-torus-2");
  auto grid = torus_grid(14);
  for (RefineMode mode : {RefineMode::practical, RefineMode::paper}) {
    RefineParameters p;
    p.mode = mode;
    auto r = refine(M, grid, p);
    EXPECT_TRUE(r.converged) << to_string(r.stop_reason);
    EXPECT_TRUE(r.eps_derived);
    EXPECT_EQ(r.parameters.constants.eps.value().text, "0.33");  // two digits above the grid's R_p = 0.3204
    EXPECT_GT(r.initial_configurations[Rule::bad_cosph], 0u);
    EXPECT_GT(inserted(r, Rule::bad_cosph), 0u);
    EXPECT_EQ(r.final.remaining[Rule::bad_cosph], 0u);
    if (mode == RefineMode::practical) expect_certified_by_own_measure(M, r);
  }
}

TEST(Refiner, PickValidRejectsHitCandidates) {
  // With δ0 = 0.1 (H3 violated) nearly every nearby 4-simplex of S^3 can be weighted into a
  // hitting set: most candidates are rejected, the good ones are inserted.
  manifold::Manifold M = builtin("sphere-3");
  auto pts = net(M, 0.4);
  RefineParameters p;
  p.mode = RefineMode::paper;
  p.constants.eps = exact("0.4");
  p.constants.gamma0 = exact("0.1");
  p.constants.delta0 = exact("0.1");
  auto r = refine(M, pts, p);
  const auto& st = r.rules[Rule::bad_cosph];
  EXPECT_GT(st.rejected_hit, 0u);
  EXPECT_GT(st.inserted, 0u);
  EXPECT_EQ(st.candidates, st.rejected_hit + st.psi_failures + st.inserted) << "every candidate is rejected or inserted";
  // With one attempt per configuration, paper mode gives up on configurations whose only
  // candidate is hit, and stops when a round inserts nothing.
  p.pick_attempts = 1;
  auto r1 = refine(M, pts, p);
  EXPECT_GT(r1.rules[Rule::bad_cosph].failures, 0u);
}

TEST(Refiner, InconsistencyRuleMakesTheStarsAgree) {
  manifold::Manifold M = builtin("clifford-torus-2");
  auto pts = net(M, 0.25);
  RefineParameters p;
  p.constants.eps = exact("0.25");
  p.mode = RefineMode::paper;
  auto paper = refine(M, pts, p);
  EXPECT_TRUE(paper.converged);
  EXPECT_GT(paper.final.inconsistent_simplices, 0u);  // Algorithm 1 alone leaves some at this eps
  p.mode = RefineMode::practical;
  auto practical = refine(M, pts, p);
  EXPECT_TRUE(practical.converged);
  EXPECT_GT(inserted(practical, Rule::inconsistent), 0u);
  EXPECT_EQ(practical.final.inconsistent_simplices, 0u);
  expect_certified_by_own_measure(M, practical);
}

TEST(Refiner, UnprotectedRuleFiresOnSO3) {
  manifold::Manifold M = builtin("so3");
  auto pts = net(M, 0.6);
  RefineParameters p;
  p.constants.eps = exact("0.6");
  p.threads = 2;
  auto r = refine(M, pts, p);
  EXPECT_TRUE(r.converged) << to_string(r.stop_reason);
  EXPECT_GT(inserted(r, Rule::unprotected), 0u);
  EXPECT_GT(inserted(r, Rule::inconsistent), 0u);
  expect_certified_by_own_measure(M, r);
}

struct CiCase {
  const char* manifold;
  const char* eps;
};

class CiSizedRefinement : public ::testing::TestWithParam<CiCase> {};

TEST_P(CiSizedRefinement, OutputIsConsistentGoodAndProtected) {
  manifold::Manifold M = builtin(GetParam().manifold);
  RefineParameters p;
  p.constants.eps = exact(GetParam().eps);
  auto r = refine(M, net(M, std::atof(GetParam().eps)), p);
  EXPECT_TRUE(r.converged) << to_string(r.stop_reason);
  EXPECT_EQ(r.stop_reason, StopReason::converged);
  expect_certified_by_own_measure(M, r);
}

INSTANTIATE_TEST_SUITE_P(Builtins, CiSizedRefinement,
                         ::testing::Values(CiCase{"clifford-torus-2", "0.25"}, CiCase{"sphere-2", "0.2"},
                                           CiCase{"torus-of-revolution", "0.3"}, CiCase{"sphere-3", "0.3"}),
                         [](const auto& info) {
                           std::string s = info.param.manifold;
                           for (auto& c : s)
                             if (c == '-') c = '_';
                           return s;
                         });

// The 12 x 12 grid of the Clifford torus refined on 1 and on 2 threads; the outputs must agree.
std::pair<RefineResult, RefineResult> on_one_and_two_threads(RefineParameters p) {
  manifold::Manifold M = builtin("clifford-torus-2");
  auto grid = torus_grid(12);
  p.threads = 1;
  auto a = refine(M, grid, p);
  p.threads = 2;
  auto b = refine(M, grid, p);
  EXPECT_EQ(a.points.coordinates, b.points.coordinates);
  EXPECT_EQ(a.complex.simplices, b.complex.simplices);
  return {std::move(a), std::move(b)};
}

TEST(Refiner, SameSeedSameOutputForAnyThreadCount) {
  RefineParameters p;
  p.seed = 7;
  const auto [a, b] = on_one_and_two_threads(p);
  manifold::Manifold M = builtin("clifford-torus-2");
  auto grid = torus_grid(12);
  p.seed = 8;
  auto c = refine(M, grid, p);
  EXPECT_NE(a.points.coordinates, c.points.coordinates);  // the picks depend on the seed
}

// Pick_valid searches hitting sets in parallel batches (1, 2, 4, ... 32 candidates): at Γ0 = 0.3
// most candidates are rejected, so batches of several run on both threads; the first good
// candidate in drawing order is taken and the generator left where drawing it left it, so points,
// complex and every statistic are the same for any thread count.
TEST(Refiner, ParallelPickValidIsTheSequentialSearch) {
  RefineParameters p;
  p.seed = 3;
  p.constants.gamma0 = exact("0.3");
  const auto [a, b] = on_one_and_two_threads(p);
  std::size_t rejected = 0, drawn = 0;
  for (Rule r : kRules) {
    EXPECT_EQ(a.rules[r].candidates, b.rules[r].candidates) << to_string(r);
    EXPECT_EQ(a.rules[r].rejected_hit, b.rules[r].rejected_hit) << to_string(r);
    EXPECT_EQ(a.rules[r].fallbacks, b.rules[r].fallbacks) << to_string(r);
    rejected += a.rules[r].rejected_hit, drawn += a.rules[r].candidates;
  }
  EXPECT_GT(rejected, 20u) << "the case must reject candidates, or no batch holds more than one";
  std::printf("[ pick_valid ] %zu candidates drawn, %zu rejected by a hitting set, %zu points added\n", drawn, rejected,
              a.points.size() - a.input_size);
}

// The look-ahead (RefineParameters::look_ahead): a candidate whose tentative star would hold a
// Γ0-bad or big cell is rejected. On 200 random points of S^2 at Γ0 = 0.3 it rejects candidates,
// the result is the same for any thread count, the run converges with every star good, and
// without the look-ahead nothing is counted as rejected.
TEST(Refiner, LookAheadRejectsCandidatesWithABadStarOfTheirOwn) {
  manifold::Manifold M = builtin("sphere-2");
  io::PointSet pts;
  sampling::Random random(5);
  sampling::sample_manifold(M, 200, random, pts);
  RefineParameters p;
  p.constants.gamma0 = exact("0.3");
  p.look_ahead = true;
  p.threads = 1;
  const auto a = refine(M, pts, p);
  p.threads = 2;
  const auto b = refine(M, pts, p);
  EXPECT_EQ(a.points.coordinates, b.points.coordinates);
  EXPECT_EQ(a.complex.simplices, b.complex.simplices);
  EXPECT_TRUE(a.converged);
  EXPECT_TRUE(a.final.all_good);
  for (Rule r : kRules) {
    EXPECT_EQ(a.rules[r].rejected_look_ahead, b.rules[r].rejected_look_ahead) << to_string(r);
    EXPECT_EQ(a.rules[r].candidates, b.rules[r].candidates) << to_string(r);
  }
  std::size_t rejected = 0;
  for (Rule r : kRules) rejected += a.rules[r].rejected_look_ahead;
  EXPECT_GT(rejected, 0u);
  p.look_ahead = false;
  const auto c = refine(M, pts, p);
  for (Rule r : kRules) EXPECT_EQ(c.rules[r].rejected_look_ahead, 0u) << to_string(r);
  std::printf("[ look-ahead ] %zu candidates rejected; %zu points added with it, %zu without\n", rejected,
              a.points.size() - a.input_size, c.points.size() - c.input_size);
}

TEST(Refiner, CapsStopTheRunAndSaySo) {
  manifold::Manifold M = builtin("sphere-2");
  auto pts = net(M, 0.3);
  RefineParameters p;
  p.constants.eps = exact("0.2");
  p.max_inserted = 3;
  auto r = refine(M, pts, p);
  EXPECT_FALSE(r.converged);
  EXPECT_EQ(r.stop_reason, StopReason::max_inserted);
  EXPECT_EQ(r.points.size() - r.input_size, 3u);
  EXPECT_FALSE(r.final.all_small);
  p.max_inserted = 0;
  p.max_rounds = 1;
  auto r2 = refine(M, pts, p);
  EXPECT_FALSE(r2.converged);
  EXPECT_EQ(r2.stop_reason, StopReason::max_rounds);
  EXPECT_EQ(r2.rounds, 1u);
  // Which rule stalled where: the first configuration left, in canonical order (rule big first).
  ASSERT_TRUE(r2.stall.has_value());
  EXPECT_EQ(r2.stall->rule, Rule::big);
  EXPECT_GE(r2.stall->point, 0);
  EXPECT_EQ(r2.stall->simplex.size(), 3u);
  EXPECT_EQ(r2.stall->location.size(), 3u);
  EXPECT_EQ(describe_stall(*r2.stall).rfind("rule big stalled at simplex [", 0), 0u) << describe_stall(*r2.stall);
  ASSERT_TRUE(r.stall.has_value());  // the max_inserted stop too
  EXPECT_FALSE(r.stall->simplex.empty() && r.stall->what.empty());
}

// Issue 15 item 1: at ε = 2 on the torus of revolution (R = 2, r = 1) the first rounds stalled
// (ψ_p misses the Delaunay balls, stars stay open). The practical mode shrinks ε locally instead
// and converges; every star cell at p is below p's local ε, and the protection and sparsity hold
// with the smallest local ε, ε / 2^eps_level (recomputed here from a fresh complex). Paper mode
// has one ε and still stalls there.
TEST(Refiner, CoarseEpsShrinksLocallyInsteadOfStalling) {
  manifold::Manifold M = builtin("torus-of-revolution");
  auto pts = net(M, 2.0);
  RefineParameters p;
  p.constants.eps = exact("2");
  auto r = refine(M, pts, p);
  ASSERT_TRUE(r.converged) << to_string(r.stop_reason);
  EXPECT_GT(r.eps_level, 0);
  EXPECT_FALSE(r.eps_sites.empty());
  std::size_t shrinks = 0;
  for (const auto& s : r.rules.values) shrinks += s.shrinks;
  EXPECT_EQ(shrinks, r.eps_sites.size());
  ASSERT_EQ(r.local_eps.size(), r.points.size());
  const double eps_min = std::ldexp(2.0, -r.eps_level);
  for (double e : r.local_eps) {
    EXPECT_LE(e, 2.0);
    EXPECT_GE(e, eps_min);
  }
  auto planes = tangential::compute_tangent_planes(M, r.points);
  tangential::TangentialComplex tc(r.points, planes);
  EXPECT_TRUE(tc.assemble().inconsistent.empty());
  const ConstantsAsDoubles P = as_doubles(r.parameters.constants);
  const double dcheck2 = P.delta0 * P.delta0 * (eps_min / 9) * (eps_min / 9);
  for (std::size_t q = 0; q < tc.size(); ++q) {
    const auto& st = tc.star(q);
    ASSERT_TRUE(st.closed);
    for (std::size_t c = 0; c < st.size(); ++c) {
      EXPECT_LT(st.radii2[c], r.local_eps[q] * r.local_eps[q]);
      const auto cell = st.cell(c);
      for (std::size_t x = 0; x < r.points.size(); ++x) {
        if (std::count(cell.begin(), cell.end(), static_cast<int>(x))) continue;
        double d2 = 0;
        for (int j = 0; j < 3; ++j) d2 += (r.points.point(x)[j] - st.centre(c)[j]) * (r.points.point(x)[j] - st.centre(c)[j]);
        EXPECT_GT(d2 - st.radii2[c], dcheck2);
      }
    }
  }
  EXPECT_GT(r.final.min_distance, eps_min / 9);

  p.mode = RefineMode::paper;
  auto paper = refine(M, pts, p);
  EXPECT_FALSE(paper.converged);
  EXPECT_EQ(paper.stop_reason, StopReason::stalled);
  EXPECT_EQ(paper.eps_level, 0);
  EXPECT_TRUE(paper.eps_sites.empty());

  // The points cap: the run stops with the points it has, and says so.
  p.mode = RefineMode::practical;
  p.max_points = pts.size() + 10;
  auto capped = refine(M, pts, p);
  EXPECT_EQ(capped.stop_reason, StopReason::max_points);
  EXPECT_EQ(capped.points.size(), pts.size() + 10);
  EXPECT_NE(std::string(advice(StopReason::max_points)).find("--max-points"), std::string::npos);
}

TEST(Refiner, ParametersAreValidated) {
  manifold::Manifold M = builtin("sphere-2");
  auto pts = net(M, 0.5);
  RefineParameters p;
  p.constants.eps = exact("0.5");
  p.constants.gamma0 = exact("0");
  EXPECT_THROW(refine(M, pts, p), std::invalid_argument);
  p.constants.gamma0 = exact("0.1");
  p.constants.alpha = exact("1.5");
  EXPECT_THROW(refine(M, pts, p), std::invalid_argument);
  p.constants.alpha = exact("0.3");
  p.constants.delta0 = exact("1");
  EXPECT_THROW(refine(M, pts, p), std::invalid_argument);
}

// One validation, on the exact values, naming the option as `delcert refine` reports it. Γ0 just
// above 1 and α just below 1 round to the double 1: validating the doubles got both wrong.
TEST(Parameters, ValidatedExactlyWithTheOptionsMessages) {
  auto message = [](const Constants& c) {
    try {
      validate(c);
    } catch (const ParameterError& e) {
      return std::string(e.what());
    }
    return std::string("valid");
  };
  Constants c;
  EXPECT_EQ(message(c), "valid");
  c.eps = exact("-1");
  EXPECT_EQ(message(c), "--eps: must be positive");
  c.eps = exact("1e-400");  // positive, but no positive double: the algorithm cannot run on it
  EXPECT_EQ(message(c), "--eps: must be at least 4.9e-324 (the smallest positive double): delcert computes with doubles");
  c.eps = exact("1e400");  // the message names the limit, not its 309 digits (issue 13 §5)
  EXPECT_EQ(message(c), "--eps: must be at most 1.8e308 (the largest double): delcert computes with doubles");
  c.eps = exact("0.3");
  c.gamma0 = exact("1.00000000000000000001");
  EXPECT_EQ(message(c), "--gamma0: must lie in (0, 1]");
  c.gamma0 = exact("1");
  c.alpha = exact("0.99999999999999999999");
  EXPECT_EQ(message(c), "valid");
  c.alpha = exact("1/2");
  c.beta = exact("0");
  EXPECT_EQ(message(c), "--beta: must be positive; the paper takes beta > 1");
  c.beta = exact("1e400");
  EXPECT_EQ(message(c), "--beta: must be at most 1.8e308 (the largest double): delcert computes with doubles");
  c.beta = exact("1.1");
  resolve_delta0(c, 2);  // Γ0 = 1 gives δ0 = 1
  EXPECT_EQ(c.delta0->text, "1");
  EXPECT_EQ(message(c), "--delta0: must lie in [0, 1); the paper takes delta0 < 1/4");
}

// The constants keep the text they were given as (report.json echoes it) and the exact value
// (claims.json writes it); the derived doubles are the values rounded towards zero.
TEST(Parameters, TextValueAndDoubles) {
  Constants c;
  c.eps = exact("1/4");
  c.gamma0 = exact("1e-1");
  EXPECT_EQ(c.gamma0.text, "1e-1");
  EXPECT_EQ(c.gamma0.value, mpq_class(1, 10));
  EXPECT_EQ(ExactParameter(mpq_class(1, 10)).text, "0.1");
  resolve_delta0(c, 3);
  EXPECT_EQ(c.delta0->value, mpq_class(1, 100));
  const ConstantsAsDoubles d = as_doubles(c);
  EXPECT_EQ(d.eps, 0.25);
  EXPECT_EQ(mpq_class(d.gamma0), mpq_class(mpq_class(1, 10).get_d()));
  EXPECT_LE(mpq_class(d.gamma0), mpq_class(1, 10));
  EXPECT_EQ(mu0_times(d.eps), 0.25 / 9);
  EXPECT_EQ(mu0_times(mpq_class(1, 4)), mpq_class(1, 36));
}

TEST(Refiner, DecimalAboveAndDefaultDelta0) {
  EXPECT_EQ(decimal_above(0.4712), exact::parse_rational("0.48"));
  EXPECT_EQ(decimal_above(0.47), exact::parse_rational("0.48"));
  EXPECT_EQ(decimal_above(3.2), exact::parse_rational("3.3"));
  EXPECT_EQ(decimal_above(0.00999), exact::parse_rational("0.01"));
  EXPECT_EQ(decimal_above(12.0), exact::parse_rational("13"));
  EXPECT_EQ(default_delta0(exact::parse_rational("0.1"), 2), exact::parse_rational("0.01"));
  EXPECT_EQ(default_delta0(exact::parse_rational("0.1"), 3), exact::parse_rational("0.01"));
  EXPECT_EQ(default_delta0(exact::parse_rational("1/5"), 4), exact::parse_rational("0.008"));
}

}  // namespace
}  // namespace delcert::refine
