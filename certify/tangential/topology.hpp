// Check 8: global topology of a complex, by the certifier's own combinatorics: purity,
// closed pseudomanifold, vertex links that are spheres, Euler characteristic and Betti numbers
// over Z/2 and Z/3 by boundary-matrix reduction.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "exact/tri.hpp"
#include "io/complex.hpp"

namespace delcert::certify {

// All faces of a simplicial complex, by dimension; each face a sorted vertex list, faces sorted.
struct FaceLattice {
  int dimension = -1;                      // top dimension
  std::vector<std::vector<int>> flat;      // flat[k]: #k-faces by (k+1), row-major, lexicographic
  // first[k][v]..first[k][v + 1]: the k-faces whose first vertex is v (v < max vertex + 1), to
  // narrow find(); empty: search all of flat[k].
  std::vector<std::vector<long>> first;
  std::size_t count(int k) const { return k <= dimension ? flat[k].size() / (k + 1) : 0; }
  // Index of a sorted k-face, or -1.
  long find(int k, const int* face) const;
};

// A simplex with n vertices has 2^n - 1 faces: the lattice is built only for simplices of at most
// kMaxLatticeVertices vertices (far above m + 1 <= 7; also keeps every `1u << n` defined) and
// throws std::invalid_argument beyond. Callers drop larger simplices first (certify.cpp refutes
// them as simplices of the wrong dimension; analyse_topology skips the lattice for them).
inline constexpr int kMaxLatticeVertices = 16;
FaceLattice face_lattice(const std::vector<std::vector<int>>& maximal_simplices, int threads = 1);

// Ranks of the boundary maps over Z/p (p prime, small): rank[k] = rank of d_k: C_k -> C_{k-1}
// (rank[0] = 0). Column reduction with clearing, top dimension first.
std::vector<long> boundary_ranks(const FaceLattice& lattice, int p);

// Betti numbers b_0..b_dim over Z/p.
std::vector<long> betti_numbers(const FaceLattice& lattice, int p);

using exact::Tri;

// Is the (pure, d-dimensional) complex given by its maximal simplices a triangulated d-sphere?
// Decided for d <= 2 (d = 0: two points; d = 1: one cycle; d = 2: connected closed surface, every
// vertex link a cycle, Euler characteristic 2) and for d = 3 (a homology sphere over Z/2, Z/3 goes
// to Regina's S^3 recognition, topology/three_sphere.hpp). For d >= 4 the answer is at best `unknown`.
Tri is_sphere(const std::vector<std::vector<int>>& simplices, int d, std::string* why);

struct TopologyReport {
  int m = 0;
  bool pure = true;                      // every maximal simplex has dimension m
  std::vector<int> impure_example;       // a maximal simplex of another dimension
  long boundary_ridges = 0;              // (m-1)-faces in 1 m-simplex
  long singular_ridges = 0;              // (m-1)-faces in >= 3 m-simplices
  std::vector<int> ridge_example;        // a ridge not in exactly 2 m-simplices
  long ridge_example_count = 0;
  long strong_components = 0;            // of the dual graph (m-simplices adjacent across ridges)
  long uncovered_vertices = 0;           // points in no simplex
  long bad_links = 0, unknown_links = 0; // vertex links that are not / not known to be (m-1)-spheres
  long bad_link_example = -1;
  std::string bad_link_reason;
  std::vector<long> f;                   // face counts f_0..f_dim
  long euler = 0;
  std::vector<long> betti_z2, betti_z3;
};

// `lattice`: face_lattice(complex.simplices) when the caller has it already (else built here).
// `threads`: the m = 3 vertex links and the two fields' ranks run in parallel; the report does not
// depend on it.
TopologyReport analyse_topology(const io::Complex& complex, int m, const FaceLattice* lattice = nullptr, int threads = 1);

}  // namespace delcert::certify
