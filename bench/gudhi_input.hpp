// GUDHI 3.7's Tangential_complex as the benchmarks' peer, and the one conversion that gives it the
// very points and tangent planes delcert uses (docs/design.md §11: same input, same planes).
#pragma once

#ifndef GUDHI_USE_TBB
#define GUDHI_USE_TBB  // GUDHI's parallel mode; bench/CMakeLists.txt links TBB
#endif
// GCC 12 false positives inside Eigen/CGAL/GUDHI headers (see core/tangential/regular_star_cgal.cpp).
#pragma GCC diagnostic ignored "-Warray-bounds"
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <CGAL/Epick_d.h>
#include <gudhi/Tangential_complex.h>
#include <tbb/global_control.h>

#include <vector>

#include "core/tangential/tangent_planes.hpp"
#include "io/points.hpp"

namespace delcert::bench {

template <int M>
struct GudhiInput {
  using K = CGAL::Epick_d<CGAL::Dynamic_dimension_tag>;
  using TC = Gudhi::tangential_complex::Tangential_complex<K, CGAL::Dimension_tag<M>, CGAL::Parallel_tag>;

  K kernel;
  std::vector<K::Point_d> points;       // #P, the input points
  typename TC::TS_container bases;      // #P tangent bases, M vectors each (for set_tangent_planes)

  GudhiInput(const io::PointSet& ps, const tangential::TangentPlanes& planes) {
    const int N = ps.dimension;
    points.reserve(ps.size());
    bases.reserve(ps.size());
    for (std::size_t i = 0; i < ps.size(); ++i) {
      auto p = ps.point(i);
      points.push_back(kernel.construct_point_d_object()(N, p.begin(), p.end()));
      std::vector<typename K::Vector_d> vectors;
      auto b = planes.basis(i);
      for (int j = 0; j < M; ++j)
        vectors.push_back(kernel.construct_vector_d_object()(N, b.begin() + j * N, b.begin() + (j + 1) * N));
      bases.emplace_back(i, vectors);
    }
  }
};

}  // namespace delcert::bench
