#include "certify/tangential/sanity.hpp"

#include <mpfr.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>
#include <optional>

#include "certify/detail/grid.hpp"
#include "certify/detail/parallel.hpp"
#include "exact/manifold_distance.hpp"
#include "exact/number_types.hpp"
#include "exact/simplex_predicates.hpp"
#include "exact/tangent_space.hpp"
#include "io/input_error.hpp"

namespace delcert::certify {

using nlohmann::json;

namespace {

// Rank of a small exact matrix (rows x cols, row-major) by Gaussian elimination over Q.
int exact_rank(std::vector<mpq_class> a, int rows, int cols) {
  int rank = 0;
  for (int c = 0; c < cols && rank < rows; ++c) {
    int piv = -1;
    for (int r = rank; r < rows; ++r)
      if (sgn(a[r * cols + c]) != 0) piv = r;
    if (piv < 0) continue;
    for (int k = 0; k < cols; ++k) std::swap(a[piv * cols + k], a[rank * cols + k]);
    for (int r = rank + 1; r < rows; ++r) {
      if (sgn(a[r * cols + c]) == 0) continue;
      mpq_class f = a[r * cols + c] / a[rank * cols + c];
      for (int k = c; k < cols; ++k) a[r * cols + k] -= f * a[rank * cols + k];
    }
    ++rank;
  }
  return rank;
}

exact::Interval sqrt_enclosure(const mpq_class& q) {
  // MPFR's directed roundings give bounds within an ulp or two; then exact comparisons of squares
  // move each end to the tightest double, so lo = the largest double with lo^2 <= q and hi = the
  // smallest with hi^2 >= q. Tightness matters: a claim s with s^2 < q must give
  // enclose(s).lo <= lo (the consistency guard of certificate.hpp relies on it).
  mpfr_t x;
  mpfr_init2(x, 53);
  mpfr_set_q(x, q.get_mpq_t(), MPFR_RNDD);
  mpfr_sqrt(x, x, MPFR_RNDD);
  double lo = mpfr_get_d(x, MPFR_RNDD);
  mpfr_set_q(x, q.get_mpq_t(), MPFR_RNDU);
  mpfr_sqrt(x, x, MPFR_RNDU);
  double hi = mpfr_get_d(x, MPFR_RNDU);
  mpfr_clear(x);
  auto square = [](double d) -> mpq_class {  // not auto: a gmpxx expression would dangle
    mpq_class v(d);
    return v * v;
  };
  const double inf = std::numeric_limits<double>::infinity();
  while (std::isfinite(lo) && square(std::nextafter(lo, inf)) <= q) lo = std::nextafter(lo, inf);
  while (hi > 0 && std::isfinite(hi) && square(std::nextafter(hi, 0.0)) >= q) hi = std::nextafter(hi, 0.0);
  return {lo, hi};
}

}  // namespace

SanityResult check_input_sanity(const io::ManifoldSpec& spec, const io::PointSet& points, const std::vector<long>& lines,
                                const std::string& file, bool accept_off_manifold, int threads) {
  const int N = spec.ambient_dimension, m = spec.intrinsic_dimension, k = N - m;
  const std::size_t n = points.size();
  auto line_of = [&](std::size_t i) { return i < lines.size() ? lines[i] : 0L; };
  // Residuals: a tight enclosure of each |F_i(p)| from exact dyadic arithmetic first
  // (ImplicitSystem::residual_enclosures); the rational |F_i(p)| only where it cannot settle the
  // comparison with the tolerance, and below for the points that can hold the largest residual.
  const exact::ImplicitSystem system(spec.equations, N);
  const exact::Interval tol = exact::enclose(spec.residual_tolerance);
  std::vector<exact::Interval> worst(n);  // encloses max_i |F_i(p)| per point
  std::vector<char> off(n, 0);            // some |F_i(p)| > residual_tolerance (decided exactly)
  std::vector<double> distance(n);  // certified upper bound on the distance from p to M
  // The distance test runs at the scale of the coordinates (exact/manifold_distance.hpp).
  double magnitude = 0;
  for (double c : points.coordinates) magnitude = std::max(magnitude, std::abs(c));
  const int scale_exponent = magnitude > 0 && std::isfinite(magnitude) ? std::ilogb(magnitude) : 0;
  const exact::ManifoldDistance to_M(spec.equations, N, spec.selector ? &*spec.selector : nullptr, scale_exponent);
  detail::parallel_for(n, threads, [&](std::size_t idx, int) {
    const auto p = points.point(idx);
    std::optional<std::vector<mpq_class>> F;  // F(p) exactly, when an enclosure does not decide
    const std::vector<exact::Interval> r = system.residual_enclosures(p);
    for (int i = 0; i < k; ++i) {
      worst[idx] = {std::max(worst[idx].lo, r[i].lo), std::max(worst[idx].hi, r[i].hi)};
      if (r[i].hi <= tol.lo) continue;  // |F_i(p)| <= tolerance
      if (!F) F = system.evaluate_exact(p);
      const mpq_class f = abs((*F)[i]);
      if (f > spec.residual_tolerance) off[idx] = 1;  // (refused below unless accepted, with the distance to M)
    }
    if (spec.selector && sgn(spec.selector->evaluate(std::span<const mpq_class>(exact::to_rational(p)))) <= 0)
      throw io::InputError(file, line_of(idx),
                           "point " + std::to_string(idx) + " lies on the wrong component: the selector " +
                               spec.selector_text + " is not > 0 there");
    // A small residual does not bound the distance to M (for (|x|^2 - 1)^2 = 0 a residual of
    // 1e-9 is a distance of 3e-5) nor prove that M is a manifold near p: certify both with an
    // interval Krawczyk test on the normal slice (exact/manifold_distance.hpp).
    const exact::DistanceCertificate d = to_M.certify(p);
    // J_F has rank k at every point of d.region (step 4 there): when p lies in it, so at p; else
    // the rank of the exact Jacobian at p decides.
    bool full_rank = d.certified;
    for (int v = 0; v < N && full_rank; ++v) full_rank = d.region[v].lo <= p[v] && p[v] <= d.region[v].hi;
    if (!full_rank) {
      if (exact_rank(system.jacobian_exact(p), k, N) != k)
        throw io::InputError(file, line_of(idx),
                             "the Jacobian of F is rank-deficient at point " + std::to_string(idx) +
                                 ", so its tangent space p + ker J_F(p) is not an m-flat; move the point");
    }
    if (!d.certified)
      throw io::InputError(file, line_of(idx),
                           "point " + std::to_string(idx) +
                               ": no point of M could be certified near it (searched up to about " +
                               num(d.searched_radius) + " from it: " + d.failure +
                               "); the spec's Jacobian may be rank-deficient on M (docs/design.md §2 requires full rank "
                               "N - m on M, e.g. write x1^2 + x2^2 + x3^2 - 1, not its square) or the point is "
                               "too far from M; fix the spec or project the point onto M");
    distance[idx] = d.distance_upper;
  });
  SanityResult R;
  CheckEntry& e = R.entry;
  for (std::size_t i = 0; i < n; ++i)
    if (off[i]) R.off_manifold.push_back(static_cast<int>(i));
  // The largest residual, exactly, at the smallest index attaining it: a point whose enclosure
  // ends below the largest lower bound cannot attain it, so only the others are evaluated (an
  // enclosure [0, 0] is the exact 0).
  double floor = 0;
  for (const auto& w : worst) floor = std::max(floor, w.lo);
  std::vector<std::size_t> can;
  for (std::size_t i = 0; i < n; ++i)
    if (worst[i].hi >= floor) can.push_back(i);
  std::vector<mpq_class> exact_worst(can.size());
  detail::parallel_for(can.size(), threads, [&](std::size_t c, int) {
    if (worst[can[c]].hi == 0) return;
    for (const mpq_class& f : system.evaluate_exact(points.point(can[c]))) exact_worst[c] = std::max(exact_worst[c], mpq_class(abs(f)));
  });
  std::size_t arg = 0;
  mpq_class maxres(0);
  for (std::size_t c = 0; c < can.size(); ++c)
    if (c == 0 || exact_worst[c] > maxres) maxres = exact_worst[c], arg = can[c];
  std::size_t far = 0;  // the smallest index attaining the largest distance bound
  for (std::size_t i = 1; i < n; ++i)
    if (distance[i] > distance[far]) far = i;
  const double maxdist = n ? distance[far] : 0.0;
  R.distance_to_M = distance;
  // Points off M, said first and with how far (issue 41: a mesh of the wrong radius), before any other check.
  const std::string off_M = R.off_manifold.empty() ? "" : "the points are not on M: " + std::to_string(R.off_manifold.size()) + " of " +
      std::to_string(n) + " point(s) off M beyond the residual tolerance " + exact::rational_to_string(spec.residual_tolerance) +
      " (exactly; the first: point " + std::to_string(R.off_manifold[0]) + ", max |F_i(p)| about " + num(worst[R.off_manifold[0]].hi) +
      "); every point is within " + num(maxdist) + " of M (certified upper bound; the largest: point " + std::to_string(far) + ")";
  if (!R.off_manifold.empty() && !accept_off_manifold)
    throw io::InputError(file, line_of(R.off_manifold[0]), off_M + ". The tangential Delaunay complex needs T_p M: project the "
                         "points onto M, raise residual_tolerance in the spec (or pass --residual-tolerance), or, for a "
                         "complex claimed to be restricted Delaunay (a mesher's output), pass it with --complex and --kind restricted");
  e.summary = std::to_string(n) + " distinct points in R^" + std::to_string(N) + ", max |F_i(p)| <= " +
              num(exact::enclose(maxres).hi) + " (tolerance " + exact::rational_to_string(spec.residual_tolerance) +
              "), every point within " + num(maxdist) + " of M (certified" +
              (maxdist > 0 ? "; the farthest: point " + std::to_string(far) : std::string()) + "), full-rank Jacobian there";
  if (!R.off_manifold.empty())
    e.summary = off_M + "; max |F_i(p)| <= " + num(exact::enclose(maxres).hi) + ", full-rank Jacobian there; accepted for the "
                "restricted Delaunay complex: checks that need T_p M are not computed; checks 11-12 look for a point's "
                "restricted Voronoi cell out to its distance to M and beyond";
  e.margin = {{"max_residual", {{"certified_upper_bound", num(exact::enclose(maxres).hi)},
                                {"enclosure", enclosure_json(exact::enclose(maxres))}}},
              {"at_point", n ? json(arg) : json(nullptr)},
              {"max_distance_to_M", {{"certified_upper_bound", num(maxdist)}, {"at_point", n ? json(far) : json(nullptr)}}}};
  e.details = {{"points", n},
               {"ambient_dimension", N},
               {"intrinsic_dimension", m},
               {"residual_tolerance", exact::rational_to_string(spec.residual_tolerance)},
               {"selector", spec.selector ? json(spec.selector_text) : json(nullptr)},
               {"jacobian_full_rank_everywhere", true},
               {"off_manifold_points", R.off_manifold.size()},
               {"first_off_manifold_point", R.off_manifold.empty() ? json(nullptr) : json(R.off_manifold[0])},
               {"distance_to_M",
                "for each point p, an interval Krawczyk test on G(t) = F(p + A^T t) (A: k orthonormalised "
                "normal directions, doubles taken exactly) proves a unique zero x* = p + A^T t* in a box, "
                "x* on the selected component, and J_F of full rank N - m on a box around x*; "
                "|p - x*| <= sup |A^T t| over the box, rounded upward"},
               {"distinct", "bit-identical and numerically equal points are refused by the reader (exit 2)"}};
  return R;
}

SparsityResult check_sparsity(const io::PointSet& points, const detail::PointGrid& grid, const mpq_class* claim,
                              exact::FilterContext& ctx, int threads) {
  SparsityResult R;
  CheckEntry& e = R.entry;
  const std::size_t n = points.size();
  const int N = points.dimension;
  if (n < 2) {
    e.verdict = Verdict::report;
    e.summary = "fewer than two points";
    return R;
  }
  auto d2 = [&](std::size_t a, std::size_t b) {
    double s = 0;
    for (int k = 0; k < N; ++k) s += (points.point(a)[k] - points.point(b)[k]) * (points.point(a)[k] - points.point(b)[k]);
    return s;
  };
  // Both passes run on the threads in blocks of points; each block keeps its best pair with ties
  // to the smallest (i, j), and the blocks are merged in order, so the pair does not depend on the
  // thread count (nor on the grid's visiting order).
  constexpr std::size_t kBlock = 2048;
  const std::size_t blocks = (n + kBlock - 1) / kBlock;
  // 1. An approximate closest pair (any pair gives a valid upper bound).
  double best = INFINITY;
  std::size_t ba = 0, bb = 1;
  for (double r = grid.spacing(); !(best < INFINITY); r *= 2) {
    std::vector<std::tuple<double, std::size_t, std::size_t>> found(blocks, {INFINITY, 0, 0});
    detail::parallel_for(blocks, threads, [&](std::size_t b, int) {
      auto& [d, fi, fj] = found[b];
      for (std::size_t i = b * kBlock; i < std::min(n, (b + 1) * kBlock); ++i)
        grid.visit_ball(points.point(i), r, [&](int j, const double*) {
          if (static_cast<std::size_t>(j) <= i) return;
          const double e = d2(i, j);
          if (e < d || (e == d && std::pair<std::size_t, std::size_t>(i, j) < std::pair(fi, fj))) d = e, fi = i, fj = j;
        });
    });
    for (const auto& [d, fi, fj] : found)
      if (d < best) best = d, ba = fi, bb = fj;
    if (r > grid.diameter()) break;
  }
  // 2. Every pair at exact squared distance <= D = |a - b|^2 is found by a query of radius
  //    r >= sqrt(D) (sqrt(hi) is correctly rounded; the factor covers its rounding).
  mpq_class D = exact::squared_distance_exact(points.point(ba).data(), points.point(bb).data(), N);
  double r = std::sqrt(exact::enclose(D).hi) * (1 + 0x1p-50);
  // Every pair with |p - q|^2 <= D, decided by exact/'s filtered predicate, is a candidate;
  // their exact squared distances give the minimum.
  R.min_squared = D, R.i = static_cast<int>(ba), R.j = static_cast<int>(bb);
  const exact::RationalConstant bound(D);
  struct Best {
    std::optional<mpq_class> q;
    int i = 0, j = 0;
  };
  std::vector<Best> found(blocks);
  std::vector<exact::FilterContext> ctxs(std::max(1, threads));
  for (auto& c : ctxs) c.force_exact = ctx.force_exact;
  detail::parallel_for(blocks, threads, [&](std::size_t b, int w) {
    Best& B = found[b];
    for (std::size_t i = b * kBlock; i < std::min(n, (b + 1) * kBlock); ++i)
      grid.visit_ball(points.point(i), r, [&](int j, const double*) {
        if (static_cast<std::size_t>(j) <= i) return;
        if (exact::compare_squared_distance(points.point(i).data(), points.point(j).data(), bound, N, ctxs[w]) > 0) return;
        mpq_class q = exact::squared_distance_exact(points.point(i).data(), points.point(j).data(), N);
        if (!B.q || q < *B.q || (q == *B.q && std::pair(int(i), j) < std::pair(B.i, B.j))) B.q = q, B.i = static_cast<int>(i), B.j = j;
      });
  });
  for (const auto& c : ctxs) ctx.stats.merge(c.stats);
  for (const Best& B : found)
    if (B.q && (*B.q < R.min_squared || (*B.q == R.min_squared && std::pair(B.i, B.j) < std::pair(R.i, R.j))))
      R.min_squared = *B.q, R.i = B.i, R.j = B.j;
  exact::Interval dist = sqrt_enclosure(R.min_squared);
  e.margin = {{"min_squared_distance", rational_json(R.min_squared)},
              {"min_distance", lower_bound_json(dist)},
              {"pair", {R.i, R.j}}};
  e.summary = "min distance in [" + num(dist.lo) + ", " + num(dist.hi) + "] between points " + std::to_string(R.i) +
              " and " + std::to_string(R.j);
  if (!claim) {
    e.verdict = Verdict::report;
    e.summary += " (no sparsity claim)";
  } else {
    e.claim = {{"sparsity", exact::rational_to_string(*claim)}, {"meaning", "every two points at distance > sparsity"}};
    e.require_at_least("min_distance", dist.lo, *claim);
    if (R.min_squared > *claim * *claim) {
      e.summary += " > claimed " + exact::rational_to_string(*claim);
    } else {
      e.refute("two points are not farther apart than the claimed sparsity");
      e.add_witness({{"pair", {R.i, R.j}},
                     {"squared_distance", rational_json(R.min_squared)},
                     {"claim_squared", rational_json(*claim * *claim)},
                     {"sign", "squared_distance - claim^2 <= 0"}});
      e.summary += ": NOT > claimed " + exact::rational_to_string(*claim);
    }
  }
  return R;
}

}  // namespace delcert::certify
