// certify/detail/param_cell.cpp: restricted Voronoi cells in rational charts (round spheres,
// flat tori and SO(3)). The charts' covering lemma is tested against points of M found independently (Gauss-
// Newton on the chart's own polynomials), the engine against the implicit one (spheres) and
// against the independent Del_M of the quaternion hull (SO(3)), with the witnesses re-checked in
// long double, and exact ties are never certified.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <array>
#include <cmath>
#include <functional>
#include <set>

#include "certify/certify.hpp"
#include "certify/restricted/param_cell.hpp"
#include "certify/intrinsic/intrinsic.hpp"
#include "certify/restricted/restricted.hpp"
#include "exact/chart.hpp"
#include "io/complex.hpp"
#include "io/points.hpp"
#include "io/spec.hpp"
#include "tests/certify/support.hpp"

namespace delcert::certify::test {
namespace {

io::ShapeSpec verified(const io::ManifoldSpec& spec) {
  const VerifiedShape V = verify_declared_shape(spec);
  if (!V.shape) throw std::logic_error("the built-in's metric is not verified: " + V.reason);
  return *V.shape;
}

std::set<std::vector<int>> simplex_set(const RestrictedDelaunay& R) {
  std::set<std::vector<int>> s;
  for (const auto& x : R.simplices) s.insert(x.simplex);
  return s;
}

// phi(v) and its Jacobian in double, from the chart's own polynomials.
struct ChartEval {
  const detail::RationalChart& C;
  double eval(const exact::Polynomial& P, const Eigen::Vector3d& v, int m) const {
    std::vector<double> x(v.data(), v.data() + m);
    return P.evaluate_with<double>(std::span<const double>(x), [&](std::size_t i) { return P.terms()[i].coefficient.get_d(); });
  }
  Eigen::VectorXd phi(const Eigen::Vector3d& v, int m) const {
    Eigen::VectorXd x(C.X.size());
    const double D = eval(C.D, v, m);
    for (std::size_t i = 0; i < C.X.size(); ++i) x[i] = eval(C.X[i], v, m) / D;
    return x;
  }
};

// Solves phi(v) = x by Gauss-Newton (numerical Jacobian) from v = 0; returns the residual.
double preimage(const ChartEval& E, int m, const Eigen::VectorXd& x, Eigen::Vector3d& v) {
  v.setZero();
  for (int it = 0; it < 60; ++it) {
    const Eigen::VectorXd f = E.phi(v, m) - x;
    Eigen::MatrixXd J(x.size(), m);
    for (int a = 0; a < m; ++a) {
      Eigen::Vector3d w = v;
      const double h = 1e-7 * (1 + std::abs(v[a]));
      w[a] += h;
      J.col(a) = (E.phi(w, m) - E.phi(v, m)) / h;
    }
    const Eigen::VectorXd step = J.colPivHouseholderQr().solve(f);
    v.head(m) -= step;
    if (step.norm() < 1e-14) break;
  }
  return (E.phi(v, m) - x).norm();
}

// LEMMA (b) of param_cell.hpp: every point of M in B(p, r) has its parameter in [-t, t]^m. Random
// points of M near p (uniform directions, distances up to r, many close to r) are pulled back by
// Gauss-Newton on the chart's polynomials, independently of how t was derived.
TEST(ParamCell, TheChartCoversTheBall) {
  Rng rng(17);
  for (const char* name :
       {"builtin:so3", "builtin:sphere-3", "builtin:sphere-2", "builtin:clifford-torus-3", "builtin:clifford-torus-2"}) {
    const io::ManifoldSpec spec = io::read_spec(name);
    const io::ShapeSpec shape = verified(spec);
    const int N = spec.ambient_dimension, m = spec.intrinsic_dimension;
    const bool torus = shape.kind == io::ShapeSpec::Kind::product_of_circles;
    // A point of M from a point y of R^N: per pair, scaled to its circle's radius (tori), or
    // normalised (spheres); SO(3) below.
    auto onto = [&](Eigen::VectorXd y) {
      if (!torus) return Eigen::VectorXd(y / y.norm());
      for (int i = 0; i < m; ++i) y.segment(2 * i, 2) *= shape.radii[i].get_d() / y.segment(2 * i, 2).norm();
      return y;
    };
    const io::PointSet P = N == 9 ? so3_net(40, 0.5, 3)
                           : torus ? (m == 3 ? torus3_bcc(3, 0.5, 4) : torus2_lattice(5, 6, 0.5, 4))
                                   : spread_sphere(N, 20, 0.3, 3);
    int tested = 0;
    for (std::size_t p = 0; p < P.size(); p += 4)
      for (double r : {0.2, 0.7, 1.3}) {
        const auto C = detail::rational_chart(shape, P.point(p), r);
        ASSERT_TRUE(C) << name << " r = " << r;
        EXPECT_LT(C->t, 4.0) << name << " r = " << r;  // not a vacuous box
        const ChartEval E{*C};
        for (int k = 0; k < 200; ++k) {
          // A random point of M: SO(3) by a random unit quaternion, spheres by a random direction.
          Eigen::VectorXd x(N);
          double len = 0;
          std::array<double, 4> q{};
          for (int i = 0; i < (N == 9 || torus ? 4 : N); ++i) {  // (q holds 4: a quaternion or a sphere's N <= 4)
            const double u1 = rng.uniform() + 1e-300, u2 = rng.uniform();
            q[i] = std::sqrt(-2 * std::log(u1)) * std::cos(2 * M_PI * u2), len += q[i] * q[i];
          }
          for (double& c : q) c /= std::sqrt(len);
          if (N == 9) {
            const double w = q[0], a = q[1], b = q[2], c = q[3];
            x << 1 - 2 * (b * b + c * c), 2 * (a * b - w * c), 2 * (a * c + w * b), 2 * (a * b + w * c),
                1 - 2 * (a * a + c * c), 2 * (b * c - w * a), 2 * (a * c - w * b), 2 * (b * c + w * a),
                1 - 2 * (a * a + b * b);
          } else if (torus) {  // uniform angles
            for (int i = 0; i < N; ++i) x[i] = rng.uniform() - 0.5;
            x = onto(x);
          } else {
            for (int i = 0; i < N; ++i) x[i] = q[i];
          }
          // Pull x towards p until it is inside B(p, r) (along the chord, then back onto M), so
          // that points near the ball's boundary are common.
          Eigen::VectorXd pp = Eigen::Map<const Eigen::VectorXd>(P.point(p).data(), N);
          const double frac = rng.uniform();
          for (int shrink = 0; shrink < 60 && (x - pp).norm() >= r; ++shrink) {
            Eigen::VectorXd y = pp + (0.9 + 0.1 * frac) * (x - pp);
            if (N == 9) {  // nearest rotation: the polar factor
              Eigen::Map<Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> Y(y.data());
              Eigen::JacobiSVD<Eigen::Matrix3d> svd(Eigen::Matrix3d(Y), Eigen::ComputeFullU | Eigen::ComputeFullV);
              Eigen::Matrix3d R = svd.matrixU() * svd.matrixV().transpose();
              Eigen::Map<Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(x.data()) = R;
            } else {
              x = onto(y);
            }
          }
          if ((x - pp).norm() >= r) continue;
          Eigen::Vector3d v;
          ASSERT_LT(preimage(E, m, x, v), 1e-9) << name << ": Gauss-Newton did not converge";
          for (int a = 0; a < m; ++a) EXPECT_LE(std::abs(v[a]), C->t) << name << " r = " << r << " |x - p| = " << (x - pp).norm();
          ++tested;
        }
      }
    EXPECT_GT(tested, 500) << name;
  }
}

// On round spheres the rational charts and the implicit engine find the same Del_RM, both
// complete, and each covering bound is at least the other's farthest certified vertex.
TEST(ParamCell, SpheresGiveTheImplicitEnginesDelRM) {
  for (int N : {3, 4}) {
    const io::ManifoldSpec spec = io::read_spec(N == 3 ? "builtin:sphere-2" : "builtin:sphere-3");
    const io::ShapeSpec shape = verified(spec);
    const io::PointSet P = spread_sphere(N, N == 3 ? 150 : 120, N == 3 ? 0.25 : 0.45, 11);
    const exact::ImplicitSystem system(spec.equations, N);
    const detail::PointGrid grid(P, spec.intrinsic_dimension);
    RestrictedDelaunayOptions o;
    o.threads = 2;
    const RestrictedDelaunay implicit = compute_restricted_delaunay(system, P, grid, o);
    o.cell.shape = &shape;
    const RestrictedDelaunay rational = compute_restricted_delaunay(system, P, grid, o);
    ASSERT_TRUE(implicit.covering_certified) << implicit.reason;
    ASSERT_TRUE(rational.covering_certified) << rational.reason;
    EXPECT_EQ(implicit.rational_chart_cells, 0);
    EXPECT_EQ(rational.rational_chart_cells, static_cast<long>(P.size()));
    EXPECT_EQ(simplex_set(implicit), simplex_set(rational)) << "N = " << N;
    EXPECT_GT(rational.simplices.size(), P.size());
    EXPECT_GE(rational.covering, implicit.vertex_distance_lower);
    EXPECT_GE(implicit.covering, rational.vertex_distance_lower);
    EXPECT_TRUE(rational.lower_faces.empty());
  }
}

// Every vertex witness of R re-checked in long double from its enclosure's midpoint x: narrow,
// on M (`on_M` asserts it), equidistant from its simplex, nearer to it than to every other point.
// Returns the number of vertices checked.
int recheck_vertices(const io::PointSet& P, const RestrictedDelaunay& R, const std::function<void(const long double*)>& on_M) {
  const int N = P.dimension;
  int checked = 0;
  for (std::size_t p = 0; p < P.size(); ++p)
    for (const auto& v : R.cells[p].vertices) {
      std::vector<long double> x(N);
      for (int i = 0; i < N; ++i) {
        EXPECT_LT(v.x[i].width(), 1e-9);
        x[i] = 0.5L * ((long double)v.x[i].lo + v.x[i].hi);
      }
      on_M(x.data());
      auto dist2 = [&](int q) {
        long double s = 0;
        for (int i = 0; i < N; ++i) s += (x[i] - P.point(q)[i]) * (x[i] - P.point(q)[i]);
        return s;
      };
      const long double r2 = dist2(v.simplex[0]);
      for (int q : v.simplex) EXPECT_NEAR(static_cast<double>(dist2(q) - r2), 0.0, 1e-9);
      for (int q = 0; q < static_cast<int>(P.size()); ++q)
        if (!std::binary_search(v.simplex.begin(), v.simplex.end(), q)) {
          EXPECT_GT(dist2(q), r2);
        }
      ++checked;
    }
  return checked;
}

// Every cell's covering bound holds at 20000 random points x of M (`sample`) in that cell (x's
// nearest point p): |x - p| <= covering_bound_p; the largest such distance is at most the
// certified covering, which is not loose (within 10% of the farthest certified vertex).
void recheck_covering(const io::PointSet& P, const RestrictedDelaunay& R, const std::function<std::vector<double>(Rng&)>& sample) {
  Rng rng(23);
  double worst = 0;
  for (int k = 0; k < 20000; ++k) {
    const std::vector<double> x = sample(rng);
    int best = -1;
    double bd = INFINITY;
    for (std::size_t p = 0; p < P.size(); ++p) {
      double d = 0;
      for (std::size_t i = 0; i < x.size(); ++i) d += (x[i] - P.point(p)[i]) * (x[i] - P.point(p)[i]);
      if (d < bd) bd = d, best = static_cast<int>(p);
    }
    EXPECT_LE(std::sqrt(bd), R.cells[best].covering_bound * (1 + 1e-12)) << "a point of the cell of " << best;
    worst = std::max(worst, std::sqrt(bd));
  }
  EXPECT_LE(worst, R.covering * (1 + 1e-12));
  EXPECT_LT(R.covering, 1.1 * R.vertex_distance_lower);
}

// A well-spread sample of SO(3) and its Del_RM in rational charts (computed once for the tests).
struct So3Case {
  io::PointSet P;
  RestrictedDelaunay R;
};
const So3Case& so3_case() {
  static const So3Case c = [] {
    So3Case k;
    k.P = so3_net(500, 0.75, 5);
    const io::ManifoldSpec spec = io::read_spec("builtin:so3");
    const io::ShapeSpec shape = verified(spec);
    const exact::ImplicitSystem system(spec.equations, 9);
    const detail::PointGrid grid(k.P, 3);
    RestrictedDelaunayOptions ro;
    ro.threads = 2;
    ro.cell.shape = &shape;
    k.R = compute_restricted_delaunay(system, k.P, grid, ro);
    return k;
  }();
  return c;
}

// SO(3): the certifier uses rational charts; on a well-spread sample checks 11, 12, 14 and 15 are
// CERTIFIED (Del_RM = Del_M, the latter from the independent quaternion hull) and check 13 is
// decided (this coarse net's Del_TM differs from Del_RM: REFUTED with witnesses); every vertex
// witness re-checks in long double: a rotation, equidistant from its simplex, nearer to it than
// to every other point.
TEST(ParamCell, So3DelRMIsCertifiedAndItsVerticesRecheck) {
  TempDir dir("param-so3");
  const io::PointSet& P = so3_case().P;
  CertifyOptions o;
  o.manifold = "builtin:so3";
  o.points = dir.file("points.txt");
  io::write_points(o.points, P);
  const Certificate c = run_certify(o);
  for (CheckId id : {CheckId::covering, CheckId::restricted_delaunay, CheckId::intrinsic_delaunay,
                     CheckId::restricted_equals_intrinsic})
    EXPECT_EQ(check(c, id).verdict, Verdict::certified) << check_name(id) << ": " << check(c, id).summary;
  EXPECT_NE(check(c, CheckId::tangential_equals_restricted).verdict, Verdict::undecided);
  EXPECT_EQ(check(c, CheckId::covering).details["rational_chart_cells"].get<long>(), static_cast<long>(P.size()));

  const RestrictedDelaunay& R = so3_case().R;
  ASSERT_TRUE(R.covering_certified) << R.reason;
  EXPECT_GT(recheck_vertices(P, R, [](const long double* x) {
              for (int i = 0; i < 3; ++i)
                for (int k = 0; k < 3; ++k) {
                  long double s = 0;
                  for (int j = 0; j < 3; ++j) s += x[3 * i + j] * x[3 * k + j];
                  EXPECT_NEAR(static_cast<double>(s), i == k ? 1.0 : 0.0, 1e-9);
                }
            }),
            static_cast<int>(4 * P.size()));
  recheck_covering(P, R, [](Rng& rng) {
    double q[4], len = 0;
    for (double& c : q) {
      const double u1 = rng.uniform() + 1e-300, u2 = rng.uniform();
      c = std::sqrt(-2 * std::log(u1)) * std::cos(2 * M_PI * u2), len += c * c;
    }
    for (double& c : q) c /= std::sqrt(len);
    const double w = q[0], a = q[1], b = q[2], cc = q[3];
    return std::vector<double>{1 - 2 * (b * b + cc * cc), 2 * (a * b - w * cc), 2 * (a * cc + w * b),
                               2 * (a * b + w * cc),     1 - 2 * (a * a + cc * cc), 2 * (b * cc - w * a),
                               2 * (a * cc - w * b),     2 * (b * cc + w * a),     1 - 2 * (a * a + b * b)};
  });
}

// An exact tie on SO(3): the identity I is at exactly the same distance from six points, the
// rotations by the same angle about the axes ±x, ±y, ±z (the same doubles c = cos, s = sin in each
// matrix, so each |I - R|^2 = 2 (1 - c)^2 + 2 s^2 exactly), and every other point is farther: I is a
// restricted Voronoi vertex of six points. Del_RM is never CERTIFIED there.
TEST(ParamCell, AnExactSixfoldTieOnSo3IsNeverCertified) {
  TempDir dir("param-so3-tie");
  const double th = 0.35, c = std::cos(th), s = std::sin(th);
  std::vector<std::vector<double>> pts;
  for (int axis = 0; axis < 3; ++axis)
    for (int sign : {1, -1}) {
      std::vector<double> R(9, 0.0);
      const int a = (axis + 1) % 3, b = (axis + 2) % 3;
      R[4 * axis] = 1;
      R[3 * a + a] = c, R[3 * b + b] = c, R[3 * a + b] = -sign * s, R[3 * b + a] = sign * s;
      pts.push_back(R);
    }
  const double tie2 = 2 * (1 - c) * (1 - c) + 2 * s * s;
  const io::PointSet& net = so3_case().P;
  for (std::size_t i = 0; i < net.size(); ++i) {
    double d = 0;
    for (int k = 0; k < 9; ++k) d += std::pow(net.point(i)[k] - (k % 4 == 0 ? 1.0 : 0.0), 2);
    if (d > tie2 + 0.3) pts.emplace_back(net.point(i).begin(), net.point(i).end());
  }
  const io::PointSet P = make_points(9, pts);
  CertifyOptions o;
  o.manifold = "builtin:so3";
  o.points = dir.file("points.txt");
  io::write_points(o.points, P);
  const Certificate cert = run_certify(o);
  EXPECT_NE(check(cert, CheckId::restricted_delaunay).verdict, Verdict::certified);
  EXPECT_NE(check(cert, CheckId::covering).verdict, Verdict::certified);
  EXPECT_NE(check(cert, CheckId::tangential_equals_restricted).verdict, Verdict::certified);
}

// A complex claimed restricted on SO(3) with one simplex of Del_RM dropped, or one added, is
// REFUTED (the dropped one by its certified restricted Voronoi vertex).
TEST(ParamCell, So3MutantsAreRefuted) {
  TempDir dir("param-so3-mutants");
  const io::PointSet& P = so3_case().P;
  const RestrictedDelaunay& R = so3_case().R;
  ASSERT_TRUE(R.covering_certified) << R.reason;
  io::Complex K;
  K.num_vertices = P.size();
  for (const auto& s : R.simplices) K.simplices.push_back(s.simplex);
  auto run_claim = [&](const io::Complex& C) {
    CertifyOptions o;
    o.manifold = "builtin:so3";
    o.points = dir.file("points.txt");
    io::write_points(o.points, P);
    o.complex = dir.file("complex.txt");
    o.kind = ComplexKind::restricted;
    io::write_complex(o.complex, C);
    return run_certify(o);
  };
  io::Complex dropped = K;
  const std::vector<int> gone = dropped.simplices[11];
  dropped.simplices.erase(dropped.simplices.begin() + 11);
  const Certificate d = run_claim(dropped);
  const CheckEntry& dd = check(d, CheckId::restricted_delaunay);
  ASSERT_EQ(dd.verdict, Verdict::refuted);
  EXPECT_EQ(dd.witnesses[0]["simplex"].get<std::vector<int>>(), gone);
  EXPECT_EQ(dd.witnesses[0]["kind"], "restricted_voronoi_vertex");
  io::Complex added = K;
  const std::set<std::vector<int>> in(K.simplices.begin(), K.simplices.end());
  std::vector<int> extra{0, 1, 2, 3};
  while (in.count(extra)) ++extra[3];
  added.simplices.push_back(extra);
  EXPECT_EQ(check(run_claim(added), CheckId::restricted_delaunay).verdict, Verdict::refuted);
}

// Flat tori T^2 and T^3 (products of circles) in the separable circle charts. On T^2 the implicit
// engine finds the same Del_RM, both complete, each covering bound at least the other's farthest
// vertex (on T^3 it takes minutes on a sample this coarse: the circle charts about a second). On
// both, every vertex witness re-checks in long double and the cells' covering bounds hold at
// random points of M; through the certifier, checks 11 and 12 are CERTIFIED and Del_RM = Del_M
// (the latter from the independent periodic lifting, certify/intrinsic_torus.cpp) is decided.
TEST(ParamCell, FlatToriInCircleChartsAreCertifiedAndTheirWitnessesRecheck) {
  for (int m : {2, 3}) {
    SCOPED_TRACE("m = " + std::to_string(m));
    const io::ManifoldSpec spec = io::read_spec(m == 2 ? "builtin:clifford-torus-2" : "builtin:clifford-torus-3");
    const io::ShapeSpec shape = verified(spec);
    const io::PointSet P = m == 2 ? torus2_lattice(16, 18, 0.3, 12) : torus3_bcc(6, 0.3, 12);
    const exact::ImplicitSystem system(spec.equations, 2 * m);
    const detail::PointGrid grid(P, m);
    RestrictedDelaunayOptions o;
    o.threads = 2;
    o.cell.shape = &shape;
    const RestrictedDelaunay rational = compute_restricted_delaunay(system, P, grid, o);
    ASSERT_TRUE(rational.covering_certified) << rational.reason;
    EXPECT_EQ(rational.rational_chart_cells, static_cast<long>(P.size()));
    EXPECT_GT(rational.simplices.size(), P.size());
    EXPECT_TRUE(rational.lower_faces.empty());
    if (m == 2) {
      o.cell.shape = nullptr;
      const RestrictedDelaunay implicit = compute_restricted_delaunay(system, P, grid, o);
      ASSERT_TRUE(implicit.covering_certified) << implicit.reason;
      EXPECT_EQ(implicit.rational_chart_cells, 0);
      EXPECT_EQ(simplex_set(implicit), simplex_set(rational));
      EXPECT_GE(rational.covering, implicit.vertex_distance_lower);
      EXPECT_GE(implicit.covering, rational.vertex_distance_lower);
    }
    EXPECT_GT(recheck_vertices(P, rational, [m](const long double* x) {
                for (int i = 0; i < m; ++i) EXPECT_NEAR(static_cast<double>(x[2 * i] * x[2 * i] + x[2 * i + 1] * x[2 * i + 1]), 1.0, 1e-9);
              }),
              static_cast<int>(P.size()));
    recheck_covering(P, rational, [m](Rng& rng) {
      std::vector<double> x;
      for (int i = 0; i < m; ++i) {
        const double a = 2 * M_PI * rng.uniform();
        x.push_back(std::cos(a)), x.push_back(std::sin(a));
      }
      return x;
    });
    TempDir dir("param-torus");
    CertifyOptions co;
    co.manifold = m == 2 ? "builtin:clifford-torus-2" : "builtin:clifford-torus-3";
    co.points = dir.file("points.txt");
    io::write_points(co.points, P);
    const Certificate c = run_certify(co);
    for (CheckId id : {CheckId::covering, CheckId::restricted_delaunay})
      EXPECT_EQ(check(c, id).verdict, Verdict::certified) << check_name(id) << ": " << check(c, id).summary;
    EXPECT_NE(check(c, CheckId::restricted_equals_intrinsic).verdict, Verdict::undecided);
    EXPECT_EQ(check(c, CheckId::covering).details["rational_chart_cells"].get<long>(), static_cast<long>(P.size()));
  }
}

// A square grid in angle space on T^2, (cos a_i, sin a_i, cos b_j, sin b_j) in doubles: exact ties
// by the product structure alone (the bisector of two of the first circle's points meets it at x1,
// the second's at x2, and (x1, x2) is equidistant from the four points of the grid cell), analysed
// in circle charts: Del_RM and the covering are never CERTIFIED.
TEST(ParamCell, AnExactTieOnTheFlatTorusIsNeverCertified) {
  TempDir dir("param-torus-tie");
  std::vector<std::vector<double>> pts;
  const int k = 10;
  for (int i = 0; i < k; ++i)
    for (int j = 0; j < k; ++j)
      pts.push_back({std::cos(2 * M_PI * i / k), std::sin(2 * M_PI * i / k), std::cos(2 * M_PI * j / k), std::sin(2 * M_PI * j / k)});
  CertifyOptions o;
  o.manifold = "builtin:clifford-torus-2";
  o.points = dir.file("points.txt");
  io::write_points(o.points, make_points(4, pts));
  const Certificate c = run_certify(o);
  EXPECT_GT(check(c, CheckId::covering).details["rational_chart_cells"].get<long>(), 0);
  EXPECT_NE(check(c, CheckId::restricted_delaunay).verdict, Verdict::certified);
  EXPECT_NE(check(c, CheckId::covering).verdict, Verdict::certified);
  EXPECT_NE(check(c, CheckId::tangential_equals_restricted).verdict, Verdict::certified);
}

}  // namespace
}  // namespace delcert::certify::test
