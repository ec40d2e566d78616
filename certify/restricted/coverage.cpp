#include "certify/restricted/coverage.hpp"

#include <Eigen/QR>

#include <algorithm>
#include <cmath>
#include <map>

#include "certify/certificate.hpp"
#include "exact/enclosure.hpp"
#include "exact/interval_arithmetic.hpp"
#include "exact/krawczyk.hpp"

namespace delcert::certify {

namespace {

using exact::Box;
using exact::Interval;
using IA = exact::IntervalNumber;

std::vector<double> centre_of(const Box& X) {
  std::vector<double> c(X.size());
  for (std::size_t i = 0; i < X.size(); ++i) c[i] = X[i].midpoint();
  return c;
}

// An upper bound of max_{x in X} |x - p| / s, s > 0, under upward rounding: max(hi - p, p - lo)
// rounded up is at least the largest deviation in each coordinate, and every later step rounds up
// too. s, a power of two near the radius it is compared with, keeps the squares from under- or
// overflowing at any magnitude of the input.
double farthest_scaled(const Box& X, std::span<const double> p, double s) {
  exact::UpwardRounding up;
  double sum = 0;
  for (std::size_t i = 0; i < X.size(); ++i) {
    const double d = std::max(X[i].hi - p[i], p[i] - X[i].lo) / s;
    sum += d * d;
  }
  return std::sqrt(sum);
}

// The polynomial with variable i standing for old variable order[i].
exact::Polynomial permuted(const exact::Polynomial& f, const std::vector<int>& order) {
  const int N = f.num_variables();
  exact::Polynomial g(N);
  for (const auto& t : f.terms()) {
    exact::Polynomial term = exact::Polynomial::constant(t.coefficient, N);
    for (int i = 0; i < N; ++i)
      if (const auto e = t.monomial.exponents[order[i]]) term = term * exact::Polynomial::variable(i, N).pow(e);
    g += std::move(term);
  }
  return g;
}

class Search {
 public:
  Search(const exact::ImplicitSystem& system, const exact::Polynomial* selector, const io::PointSet& P,
         const detail::PointGrid& grid, double r)
      : system_(system), P_(P), grid_(grid), r_(r), N_(system.ambient_dimension()),
        m_(system.intrinsic_dimension()), F_(system.equations(), m_) {
    if (selector) sel_.emplace(std::vector<exact::Polynomial>{*selector}, N_ - 1);
    s_ = std::ldexp(1.0, std::ilogb(r));
    r_scaled_ = r / s_;  // exact: a representable quotient in [1, 2)
  }

  // (a): no point of M in X.
  bool free_of_M(const Box& X) const {
    if (sel_ && sel_->enclose(0, X).hi <= 0) return true;
    const int k = N_ - m_;
    std::vector<double> x0;
    for (int i = 0; i < k; ++i) {
      const Interval f = F_.enclose(i, X);
      if (f.lo > 0 || f.hi < 0) return true;
      if (x0.empty()) x0 = centre_of(X);
      Box c0(N_);
      for (int v = 0; v < N_; ++v) c0[v] = Interval::point(x0[v]);
      const Interval f0 = F_.enclose(i, c0);
      exact::UpwardRounding up;
      IA acc = exact::to_interval_number(f0);
      for (int v = 0; v < N_; ++v) {
        const Interval d = v < m_ ? F_.enclose_parameter_derivative(i, v, X) : F_.enclose_derivative(i, v - m_, X);
        acc += exact::to_interval_number(d) * (IA(X[v].lo, X[v].hi) - IA(x0[v]));
      }
      if (acc.inf() > 0 || acc.sup() < 0) return true;
    }
    return false;
  }

  // (b): X inside the open ball B(p, r) of the sample point nearest its centre.
  bool inside_a_ball(const Box& X) const {
    const std::vector<double> x0 = centre_of(X);
    int best = -1;
    double best_d2 = INFINITY;
    grid_.visit_ball(x0, r_, [&](int q, const double* y) {
      double d2 = 0;
      for (int v = 0; v < N_; ++v) d2 += (y[v] - x0[v]) * (y[v] - x0[v]);
      if (d2 < best_d2 || best < 0) best_d2 = d2, best = q;
    });
    return best >= 0 && farthest_scaled(X, P_.point(best), s_) < r_scaled_;
  }

  // A certified point of M near X far from P, or nothing.
  std::optional<FarPoint> far_point(const Box& X) {
    const std::vector<double> x0 = centre_of(X);
    std::vector<int> unknowns;
    {
      exact::NearestRounding near;
      Eigen::MatrixXd J = system_.jacobian(x0);
      for (int i = 0; i < J.rows(); ++i)
        if (J.row(i).norm() > 0) J.row(i) /= J.row(i).norm();
      if (!J.allFinite()) return std::nullopt;
      Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(J);
      for (int i = 0; i < N_ - m_; ++i) unknowns.push_back(qr.colsPermutation().indices()[i]);
    }
    std::sort(unknowns.begin(), unknowns.end());
    std::vector<int> order;  // fixed coordinates first, then the unknowns
    for (int v = 0; v < N_; ++v)
      if (!std::binary_search(unknowns.begin(), unknowns.end(), v)) order.push_back(v);
    order.insert(order.end(), unknowns.begin(), unknowns.end());
    auto it = systems_.find(order);
    if (it == systems_.end()) {
      std::vector<exact::Polynomial> eqs;
      for (const auto& f : system_.equations()) eqs.push_back(permuted(f, order));
      it = systems_.emplace(order, exact::ParametricSystem(std::move(eqs), m_)).first;
    }
    Box U(m_), H(N_ - m_);
    for (int a = 0; a < m_; ++a) U[a] = Interval::point(x0[order[a]]);
    for (int j = 0; j < N_ - m_; ++j) {
      const Interval& s = X[order[m_ + j]];
      const double w = s.hi - s.lo;
      H[j] = {s.lo - w, s.hi + w};
    }
    ++krawczyk_calls;
    const exact::KrawczykResult k = exact::krawczyk(it->second, U, H);
    if (k.status != exact::RootStatus::unique_root) return std::nullopt;
    FarPoint f;
    f.x = Box(N_);
    for (int a = 0; a < m_; ++a) f.x[order[a]] = U[a];
    for (int j = 0; j < N_ - m_; ++j) f.x[order[m_ + j]] = k.box[j];
    if (sel_ && !(sel_->enclose(0, f.x).lo > 0)) return std::nullopt;  // x* in {F = 0}, not proven in M
    f.distance_lower = distance_lower_bound(f.x, f.nearest);
    return f;
  }

  // A certified lower bound of |x - q| over x in X and q in P (the file's comment: the nearest
  // point of a non-empty ball query, then every point that can be nearer than it).
  double distance_lower_bound(const Box& X, int& nearest) const {
    const std::vector<double> x0 = centre_of(X);
    const double h = farthest_scaled(X, x0, 1.0);  // the half diagonal about x0, rounded up
    std::vector<int> near;
    for (double R = std::max(2 * h, grid_.spacing()); near.empty(); R *= 2) {
      near = grid_.ball(x0, R);
      if (!(R < INFINITY)) break;
    }
    double D = INFINITY, R2 = INFINITY;
    {
      exact::UpwardRounding up;
      for (int q : near) {
        double d2 = 0;
        for (int v = 0; v < N_; ++v) {
          const double d = std::max(P_.point(q)[v] - x0[v], x0[v] - P_.point(q)[v]);
          d2 += d * d;
        }
        D = std::min(D, std::sqrt(d2));
      }
      R2 = D + 2 * h;
    }
    double best = INFINITY;
    for (int q : grid_.ball(x0, R2)) {
      mpq_class g2 = 0;
      for (int v = 0; v < N_; ++v) {
        const double y = P_.point(q)[v];
        mpq_class gap = 0;
        if (y < X[v].lo) gap = mpq_class(X[v].lo) - mpq_class(y);
        else if (y > X[v].hi) gap = mpq_class(y) - mpq_class(X[v].hi);
        g2 += gap * gap;
      }
      const double L = sqrt(exact::Enclosure(g2)).lower();
      if (L < best) best = L, nearest = q;
    }
    return best;
  }

  long krawczyk_calls = 0;

 private:
  const exact::ImplicitSystem& system_;
  const io::PointSet& P_;
  const detail::PointGrid& grid_;
  double r_;
  int N_, m_;
  exact::ParametricSystem F_;                // the equations, all N variables (m "parameters")
  std::optional<exact::ParametricSystem> sel_;  // the selector, one equation
  double s_ = 1, r_scaled_ = 0;
  std::map<std::vector<int>, exact::ParametricSystem> systems_;  // Krawczyk's systems by variable order
};

}  // namespace

CoverageSearch search_coverage(const exact::ImplicitSystem& system, const exact::Polynomial* selector,
                               const io::PointSet& points, const detail::PointGrid& grid, const Box& box,
                               double c, double r, double target, const CoverageOptions& options) {
  CoverageSearch out;
  if (!(c < r) || !(r > 0) || !std::isfinite(r)) {
    out.reason = "the covering argument does not hold (c < r is needed)";
    return out;
  }
  const int N = system.ambient_dimension();
  Search S(system, selector, points, grid, r);
  // The size limit: a box of widest side w has diagonal at most (r - c) / 8.
  out.size_limit = (r - c) / (8 * std::sqrt(double(N)));
  struct Item {
    Box X;
    bool tried;  // Krawczyk was tried on it or an ancestor
  };
  std::vector<Item> stack{{box, false}};
  while (!stack.empty()) {
    if (out.boxes >= options.max_boxes) {
      out.undecided_boxes += static_cast<long>(stack.size());
      if (out.undecided.size() < 5) out.undecided.push_back(centre_of(stack.back().X));
      out.reason = "the search of the bounding box ran out of its box budget (" + std::to_string(options.max_boxes) + ")";
      break;
    }
    Item it = std::move(stack.back());
    stack.pop_back();
    ++out.boxes;
    const Box& X = it.X;
    if (S.free_of_M(X)) {
      ++out.excluded;
      continue;
    }
    int widest = 0;
    double half_diagonal2 = 0;
    for (int v = 0; v < N; ++v) {
      if (X[v].width() > X[widest].width()) widest = v;
      half_diagonal2 += X[v].width() * X[v].width() / 4;
    }
    const double w = X[widest].width();
    if (std::sqrt(half_diagonal2) < r && S.inside_a_ball(X)) {
      ++out.inside_balls;
      continue;
    }
    if (w <= out.size_limit && !it.tried) {
      it.tried = true;
      if (auto f = S.far_point(X); f && f->distance_lower > c) {
        if (!out.far || f->distance_lower > out.far->distance_lower) out.far = std::move(f);
        if (out.far->distance_lower >= target) break;
        continue;  // this piece of M is far from P: nothing more to learn here
      }
    }
    if (w <= out.size_limit / 4) {
      ++out.undecided_boxes;
      if (out.undecided.size() < 5) out.undecided.push_back(centre_of(X));
      if (out.reason.empty())
        out.reason = "a box of the bounding box is neither proven free of M nor within r of a sample point";
      continue;
    }
    const double mid = X[widest].midpoint();  // before `it` (and X, a reference into it) is moved from
    Item lo = it, hi = std::move(it);
    lo.X[widest].hi = mid, hi.X[widest].lo = mid;
    stack.push_back(std::move(hi));
    stack.push_back(std::move(lo));
  }
  out.krawczyk_calls = S.krawczyk_calls;
  if (out.far)
    out.reason = "a point of M is at distance >= " + num(out.far->distance_lower) +
                 " from P, beyond the covering bound of the restricted cells: P does not sample all of M";
  out.covered = !out.far && out.undecided_boxes == 0 && out.reason.empty();
  return out;
}

CoverageProof prove_coverage(const exact::ImplicitSystem& system, const exact::Polynomial* selector,
                             const std::vector<std::pair<double, double>>& bounding_box,
                             const std::string& connected_shape, const io::PointSet& points,
                             const detail::PointGrid& grid, const RestrictedDelaunay& R, double target,
                             const CoverageOptions& options) {
  CoverageProof out;
  if (!R.covering_certified) {
    out.reason = R.reason;
    out.argument = "none: the covering argument of the restricted cells does not hold";
    return out;
  }
  if (!connected_shape.empty() && !R.simplices.empty()) {
    out.proven = true;
    out.argument = "M is connected (its equations are exactly those of the declared " + connected_shape +
                   ", verified) and holds a restricted Voronoi vertex, within c of P: all of M is within c of P "
                   "(certify/coverage.hpp, argument 1)";
    return out;
  }
  if (bounding_box.empty()) {
    out.reason = "M may have components with no sample point: the spec declares no bounding_box to search";
    out.argument = "only the components of M that hold a point within c of P are proven within c of P; the spec "
                   "declares no bounding box" +
                   std::string(connected_shape.empty() ? " and no verified connected shape" : "") +
                   (R.simplices.empty() ? " (and no restricted Voronoi vertex was found)" : "");
    return out;
  }
  // The declared box, one ulp wider on each side: io reads each rational bound into the nearest
  // double or the one toward zero, either way within one ulp of it.
  Box B(bounding_box.size());
  for (std::size_t i = 0; i < bounding_box.size(); ++i)
    B[i] = {std::nextafter(bounding_box[i].first, -INFINITY), std::nextafter(bounding_box[i].second, INFINITY)};
  out.search = search_coverage(system, selector, points, grid, B, R.covering, R.min_radius, target, options);
  out.proven = out.search->covered;
  out.reason = out.search->reason;
  out.argument = "M lies in the spec's bounding_box (the spec's declaration, assumed, like the reach); every box of a "
                 "subdivision of it is proven free of M or inside the open ball B(p, r) of a sample point, r = min_p "
                 "r_p (certify/coverage.hpp, argument 2)" +
                 std::string(out.proven ? ": all of M is within c of P" : ": not completed");
  return out;
}

}  // namespace delcert::certify
