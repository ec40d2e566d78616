#include "core/sampling/sampling.hpp"

#include <Eigen/Core>
#include <cmath>
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <utility>

#include <limits>
#include <numbers>
#include <queue>
#include <stdexcept>

#include "core/spatial/neighbour_index.hpp"
#include "io/input_error.hpp"

namespace delcert::sampling {

namespace {

using Kind = io::ShapeSpec::Kind;

// Haar measure on SO(3): a uniform unit quaternion, as a row-major rotation matrix R[0..9). The
// Frobenius metric on SO(3) is bi-invariant, so Haar measure is its volume measure.
void uniform_rotation(Random& rng, double* R) {
  double q[4], n2 = 0;
  while (n2 < 1e-20) {
    n2 = 0;
    for (double& v : q) v = rng.normal(), n2 += v * v;
  }
  double n = std::sqrt(n2), w = q[0] / n, x = q[1] / n, y = q[2] / n, z = q[3] / n;
  const double M[9] = {1 - 2 * (y * y + z * z), 2 * (x * y - z * w),     2 * (x * z + y * w),
                       2 * (x * y + z * w),     1 - 2 * (x * x + z * z), 2 * (y * z - x * w),
                       2 * (x * z - y * w),     2 * (y * z + x * w),     1 - 2 * (x * x + y * y)};
  std::copy(M, M + 9, R);
}

void sample_shape(const io::ShapeSpec& sh, int N, Random& rng, std::vector<double>& p) {
  p.assign(N, 0.0);
  const double two_pi = 2 * std::numbers::pi;
  switch (sh.kind) {
    case Kind::sphere: {
      double norm2 = 0;
      while (norm2 < 1e-20) {
        norm2 = 0;
        for (int j = 0; j < N; ++j) p[j] = rng.normal(), norm2 += p[j] * p[j];
      }
      double s = sh.radius.get_d() / std::sqrt(norm2);
      for (int j = 0; j < N; ++j) p[j] = sh.center[j].get_d() + s * p[j];
      break;
    }
    case Kind::product_of_circles:
      for (std::size_t c = 0; c < sh.radii.size(); ++c) {
        double a = rng.uniform(0, two_pi), r = sh.radii[c].get_d();
        p[2 * c] = r * std::cos(a);
        p[2 * c + 1] = r * std::sin(a);
      }
      break;
    case Kind::torus_of_revolution: {
      // Area element (R + r cos v) du dv: rejection on v.
      double R = sh.major_radius.get_d(), r = sh.minor_radius.get_d();
      double u = rng.uniform(0, two_pi), v;
      do v = rng.uniform(0, two_pi);
      while (rng.uniform() * (R + r) >= R + r * std::cos(v));
      p[0] = (R + r * std::cos(v)) * std::cos(u);
      p[1] = (R + r * std::cos(v)) * std::sin(u);
      p[2] = r * std::sin(v);
      break;
    }
    case Kind::so3:
      uniform_rotation(rng, p.data());
      break;
    case Kind::product:
      // The volume measure of a Riemannian product is the product of the factors' volume
      // measures: each factor sampled on its own, uniformly.
      for (const io::ShapeFactor& f : sh.factors) {
        if (f.kind == io::ShapeFactor::Kind::so3) {
          double R[9];
          uniform_rotation(rng, R);
          for (int k = 0; k < 9; ++k) p[f.coordinates[k]] = R[k];
          continue;
        }
        double norm2 = 0;
        std::vector<double> x(f.coordinates.size());
        while (norm2 < 1e-20) {
          norm2 = 0;
          for (double& v : x) v = rng.normal(), norm2 += v * v;
        }
        const double s = f.radius.get_d() / std::sqrt(norm2);
        for (std::size_t k = 0; k < x.size(); ++k) p[f.coordinates[k]] = s * x[k];
      }
      break;
  }
}

}  // namespace

void sample_manifold(const manifold::Manifold& manifold, std::size_t count, Random& rng, io::PointSet& out,
                     const std::function<void(std::size_t)>& on_point) {
  const auto& spec = manifold.spec();
  const int N = manifold.ambient_dimension();
  out.dimension = N;
  out.coordinates.reserve(out.coordinates.size() + count * N);
  std::vector<double> p;
  if (spec.parametrization) {
    for (std::size_t i = 0; i < count; ++i) {
      sample_shape(*spec.parametrization, N, rng, p);
      out.push_back(p);
      if (on_point) on_point(i + 1);
    }
    return;
  }
  std::size_t produced = 0, attempts = 0;
  p.resize(N);
  while (produced < count) {
    if (++attempts > 100 * count + 1000)
      throw io::InputError(spec.source, 0,
                           "sampling: too few bounding-box points project onto M; check the bounding box and the "
                           "equations");
    for (int j = 0; j < N; ++j) p[j] = rng.uniform(spec.bounding_box[j].first, spec.bounding_box[j].second);
    auto z = manifold.project(p);
    if (!z || !manifold.on_selected_component(manifold::as_span(*z))) continue;
    bool inside = true;
    for (int j = 0; j < N; ++j)
      inside = inside && (*z)[j] >= spec.bounding_box[j].first && (*z)[j] <= spec.bounding_box[j].second;
    if (!inside) continue;
    out.push_back(manifold::as_span(*z));
    ++produced;
    if (on_point) on_point(produced);
  }
}

std::vector<std::size_t> farthest_point_selection(const io::PointSet& dense, double eps, double* covering_radius,
                                                  const std::function<void(std::size_t)>& on_select) {
  const std::size_t n = dense.size();
  std::vector<std::size_t> selected;
  if (!n) {
    if (covering_radius) *covering_radius = 0;
    return selected;
  }
  const spatial::NeighbourIndex tree(dense);
  std::vector<double> dist2(n, std::numeric_limits<double>::infinity());
  // Lazy max-heap of (squared distance to the selection, index); ties go to the smaller index.
  using Item = std::pair<double, std::size_t>;
  auto cmp = [](const Item& a, const Item& b) { return a.first < b.first || (a.first == b.first && a.second > b.second); };
  std::priority_queue<Item, std::vector<Item>, decltype(cmp)> heap(cmp);
  const double eps2 = eps * eps;
  std::size_t next = 0;
  double radius2 = std::numeric_limits<double>::infinity();
  for (;;) {
    selected.push_back(next);
    if (on_select) on_select(selected.size());
    auto q = dense.point(next);
    // Every point is within radius2 of the selection, so only points within radius2 of the new
    // point can get closer.
    tree.for_each_in_ball(q, radius2, [&](std::size_t i, double d2) {
      if (d2 < dist2[i]) {
        dist2[i] = d2;
        heap.emplace(d2, i);
      }
    });
    while (!heap.empty() && heap.top().first != dist2[heap.top().second]) heap.pop();
    if (heap.empty()) {
      radius2 = 0;
      break;
    }
    radius2 = heap.top().first;
    if (radius2 < eps2) break;
    next = heap.top().second;
    heap.pop();
  }
  if (covering_radius) *covering_radius = std::sqrt(radius2);
  return selected;
}

EpsNetResult eps_net(const manifold::Manifold& manifold, const EpsNetOptions& options) {
  if (!(options.eps > 0) || !std::isfinite(options.eps)) throw std::invalid_argument("eps must be a positive number");
  Random rng(options.seed);
  io::PointSet dense;
  dense.dimension = manifold.ambient_dimension();
  std::size_t target = options.min_dense;
  std::vector<std::size_t> selected;
  double cover = 0;
  bool capped = false;
  for (int round = 0; round < 6; ++round) {
    std::function<void(std::size_t)> on_point, on_select;
    if (options.progress) {
      const std::size_t before = dense.size();
      options.progress("dense sample", round + 1, before, target);
      on_point = [&, before, round](std::size_t k) { options.progress("dense sample", round + 1, before + k, target); };
      on_select = [&, round](std::size_t k) { options.progress("net extraction", round + 1, k, 0); };
    }
    sample_manifold(manifold, target - dense.size(), rng, dense, on_point);
    selected = farthest_point_selection(dense, options.eps, &cover, on_select);
    auto wanted = static_cast<std::size_t>(options.oversampling * static_cast<double>(selected.size()));
    capped = wanted > options.max_dense;
    wanted = std::min(std::max(wanted, options.min_dense), options.max_dense);
    if (wanted <= dense.size() * 11 / 10) break;  // dense enough: within 10% of the target
    target = wanted;
  }
  EpsNetResult r;
  r.points.dimension = dense.dimension;
  for (auto i : selected) {
    r.points.push_back(dense.point(i));
    r.max_residual = std::max(r.max_residual, manifold.residual(dense.point(i)));
  }
  r.covering_radius = cover;
  r.dense_size = dense.size();
  r.dense_capped = capped;
  const spatial::NeighbourIndex tree(r.points);
  double min2 = std::numeric_limits<double>::infinity();
  std::vector<std::pair<double, std::size_t>> nn;
  for (std::size_t i = 0; i < r.points.size(); ++i) {
    tree.nearest(r.points.point(i), 2, nn);
    if (nn.size() == 2) min2 = std::min(min2, nn[1].first);
  }
  r.min_distance = std::isfinite(min2) ? std::sqrt(min2) : 0;
  return r;
}

EpsNetResult eps_net_with_at_least(const manifold::Manifold& manifold, const EpsNetOptions& options,
                                   std::size_t min_points, int* halvings) {
  EpsNetOptions o = options;
  EpsNetResult net = eps_net(manifold, o);
  int h = 0;
  while (net.points.size() < min_points && h < 20) {
    ++h;
    o.eps /= 2;
    net = eps_net(manifold, o);
  }
  if (halvings) *halvings = h;
  return net;
}

EpsNetEstimate estimate_eps_net(const manifold::Manifold& manifold, const EpsNetOptions& options) {
  if (!(options.eps > 0) || !std::isfinite(options.eps)) throw std::invalid_argument("eps must be a positive number");
  Random rng(options.seed);
  io::PointSet pilot;
  pilot.dimension = manifold.ambient_dimension();
  sample_manifold(manifold, options.min_dense, rng, pilot);
  const double m = manifold.intrinsic_dimension();
  double eps = options.eps, cover = 0, scale = 1;
  std::size_t k = 0;
  for (int j = 0; j < 2000; ++j) {
    k = farthest_point_selection(pilot, eps, &cover).size();
    const double step = k == pilot.size() ? 256 : 2;  // every point selected: far too fine, jump
    if (4 * k <= pilot.size() || !std::isfinite(eps * step)) break;
    eps *= step, scale *= std::pow(step, m);
  }
  EpsNetEstimate e;
  e.net_points = static_cast<double>(k) * scale;  // (may overflow to inf for an absurd eps)
  e.eps_at_cap = eps * std::pow(options.oversampling * static_cast<double>(k) / static_cast<double>(options.max_dense), 1 / m);
  e.dense_points = std::max(options.oversampling * e.net_points, static_cast<double>(options.min_dense));
  return e;
}

namespace {

// `units` x 10^`exponent` as a decimal a person reads and --eps parses exactly: "0.0071", "12", "3.5e-07".
std::string decimal_text(long long units, int exponent) {
  std::string digits = std::to_string(units);
  while (digits.size() > 1 && digits.back() == '0') digits.pop_back(), ++exponent;
  const int lead = exponent + static_cast<int>(digits.size()) - 1;  // the power of ten of the first digit
  if (lead < -5 || lead > 6) {
    std::string mantissa = digits.substr(0, 1) + (digits.size() > 1 ? "." + digits.substr(1) : "");
    return mantissa + "e" + std::to_string(lead);
  }
  if (exponent >= 0) return digits + std::string(static_cast<std::size_t>(exponent), '0');
  const int point = static_cast<int>(digits.size()) + exponent;  // digits before the decimal point
  if (point > 0) return digits.substr(0, static_cast<std::size_t>(point)) + "." + digits.substr(static_cast<std::size_t>(point));
  return "0." + std::string(static_cast<std::size_t>(-point), '0') + digits;
}

// The smallest 2-significant-digit decimal >= x (x > 0, finite): 0.00706 -> "0.0071", 0.0070 -> "0.007".
std::pair<long long, int> round_up_two_digits(double x) {
  int exponent = static_cast<int>(std::floor(std::log10(x))) - 1;
  auto units = static_cast<long long>(std::ceil(x / std::pow(10.0, exponent)));
  if (units < 10) units *= 10, --exponent;  // log10 rounded up across a power of ten
  while (static_cast<double>(units) * std::pow(10.0, exponent) < x) ++units;
  if (units >= 100) units = (units + 9) / 10, ++exponent;
  return {units, exponent};
}

bool fits_the_cap(const manifold::Manifold& manifold, const EpsNetOptions& options, double eps) {
  EpsNetOptions o = options;
  o.eps = eps;
  return estimate_eps_net(manifold, o).dense_points <= static_cast<double>(options.max_dense);
}

}  // namespace

std::string smallest_eps_within_cap(const manifold::Manifold& manifold, const EpsNetOptions& options) {
  const EpsNetEstimate e = estimate_eps_net(manifold, options);
  double from = std::isfinite(e.eps_at_cap) && e.eps_at_cap > options.eps ? e.eps_at_cap : options.eps;
  auto [units, exponent] = round_up_two_digits(from);
  // The estimate at another eps is another pilot run: eps_at_cap is only where it extrapolates to,
  // so the suggestion is checked, and raised one step (of the second digit) until it fits. Both
  // doubles the decimal may become are checked: the nearest and the one below it (a rational's
  // get_d truncates), so that the suggestion, fed back as --eps, is accepted.
  for (int step = 0; step < 1000; ++step) {
    const std::string text = decimal_text(units, exponent);
    const double nearest = std::strtod(text.c_str(), nullptr);
    if (fits_the_cap(manifold, options, nearest) && fits_the_cap(manifold, options, std::nextafter(nearest, 0.0)))
      return text;
    if (++units >= 100) units = 10, ++exponent;
  }
  return decimal_text(units, exponent);  // (not reached for a manifold of finite size: a coarse eps fits)
}

void check_eps_net_size(const manifold::Manifold& manifold, const sampling::EpsNetOptions& options) {
  const sampling::EpsNetEstimate e = sampling::estimate_eps_net(manifold, options);
  const double cap = static_cast<double>(options.max_dense);
  if (e.dense_points > cap) {
    char dense[32], msg[600];
    std::snprintf(dense, sizeof dense, std::isfinite(e.dense_points) ? "about %.3g" : "more than 1e308", e.dense_points);
    std::snprintf(msg, sizeof msg,
                  "%g is too small for this command: its eps-net needs a dense sample of %s points, more than the cap "
                  "of %.3g (about %.0f per net point: nets of at most about %.0f points); give eps >= %s",
                  options.eps, dense, cap, options.oversampling, cap / options.oversampling,
                  smallest_eps_within_cap(manifold, options).c_str());
    throw io::InputError("--eps", 0, msg);
  }
  if (e.dense_points > 1e6)
    std::fprintf(stderr, "warning: eps %g: an eps-net of about %.3g points from a dense sample of about %.3g points; "
                 "this takes a while\n", options.eps, e.net_points, e.dense_points);
}

}  // namespace delcert::sampling
