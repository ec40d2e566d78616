// Combinatorial checks of a simplicial complex given by its maximal simplices: f-vector, Euler
// characteristic, purity and the pseudomanifold conditions.
#pragma once

#include <cstddef>
#include <vector>

#include "io/complex.hpp"

namespace delcert::tangential {

struct ComplexTopology {
  int dimension = -1;                             // largest simplex dimension (-1: empty)
  std::vector<std::size_t> maximal_by_dimension;  // [d]: maximal d-simplices
  std::vector<std::size_t> faces_by_dimension;    // [d]: all d-simplices (the f-vector)
  long euler_characteristic = 0;                  // sum_d (-1)^d f_d
  bool pure = false;                              // every maximal simplex has dimension `dimension`
  std::size_t ridges = 0;                         // (dimension-1)-faces of the top simplices
  std::size_t boundary_ridges = 0;                // ridges in exactly one top simplex
  std::size_t singular_ridges = 0;                // ridges in three or more top simplices
  std::size_t components = 0;                     // classes of top simplices joined through ridges
  // Pure, every ridge in exactly two top simplices, and strongly connected (one component).
  bool pseudomanifold = false;
};

ComplexTopology analyze_complex(const io::Complex& complex);

}  // namespace delcert::tangential
