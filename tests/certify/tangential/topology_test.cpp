// The certifier's own combinatorial topology against known answers.
#include <gtest/gtest.h>

#include <cstdint>
#include <numeric>

#include "certify/tangential/topology.hpp"

namespace delcert::certify {
namespace {

using Simplices = std::vector<std::vector<int>>;

const Simplices kOctahedron = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
// The 6-vertex real projective plane.
const Simplices kRP2 = {{0, 1, 2}, {0, 2, 3}, {0, 3, 4}, {0, 4, 5}, {0, 5, 1},
                        {1, 2, 4}, {2, 3, 5}, {3, 4, 1}, {4, 5, 2}, {5, 1, 3}};

// A k x k grid torus, each square split by a diagonal.
Simplices grid_torus(int k) {
  Simplices out;
  auto v = [&](int i, int j) { return ((i + k) % k) * k + (j + k) % k; };
  for (int i = 0; i < k; ++i)
    for (int j = 0; j < k; ++j) {
      out.push_back({v(i, j), v(i + 1, j), v(i + 1, j + 1)});
      out.push_back({v(i, j), v(i + 1, j + 1), v(i, j + 1)});
    }
  return out;
}

// The boundary of the (d+1)-simplex: a d-sphere.
Simplices simplex_boundary(int d) {
  Simplices out;
  for (int skip = 0; skip <= d + 1; ++skip) {
    std::vector<int> s;
    for (int v = 0; v <= d + 1; ++v)
      if (v != skip) s.push_back(v);
    out.push_back(s);
  }
  return out;
}

TEST(Topology, BettiNumbersKnownAnswers) {
  auto betti = [](const Simplices& s, int p) { return betti_numbers(face_lattice(s), p); };
  EXPECT_EQ(betti(kOctahedron, 2), (std::vector<long>{1, 0, 1}));
  EXPECT_EQ(betti(kOctahedron, 3), (std::vector<long>{1, 0, 1}));
  EXPECT_EQ(betti(grid_torus(4), 2), (std::vector<long>{1, 2, 1}));
  EXPECT_EQ(betti(grid_torus(5), 3), (std::vector<long>{1, 2, 1}));
  EXPECT_EQ(betti(kRP2, 2), (std::vector<long>{1, 1, 1}));  // torsion Z/2 shows over Z/2 only
  EXPECT_EQ(betti(kRP2, 3), (std::vector<long>{1, 0, 0}));
  EXPECT_EQ(betti(simplex_boundary(3), 2), (std::vector<long>{1, 0, 0, 1}));
  EXPECT_EQ(betti(simplex_boundary(4), 3), (std::vector<long>{1, 0, 0, 0, 1}));
  Simplices two = kOctahedron;  // two disjoint spheres
  for (auto s : kOctahedron) {
    for (int& v : s) v += 6;
    two.push_back(s);
  }
  EXPECT_EQ(betti(two, 2), (std::vector<long>{2, 0, 2}));
}

// The 3-torus: a k x k x k grid of cubes, each cut into the six tetrahedra of its main diagonal
// (Freudenthal's subdivision: one per order of the three axes), k >= 3 for a simplicial complex.
Simplices grid_three_torus(int k) {
  Simplices out;
  auto v = [&](int a, int b, int c) { return ((a % k) * k + b % k) * k + c % k; };
  const int orders[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  for (int a = 0; a < k; ++a)
    for (int b = 0; b < k; ++b)
      for (int c = 0; c < k; ++c)
        for (const auto& o : orders) {
          int x[3] = {a, b, c};
          std::vector<int> t{v(x[0], x[1], x[2])};
          for (int axis : o) {
            ++x[axis];
            t.push_back(v(x[0], x[1], x[2]));
          }
          out.push_back(t);
        }
  return out;
}

// rank of d_k over Z/p by dense Gaussian elimination: the reference for boundary_ranks.
long dense_rank(const FaceLattice& L, int k, int p) {
  const long rows = static_cast<long>(L.count(k - 1)), cols = static_cast<long>(L.count(k));
  std::vector<std::vector<int>> a(cols, std::vector<int>(rows, 0));
  for (long j = 0; j < cols; ++j)
    for (int i = 0; i <= k; ++i) {
      std::vector<int> face;
      for (int t = 0; t <= k; ++t)
        if (t != i) face.push_back(L.flat[k][j * (k + 1) + t]);
      a[j][L.find(k - 1, face.data())] = i % 2 ? p - 1 : 1;
    }
  long rank = 0;
  for (long r = 0; r < rows; ++r) {
    long piv = rank;
    while (piv < cols && a[piv][r] == 0) ++piv;
    if (piv == cols) continue;
    std::swap(a[piv], a[rank]);
    int inv = 1;
    while (a[rank][r] * inv % p != 1) ++inv;
    for (long j = rank + 1; j < cols; ++j)
      if (int f = a[j][r] * inv % p)
        for (long t = 0; t < rows; ++t) a[j][t] = ((a[j][t] - f * a[rank][t]) % p + p) % p;
    ++rank;
  }
  return rank;
}

TEST(Topology, BettiNumbersOfThreeManifolds) {
  // The peeling of boundary_ranks removes all of d_2 on a 3-sphere; with b_1 = 3 a core is left
  // to the reduction (so both paths are tested).
  for (int p : {2, 3}) {
    EXPECT_EQ(betti_numbers(face_lattice(grid_three_torus(3)), p), (std::vector<long>{1, 3, 3, 1}));
    EXPECT_EQ(betti_numbers(face_lattice(grid_three_torus(4)), p), (std::vector<long>{1, 3, 3, 1}));
  }
}

// Random subcomplexes of the 3-torus and of its 2-skeleton, vertices relabelled at random (no
// pseudomanifold: the forest shortcut does not apply, so d_3 and d_2 are peeled by rows and
// columns in many orders, and d_3's clearing feeds d_2): every rank equals the dense one.
TEST(Topology, BoundaryRanksMatchDenseEliminationOnRandomComplexes) {
  const Simplices all = grid_three_torus(3);
  Simplices triangles;
  for (const auto& t : all)
    for (int skip = 0; skip < 4; ++skip) {
      std::vector<int> f;
      for (int i = 0; i < 4; ++i)
        if (i != skip) f.push_back(t[i]);
      triangles.push_back(f);
    }
  std::uint64_t state = 12345;
  auto next = [&] { return (state = state * 6364136223846793005ull + 1442695040888963407ull) >> 33; };
  for (int trial = 0; trial < 80; ++trial) {
    std::vector<int> label(27);
    std::iota(label.begin(), label.end(), 0);
    for (int i = 26; i > 0; --i) std::swap(label[i], label[next() % (i + 1)]);
    Simplices some;
    const unsigned keep = 30 + trial % 14 * 5;  // per cent
    for (const auto& t : trial % 2 ? triangles : all)
      if (next() % 100 < keep) {
        std::vector<int> r;
        for (int v : t) r.push_back(label[v]);
        some.push_back(r);
      }
    const FaceLattice L = face_lattice(some);
    for (int p : {2, 3}) {
      const std::vector<long> rank = boundary_ranks(L, p);
      for (int k = 1; k <= L.dimension; ++k) EXPECT_EQ(rank[k], dense_rank(L, k, p)) << "trial " << trial << ", d_" << k;
    }
  }
}

TEST(Topology, SphereRecognition) {
  std::string why;
  EXPECT_EQ(is_sphere({{1}, {2}}, 0, &why), Tri::yes);
  EXPECT_EQ(is_sphere({{1}, {2}, {3}}, 0, &why), Tri::no);
  EXPECT_EQ(is_sphere({{0, 1}, {1, 2}, {2, 0}}, 1, &why), Tri::yes);
  EXPECT_EQ(is_sphere({{0, 1}, {1, 2}, {2, 0}, {3, 4}, {4, 5}, {5, 3}}, 1, &why), Tri::no);  // two cycles
  EXPECT_EQ(is_sphere({{0, 1}, {1, 2}}, 1, &why), Tri::no);                                   // a path
  EXPECT_EQ(is_sphere(kOctahedron, 2, &why), Tri::yes);
  EXPECT_EQ(is_sphere(grid_torus(4), 2, &why), Tri::no);
  EXPECT_NE(why.find("Euler"), std::string::npos) << why;
  EXPECT_EQ(is_sphere(kRP2, 2, &why), Tri::no);
  EXPECT_EQ(is_sphere(simplex_boundary(3), 3, &why), Tri::yes);      // Regina (topology_m4_test.cpp)
  EXPECT_EQ(is_sphere(simplex_boundary(4), 4, &why), Tri::unknown);  // homology sphere only
}

TEST(Topology, ReportOnComplexes) {
  io::Complex K{6, kOctahedron};
  TopologyReport R = analyse_topology(K, 2);
  EXPECT_TRUE(R.pure);
  EXPECT_EQ(R.boundary_ridges + R.singular_ridges + R.bad_links + R.uncovered_vertices, 0);
  EXPECT_EQ(R.euler, 2);
  EXPECT_EQ(R.f, (std::vector<long>{6, 12, 8}));
  EXPECT_EQ(R.strong_components, 1);

  io::Complex missing{6, {kOctahedron.begin(), kOctahedron.end() - 1}};
  R = analyse_topology(missing, 2);
  EXPECT_EQ(R.boundary_ridges, 3);
  EXPECT_GE(R.bad_links, 3);

  io::Complex impure{7, kOctahedron};
  impure.simplices.push_back({5, 6});
  R = analyse_topology(impure, 2);
  EXPECT_FALSE(R.pure);
  EXPECT_EQ(R.impure_example, (std::vector<int>{5, 6}));

  io::Complex torus{16, grid_torus(4)};
  R = analyse_topology(torus, 2);
  EXPECT_EQ(R.bad_links, 0);
  EXPECT_EQ(R.euler, 0);
  EXPECT_EQ(R.betti_z3, (std::vector<long>{1, 2, 1}));

  io::Complex uncovered{7, kOctahedron};
  EXPECT_EQ(analyse_topology(uncovered, 2).uncovered_vertices, 1);

  // Two octahedra glued at a vertex (5 and 11 are one): its link is two cycles. The links are
  // tested on the threads; the report names the same vertex and reason for any thread count.
  io::Complex pinched{11, kOctahedron};
  for (auto s : kOctahedron) {
    for (int& v : s) v = v == 5 ? 5 : v < 5 ? v + 6 : 10;
    pinched.simplices.push_back(s);
  }
  for (int threads : {1, 2, 3}) {
    R = analyse_topology(pinched, 2, nullptr, threads);
    EXPECT_EQ(R.bad_links, 1);
    EXPECT_EQ(R.bad_link_example, 5);
    EXPECT_EQ(R.boundary_ridges + R.singular_ridges, 0);
    EXPECT_EQ(R.betti_z2, (std::vector<long>{1, 0, 2}));
  }
}

// m = 3: vertex links are 2-spheres (analyse_topology's fast path must agree with is_sphere).
TEST(Topology, VertexLinksOfThreeManifolds) {
  Simplices boundary4;  // the boundary of the 4-simplex: a 3-sphere, every link a tetrahedron boundary
  for (int skip = 0; skip < 5; ++skip) {
    std::vector<int> t;
    for (int v = 0; v < 5; ++v)
      if (v != skip) t.push_back(v);
    boundary4.push_back(t);
  }
  io::Complex K{5, boundary4};
  TopologyReport R = analyse_topology(K, 3);
  EXPECT_EQ(R.bad_links, 0);
  EXPECT_EQ(R.unknown_links, 0);
  EXPECT_EQ(R.euler, 0);
  EXPECT_EQ(R.betti_z2, (std::vector<long>{1, 0, 0, 1}));
  EXPECT_EQ(R.betti_z3, (std::vector<long>{1, 0, 0, 1}));
  // Two 3-spheres sharing vertex 0: its link is two disjoint 2-spheres; every other link is fine.
  Simplices wedge = boundary4;
  for (auto t : boundary4) {
    for (int& v : t)
      if (v) v += 4;
    wedge.push_back(t);
  }
  io::Complex W{9, wedge};
  R = analyse_topology(W, 3);
  EXPECT_EQ(R.bad_links, 1);
  EXPECT_EQ(R.bad_link_example, 0);
  std::string why;
  Simplices link0;
  for (const auto& t : wedge)
    if (t[0] == 0) link0.push_back(std::vector<int>(t.begin() + 1, t.end()));
  EXPECT_EQ(is_sphere(link0, 2, &why), Tri::no);
  EXPECT_EQ(R.bad_link_reason, why);
  // The same report with the links and the fields in parallel; also on three wedges (three bad
  // links: the first by index is named) and with an uncovered vertex.
  Simplices more = wedge;
  for (auto t : boundary4) {
    for (int& v : t) v = v ? v + 8 : 4;  // shares vertex 4 with the second sphere
    more.push_back(t);
  }
  for (const io::Complex& C : {W, io::Complex{14, more}}) {
    const TopologyReport A = analyse_topology(C, 3, nullptr, 1), B = analyse_topology(C, 3, nullptr, 3);
    EXPECT_EQ(A.bad_links, B.bad_links);
    EXPECT_EQ(A.bad_link_example, B.bad_link_example);
    EXPECT_EQ(A.bad_link_reason, B.bad_link_reason);
    EXPECT_EQ(A.uncovered_vertices, B.uncovered_vertices);
    EXPECT_EQ(A.betti_z2, B.betti_z2);
    EXPECT_EQ(A.betti_z3, B.betti_z3);
  }
  const TopologyReport M = analyse_topology(io::Complex{14, more}, 3, nullptr, 2);
  EXPECT_EQ(M.bad_links, 2);  // vertices 0 and 4
  EXPECT_EQ(M.bad_link_example, 0);
  EXPECT_EQ(M.uncovered_vertices, 1);  // vertex 13
}

}  // namespace
}  // namespace delcert::certify
