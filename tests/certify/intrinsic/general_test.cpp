// Del_M on a general M (certify/intrinsic/general.hpp, issue 40): the engine that bounds the
// geodesic distance, run with the closed-form metric WITHHELD, must never contradict the
// closed-form engines (certify/intrinsic/intrinsic_*.cpp) on the same input, and must decide
// most of it; on a manifold with no closed form it certifies only Del_RM simplices.
#include <gtest/gtest.h>

#include <set>
#include <vector>

#include "certify/detail/grid.hpp"
#include "certify/intrinsic/intrinsic.hpp"
#include "certify/intrinsic/general.hpp"
#include "certify/restricted/restricted.hpp"
#include "io/spec.hpp"
#include "tests/certify/support.hpp"

namespace delcert::certify {
namespace {

using Simplices = std::set<std::vector<int>>;

struct Engines {
  RestrictedDelaunay R;
  IntrinsicDelaunay D;
};

// Check 12's Del_RM, then Del_M from its simplices (plus `extra` candidates) with the general
// engine when the spec has no verified metric. The points are doubles rounded from points of M
// (a few ulps away): 2^-40 bounds their distance to M on these unit-scale shapes.
Engines run(const io::ManifoldSpec& spec, const io::PointSet& P, const std::vector<std::vector<int>>& extra = {}) {
  const exact::ImplicitSystem system(spec.equations, spec.ambient_dimension);
  const detail::PointGrid grid(P, spec.intrinsic_dimension);
  const std::vector<double> delta(P.size(), 0x1p-40);
  RestrictedDelaunayOptions ro;
  ro.threads = 2;
  ro.distance_to_M = &delta;
  Engines r{compute_restricted_delaunay(system, P, grid, ro), {}};
  std::vector<std::vector<int>> candidates = extra;
  for (const auto& s : r.R.simplices) candidates.push_back(s.simplex);
  GeneralMetricInput in;
  in.system = &system, in.distance_to_M = &delta, in.restricted = &r.R, in.cell = ro.cell;
  r.D = compute_intrinsic_delaunay(spec, P, grid, candidates, 2, &in);
  return r;
}

Simplices certified(const IntrinsicDelaunay& D) {
  Simplices s;
  for (const auto& x : D.simplices) s.insert(x.simplex);
  return s;
}

// The simplices whose emptiness needed PIECES (general.cpp: a point not separated on the whole
// region, separated on every piece of it); each entry's least margin is positive, and the whole
// witness is coherent: the radius bound is below the distance bound of every point proven on the
// whole region.
std::size_t proven_on_pieces(const IntrinsicDelaunay& D) {
  std::size_t n = 0;
  for (const auto& s : D.simplices) {
    const auto& w = s.witness;
    EXPECT_EQ(w.value("kind", ""), "intrinsic_voronoi_vertex");
    if (w.at("others_distance_lower").is_number()) {
      EXPECT_GT(w.at("others_distance_lower").get<double>(), w.at("geodesic_radius_upper").get<double>());
    }
    const auto& pieces = w.at("others_on_pieces");
    for (const auto& e : pieces) {
      EXPECT_GE(e.at("pieces").get<long>(), 3);  // the region itself failed, then at least two halves
      EXPECT_GT(e.at("margin_lower").get<double>(), 0.0);
    }
    if (!pieces.empty()) ++n;
  }
  return n;
}

// The differential property: what the general engine certifies is in the closed-form Del_M, what
// it rejects is not, and when it claims completeness the two agree; it decides at least `share`.
void expect_no_contradiction(const std::string& builtin, const io::PointSet& P, double share, bool expect_pieces) {
  const io::ManifoldSpec with = io::read_spec(builtin);
  io::ManifoldSpec without = with;
  without.metric.reset();
  const Engines closed = run(with, P), general = run(without, P);
  ASSERT_TRUE(closed.D.computed) << closed.D.reason;
  ASSERT_TRUE(closed.D.complete) << closed.D.reason;
  ASSERT_TRUE(general.D.computed) << general.D.reason;
  EXPECT_EQ(general.D.metric, "general");
  const Simplices truth = certified(closed.D), mine = certified(general.D);
  for (const auto& s : mine) EXPECT_TRUE(truth.count(s)) << "certified in Del_M by the general engine only";
  for (const auto& r : general.D.rejected) EXPECT_FALSE(truth.count(r.simplex)) << "rejected, yet in Del_M";
  if (general.D.complete) {
    EXPECT_EQ(mine, truth);
  }
  EXPECT_GE(static_cast<double>(mine.size()), share * static_cast<double>(truth.size()))
      << general.D.reason << " (" << mine.size() << " of " << truth.size() << ")";
  // The piecewise emptiness is exercised here, against the closed form (on a random sample; on a
  // lattice every point is separated on the whole region or not at all).
  const std::size_t pieces = proven_on_pieces(general.D);
  if (expect_pieces) {
    EXPECT_GT(pieces, 0u);
  }
}

TEST(GeneralIntrinsic, SphereWithTheMetricWithheldNeverContradictsTheClosedForm) {
  expect_no_contradiction("builtin:sphere-2", test::spread_sphere(3, 500, 0.12, 11), 0.8, true);
}

TEST(GeneralIntrinsic, FlatTorusInCodimensionTwoNeverContradictsTheClosedForm) {
  expect_no_contradiction("builtin:clifford-torus-2", test::torus2_lattice(20, 24), 0.8, false);
}

TEST(GeneralIntrinsic, TorusOfRevolutionCertifiesOnlyRestrictedSimplices) {
  const io::ManifoldSpec spec = io::read_spec("builtin:torus-of-revolution");
  const io::PointSet P = test::torus_of_revolution(48, 24);
  const Engines r = run(spec, P);
  ASSERT_TRUE(r.D.computed) << r.D.reason;
  ASSERT_TRUE(r.R.covering_certified) << r.R.reason;
  Simplices rm;
  for (const auto& s : r.R.simplices) rm.insert(s.simplex);
  const Simplices mine = certified(r.D);
  EXPECT_GE(mine.size(), rm.size() / 2) << r.D.reason;  // most decided
  for (const auto& s : mine) EXPECT_TRUE(rm.count(s));
  for (const auto& s : r.D.simplices) EXPECT_EQ(s.witness.value("kind", ""), "intrinsic_voronoi_vertex");
  proven_on_pieces(r.D);  // (a lattice: the witnesses are checked, the pieces may not be needed)
  if (!r.D.complete) {
    EXPECT_FALSE(r.D.reason.empty());
  }
}

// A candidate that is not Delaunay (an edge of the complex flipped) is never certified.
TEST(GeneralIntrinsic, AFlippedTriangleIsNeverCertified) {
  const io::ManifoldSpec with = io::read_spec("builtin:sphere-2");
  io::ManifoldSpec spec = with;
  spec.metric.reset();
  const io::PointSet P = test::spread_sphere(3, 300, 0.15, 5);
  const Engines base = run(spec, P);
  // Two triangles sharing an edge {a, b}: {a, b, c} and {a, b, d}; the flip gives {a, c, d}, {b, c, d}.
  std::vector<std::vector<int>> flipped;
  for (std::size_t i = 0; i < base.R.simplices.size() && flipped.empty(); ++i)
    for (std::size_t j = i + 1; j < base.R.simplices.size() && flipped.empty(); ++j) {
      const auto &s = base.R.simplices[i].simplex, &t = base.R.simplices[j].simplex;
      std::vector<int> common, all;
      std::set_intersection(s.begin(), s.end(), t.begin(), t.end(), std::back_inserter(common));
      if (common.size() != 2) continue;
      std::set_union(s.begin(), s.end(), t.begin(), t.end(), std::back_inserter(all));
      for (int e : common) {
        std::vector<int> f;
        for (int v : all)
          if (v != e) f.push_back(v);
        flipped.push_back(f);
      }
    }
  ASSERT_EQ(flipped.size(), 2u);
  const Engines r = run(spec, P, flipped);
  const Simplices mine = certified(r.D);
  for (const auto& f : flipped) {
    EXPECT_FALSE(mine.count(f));
    if (r.D.complete) {
      EXPECT_TRUE(std::any_of(r.D.rejected.begin(), r.D.rejected.end(), [&](const auto& x) { return x.simplex == f; }));
    }
  }
}

}  // namespace
}  // namespace delcert::certify
