#include "certify/tangential/reach_check.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "certify/detail/grid.hpp"
#include "certify/detail/parallel.hpp"
#include "certify/tangential/theorem.hpp"
#include "exact/geodesic_bounds.hpp"
#include "exact/interval_arithmetic.hpp"
#include "exact/manifold_distance.hpp"
#include "exact/number_types.hpp"

namespace delcert::certify {

namespace {

using IA = exact::IntervalNumber;

// What one sample point contributes: the box P* holding its point p* of M, J_F(P*) and Λ >= λ_max.
struct BasePoint {
  bool usable = false;
  exact::Box box;
  std::vector<exact::Interval> J;  // k x N
  double lambda_max = 0;
  double distance = 0;  // >= |p* - p|
};

// The smallest magnitude in the interval (0 when it holds 0).
double mig(const IA& x) { return x.inf() > 0 ? x.inf() : x.sup() < 0 ? -x.sup() : 0.0; }

// The witness for the orientation (a, b): tangent space at a* (reach_check.hpp, THE BOUNDS). The
// caller holds upward rounding.
std::optional<ReachWitness> test_pair(const BasePoint& a, const BasePoint& b, int ia, int ib, double tau_lo, int k, int N) {
  std::vector<IA> d(N);
  IA d2(0);
  for (int v = 0; v < N; ++v) {
    d[v] = exact::to_interval_number(b.box[v]) - exact::to_interval_number(a.box[v]);
    d2 += exact::square(d[v]);
  }
  IA jd2(0);
  for (int e = 0; e < k; ++e) {
    IA s(0);
    for (int v = 0; v < N; ++v) s += exact::to_interval_number(a.J[e * N + v]) * d[v];
    jd2 += exact::square(IA(mig(s)));
  }
  const double normal = exact::sqrt(IA(jd2.inf()) / IA(a.lambda_max)).inf();
  const double federer = (IA(d2.sup()) / (IA(2) * IA(tau_lo))).sup();
  if (!(normal > federer)) return std::nullopt;  // (NaN or infinite bounds refute nothing)
  ReachWitness w;
  w.i = std::min(ia, ib), w.j = std::max(ia, ib), w.tangent_at = ia;
  w.normal_distance_lower = normal, w.squared_distance_upper = d2.sup(), w.federer_bound_upper = federer;
  return w;
}

}  // namespace

std::optional<ReachWitness> refute_declared_reach(const exact::ImplicitSystem& system, const exact::Polynomial* selector,
                                                  const io::PointSet& points, const detail::PointGrid& grid,
                                                  const io::ReachSpec& reach, double radius, int threads) {
  const int N = system.ambient_dimension(), k = system.codimension();
  const int n = static_cast<int>(points.size());
  const double tau_lo = sqrt_lower(reach.squared);
  if (!(tau_lo > 0) || k == 0 || n < 2) return std::nullopt;
  // The points of M, at the scale of the coordinates (as check 1 runs the same test, sanity.cpp).
  double magnitude = 0;
  for (double c : points.coordinates) magnitude = std::max(magnitude, std::abs(c));
  const int scale_exponent = magnitude > 0 && std::isfinite(magnitude) ? std::ilogb(magnitude) : 0;
  const exact::ManifoldDistance to_M(system.equations(), N, selector, scale_exponent);
  std::vector<BasePoint> base(n);
  detail::parallel_for(n, threads, [&](std::size_t i, int) {
    const exact::DistanceCertificate c = to_M.certify(points.point(i));
    BasePoint& b = base[i];
    if (!c.certified || !exact::jacobian_enclosure(system, c.zero_box, b.J)) return;
    // Rows scaled to magnitude about 1 (ROW SCALING, reach_check.hpp), by outward-rounded products.
    exact::UpwardRounding up;
    for (int e = 0; e < k; ++e) {
      double big = 0;
      for (int v = 0; v < N; ++v) big = std::max({big, std::abs(b.J[e * N + v].lo), std::abs(b.J[e * N + v].hi)});
      if (!(big > 0)) return;  // a zero row: J_F(p*) has rank < k (never after check 1)
      const IA scale(std::ldexp(1.0, -std::ilogb(big)));
      for (int v = 0; v < N; ++v) b.J[e * N + v] = exact::to_interval(exact::to_interval_number(b.J[e * N + v]) * scale);
    }
    b.lambda_max = exact::gram_eigenvalue_bounds(b.J, k, N).upper;
    b.box = c.zero_box, b.distance = c.distance_upper;
    b.usable = b.lambda_max < INFINITY && std::isfinite(b.distance);
  });
  // Pairs beyond 2 τ + the two distances to M cannot refute (dist(d, T) <= |d|): the cap (work only).
  double far = 0;
  for (const BasePoint& b : base)
    if (b.usable) far = std::max(far, b.distance);
  std::vector<std::optional<ReachWitness>> found(n);
  detail::parallel_for(n, threads, [&](std::size_t i, int) {
    if (!base[i].usable) return;
    exact::UpwardRounding up;
    const exact::Interval tau = exact::enclose(reach.squared);
    const double cap = (IA(2) * exact::sqrt(IA(tau.hi)) + IA(base[i].distance) + IA(far)).sup();
    const double r = std::min(radius, cap);
    for (int j : grid.ball(points.point(i), r)) {  // increasing j
      if (j <= static_cast<int>(i) || !base[j].usable) continue;
      auto w = test_pair(base[i], base[j], static_cast<int>(i), j, tau_lo, k, N);
      if (!w) w = test_pair(base[j], base[i], j, static_cast<int>(i), tau_lo, k, N);
      if (w) {
        found[i] = w;
        return;
      }
    }
  });
  for (auto& w : found)
    if (w) return w;
  return std::nullopt;
}

void record_reach_refutation(CheckEntry& entry, const ReachWitness& w, const io::ReachSpec& reach) {
  entry.refute("the spec's declared reach is false: two points of M violate Federer's inequality "
               "dist(y - x, T_x M) <= |y - x|^2 / (2 reach)");
  entry.add_witness({{"kind", "declared_reach_is_false"},
                     {"points", {w.i, w.j}},
                     {"tangent_at", w.tangent_at},
                     {"normal_distance_lower", w.normal_distance_lower},
                     {"squared_distance_upper", w.squared_distance_upper},
                     {"federer_bound_upper", w.federer_bound_upper},
                     {"declared_reach", reach.text}});
  entry.summary += "; DECLARED REACH " + reach.text + " IS FALSE: the points of M near points " + std::to_string(w.i) +
                   " and " + std::to_string(w.j) + " are " + num(w.normal_distance_lower) +
                   " or more from the tangent space at " + std::to_string(w.tangent_at) + "'s, above " +
                   num(w.federer_bound_upper) + " >= |y - x|^2 / (2 reach) (Federer)";
}

}  // namespace delcert::certify
