#include "certify/intrinsic/intrinsic.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

#include "exact/polynomial.hpp"

#include "certify/intrinsic/engines.hpp"
#include "certify/intrinsic/general.hpp"

namespace delcert::certify {

namespace {

// F = lambda G for some rational lambda != 0 (exact polynomial identity).
bool proportional(const exact::Polynomial& F, const exact::Polynomial& G) {
  if (F.is_zero() || G.is_zero()) return false;
  const exact::Term& f0 = F.terms().front();
  for (const exact::Term& g : G.terms())
    if (g.monomial == f0.monomial) return F == G.scaled(mpq_class(f0.coefficient / g.coefficient));
  return false;
}

// sum_v (x_v - c_v)^2 - r^2 over the given variables.
exact::Polynomial sphere_polynomial(const std::vector<int>& vars, const std::vector<mpq_class>& centre,
                                    const mpq_class& r, int N) {
  exact::Polynomial P = exact::Polynomial::constant(-r * r, N);
  for (std::size_t i = 0; i < vars.size(); ++i) {
    const exact::Polynomial d = exact::Polynomial::variable(vars[i], N) - exact::Polynomial::constant(centre[i], N);
    P = P + d * d;
  }
  return P;
}

// The declared metric is used only when the equations are exactly those of the declared shape
// (up to nonzero rational factors and order): then M is that shape, and the closed-form geodesic
// distance is M's own. Otherwise the declaration is not trusted.
// The equations of SO(3): the rows (or the columns) of x1..x9 (row-major) orthonormal.
std::vector<exact::Polynomial> so3_polynomials(bool rows, int N) {
  auto x = [&](int i, int j) { return exact::Polynomial::variable(rows ? 3 * i + j : 3 * j + i, N); };
  std::vector<exact::Polynomial> e;
  for (int i = 0; i < 3; ++i)
    for (int k = i; k < 3; ++k)
      e.push_back(x(i, 0) * x(k, 0) + x(i, 1) * x(k, 1) + x(i, 2) * x(k, 2) -
                  exact::Polynomial::constant(mpq_class(i == k), N));
  return e;
}

// Each equation proportional to a distinct one of `expected`, "" when so.
std::string unmatched(const std::vector<exact::Polynomial>& equations, const std::vector<exact::Polynomial>& expected) {
  if (equations.size() != expected.size()) return "the spec has another number of equations than its metric";
  std::vector<bool> used(expected.size(), false);
  for (std::size_t i = 0; i < equations.size(); ++i) {
    bool found = false;
    for (std::size_t j = 0; j < expected.size() && !found; ++j)
      if (!used[j] && proportional(equations[i], expected[j])) used[j] = found = true;
    if (!found)
      return "equation " + std::to_string(i + 1) + " is not (a multiple of) an equation of the declared metric's shape";
  }
  return "";
}

// The declared metric is used only when the equations are exactly those of the declared shape
// (up to nonzero rational factors and order): then M is that shape, and the closed-form geodesic
// distance is M's own. Otherwise the declaration is not trusted.
std::string metric_mismatch(const io::ManifoldSpec& spec, const io::ShapeSpec& g) {
  const int N = spec.ambient_dimension;
  if (g.kind == io::ShapeSpec::Kind::so3) {
    // O(3) has two components; M is SO(3) only with a selector that is a positive multiple of det.
    const std::string by_rows = unmatched(spec.equations, so3_polynomials(true, N));
    if (!by_rows.empty() && !unmatched(spec.equations, so3_polynomials(false, N)).empty()) return by_rows;
    auto x = [&](int i, int j) { return exact::Polynomial::variable(3 * i + j, N); };
    const exact::Polynomial det = x(0, 0) * (x(1, 1) * x(2, 2) - x(1, 2) * x(2, 1)) -
                                  x(0, 1) * (x(1, 0) * x(2, 2) - x(1, 2) * x(2, 0)) +
                                  x(0, 2) * (x(1, 0) * x(2, 1) - x(1, 1) * x(2, 0));
    if (!spec.selector || !proportional(*spec.selector, det))
      return "the selector is not a multiple of the determinant: M may be O(3), or its other component";
    const exact::Term& t = det.terms().front();
    for (const exact::Term& s : spec.selector->terms())
      if (s.monomial == t.monomial && sgn(s.coefficient) * sgn(t.coefficient) < 0)
        return "the selector is a negative multiple of the determinant: M is the component det = -1, not SO(3)";
    return "";
  }
  std::vector<exact::Polynomial> expected;
  if (g.kind == io::ShapeSpec::Kind::product) {
    for (const auto& f : g.factors)
      expected.push_back(sphere_polynomial(f.coordinates, std::vector<mpq_class>(f.coordinates.size(), 0), f.radius, N));
  } else if (g.kind == io::ShapeSpec::Kind::sphere) {
    std::vector<int> vars(N);
    for (int v = 0; v < N; ++v) vars[v] = v;
    expected.push_back(sphere_polynomial(vars, g.center, g.radius, N));
  } else {
    for (std::size_t i = 0; i < g.radii.size(); ++i)
      expected.push_back(sphere_polynomial({int(2 * i), int(2 * i + 1)}, {0, 0}, g.radii[i], N));
  }
  const std::string why = unmatched(spec.equations, expected);
  if (!why.empty()) return why;
  if (spec.selector) return "the spec has a selector: M may be only a component of the declared shape";
  return "";
}

// Every factor a round sphere (a circle included).
bool spheres_only(const std::vector<io::ShapeFactor>& fs) {
  return std::all_of(fs.begin(), fs.end(), [](const io::ShapeFactor& f) { return f.kind == io::ShapeFactor::Kind::sphere; });
}

}  // namespace

VerifiedShape verify_declared_shape(const io::ManifoldSpec& spec) {
  const int m = spec.intrinsic_dimension, N = spec.ambient_dimension;
  VerifiedShape V;
  if (!spec.metric) {
    V.reason = "no closed-form geodesic distance: the spec declares no metric";
    return V;
  }
  // A product whose factors are one shape this version handles, written as that shape: one sphere
  // or one SO(3) on x1..xN in order, or circles on (x1, x2), (x3, x4), ... in order.
  io::ShapeSpec g = *spec.metric;
  bool geodesic = false;
  if (g.kind == io::ShapeSpec::Kind::product) {
    auto in_order = [](const std::vector<io::ShapeFactor>& fs) {
      int next = 0;
      for (const auto& f : fs)
        for (int x : f.coordinates)
          if (x != next++) return false;
      return true;
    };
    const bool circles = std::all_of(g.factors.begin(), g.factors.end(), [](const io::ShapeFactor& f) {
      return f.kind == io::ShapeFactor::Kind::sphere && f.coordinates.size() == 2;
    });
    std::string factors;
    for (const auto& f : g.factors)
      factors += (factors.empty() ? "" : " x ") +
                 (f.kind == io::ShapeFactor::Kind::so3 ? std::string("SO(3)") : "S^" + std::to_string(f.dimension()));
    const bool ordered = in_order(g.factors), one = g.factors.size() == 1;
    if (ordered && one && g.factors[0].kind == io::ShapeFactor::Kind::sphere) {
      g.kind = io::ShapeSpec::Kind::sphere, g.center.assign(N, mpq_class(0)), g.radius = g.factors[0].radius;
    } else if (ordered && one) {
      g.kind = io::ShapeSpec::Kind::so3;
    } else if (ordered && circles) {
      g.kind = io::ShapeSpec::Kind::product_of_circles;
      for (const auto& f : g.factors) g.radii.push_back(f.radius);
    } else if (spheres_only(g.factors) && m <= 3) {
      geodesic = true;  // stays a product: GEODESIC cells (certify/intrinsic_product.cpp)
    } else {
      V.metric = "product";
      V.reason = "Del_M for the product " + factors + " is not built in this version (" +
                 (spheres_only(g.factors) ? "m > 3" : "an SO(3) factor") + "; docs/design.md §12)";
      return V;
    }
  }
  const bool sphere = g.kind == io::ShapeSpec::Kind::sphere && N == m + 1;
  const bool torus = g.kind == io::ShapeSpec::Kind::product_of_circles && N == 2 * m && static_cast<int>(g.radii.size()) == m;
  const bool so3 = g.kind == io::ShapeSpec::Kind::so3 && N == 9 && m == 3;
  V.metric = geodesic                                          ? "product"
             : g.kind == io::ShapeSpec::Kind::so3                 ? "so3"
             : g.kind == io::ShapeSpec::Kind::sphere              ? "sphere"
             : g.kind == io::ShapeSpec::Kind::product_of_circles ? "product_of_circles"
                                                                 : "torus_of_revolution";
  if (sphere || torus || so3 || geodesic) {
    const std::string mismatch = metric_mismatch(spec, g);
    if (!mismatch.empty()) {
      V.reason = "the declared metric is not used: " + mismatch;
      return V;
    }
    V.shape = std::move(g);
    return V;
  }
  V.reason = "Del_M for the declared metric (" + V.metric + ", m = " + std::to_string(m) + ", N = " +
             std::to_string(N) + ") is not built in this version (docs/design.md §12)";
  return V;
}

IntrinsicDelaunay compute_intrinsic_delaunay(const io::ManifoldSpec& spec, const io::PointSet& points,
                                             const detail::PointGrid& grid,
                                             const std::vector<std::vector<int>>& candidates, int threads,
                                             const GeneralMetricInput* general) {
  const int m = spec.intrinsic_dimension;
  for (const auto& s : candidates) {
    if (static_cast<int>(s.size()) != m + 1) throw std::invalid_argument("an intrinsic candidate is not an m-simplex");
    for (std::size_t i = 0; i < s.size(); ++i)
      if (s[i] < 0 || static_cast<std::size_t>(s[i]) >= points.size() || (i && s[i - 1] >= s[i]))
        throw std::invalid_argument("an intrinsic candidate is not a sorted set of point indices");
  }
  VerifiedShape V = verify_declared_shape(spec);
  if (!V.shape && general && m <= 3) return detail::intrinsic_delaunay_general(spec, points, grid, candidates, *general, threads);
  if (!V.shape) {
    IntrinsicDelaunay D;
    D.metric = V.metric, D.reason = V.reason;
    return D;
  }
  const io::ShapeSpec& g = *V.shape;
  if (g.kind == io::ShapeSpec::Kind::product) return detail::intrinsic_delaunay_product(spec, g, points, grid, candidates, threads);
  return g.kind == io::ShapeSpec::Kind::sphere ? detail::intrinsic_delaunay_sphere(g, points, grid, candidates, threads)
         : g.kind == io::ShapeSpec::Kind::so3  ? detail::intrinsic_delaunay_so3(points, grid, candidates, threads)
                                               : detail::intrinsic_delaunay_flat_torus(g, points, grid, candidates, threads);
}

}  // namespace delcert::certify
