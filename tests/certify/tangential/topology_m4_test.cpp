// Topology at m = 4 (issue 12): vertex links are 3-manifolds, recognised as 3-spheres by Regina
// (topology/three_sphere.hpp) after certify/'s own checks. The Poincare homology sphere, which the
// homology over Z/2 and Z/3 cannot tell from S^3, comes from Regina's census, subdivided into a
// simplicial complex (tests/topology/regina_complex.hpp).
#include <gtest/gtest.h>

#include <algorithm>

#include <regina-normal/triangulation/example3.h>

#include "certify/tangential/topology.hpp"
#include "tests/topology/regina_complex.hpp"

namespace delcert::certify {
namespace {

using Simplices = std::vector<std::vector<int>>;

// The boundary of the 5-dimensional cross-polytope (vertices +-e_i as i and i + 5): an S^4 with
// 32 4-simplices, every vertex link the boundary of the 4-dimensional cross-polytope.
Simplices cross_polytope_boundary_4() {
  Simplices out;
  for (int signs = 0; signs < 32; ++signs) {
    std::vector<int> s;
    for (int i = 0; i < 5; ++i) s.push_back(i + ((signs >> i) & 1) * 5);
    out.push_back(s);
  }
  return out;
}

// The suspension of a 3-complex with vertices 0..n-1, by apexes n and n + 1.
Simplices suspension(const Simplices& K, int n) {
  Simplices out;
  for (int apex : {n, n + 1})
    for (auto s : K) {
      s.push_back(apex);
      out.push_back(s);
    }
  return out;
}

int vertex_count(const Simplices& K) {
  int n = 0;
  for (const auto& s : K)
    for (int v : s) n = std::max(n, v + 1);
  return n;
}

TEST(TopologyM4, FourSpheresHaveRecognisedLinks) {
  {
    io::Complex K{10, cross_polytope_boundary_4()};
    TopologyReport R = analyse_topology(K, 4);
    EXPECT_EQ(R.bad_links, 0) << R.bad_link_reason;
    EXPECT_EQ(R.unknown_links, 0) << R.bad_link_reason;
    EXPECT_EQ(R.betti_z2, (std::vector<long>{1, 0, 0, 0, 1}));
  }
  // The suspension of the boundary of the 4-simplex: S^4 again, two links of 5 tetrahedra and
  // five links that are suspensions of 2-spheres.
  Simplices b4;
  for (int skip = 0; skip < 5; ++skip) {
    std::vector<int> t;
    for (int v = 0; v < 5; ++v)
      if (v != skip) t.push_back(v);
    b4.push_back(t);
  }
  io::Complex K{7, suspension(b4, 5)};
  TopologyReport R = analyse_topology(K, 4);
  EXPECT_EQ(R.bad_links + R.unknown_links, 0) << R.bad_link_reason;
}

// L(5,1) and the Poincare sphere are homology 3-spheres over Z/2 and Z/3: is_sphere used to say
// `unknown`; Regina says no.
TEST(TopologyM4, HomologySpheresThatAreNotSpheres) {
  std::string why;
  EXPECT_EQ(is_sphere(tests::simplicial_complex(regina::Example<3>::lens(5, 1)), 3, &why), Tri::no);
  EXPECT_NE(why.find("Z_5"), std::string::npos) << why;
  EXPECT_EQ(is_sphere(tests::simplicial_complex(regina::Example<3>::poincare()), 3, &why), Tri::no);
  EXPECT_NE(why.find("other than the 3-sphere"), std::string::npos) << why;
}

// The suspension of the Poincare homology sphere P: a homology 4-sphere that is not a manifold
// (the two apexes have link P). Its topology must never pass: both apexes are bad links, named.
TEST(TopologyM4, SuspendedPoincareSphereIsRefuted) {
  const Simplices P = tests::simplicial_complex(regina::Example<3>::poincare());
  const int n = vertex_count(P);
  io::Complex K{static_cast<std::size_t>(n + 2), suspension(P, n)};
  TopologyReport R = analyse_topology(K, 4);
  EXPECT_EQ(R.bad_links, 2);
  EXPECT_EQ(R.unknown_links, 0) << R.bad_link_reason;
  EXPECT_EQ(R.bad_link_example, n);
  EXPECT_NE(R.bad_link_reason.find("3-manifold other than the 3-sphere"), std::string::npos) << R.bad_link_reason;
  EXPECT_EQ(R.betti_z2, (std::vector<long>{1, 0, 0, 0, 1}));  // what homology alone would accept
  EXPECT_EQ(R.betti_z3, (std::vector<long>{1, 0, 0, 0, 1}));
}

}  // namespace
}  // namespace delcert::certify
