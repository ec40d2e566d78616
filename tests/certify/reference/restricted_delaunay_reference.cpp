#include "restricted_delaunay_reference.hpp"

#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Interval_nt.h>
#include <CGAL/gmpxx.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>

#include <algorithm>
#include <map>
#include <set>
#include <span>
#include <stdexcept>
#include <unordered_map>

namespace delcert::reference {

// ---------------------------------------------------------------------------------------------
// UPoly

UPoly::UPoly(int c) : UPoly(mpq_class(c)) {}
UPoly::UPoly(mpq_class c) {
  if (sgn(c) != 0) c_.push_back(std::move(c));
}
UPoly::UPoly(std::vector<mpq_class> coefficients) : c_(std::move(coefficients)) { trim(); }

UPoly UPoly::linear(const mpq_class& c0, const mpq_class& c1) { return UPoly(std::vector<mpq_class>{c0, c1}); }

UPoly UPoly::from_roots(const std::vector<mpq_class>& roots) {
  UPoly p(1);
  for (const auto& r : roots) p = p * linear(-r, 1);
  return p;
}

void UPoly::trim() {
  while (!c_.empty() && sgn(c_.back()) == 0) c_.pop_back();
}

mpq_class UPoly::operator()(const mpq_class& t) const {
  mpq_class v = 0;
  for (auto it = c_.rbegin(); it != c_.rend(); ++it) v = v * t + *it;
  return v;
}

int UPoly::sign_at(const mpq_class& t) const { return sgn((*this)(t)); }
int UPoly::sign_at_infinity() const { return c_.empty() ? 0 : sgn(c_.back()); }

UPoly UPoly::derivative() const {
  std::vector<mpq_class> d;
  for (std::size_t i = 1; i < c_.size(); ++i) d.push_back(c_[i] * static_cast<long>(i));
  return UPoly(std::move(d));
}

UPoly UPoly::monic() const {
  if (c_.empty()) return *this;
  UPoly r = *this;
  const mpq_class lead = c_.back();
  for (auto& c : r.c_) c /= lead;
  return r;
}

UPoly UPoly::primitive() const {
  if (c_.empty()) return *this;
  mpz_class den = 1, num = 0;
  for (const auto& c : c_) mpz_lcm(den.get_mpz_t(), den.get_mpz_t(), c.get_den_mpz_t());
  std::vector<mpz_class> ints;
  for (const auto& c : c_) {
    ints.push_back(c.get_num() * (den / c.get_den()));
    mpz_gcd(num.get_mpz_t(), num.get_mpz_t(), ints.back().get_mpz_t());
  }
  std::vector<mpq_class> out;
  for (const auto& z : ints) out.emplace_back(mpz_class(z / num));
  return UPoly(std::move(out));
}

UPoly operator+(const UPoly& a, const UPoly& b) {
  std::vector<mpq_class> c(std::max(a.c_.size(), b.c_.size()));
  for (std::size_t i = 0; i < a.c_.size(); ++i) c[i] += a.c_[i];
  for (std::size_t i = 0; i < b.c_.size(); ++i) c[i] += b.c_[i];
  return UPoly(std::move(c));
}

UPoly operator-(const UPoly& a, const UPoly& b) {
  std::vector<mpq_class> c(std::max(a.c_.size(), b.c_.size()));
  for (std::size_t i = 0; i < a.c_.size(); ++i) c[i] += a.c_[i];
  for (std::size_t i = 0; i < b.c_.size(); ++i) c[i] -= b.c_[i];
  return UPoly(std::move(c));
}

UPoly operator*(const UPoly& a, const UPoly& b) {
  if (a.c_.empty() || b.c_.empty()) return UPoly();
  std::vector<mpq_class> c(a.c_.size() + b.c_.size() - 1);
  for (std::size_t i = 0; i < a.c_.size(); ++i)
    for (std::size_t j = 0; j < b.c_.size(); ++j) c[i + j] += a.c_[i] * b.c_[j];
  return UPoly(std::move(c));
}

std::pair<UPoly, UPoly> divmod(const UPoly& a, const UPoly& b) {
  if (b.is_zero()) throw std::invalid_argument("UPoly division by zero");
  std::vector<mpq_class> r = a.c_;
  const int db = b.degree();
  std::vector<mpq_class> q(a.degree() >= db ? a.degree() - db + 1 : 0);
  for (int k = a.degree() - db; k >= 0; --k) {
    const mpq_class f = r[k + db] / b.c_.back();
    q[k] = f;
    if (sgn(f) == 0) continue;
    for (int j = 0; j <= db; ++j) r[k + j] -= f * b.c_[j];
  }
  return {UPoly(std::move(q)), UPoly(std::move(r))};
}

UPoly gcd(UPoly a, UPoly b) {
  while (!b.is_zero()) {
    UPoly r = divmod(a, b).second.primitive();  // keeps the numbers small; the gcd is unchanged
    a = std::move(b);
    b = std::move(r);
  }
  return a.monic();
}

std::string UPoly::to_string() const {
  if (c_.empty()) return "0";
  std::string s;
  for (std::size_t i = c_.size(); i-- > 0;) {
    if (sgn(c_[i]) == 0) continue;
    if (!s.empty()) s += " + ";
    s += "(" + c_[i].get_str() + ")";
    if (i > 0) s += "*t^" + std::to_string(i);
  }
  return s;
}

// ---------------------------------------------------------------------------------------------
// Sturm sequences

namespace {

// The Sturm sequence s, s', -rem(s, s'), ... of a square-free s (each member scaled by a positive
// constant, which changes no sign).
struct Sturm {
  std::vector<UPoly> seq;
  explicit Sturm(const UPoly& s) {
    seq.push_back(s);
    if (s.degree() <= 0) return;
    seq.push_back(s.derivative());
    while (seq.back().degree() > 0) {
      UPoly r = divmod(seq[seq.size() - 2], seq.back()).second;
      if (r.is_zero()) break;
      std::vector<mpq_class> c = r.primitive().coefficients();  // a positive multiple of r
      for (auto& x : c) x = -x;
      seq.emplace_back(std::move(c));
    }
  }
  static int variations(const std::vector<int>& signs) {
    int v = 0, last = 0;
    for (int s : signs) {
      if (s == 0) continue;
      if (last != 0 && s != last) ++v;
      last = s;
    }
    return v;
  }
  int at(const mpq_class& t) const {
    std::vector<int> s;
    for (const auto& p : seq) s.push_back(p.sign_at(t));
    return variations(s);
  }
  int at_infinity() const {
    std::vector<int> s;
    for (const auto& p : seq) s.push_back(p.sign_at_infinity());
    return variations(s);
  }
  // Distinct roots in (lo, hi) (hi empty: (lo, inf)); s(lo), s(hi) non-zero.
  int count_open(const mpq_class& lo, const std::optional<mpq_class>& hi) const {
    return at(lo) - (hi ? at(*hi) : at_infinity());
  }
};

UPoly square_free(const UPoly& f) { return divmod(f, gcd(f, f.derivative())).first.primitive(); }

// An upper bound of |t| over the complex roots of f (Cauchy): 1 + max |c_i / c_d|.
mpq_class cauchy_bound(const UPoly& f) {
  mpq_class m = 0;
  for (int i = 0; i < f.degree(); ++i) m = std::max(m, mpq_class(abs(f.coefficients()[i] / f.leading())));
  return m + 1;
}

struct Reduced {
  UPoly s;  // square-free part of f with the roots at lo and hi divided out
  bool root_at_lo = false, root_at_hi = false;
};

// g = gcd(f, f') when already known.
Reduced reduce(const UPoly& f, const mpq_class& lo, const std::optional<mpq_class>& hi,
               const UPoly* g = nullptr) {
  Reduced r{g ? divmod(f, *g).first.primitive() : square_free(f)};
  if (r.s.sign_at(lo) == 0) {
    r.root_at_lo = true;
    r.s = divmod(r.s, UPoly::linear(-lo, 1)).first;
  }
  if (hi && r.s.sign_at(*hi) == 0) {
    r.root_at_hi = true;
    r.s = divmod(r.s, UPoly::linear(-*hi, 1)).first;
  }
  return r;
}

}  // namespace

int count_distinct_roots(const UPoly& f, const mpq_class& lo, const std::optional<mpq_class>& hi) {
  if (f.is_zero()) throw std::invalid_argument("count_distinct_roots: zero polynomial");
  if (hi && !(lo < *hi)) {
    if (lo == *hi) return f.sign_at(lo) == 0 ? 1 : 0;
    throw std::invalid_argument("count_distinct_roots: empty interval");
  }
  const Reduced r = reduce(f, lo, hi);
  return int(r.root_at_lo) + int(r.root_at_hi) + Sturm(r.s).count_open(lo, hi);
}

RootAnalysis analyse_roots(const UPoly& f_in, const mpq_class& lo, const std::optional<mpq_class>& hi) {
  const UPoly f = f_in.primitive();  // a positive multiple: same roots, same signs
  RootAnalysis a;
  if (f.is_zero()) {
    a.identically_zero = true;
    return a;
  }
  if (hi && lo == *hi) {  // a single point
    a.root_at_lo = a.root_at_hi = f.sign_at(lo) == 0;
    a.distinct_roots = a.root_at_lo ? 1 : 0;
    if (a.root_at_lo) {
      a.isolating = std::pair{lo, lo};
      a.repeated_root = gcd(f, f.derivative()).sign_at(lo) == 0;
    }
    return a;
  }
  if (hi && !(lo < *hi)) throw std::invalid_argument("analyse_roots: empty interval");
  const UPoly g = gcd(f, f.derivative());  // its roots are the multiple roots of f
  const Reduced r = reduce(f, lo, hi, &g);
  const Sturm sturm(r.s);
  a.root_at_lo = r.root_at_lo;
  a.root_at_hi = r.root_at_hi;
  const int interior = sturm.count_open(lo, hi);
  a.distinct_roots = int(r.root_at_lo) + int(r.root_at_hi) + interior;
  a.repeated_root = g.degree() > 0 && count_distinct_roots(g, lo, hi) > 0;
  if (r.root_at_lo) {
    a.isolating = std::pair{lo, lo};
  } else if (r.root_at_hi) {
    a.isolating = std::pair{*hi, *hi};
  } else if (interior > 0) {
    // Bisection on (l, h) with s(l), s(h) != 0 and at least one root of s inside, until exactly one.
    mpq_class l = lo, h = hi ? *hi : std::max(mpq_class(lo + 1), cauchy_bound(r.s));
    while (true) {
      const int n = sturm.count_open(l, h);
      if (n == 1) {
        a.isolating = std::pair{l, h};
        break;
      }
      mpq_class m = (l + h) / 2;
      if (r.s.sign_at(m) == 0) {
        a.isolating = std::pair{m, m};
        break;
      }
      if (sturm.count_open(l, m) > 0)
        h = m;
      else
        l = m;
    }
  }
  return a;
}

UPoly restrict_to_line(const exact::Polynomial& F, const std::array<mpq_class, 3>& start,
                       const std::array<mpq_class, 3>& direction) {
  if (F.num_variables() != 3) throw std::invalid_argument("restrict_to_line: F needs 3 variables");
  std::array<UPoly, 3> x;
  for (int i = 0; i < 3; ++i) x[i] = UPoly::linear(start[i], direction[i]);
  return F.evaluate_with<UPoly>(std::span<const UPoly>(x), [&](std::size_t i) {
    return UPoly(F.terms()[i].coefficient);
  });
}

const char* to_string(Degeneracy d) {
  switch (d) {
    case Degeneracy::none: return "none";
    case Degeneracy::edge_in_manifold: return "Voronoi edge lies in M";
    case Degeneracy::voronoi_vertex_on_manifold: return "Voronoi vertex on M";
    case Degeneracy::tangency: return "Voronoi edge tangent to M";
    case Degeneracy::cocircular: return "4 cocircular points: Delaunay triangulation not unique";
  }
  return "?";
}

std::array<mpq_class, 3> VoronoiEdge::point(const mpq_class& t) const {
  std::array<mpq_class, 3> p;
  for (int i = 0; i < 3; ++i) p[i] = start[i] + t * direction[i];
  return p;
}

std::vector<Triangle> RestrictedDelaunayReference::triangles() const {
  std::vector<Triangle> t;
  for (const auto& r : restricted) t.push_back(r.vertices);
  return t;
}
std::vector<Triangle> RestrictedDelaunayReference::degenerate_triangles() const {
  std::vector<Triangle> t;
  for (const auto& r : degenerate) t.push_back(r.vertices);
  return t;
}

const exact::Polynomial& surface_equation(const io::ManifoldSpec& spec) {
  if (spec.ambient_dimension != 3 || spec.intrinsic_dimension != 2 || spec.equations.size() != 1)
    throw std::invalid_argument("restricted Delaunay reference: " + spec.name + " is not a surface in R^3");
  return spec.equations.front();
}

// ---------------------------------------------------------------------------------------------
// The reference

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vb = CGAL::Triangulation_vertex_base_with_info_3<std::size_t, K>;
using Tds = CGAL::Triangulation_data_structure_3<Vb, CGAL::Delaunay_triangulation_cell_base_3<K>>;
using DT = CGAL::Delaunay_triangulation_3<K, Tds>;
using Vec = std::array<mpq_class, 3>;

Vec sub(const Vec& a, const Vec& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
mpq_class dot(const Vec& a, const Vec& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
Vec cross(const Vec& a, const Vec& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

// Circumcentre of a non-degenerate tetrahedron, exactly: x = p0 + y with 2 (pi - p0) . y = |pi - p0|^2,
// solved by Cramer's rule, y = (|u|^2 (v x w) + |v|^2 (w x u) + |w|^2 (u x v)) / (2 u . (v x w)).
Vec circumcentre(const Vec& p0, const Vec& p1, const Vec& p2, const Vec& p3) {
  const Vec u = sub(p1, p0), v = sub(p2, p0), w = sub(p3, p0);
  const Vec vw = cross(v, w), wu = cross(w, u), uv = cross(u, v);
  const mpq_class det = 2 * dot(u, vw);
  if (sgn(det) == 0) throw std::logic_error("circumcentre of a flat tetrahedron");
  const mpq_class a = dot(u, u), b = dot(v, v), c = dot(w, w);
  Vec x;
  for (int i = 0; i < 3; ++i) x[i] = p0[i] + (a * vw[i] + b * wu[i] + c * uv[i]) / det;
  return x;
}

// A filter that only ever concludes "F has no zero on the segment [A, B]": A and B are enclosed by
// evaluating the same Cramer formula in interval arithmetic (CGAL::Interval_nt, which rounds
// outward itself; a division by an interval holding 0 gives an unbounded interval), the segment by
// the box hull of the two enclosures, and F on that box by interval evaluation (an enclosure of
// every value of F on the box). If the enclosure excludes 0, so does f on [0, 1]: exact. Otherwise
// the exact computation decides.
using I = CGAL::Interval_nt<>;
using IVec = std::array<I, 3>;

IVec interval_circumcentre(const std::array<std::array<double, 3>, 4>& p) {
  IVec u, v, w;
  for (int k = 0; k < 3; ++k) {
    u[k] = I(p[1][k]) - I(p[0][k]);
    v[k] = I(p[2][k]) - I(p[0][k]);
    w[k] = I(p[3][k]) - I(p[0][k]);
  }
  const auto icross = [](const IVec& a, const IVec& b) {
    return IVec{a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
  };
  const auto idot = [](const IVec& a, const IVec& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; };
  const IVec vw = icross(v, w), wu = icross(w, u), uv = icross(u, v);
  const I det = 2 * idot(u, vw), a = idot(u, u), b = idot(v, v), c = idot(w, w);
  IVec x;
  for (int k = 0; k < 3; ++k) x[k] = I(p[0][k]) + (a * vw[k] + b * wu[k] + c * uv[k]) / det;
  return x;
}

}  // namespace

RestrictedDelaunayReference restricted_delaunay_reference(const io::PointSet& P, const exact::Polynomial& F) {
  if (P.dimension != 3) throw std::invalid_argument("restricted Delaunay reference: points must be in R^3");
  if (F.num_variables() != 3) throw std::invalid_argument("restricted Delaunay reference: F needs 3 variables");
  const std::size_t n = P.size();
  std::vector<Vec> exact(n);
  std::vector<std::pair<K::Point_3, std::size_t>> input;
  for (std::size_t i = 0; i < n; ++i) {
    const auto p = P.point(i);
    exact[i] = {mpq_class(p[0]), mpq_class(p[1]), mpq_class(p[2])};  // exact: a double is a rational
    input.emplace_back(K::Point_3(p[0], p[1], p[2]), i);
  }
  DT dt(input.begin(), input.end());
  if (dt.number_of_vertices() != n) throw std::invalid_argument("restricted Delaunay reference: duplicate points");
  if (dt.dimension() != 3) throw std::invalid_argument("restricted Delaunay reference: points are coplanar");

  RestrictedDelaunayReference out;
  out.finite_cells = dt.number_of_finite_cells();
  std::vector<I> coefficient_enclosures;
  for (const auto& term : F.terms()) coefficient_enclosures.emplace_back(CGAL::to_interval(term.coefficient));
  std::unordered_map<DT::Cell_handle, IVec> interval_centres;
  const auto interval_centre = [&](DT::Cell_handle c) -> const IVec& {
    auto it = interval_centres.find(c);
    if (it == interval_centres.end()) {
      std::array<std::array<double, 3>, 4> p;
      for (int i = 0; i < 4; ++i)
        for (int k = 0; k < 3; ++k) p[i][k] = P.point(c->vertex(i)->info())[k];
      it = interval_centres.emplace(c, interval_circumcentre(p)).first;
    }
    return it->second;
  };
  const auto certainly_misses = [&](DT::Cell_handle c, DT::Cell_handle nb) {
    const IVec &a = interval_centre(c), &b = interval_centre(nb);
    IVec box;
    for (int k = 0; k < 3; ++k)
      box[k] = I(std::min(a[k].inf(), b[k].inf()), std::max(a[k].sup(), b[k].sup()));
    const I value = F.evaluate_with<I>(std::span<const I>(box), [&](std::size_t i) { return coefficient_enclosures[i]; });
    return CGAL::certainly(value > 0) || CGAL::certainly(value < 0);
  };
  std::unordered_map<DT::Cell_handle, Vec> centres;
  const auto centre = [&](DT::Cell_handle c) -> const Vec& {
    auto it = centres.find(c);
    if (it == centres.end()) {
      const auto v = [&](int i) -> const Vec& { return exact[c->vertex(i)->info()]; };
      it = centres.emplace(c, circumcentre(v(0), v(1), v(2), v(3))).first;
    }
    return it->second;
  };

  for (auto f = dt.finite_facets_begin(); f != dt.finite_facets_end(); ++f) {
    DT::Cell_handle c = f->first;
    const int i = f->second;
    DT::Cell_handle nb = c->neighbor(i);
    const int j = nb->index(c);
    ++out.delaunay_triangles;
    // side_of_sphere needs a finite point: test the mirror vertex against the other cell if needed.
    const bool cospherical = dt.is_infinite(nb->vertex(j))
                                 ? dt.side_of_sphere(nb, c->vertex(i)->point()) == CGAL::ON_BOUNDARY
                                 : dt.side_of_sphere(c, nb->vertex(j)->point()) == CGAL::ON_BOUNDARY;
    if (cospherical) ++out.cospherical_facets;

    std::array<DT::Vertex_handle, 3> tv;
    for (int k = 0, m = 0; k < 4; ++k)
      if (k != i) tv[m++] = c->vertex(k);
    ReferenceTriangle t;
    t.vertices = {tv[0]->info(), tv[1]->info(), tv[2]->info()};
    std::sort(t.vertices.begin(), t.vertices.end());

    VoronoiEdge& e = t.edge;
    if (dt.is_infinite(c) || dt.is_infinite(nb)) {
      ++out.hull_triangles;
      DT::Cell_handle fin = dt.is_infinite(c) ? nb : c;
      const int opposite = dt.is_infinite(c) ? j : i;  // index in fin of the vertex off the facet
      const Vec& a = exact[t.vertices[0]];
      Vec normal = cross(sub(exact[t.vertices[1]], a), sub(exact[t.vertices[2]], a));
      if (sgn(dot(normal, sub(exact[fin->vertex(opposite)->info()], a))) > 0)
        for (auto& x : normal) x = -x;
      e.start = centre(fin);
      e.direction = normal;
      e.ray = true;
    } else {
      if (certainly_misses(c, nb)) continue;
      ++out.exact_segments;
      e.start = centre(c);
      e.direction = sub(centre(nb), e.start);
    }
    e.restricted = restrict_to_line(F, e.start, e.direction);
    e.roots = analyse_roots(e.restricted, 0, e.ray ? std::nullopt : std::optional<mpq_class>(1));
    const bool meets = e.roots.identically_zero || e.roots.distinct_roots > 0;
    if (!meets) continue;

    if (e.roots.identically_zero) {
      t.degeneracy = Degeneracy::edge_in_manifold;
    } else if (e.roots.root_at_lo || e.roots.root_at_hi) {
      t.degeneracy = Degeneracy::voronoi_vertex_on_manifold;
    } else if (e.roots.repeated_root) {
      t.degeneracy = Degeneracy::tangency;
    } else {
      // A fourth point on abc's circumcircle: among the vertices of the cells around abc's edges.
      std::set<std::size_t> tested;
      for (int a = 0; a < 3 && t.degeneracy == Degeneracy::none; ++a) {
        const int ia = c->index(tv[a]), ib = c->index(tv[(a + 1) % 3]);
        auto cc = dt.incident_cells(c, ia, ib), done = cc;
        do {
          for (int k = 0; k < 4; ++k) {
            DT::Vertex_handle d = cc->vertex(k);
            if (dt.is_infinite(d) || d == tv[0] || d == tv[1] || d == tv[2]) continue;
            if (!tested.insert(d->info()).second) continue;
            const auto &p = tv[0]->point(), &q = tv[1]->point(), &r = tv[2]->point(), &s = d->point();
            if (CGAL::orientation(p, q, r, s) == CGAL::COPLANAR &&
                CGAL::coplanar_side_of_bounded_circle(p, q, r, s) == CGAL::ON_BOUNDARY)
              t.degeneracy = Degeneracy::cocircular;
          }
        } while (++cc != done);
      }
    }
    (t.degeneracy == Degeneracy::none ? out.restricted : out.degenerate).push_back(std::move(t));
  }
  const auto by_vertices = [](const ReferenceTriangle& a, const ReferenceTriangle& b) { return a.vertices < b.vertices; };
  std::sort(out.restricted.begin(), out.restricted.end(), by_vertices);
  std::sort(out.degenerate.begin(), out.degenerate.end(), by_vertices);
  return out;
}

}  // namespace delcert::reference
