// topology/three_sphere: Regina's 3-sphere recognition on vertex-labelled simplicial complexes.
// The non-spheres come from Regina's own census (the test, unlike topology/, uses Regina directly),
// turned into simplicial complexes by tests/topology/regina_complex.hpp.
#include "topology/three_sphere.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <regina-normal/core/engine.h>
#include <regina-normal/triangulation/example3.h>

#include "tests/topology/regina_complex.hpp"

namespace {

using delcert::topology::recognise_3_sphere;
using delcert::topology::SphereAnswer;
using delcert::tests::simplicial_complex;

std::vector<std::vector<int>> simplex_boundary_3() {  // the boundary of the 4-simplex: 5 tetrahedra
  std::vector<std::vector<int>> out;
  for (int skip = 0; skip < 5; ++skip) {
    std::vector<int> t;
    for (int v = 0; v < 5; ++v)
      if (v != skip) t.push_back(v);
    out.push_back(t);
  }
  return out;
}

std::vector<std::vector<int>> cross_polytope_boundary_3() {  // vertices +-e_i as i and i + 4: 16 tetrahedra
  std::vector<std::vector<int>> out;
  for (int signs = 0; signs < 16; ++signs) {
    std::vector<int> t;
    for (int i = 0; i < 4; ++i) t.push_back(i + ((signs >> i) & 1) * 4);
    out.push_back(t);
  }
  return out;
}

TEST(ThreeSphere, SpheresAreRecognised) {
  std::string why;
  EXPECT_EQ(recognise_3_sphere(simplex_boundary_3(), &why), SphereAnswer::yes) << why;
  EXPECT_NE(why.find("3-sphere"), std::string::npos) << why;
  EXPECT_EQ(recognise_3_sphere(cross_polytope_boundary_3(), &why), SphereAnswer::yes) << why;
  // Labels and orders are arbitrary: relabel, shuffle the tetrahedra and their vertices.
  auto K = cross_polytope_boundary_3();
  for (auto& t : K) {
    for (int& v : t) v = 1000 - 7 * v;
    std::rotate(t.begin(), t.begin() + 1 + (t[0] % 3 + 3) % 3, t.end());
  }
  std::reverse(K.begin(), K.end());
  std::swap(K[2], K[9]);
  EXPECT_EQ(recognise_3_sphere(K, &why), SphereAnswer::yes) << why;
  // A barycentric subdivision of Regina's own one-tetrahedron 3-sphere.
  EXPECT_EQ(recognise_3_sphere(simplicial_complex(regina::Example<3>::sphere()), &why), SphereAnswer::yes) << why;
}

// The cases a homology test over Z/2 and Z/3 cannot tell from S^3 (L(5,1), the Poincare homology
// sphere) and one it can (S^2 x S^1): Regina says no, and its H_1 shows that the gluing of the
// labelled complex is the right one.
TEST(ThreeSphere, OtherThreeManifoldsAreNot) {
  std::string why;
  auto poincare = simplicial_complex(regina::Example<3>::poincare());
  EXPECT_EQ(recognise_3_sphere(poincare, &why), SphereAnswer::no) << why;
  EXPECT_NE(why.find("H_1 = 0"), std::string::npos) << why;
  EXPECT_EQ(recognise_3_sphere(simplicial_complex(regina::Example<3>::lens(5, 1)), &why), SphereAnswer::no) << why;
  EXPECT_NE(why.find("H_1 = Z_5"), std::string::npos) << why;
  EXPECT_EQ(recognise_3_sphere(simplicial_complex(regina::Example<3>::s2xs1()), &why), SphereAnswer::no) << why;
  EXPECT_NE(why.find("H_1 = Z"), std::string::npos) << why;
}

TEST(ThreeSphere, NonManifoldsAreNot) {
  std::string why;
  EXPECT_EQ(recognise_3_sphere({}, &why), SphereAnswer::no);
  EXPECT_EQ(recognise_3_sphere({{0, 1, 2}}, &why), SphereAnswer::no);
  EXPECT_EQ(recognise_3_sphere({{0, 1, 2, 2}}, &why), SphereAnswer::no);
  auto K = simplex_boundary_3();
  K.push_back(K[0]);
  EXPECT_EQ(recognise_3_sphere(K, &why), SphereAnswer::no);
  EXPECT_NE(why.find("twice"), std::string::npos) << why;
  // One tetrahedron missing: a ball, with boundary triangles in 1 tetrahedron.
  K = simplex_boundary_3();
  K.pop_back();
  EXPECT_EQ(recognise_3_sphere(K, &why), SphereAnswer::no);
  EXPECT_NE(why.find("lies in 1 tetrahedra"), std::string::npos) << why;
  // Two 3-spheres sharing a vertex: connected, but the shared vertex's link is two 2-spheres.
  K = simplex_boundary_3();
  for (auto t : cross_polytope_boundary_3()) {
    for (int& v : t) v = v == 0 ? 0 : v + 10;
    K.push_back(t);
  }
  EXPECT_EQ(recognise_3_sphere(K, &why), SphereAnswer::no);
  EXPECT_NE(why.find("vertex has a disconnected link"), std::string::npos) << why;
  // Two disjoint spheres.
  K = simplex_boundary_3();
  for (auto t : simplex_boundary_3()) {
    for (int& v : t) v += 10;
    K.push_back(t);
  }
  EXPECT_EQ(recognise_3_sphere(K, &why), SphereAnswer::no);
}

TEST(ThreeSphere, TheRecogniserNamesReginasVersion) {
  EXPECT_EQ(delcert::topology::recogniser(),
            std::string("Regina ") + regina::versionString() + " (3-sphere recognition)");
}

}  // namespace
