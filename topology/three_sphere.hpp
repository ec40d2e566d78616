// Is a closed simplicial 3-complex a triangulated 3-sphere? Decided by Regina's 3-sphere
// recognition (Rubinstein's algorithm with Jaco-Rubinstein crushing; Burton's implementation in
// libregina-engine), an exact combinatorial decision procedure. certify/ asks it for the vertex
// links of 4-manifold complexes, once per link, after its own checks (docs/design.md §5: a link
// check by a maintained library, outside the numeric predicates). This header names no Regina type.
#pragma once

#include <string>
#include <vector>

namespace delcert::topology {

enum class SphereAnswer { yes, no, unknown };

// `tetrahedra`: the 3-simplices of a simplicial complex, by vertex labels (any ints; each
// tetrahedron 4 distinct labels, no tetrahedron twice, else the answer is no). yes: the complex is a triangulated
// 3-sphere; no: it is not (not a closed connected 3-manifold, or a 3-manifold other than S^3);
// unknown: Regina could not decide (it threw). `why` (if not null) gets the reason for no and
// unknown, and a short confirmation for yes.
SphereAnswer recognise_3_sphere(const std::vector<std::vector<int>>& tetrahedra, std::string* why);

// "Regina 7.3 (3-sphere recognition)": the library and version that decides, for the certificate.
std::string recogniser();

}  // namespace delcert::topology
