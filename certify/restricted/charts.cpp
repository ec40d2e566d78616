// The rational charts of the shapes the certifier has verified (docs/design.md, "Rational charts"): a sphere's
// stereographic chart, a product of circles' per-factor charts and SO(3)'s quaternion chart, each with the
// radius of the ball it covers. param_cell.cpp analyses restricted Voronoi cells in them.
#include "certify/restricted/charts.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "certify/intrinsic/engines.hpp"
#include "certify/restricted/param_cell.hpp"
#include "exact/linear_algebra.hpp"
#include "exact/number_types.hpp"
#include "exact/polynomial.hpp"

namespace delcert::certify::detail {

using exact::Interval;
using exact::Polynomial;
using IA = exact::IntervalNumber;

namespace {

// A double rounded to a multiple of 2^-30 (a short exact rational; only closeness matters).
mpq_class dyadic(double x) {
  mpq_class q(std::nearbyint(std::ldexp(x, 30)));
  q /= mpq_class(mpz_class(1) << 30);
  return q;
}

Polynomial sum_of_squares(int m) {  // |v|^2
  Polynomial s(m);
  for (int a = 0; a < m; ++a) s = s + Polynomial::variable(a, m) * Polynomial::variable(a, m);
  return s;
}

std::optional<RationalChart> sphere_chart(const io::ShapeSpec& g, std::span<const double> p, double r) {
  const int N = static_cast<int>(g.center.size()), m = N - 1;
  std::vector<double> u(N);
  for (int i = 0; i < N; ++i) u[i] = p[i] - g.center[i].get_d();
  const std::optional<std::vector<mpq_class>> unit = rational_unit_near(std::move(u));
  if (!unit) return std::nullopt;
  const std::vector<mpq_class>& n = *unit;
  const std::vector<std::vector<mpq_class>> E = householder_frame(n);
  const Polynomial v2 = sum_of_squares(m), one = Polynomial::constant(1, m);
  RationalChart C;
  C.D = one + v2;
  for (int i = 0; i < N; ++i) {
    Polynomial Xi = C.D.scaled(g.center[i]) + (one - v2).scaled(g.radius * n[i]);
    for (int col = 0; col < m; ++col) Xi = Xi + Polynomial::variable(col, m).scaled(2 * g.radius * E[i][col]);
    C.X.push_back(std::move(Xi));
  }
  // (a): |X - c D|^2 = rho^2 D^2.
  Polynomial id = (C.D * C.D).scaled(-g.radius * g.radius);
  for (int i = 0; i < N; ++i) {
    const Polynomial d = C.X[i] - C.D.scaled(g.center[i]);
    id = id + d * d;
  }
  if (!id.is_zero()) throw std::logic_error("restricted cell: the sphere's rational chart fails its identity");
  std::vector<mpq_class> apex(N);
  for (int i = 0; i < N; ++i) apex[i] = g.center[i] + g.radius * n[i];
  exact::UpwardRounding up;
  C.t = half_width(IA(r) + distance_to(p, apex), IA(2) * ia(exact::enclose(g.radius)));
  C.centre = g.center, C.radius2 = g.radius * g.radius;
  if (!(C.t > 0)) return std::nullopt;
  return C;
}

// The circle chart per pair of coordinates (param_cell.hpp, PRODUCT OF CIRCLES).
std::optional<TorusChart> circle_charts(const io::ShapeSpec& g, std::span<const double> p, double r) {
  const int m = static_cast<int>(g.radii.size());
  if (static_cast<int>(p.size()) != 2 * m || m > 3) return std::nullopt;
  TorusChart C;
  for (int i = 0; i < m; ++i) {
    const std::optional<std::vector<mpq_class>> unit = rational_unit_near({p[2 * i], p[2 * i + 1]});
    if (!unit) return std::nullopt;
    const std::array<mpq_class, 2> n{(*unit)[0], (*unit)[1]};
    if (n[0] * n[0] + n[1] * n[1] != 1) throw std::logic_error("restricted cell: the circle chart's direction is not a unit vector");
    exact::UpwardRounding up;
    const std::vector<mpq_class> apex{g.radii[i] * n[0], g.radii[i] * n[1]};
    const double t = half_width(IA(r) + distance_to(p.subspan(2 * i, 2), apex), IA(2) * ia(exact::enclose(g.radii[i])));
    if (!(t > 0)) return std::nullopt;
    C.r.push_back(g.radii[i]), C.n.push_back(n), C.t.push_back(t);
  }
  return C;
}

// The same chart as one RationalChart (tests): X_{2i+j} = r_i ((1 - v_i^2) n_ij + 2 v_i n'_ij)
// prod_{l != i} (1 + v_l^2), D = prod_l (1 + v_l^2), t the largest half-width.
RationalChart torus_rational_chart(const TorusChart& T) {
  const int m = static_cast<int>(T.r.size());
  const Polynomial one = Polynomial::constant(1, m);
  RationalChart C;
  C.D = one;
  for (int l = 0; l < m; ++l) C.D = C.D * (one + Polynomial::variable(l, m) * Polynomial::variable(l, m));
  for (int i = 0; i < m; ++i) {
    Polynomial rest = one;
    for (int l = 0; l < m; ++l)
      if (l != i) rest = rest * (one + Polynomial::variable(l, m) * Polynomial::variable(l, m));
    const Polynomial v = Polynomial::variable(i, m), v2 = v * v;
    const std::array<mpq_class, 2> np{-T.n[i][1], T.n[i][0]};
    for (int j = 0; j < 2; ++j)
      C.X.push_back(((one - v2).scaled(T.r[i] * T.n[i][j]) + v.scaled(2 * T.r[i] * np[j])) * rest);
  }
  C.t = *std::max_element(T.t.begin(), T.t.end());
  C.centre.assign(2 * m, mpq_class(0));
  for (const auto& r : T.r) C.radius2 += r * r;
  return C;
}

// B(E_ij) for the nine matrix units: R(y)_ij = y^T B(E_ij) y.
const std::array<Mat4, 9>& davenport_units() {
  static const std::array<Mat4, 9> units = [] {
    std::array<Mat4, 9> u;
    for (int ij = 0; ij < 9; ++ij) {
      std::array<mpq_class, 9> unit{};
      unit[ij] = 1;
      u[ij] = davenport(unit);
    }
    return u;
  }();
  return units;
}

// R(y) R(y)^T = |y|^4 I for the quaternion y = (y1..y4) as exact polynomials in 4 variables
// (the rotation of y times |y|^2 is |y|^2 times an orthogonal matrix); checked once per process.
bool quaternion_identity() {
  static const bool holds = [] {
    std::array<Polynomial, 9> R;
    Polynomial n2(4);
    for (int s = 0; s < 4; ++s) n2 = n2 + Polynomial::variable(s, 4) * Polynomial::variable(s, 4);
    for (int ij = 0; ij < 9; ++ij) {
      R[ij] = Polynomial(4);
      for (int s = 0; s < 4; ++s)
        for (int t = 0; t < 4; ++t)
          if (davenport_units()[ij][s][t] != 0)
            R[ij] = R[ij] + (Polynomial::variable(s, 4) * Polynomial::variable(t, 4)).scaled(davenport_units()[ij][s][t]);
    }
    const Polynomial n4 = n2 * n2;
    for (int i = 0; i < 3; ++i)
      for (int k = i; k < 3; ++k) {
        const Polynomial dot = R[3 * i] * R[3 * k] + R[3 * i + 1] * R[3 * k + 1] + R[3 * i + 2] * R[3 * k + 2];
        if (!(i == k ? dot - n4 : dot).is_zero()) return false;
      }
    return true;
  }();
  return holds;
}

std::optional<RationalChart> so3_chart(std::span<const double> p, double r) {
  std::array<mpq_class, 9> pq;
  for (int i = 0; i < 9; ++i) {
    if (!std::isfinite(p[i])) return std::nullopt;
    pq[i] = p[i];
  }
  const std::array<double, 4> e = top_eigenvector(davenport(pq));
  std::array<mpq_class, 4> y;  // integers (|y| about 1024): any nonzero y~ is correct, small ones are fast
  for (int i = 0; i < 4; ++i) y[i] = std::nearbyint(1024 * e[i]);
  const mpq_class y2 = y[0] * y[0] + y[1] * y[1] + y[2] * y[2] + y[3] * y[3];
  if (y2 == 0) return std::nullopt;
  const mpq_class &a = y[0], &b = y[1], &c = y[2], &d = y[3];
  const std::array<std::array<mpq_class, 4>, 3> E{{{-b, a, -d, c}, {-c, d, a, -b}, {-d, -c, b, a}}};
  // (a) in two exact steps. (1) Once: R(y) R(y)^T = |y|^4 I as polynomials in y (quaternion_identity).
  // (2) Per chart: y~, e1, e2, e3 pairwise orthogonal with |e_k|^2 = |y~|^2, so that
  // |y~ + E v|^2 = |y~|^2 (1 + |v|^2) = D(v). Then X = R(y~ + E v) has X X^T = D^2 I: X / D is
  // orthogonal, and its determinant, continuous on the connected R^3 with values +-1, is its value
  // at v = 0 (det R(y~) / |y~|^6, checked > 0 below): phi(v) is in SO(3).
  if (!quaternion_identity()) throw std::logic_error("restricted cell: R(y) R(y)^T != |y|^4 I");
  for (int k = 0; k < 3; ++k) {
    mpq_class dy(0);
    for (int i = 0; i < 4; ++i) dy += y[i] * E[k][i];
    if (dy != 0) throw std::logic_error("restricted cell: the SO(3) chart's basis is not orthogonal to y~");
    for (int l = 0; l < 3; ++l) {
      mpq_class dk(0);
      for (int i = 0; i < 4; ++i) dk += E[k][i] * E[l][i];
      if (dk != (k == l ? y2 : mpq_class(0))) throw std::logic_error("restricted cell: the SO(3) chart's basis is not orthogonal");
    }
  }
  const int m = 3;
  std::array<Polynomial, 4> Y;  // y~ + E v
  for (int i = 0; i < 4; ++i) {
    Y[i] = Polynomial::constant(y[i], m);
    for (int k = 0; k < 3; ++k) Y[i] = Y[i] + Polynomial::variable(k, m).scaled(E[k][i]);
  }
  RationalChart C;
  C.D = (Polynomial::constant(1, m) + sum_of_squares(m)).scaled(y2);
  std::array<std::array<Polynomial, 4>, 4> YY;  // Y_s Y_t, s <= t
  for (int s = 0; s < 4; ++s)
    for (int t = s; t < 4; ++t) YY[s][t] = Y[s] * Y[t];
  for (int ij = 0; ij < 9; ++ij) {
    const Mat4& B = davenport_units()[ij];
    Polynomial Xij(m);
    for (int s = 0; s < 4; ++s)
      for (int t = s; t < 4; ++t)
        if (const mpq_class w = s == t ? B[s][s] : B[s][t] + B[t][s]; w != 0) Xij = Xij + YY[s][t].scaled(w);
    C.X.push_back(std::move(Xij));
  }
  std::vector<mpq_class> p0(9);  // phi(0) = R(y~) / |y~|^2
  for (int ij = 0; ij < 9; ++ij) {
    const auto& t0 = C.X[ij].terms();
    mpq_class c0(0);
    for (const auto& t : t0)
      if (std::all_of(t.monomial.exponents.begin(), t.monomial.exponents.end(), [](auto e) { return e == 0; }))
        c0 = t.coefficient;
    p0[ij] = c0 / y2;
  }
  const mpq_class det0 = p0[0] * (p0[4] * p0[8] - p0[5] * p0[7]) - p0[1] * (p0[3] * p0[8] - p0[5] * p0[6]) +
                         p0[2] * (p0[3] * p0[7] - p0[4] * p0[6]);
  if (sgn(det0) <= 0) throw std::logic_error("restricted cell: the SO(3) rational chart has det != 1");
  exact::UpwardRounding up;
  C.t = half_width(IA(r) + distance_to(p, p0), exact::sqrt(IA(8)));
  C.centre.assign(9, mpq_class(0)), C.radius2 = 3;  // |x|^2 = trace(x x^T) = 3 on O(3)
  if (!(C.t > 0)) return std::nullopt;
  return C;
}

}  // namespace

// An Interval as an IntervalNumber (the same bounds).
IA ia(const Interval& i) { return exact::to_interval_number(i); }

// t = s / sqrt(1 - s^2) rounded up from an upper bound r' of the distance (s = r' / scale); 0 when s >= 1.
double half_width(const IA& r_prime, const IA& scale) {
  exact::UpwardRounding up;
  const IA s = r_prime / scale;
  if (!(s.sup() < 1)) return 0;
  const double t = (s / exact::sqrt(IA(1) - exact::square(s))).sup();
  return std::isfinite(t) ? t : 0;
}

// sup |p - a| for a rational point a, enclosed from the exact doubles of p.
IA distance_to(std::span<const double> p, const std::vector<mpq_class>& a) {
  exact::UpwardRounding up;
  IA d(0);
  for (std::size_t i = 0; i < a.size(); ++i) d += exact::square(IA(p[i]) - ia(exact::enclose(a[i])));
  return exact::sqrt(d);
}

// A rational unit vector near the direction of u (none when u is 0 or not finite): with u
// normalised and k its largest coordinate (sign sk), the inverse stereographic image (pole
// -sk e_k) of the dyadic w_j = u_j / (1 + sk u_k), exactly unit. The sphere's n, each circle's n_i.
std::optional<std::vector<mpq_class>> rational_unit_near(std::vector<double> u) {
  const int N = static_cast<int>(u.size());
  double len = 0;
  for (int i = 0; i < N; ++i) len = std::hypot(len, u[i]);
  if (!(len > 0) || !std::isfinite(len)) return std::nullopt;
  int k = 0;
  for (int i = 0; i < N; ++i) {
    u[i] /= len;
    if (std::abs(u[i]) > std::abs(u[k])) k = i;
  }
  const int sk = u[k] < 0 ? -1 : 1;
  std::vector<mpq_class> w(N, mpq_class(0)), n(N);
  mpq_class W(0);
  for (int j = 0; j < N; ++j)
    if (j != k) w[j] = dyadic(u[j] / (1 + sk * u[k])), W += w[j] * w[j];
  for (int j = 0; j < N; ++j) n[j] = j == k ? mpq_class(sk * (1 - W) / (1 + W)) : mpq_class(2 * w[j] / (1 + W));
  return n;
}

// E (N x (N - 1)): the columns j != l of H = I - 2 a a^T / |a|^2, a = n + sgn(n_l) e_l
// (|a|^2 >= 2, l the largest |n_l|), which sends -sgn(n_l) e_l to the rational unit n:
// orthonormal, orthogonal to n, exactly.
std::vector<std::vector<mpq_class>> householder_frame(const std::vector<mpq_class>& n) {
  const int N = static_cast<int>(n.size());
  int l = 0;
  for (int j = 0; j < N; ++j)
    if (abs(n[j]) > abs(n[l])) l = j;
  std::vector<mpq_class> a = n;
  a[l] += sgn(n[l]) < 0 ? -1 : 1;
  mpq_class a2(0);
  for (const auto& x : a) a2 += x * x;
  std::vector<std::vector<mpq_class>> E(N);
  for (int i = 0; i < N; ++i)
    for (int j = 0; j < N; ++j)
      if (j != l) E[i].push_back((i == j ? mpq_class(1) : mpq_class(0)) - 2 * a[i] * a[j] / a2);
  return E;
}

std::optional<RationalChart> rational_chart(const io::ShapeSpec& shape, std::span<const double> p, double r) {
  const int N = static_cast<int>(p.size());
  if (shape.kind == io::ShapeSpec::Kind::sphere && N == static_cast<int>(shape.center.size()) && (N == 3 || N == 4))
    return sphere_chart(shape, p, r);
  if (shape.kind == io::ShapeSpec::Kind::so3 && N == 9) return so3_chart(p, r);
  if (auto T = torus_chart(shape, p, r)) return torus_rational_chart(*T);
  return std::nullopt;
}

std::optional<TorusChart> torus_chart(const io::ShapeSpec& shape, std::span<const double> p, double r) {
  if (shape.kind != io::ShapeSpec::Kind::product_of_circles) return std::nullopt;
  return circle_charts(shape, p, r);
}

}  // namespace delcert::certify::detail
