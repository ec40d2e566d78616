// Test helper: a Regina 3-manifold triangulation as a vertex-labelled simplicial complex (what
// delcert's complexes are), for tests that take their non-spheres from Regina's census.
#pragma once

#include <algorithm>
#include <vector>

#include <regina-normal/triangulation/dim3.h>

namespace delcert::tests {

// Every face of T, as the sorted indices of its vertices.
template <int k, typename Faces>
std::vector<std::vector<int>> face_labels(const Faces& faces) {
  std::vector<std::vector<int>> out;
  for (auto* f : faces) {
    std::vector<int> s;
    for (int i = 0; i <= k; ++i) s.push_back(static_cast<int>(f->vertex(i)->index()));
    std::sort(s.begin(), s.end());
    out.push_back(s);
  }
  return out;
}

// Is T a simplicial complex: every face has distinct vertices, and no two faces of one dimension
// have the same vertices?
inline bool is_simplicial(const regina::Triangulation<3>& T) {
  auto distinct = [](std::vector<std::vector<int>> faces) {
    for (const auto& s : faces)
      if (std::adjacent_find(s.begin(), s.end()) != s.end()) return false;
    std::sort(faces.begin(), faces.end());
    return std::adjacent_find(faces.begin(), faces.end()) == faces.end();
  };
  return distinct(face_labels<1>(T.edges())) && distinct(face_labels<2>(T.triangles())) &&
         distinct(face_labels<3>(T.tetrahedra()));
}

// T's tetrahedra by vertex index, after barycentric subdivisions until T is a simplicial complex
// (Regina's census triangulations are not: few tetrahedra, glued to themselves; the second
// subdivision of any triangulation is simplicial).
inline std::vector<std::vector<int>> simplicial_complex(regina::Triangulation<3> T) {
  while (!is_simplicial(T)) T.subdivide();
  return face_labels<3>(T.tetrahedra());
}

}  // namespace delcert::tests
