// gudhi_export: GUDHI 3.7's tangential complex of a point set, written as a delcert-complex file,
// so that delcert-certify can judge a complex made by another producer (fixtures/report/ holds
// one, refuted, shown by the HTML report's test). Not a benchmark: built here because bench/ is
// where GUDHI is linked. It gives GUDHI the very points and tangent planes delcert uses
// (bench/gudhi_input.hpp) and runs it on one thread, so the output is deterministic.
//
//   gudhi_export MANIFOLD POINTS OUT     e.g. gudhi_export builtin:clifford-torus-2 net.txt gudhi.complex
//
// The file lists the m-simplices of the union of GUDHI's stars, inconsistent ones included
// (Tangential_complex::create_complex), with no perturbation applied.
#include "bench/gudhi_input.hpp"

#include <gudhi/Simplex_tree.h>

#include <iostream>
#include <vector>

#include "core/manifold/manifold.hpp"
#include "core/tangential/tangent_planes.hpp"
#include "io/complex.hpp"
#include "io/points.hpp"
#include "io/spec.hpp"

namespace {

using namespace delcert;

template <int M>
io::Complex gudhi_complex(const io::PointSet& points, const tangential::TangentPlanes& planes) {
  const bench::GudhiInput<M> gudhi(points, planes);
  tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
  typename bench::GudhiInput<M>::TC tc(gudhi.points, M, gudhi.kernel);
  tc.set_tangent_planes(gudhi.bases);
  tc.compute_tangential_complex();
  Gudhi::Simplex_tree<> tree;
  tc.create_complex(tree);
  io::Complex out;
  out.num_vertices = points.size();
  for (auto sh : tree.skeleton_simplex_range(M)) {
    if (tree.dimension(sh) != M) continue;
    std::vector<int> s;
    for (auto v : tree.simplex_vertex_range(sh)) s.push_back(static_cast<int>(v));
    std::sort(s.begin(), s.end());
    out.simplices.push_back(s);
  }
  std::sort(out.simplices.begin(), out.simplices.end());
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 4) {
    std::cerr << "usage: gudhi_export MANIFOLD POINTS OUT\n";
    return 2;
  }
  try {
    manifold::Manifold manifold(io::read_spec(argv[1]));
    io::PointSet points = io::read_points(argv[2]);
    auto planes = tangential::compute_tangent_planes(manifold, points, 1);
    io::Complex c;
    switch (manifold.intrinsic_dimension()) {
      case 2: c = gudhi_complex<2>(points, planes); break;
      case 3: c = gudhi_complex<3>(points, planes); break;
      default: std::cerr << "gudhi_export: m = 2 or 3 only\n"; return 2;
    }
    io::write_complex(argv[3], c);
    std::cout << c.simplices.size() << " simplices of dimension " << manifold.intrinsic_dimension() << "\n";
  } catch (const std::exception& e) {
    std::cerr << "gudhi_export: " << e.what() << "\n";
    return 2;
  }
}
