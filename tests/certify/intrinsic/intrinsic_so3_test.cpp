// Del_M on SO(3) (certify/intrinsic_so3.cpp, checks 14 and 15): an independent reference (CGAL's
// 4D Delaunay triangulation of the quaternions +-q: its convex hull, modulo the antipodal map),
// gift wrapping from one seed, mutants, the nearest-rotation convention (scaling moves no
// projection), an exact tie (the tetrahedral group) and a metric declaration that does not match.
#include <gtest/gtest.h>

#include <CGAL/Delaunay_triangulation.h>
#include <CGAL/Epick_d.h>

#include <array>
#include <cmath>
#include <map>
#include <set>

#include "certify/detail/grid.hpp"
#include "certify/intrinsic/intrinsic.hpp"
#include "io/spec.hpp"
#include "tests/certify/support.hpp"

namespace delcert::certify::test {
namespace {

using Simplex = std::vector<int>;
using Quaternions = std::vector<std::array<double, 4>>;

// The reference: the facets of conv{+-q_i} (the full cells of the Delaunay triangulation of the
// lifted points that hold its infinite vertex), as sets of point indices.
std::set<Simplex> hull_reference(const Quaternions& q) {
  using K = CGAL::Epick_d<CGAL::Dimension_tag<4>>;
  using T = CGAL::Delaunay_triangulation<K>;
  T t(4);
  std::map<T::Vertex_handle, int> index;
  for (std::size_t i = 0; i < q.size(); ++i)
    for (int s : {1, -1}) {
      const T::Vertex_handle v = t.insert(K::Point_d(s * q[i][0], s * q[i][1], s * q[i][2], s * q[i][3]));
      index[v] = static_cast<int>(i);
    }
  std::set<Simplex> facets;
  for (auto c = t.full_cells_begin(); c != t.full_cells_end(); ++c) {
    if (!t.is_infinite(c)) continue;
    Simplex s;
    for (int j = 0; j <= 4; ++j)
      if (!t.is_infinite(c->vertex(j))) s.push_back(index.at(c->vertex(j)));
    std::sort(s.begin(), s.end());
    facets.insert(s);
  }
  return facets;
}

// The side of lifted point y relative to the hyperplane through the lifted simplex (long double,
// for re-checking witnesses whose margins are far above rounding).
int side(const Quaternions& q, const nlohmann::json& lift, const nlohmann::json& y) {
  long double a[5][5];
  auto row = [&](int r, const nlohmann::json& e) {
    const int k = e[0].get<int>(), s = e[1].get<int>();
    a[r][0] = 1;
    for (int j = 0; j < 4; ++j) a[r][j + 1] = s * static_cast<long double>(q[k][j]);
  };
  for (int r = 0; r < 4; ++r) row(r, lift[r]);
  row(4, y);
  long double det = 1;  // Gaussian elimination with partial pivoting
  for (int c = 0; c < 5; ++c) {
    int p = c;
    for (int r = c + 1; r < 5; ++r)
      if (std::abs(a[r][c]) > std::abs(a[p][c])) p = r;
    if (p != c) {
      for (int j = 0; j < 5; ++j) std::swap(a[p][j], a[c][j]);
      det = -det;
    }
    det *= a[c][c];
    for (int r = c + 1; r < 5; ++r) {
      const long double f = a[r][c] / a[c][c];
      for (int j = c; j < 5; ++j) a[r][j] -= f * a[c][j];
    }
  }
  return det > 0 ? 1 : det < 0 ? -1 : 0;
}

TEST(IntrinsicSO3, AgreesWithTheHullOfTheQuaternionsFromOneSeed) {
  Quaternions q;
  const io::PointSet P = so3_net(1500, 0.6, 7, &q);
  ASSERT_GT(P.size(), 200u);
  for (auto& x : q)  // the certifier's sign: w >= 0 (docs/certificate.md)
    if (x[0] < 0)
      for (double& c : x) c = -c;
  const io::ManifoldSpec spec = io::read_spec("builtin:so3");
  const std::set<Simplex> truth = hull_reference(q);
  ASSERT_GT(truth.size(), 4 * P.size());
  // From the whole reference as candidates, and from one facet of it (gift wrapping finds the rest).
  for (const std::vector<Simplex>& candidates :
       {std::vector<Simplex>(truth.begin(), truth.end()), std::vector<Simplex>{*truth.begin()}}) {
    const IntrinsicDelaunay D = del_m(spec, P, candidates);
    ASSERT_TRUE(D.computed) << D.reason;
    EXPECT_EQ(D.metric, "so3");
    EXPECT_TRUE(D.complete) << D.reason;
    EXPECT_EQ(simplices(D), truth);
    EXPECT_TRUE(D.undecided.empty());
  }
  // Every certified witness re-checks: all other lifted points on one side of its lift's hyperplane.
  const IntrinsicDelaunay D = del_m(spec, P, {*truth.begin()});
  for (std::size_t i = 0; i < D.simplices.size(); i += 97) {
    const nlohmann::json& lift = D.simplices[i].witness["lift"];
    ASSERT_EQ(lift.size(), 4u);
    std::set<int> sides;
    for (std::size_t k = 0; k < P.size(); ++k)
      for (int s : {1, -1}) {
        const nlohmann::json y = {static_cast<int>(k), s};
        if (std::find(lift.begin(), lift.end(), y) == lift.end()) sides.insert(side(q, lift, y));
      }
    EXPECT_EQ(sides.size(), 1u) << D.simplices[i].witness.dump();
    EXPECT_EQ(sides.count(0), 0u);
  }
}

// Mutants: a certified tetrahedron with one vertex replaced by a nearby point outside it is
// proven not in Del_M, each of the eight lifts with two points on opposite sides that re-check.
TEST(IntrinsicSO3, MutantsAreRejectedWithWitnessesThatRecheck) {
  Quaternions q;
  const io::PointSet P = so3_net(1500, 0.6, 7, &q);
  for (auto& x : q)
    if (x[0] < 0)
      for (double& c : x) c = -c;
  const io::ManifoldSpec spec = io::read_spec("builtin:so3");
  const std::set<Simplex> truth = hull_reference(q);
  std::vector<Simplex> mutants;
  for (auto it = truth.begin(); it != truth.end() && mutants.size() < 40; std::advance(it, 7)) {
    for (int other = 0; other < static_cast<int>(P.size()); other += 13) {
      Simplex m = *it;
      if (std::count(m.begin(), m.end(), other)) continue;
      m[other % 4] = other;
      std::sort(m.begin(), m.end());
      if (!truth.count(m)) {
        mutants.push_back(m);
        break;
      }
    }
  }
  const IntrinsicDelaunay D = del_m(spec, P, mutants);
  for (const auto& s : D.simplices) EXPECT_TRUE(truth.count(s.simplex));
  std::set<Simplex> rejected;
  for (const auto& r : D.rejected) {
    rejected.insert(r.simplex);
    ASSERT_EQ(r.witness["lifts"].size(), 8u);
    for (const auto& l : r.witness["lifts"]) {
      const auto& both = l["points_on_both_sides"];
      EXPECT_EQ(side(q, l["lift"], both[0]), -side(q, l["lift"], both[1])) << l.dump();
    }
  }
  for (const auto& m : mutants) EXPECT_TRUE(rejected.count(m)) << m[0] << "," << m[1] << "," << m[2] << "," << m[3];
}

// The convention: d_M(x, p) := d_M(x, pi(p)), pi the nearest rotation. Scaling p by s > 0 keeps
// pi(p) (B(s p) = s B(p)): Del_M is unchanged for points far off SO(3).
TEST(IntrinsicSO3, ScalingMovesNoProjection) {
  Quaternions q;
  const io::PointSet P = so3_net(600, 0.7, 3, &q);
  io::PointSet S;
  S.dimension = 9;
  for (std::size_t i = 0; i < P.size(); ++i) {
    const double s = 1 + 0.25 * static_cast<double>(i % 5);  // 1, 1.25, ..., 2: exact in binary
    std::vector<double> x(9);
    for (int j = 0; j < 9; ++j) x[j] = s * P.point(i)[j];
    S.push_back(x);
  }
  const io::ManifoldSpec spec = io::read_spec("builtin:so3");
  const std::set<Simplex> truth = hull_reference(q);
  const IntrinsicDelaunay D = del_m(spec, S, {*truth.begin()});
  ASSERT_TRUE(D.computed) << D.reason;
  EXPECT_TRUE(D.complete) << D.reason;
  EXPECT_EQ(simplices(D), truth);
  // Adversarial magnitudes: every point scaled by 2^k (exact in binary). The enclosures work on
  // B scaled back to [1/2, 1); the distances to SO(3) (about |p|) only widen the test radius.
  // Beyond 2^511, |p|^2 overflows a double: the engine stops and says so, never guesses.
  for (int k : {-1000, -300, 300, 500, 600}) {
    SCOPED_TRACE(k);
    io::PointSet T;
    T.dimension = 9;
    for (std::size_t i = 0; i < P.size(); ++i) {
      std::vector<double> x(9);
      for (int j = 0; j < 9; ++j) x[j] = std::ldexp(P.point(i)[j], k);
      T.push_back(x);
    }
    const IntrinsicDelaunay E = del_m(spec, T, {*truth.begin()});
    if (k == 600) {
      EXPECT_FALSE(E.computed);
      EXPECT_NE(E.reason.find("overflows"), std::string::npos) << E.reason;
      continue;
    }
    ASSERT_TRUE(E.computed) << E.reason;
    EXPECT_TRUE(E.complete) << E.reason;
    EXPECT_EQ(simplices(E), truth);
  }
}

// The 12 rotations of the tetrahedral group (rational, exactly on SO(3)) lift to the 24 vertices
// of the 24-cell, whose facets are octahedra: six cospherical points, an exact tie. Never
// certified, never complete, and the reason says why.
TEST(IntrinsicSO3, TheTetrahedralGroupIsATieAndNeverCertified) {
  std::vector<std::vector<double>> rotations;
  for (int perm = 0; perm < 3; ++perm)  // cyclic permutation matrices times diagonal signs of det 1
    for (int signs = 0; signs < 4; ++signs) {
      const double d[3] = {signs & 1 ? -1.0 : 1.0, signs & 2 ? -1.0 : 1.0, (signs == 1 || signs == 2) ? -1.0 : 1.0};
      std::vector<double> R(9, 0.0);
      for (int i = 0; i < 3; ++i) R[3 * i + (i + perm) % 3] = d[i];
      rotations.push_back(R);
    }
  const io::PointSet P = make_points(9, rotations);
  std::vector<Simplex> all;
  for (int a = 0; a < 12; ++a)
    for (int b = a + 1; b < 12; ++b)
      for (int c = b + 1; c < 12; ++c)
        for (int d = c + 1; d < 12; ++d) all.push_back({a, b, c, d});
  const IntrinsicDelaunay D = del_m(io::read_spec("builtin:so3"), P, all);
  ASSERT_TRUE(D.computed) << D.reason;
  EXPECT_FALSE(D.complete);
  EXPECT_TRUE(D.simplices.empty());
  ASSERT_FALSE(D.undecided.empty());
  EXPECT_NE(D.undecided[0].reason.find("not protected"), std::string::npos) << D.undecided[0].reason;
}

// A point whose nearest rotation is not unique (a reflection: the top eigenvalue of its Davenport
// matrix is triple; the zero matrix: every rotation is nearest) stops the engine, naming it.
TEST(IntrinsicSO3, APointWithoutAUniqueNearestRotationIsNamed) {
  Quaternions q;
  const io::PointSet P = so3_net(400, 0.8, 5, &q);
  const std::set<Simplex> truth = hull_reference(q);
  for (const std::vector<double>& bad : {std::vector<double>{1, 0, 0, 0, 1, 0, 0, 0, -1}, std::vector<double>(9, 0.0)}) {
    io::PointSet B = P;
    B.push_back(bad);
    const IntrinsicDelaunay D = del_m(io::read_spec("builtin:so3"), B, {*truth.begin()});
    EXPECT_FALSE(D.computed);
    EXPECT_NE(D.reason.find("point " + std::to_string(P.size()) + ": the largest eigenvalue"), std::string::npos)
        << D.reason;
  }
}

// The declared metric is used only for SO(3) itself: equations by rows or by columns, and a
// selector that is a positive multiple of det. O(3) (no selector) and the other component are not.
TEST(IntrinsicSO3, TheMetricIsUsedOnlyForSO3Itself) {
  Quaternions q;
  const io::PointSet P = so3_net(400, 0.8, 5, &q);
  const std::set<Simplex> truth = hull_reference(q);
  const std::string text = io::builtin_spec_text("so3");
  auto with = [&](const std::string& from, const std::string& to) {
    std::string t = text;
    const auto at = t.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    return io::parse_spec(t.replace(at, from.size(), to), "test");
  };
  const std::string det = "\"x1*(x5*x9 - x6*x8) - x2*(x4*x9 - x6*x7) + x3*(x4*x8 - x5*x7)\"";
  const std::string rows = "\"x1*x4 + x2*x5 + x3*x6\",\n    \"x1*x7 + x2*x8 + x3*x9\",\n    \"x4*x7 + x5*x8 + x6*x9\"";
  {
    const IntrinsicDelaunay D = del_m(with(det, "\"2*(" + det.substr(1, det.size() - 2) + ")\""), P, {*truth.begin()});
    EXPECT_TRUE(D.complete) << D.reason;  // a positive multiple
  }
  for (const auto& [from, to, why] :
       std::vector<std::array<std::string, 3>>{{det, "\"-(" + det.substr(1, det.size() - 2) + ")\"", "negative multiple"},
                                               {det, "\"x1*x5*x9\"", "not a multiple of the determinant"},
                                               {rows, "\"x1*x2 + x4*x5 + x7*x8\",\n \"x1*x3 + x4*x6 + x7*x9\",\n \"x4*x7 + x5*x8 + x6*x9\"",
                                                "not (a multiple of)"}}) {
    SCOPED_TRACE(why);
    const IntrinsicDelaunay D = del_m(with(from, to), P, {*truth.begin()});
    EXPECT_FALSE(D.computed);
    EXPECT_NE(D.reason.find("not used"), std::string::npos) << D.reason;
    EXPECT_NE(D.reason.find(why), std::string::npos) << D.reason;
  }
  {  // the columns orthonormal: the same SO(3)
    std::string t = text;
    const auto from = t.find("\"equations\""), to = t.find("]", from);
    t.replace(from, to + 1 - from,
              R"("equations": ["x1^2 + x4^2 + x7^2 - 1", "x2^2 + x5^2 + x8^2 - 1", "x3^2 + x6^2 + x9^2 - 1",
                 "x1*x2 + x4*x5 + x7*x8", "x1*x3 + x4*x6 + x7*x9", "x2*x3 + x5*x6 + x8*x9"])");
    const IntrinsicDelaunay D = del_m(io::parse_spec(t, "test"), P, {*truth.begin()});
    EXPECT_TRUE(D.complete) << D.reason;
    EXPECT_EQ(simplices(D), truth);
  }
}

}  // namespace
}  // namespace delcert::certify::test
