// The regular-triangulation path: the only translation unit of delcert that instantiates a CGAL
// triangulation (dD, static dimension m = 2, 3, 4; Epick_d's filtered exact predicates, with
// CGAL's symbolic perturbation for exact degeneracies). Used where the certified power-cell
// clipping cannot decide a sign, and as the reference in tests (StarPath::regular_triangulation).
// GCC 12 reports -Warray-bounds false positives inside Eigen's fixed-capacity matrices used by
// CGAL's dD kernel (middle-end warnings, located in the headers, so the pragma must precede them).
#pragma GCC diagnostic ignored "-Warray-bounds"
#include <CGAL/Epick_d.h>
#include <CGAL/Regular_triangulation.h>
#include <CGAL/Regular_triangulation_traits_adapter.h>
#include <CGAL/Triangulation_data_structure.h>
#include <CGAL/Triangulation_full_cell.h>
#include <CGAL/Triangulation_vertex.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <vector>

#include "core/tangential/detail/local_problem.hpp"

namespace delcert::tangential::detail {

namespace {

template <int M>
void regular_star(Neighbourhood& nb, LocalStar& out) {
  using K = CGAL::Epick_d<CGAL::Dimension_tag<M>>;
  using Traits = CGAL::Regular_triangulation_traits_adapter<K>;
  // Vertex data: -1 for p, local index + 1 for a neighbour, 0 while unset.
  using Vb = CGAL::Triangulation_vertex<Traits, int>;
  using Cb = CGAL::Triangulation_full_cell<Traits>;
  using TDS = CGAL::Triangulation_data_structure<CGAL::Dimension_tag<M>, Vb, Cb>;
  using RT = CGAL::Regular_triangulation<K, TDS>;
  using Vertex_handle = typename RT::Vertex_handle;
  using Full_cell_handle = typename RT::Full_cell_handle;

  const K kernel;
  auto make_point = kernel.construct_point_d_object();
  auto make_weighted = kernel.construct_weighted_point_d_object();

  auto weight = kernel.compute_weight_d_object();
  auto bare = kernel.point_drop_weight_d_object();
  auto coordinate = kernel.compute_coordinate_d_object();
  auto same_point = [&](const typename K::Weighted_point_d& wp, const LocalPoint& q) {
    if (weight(wp) != q.w) return false;
    auto pt = bare(wp);
    for (int j = 0; j < M; ++j)
      if (coordinate(pt, j) != q.u[j]) return false;
    return true;
  };

  RT tr(M);
  const double origin[M] = {};
  Vertex_handle vp = tr.insert(make_weighted(make_point(M, origin, origin + M), 0.0));
  vp->data() = -1;

  std::vector<Full_cell_handle> incident;
  const LocalPoint* rows[kMaxM];
  // Squared radius bound of the current star (infinite while it is not a closed fan).
  auto star_radius2 = [&]() {
    if (tr.current_dimension() < M) return std::numeric_limits<double>::infinity();
    incident.clear();
    tr.incident_full_cells(vp, std::back_inserter(incident));
    double r2 = 0;
    for (Full_cell_handle c : incident) {
      if (tr.is_infinite(c)) return std::numeric_limits<double>::infinity();
      int k = 0;
      for (int j = 0; j <= M; ++j) {
        int d = c->vertex(j)->data();
        if (d > 0) rows[k++] = &nb[d - 1];
      }
      std::sort(rows, rows + k, [](const LocalPoint* x, const LocalPoint* y) { return x->global < y->global; });
      double v[kMaxM];
      if (k != M || !solve_centre(M, rows, v)) return std::numeric_limits<double>::infinity();
      double s = 0;
      for (int j = 0; j < M; ++j) s += v[j] * v[j];
      r2 = std::max(r2, s);
    }
    // The centre is only approximate here (the exact cell is decided by CGAL): a wide margin.
    return r2 * (1 + 1e-6);
  };

  double r2 = std::numeric_limits<double>::infinity();
  std::size_t i = 0;
  for (;; ++i) {
    if (!nb.ensure(i + 1)) break;
    const LocalPoint& q = nb[i];
    if (q.d2 > 4 * r2 * (1 + kCompletenessMargin)) break;
    Vertex_handle v = tr.insert_if_in_star(make_weighted(make_point(M, q.u, q.u + M), q.w), vp);
    if (v == Vertex_handle()) continue;  // q is hidden or does not touch p's star
    const int d = v->data();
    // d > 0 with a different weighted point: q has the same projection as an earlier neighbour
    // and a larger weight, so CGAL replaced that vertex's point by q's (the earlier one is hidden).
    if (d == 0 || (d > 0 && !same_point(v->point(), nb[d - 1]))) {
      v->data() = static_cast<int>(i) + 1;
      r2 = star_radius2();
    }
  }
  out.considered = i;
  out.cells.clear();
  out.closed = tr.current_dimension() == M;
  if (tr.current_dimension() < M) return;
  incident.clear();
  tr.incident_full_cells(vp, std::back_inserter(incident));
  for (Full_cell_handle c : incident) {
    if (tr.is_infinite(c)) {
      out.closed = false;
      continue;
    }
    for (int j = 0; j <= M; ++j) {
      int d = c->vertex(j)->data();
      if (d > 0) out.cells.push_back(d - 1);
    }
  }
}

}  // namespace

void regular_triangulation_star(Neighbourhood& nb, LocalStar& out) {
  switch (nb.m()) {
    case 2: regular_star<2>(nb, out); break;
    case 3: regular_star<3>(nb, out); break;
    default: regular_star<4>(nb, out); break;
  }
}

}  // namespace delcert::tangential::detail
