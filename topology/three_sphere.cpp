#include "topology/three_sphere.hpp"

#include <algorithm>
#include <array>
#include <cstddef>
#include <exception>
#include <tuple>
#include <utility>

#include <regina-normal/core/engine.h>  // prefixed: "core/" is our producer's folder
#include <regina-normal/triangulation/dim3.h>

namespace delcert::topology {

std::string recogniser() { return std::string("Regina ") + regina::versionString() + " (3-sphere recognition)"; }

SphereAnswer recognise_3_sphere(const std::vector<std::vector<int>>& tetrahedra, std::string* why) {
  auto answer = [&](SphereAnswer a, std::string w) {
    if (why) *why = std::move(w);
    return a;
  };
  auto no = [&](const std::string& w) { return answer(SphereAnswer::no, w); };
  if (tetrahedra.empty()) return no("no tetrahedra");
  std::vector<std::array<int, 4>> tets;
  for (const auto& s : tetrahedra) {
    if (s.size() != 4) return no("a simplex with " + std::to_string(s.size()) + " vertices, not 4");
    auto& t = tets.emplace_back(std::array<int, 4>{s[0], s[1], s[2], s[3]});
    std::sort(t.begin(), t.end());
    if (std::adjacent_find(t.begin(), t.end()) != t.end()) return no("a tetrahedron with a repeated vertex");
  }
  {
    auto sorted = tets;
    std::sort(sorted.begin(), sorted.end());
    if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end()) return no("a tetrahedron listed twice");
  }
  // Facet f of a tetrahedron is the triangle opposite its vertex f (Regina's numbering); the
  // vertices of tetrahedron j are tets[j][0..3].
  struct Side {
    std::array<int, 3> triangle;
    std::size_t tet;
    int facet;
    bool operator<(const Side& o) const { return std::tie(triangle, tet, facet) < std::tie(o.triangle, o.tet, o.facet); }
  };
  std::vector<Side> sides;
  std::vector<std::pair<int, int>> edges;
  std::vector<int> vertices;
  for (std::size_t j = 0; j < tets.size(); ++j) {
    const auto& t = tets[j];
    for (int f = 0; f < 4; ++f) {
      std::array<int, 3> tri{};
      for (int i = 0, n = 0; i < 4; ++i)
        if (i != f) tri[n++] = t[i];
      sides.push_back({tri, j, f});
      vertices.push_back(t[f]);
      for (int g = f + 1; g < 4; ++g) edges.emplace_back(t[f], t[g]);
    }
  }
  std::sort(sides.begin(), sides.end());
  std::sort(vertices.begin(), vertices.end());
  vertices.erase(std::unique(vertices.begin(), vertices.end()), vertices.end());
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  try {
    regina::Triangulation<3> T;
    for (std::size_t j = 0; j < tets.size(); ++j) T.newTetrahedron();
    for (std::size_t a = 0; a < sides.size();) {
      std::size_t b = a;
      while (b < sides.size() && sides[b].triangle == sides[a].triangle) ++b;
      if (b - a != 2) {
        const auto& t = sides[a].triangle;
        return no("triangle {" + std::to_string(t[0]) + "," + std::to_string(t[1]) + "," + std::to_string(t[2]) +
                  "} lies in " + std::to_string(b - a) + " tetrahedra, not 2");
      }
      // Glue facet x.facet of x.tet to facet y.facet of y.tet: vertex i of x.tet goes to the vertex
      // of y.tet with the same label, the vertex opposite the shared triangle to the opposite one.
      const Side& x = sides[a];
      const Side& y = sides[a + 1];
      std::array<int, 4> image{};
      for (int i = 0; i < 4; ++i) {
        const auto& to = tets[y.tet];
        image[i] = i == x.facet ? y.facet : static_cast<int>(std::find(to.begin(), to.end(), tets[x.tet][i]) - to.begin());
      }
      T.tetrahedron(x.tet)->join(x.facet, T.tetrahedron(y.tet), regina::Perm<4>(image[0], image[1], image[2], image[3]));
      a = b;
    }
    // Regina's triangulation is the complex with its vertices and edges pulled apart wherever
    // their links are disconnected: the same space only when nothing was pulled apart.
    if (T.countVertices() != vertices.size())
      return no("not a 3-manifold: a vertex has a disconnected link (" + std::to_string(vertices.size()) +
                " vertices, " + std::to_string(T.countVertices()) + " after separating their links)");
    if (T.countEdges() != edges.size())
      return no("not a 3-manifold: an edge has a disconnected link (" + std::to_string(edges.size()) + " edges, " +
                std::to_string(T.countEdges()) + " after separating their links)");
    if (!T.isConnected()) return no("not connected");
    if (!T.isValid()) return no("not a 3-manifold: a vertex link is neither a sphere nor a disc");
    if (!T.isClosed()) return no("not a closed 3-manifold: a vertex link is not a 2-sphere");
    // Homeomorphism-preserving moves first: Regina's recognition on a large unsimplified
    // triangulation is far slower (the subdivided Poincare sphere, 2880 tetrahedra: minutes, not
    // a second).
    T.intelligentSimplify();
    if (T.isSphere()) return answer(SphereAnswer::yes, "a 3-sphere (" + recogniser() + ")");
    return no("a closed 3-manifold other than the 3-sphere, H_1 = " + T.homology().str() + " (" + recogniser() + ")");
  } catch (const std::exception& e) {
    return answer(SphereAnswer::unknown, std::string("Regina could not decide: ") + e.what());
  }
}

}  // namespace delcert::topology
