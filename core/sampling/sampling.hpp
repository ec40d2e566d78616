// Sampling a manifold: uniform random samples and epsilon-nets by farthest-point selection.
#pragma once

#include <cstdint>
#include <functional>
#include <string>

#include "core/manifold/manifold.hpp"
#include "core/sampling/random.hpp"
#include "io/points.hpp"

namespace delcert::sampling {

// Appends `count` random points of M to `out`. Built-in shapes (the spec's "parametrization")
// are sampled through their parametrisation, uniformly with respect to volume. Any other spec:
// uniform points of its bounding box projected onto M (not volume-uniform; failures retried).
// Throws std::runtime_error if a generic spec yields no projectable points. `on_point`, when
// given, is called after each point with the number of points appended so far (for a progress line).
void sample_manifold(const manifold::Manifold& manifold, std::size_t count, Random& random, io::PointSet& out,
                     const std::function<void(std::size_t)>& on_point = {});

struct EpsNetOptions {
  double eps = 0.25;
  std::uint64_t seed = 1;
  // The dense sample has about `oversampling` points per net point (at least `min_dense`).
  double oversampling = 30;
  std::size_t min_dense = 4000;
  std::size_t max_dense = 4'000'000;
  // For a progress line, never changing the result: called with (phase, round, done, total) as the
  // dense sample grows ("dense sample", round 1 to 6, points so far, its target size) and during
  // each farthest-point selection ("net extraction", round, points selected so far, total 0).
  std::function<void(const char*, int, std::size_t, std::size_t)> progress;
};

struct EpsNetResult {
  io::PointSet points;            // in selection order
  double covering_radius = 0;     // max distance from a dense-sample point to the net (< eps)
  double min_distance = 0;        // smallest pairwise distance in the net (>= eps)
  double max_residual = 0;        // max over net points of max_i |F_i(p)|
  std::size_t dense_size = 0;
  // The dense sample stopped at options.max_dense points, fewer than `oversampling` per net
  // point: the net is still eps-sparse, but covers M less surely (a coarser eps avoids it).
  bool dense_capped = false;
};

// An eps-net of M: farthest-point selection from a dense sample, stopping when every dense
// point is within eps of the net. The output is eps-sparse (pairwise distance >= eps) and, as
// far as the dense sample can tell, an eps-sample. Same options, same bytes.
EpsNetResult eps_net(const manifold::Manifold& manifold, const EpsNetOptions& options);

// The starting sample of `refine --eps`: eps_net, but when an eps as coarse as M itself gives
// fewer than min_points points (a star needs m + 2), the net at eps/2, eps/4, ... (at most 20
// halvings; *halvings, when given, says how many were taken).
EpsNetResult eps_net_with_at_least(const manifold::Manifold& manifold, const EpsNetOptions& options,
                                   std::size_t min_points, int* halvings = nullptr);

// A pilot estimate of eps_net's sizes, before the run: farthest-point selection on a pilot of
// `min_dense` random points (same seed), at eps or, where the pilot is too coarse to tell (more
// than a quarter of it selected), at eps' = 2^j eps with the count scaled by (eps' / eps)^m.
// Deterministic; an order of magnitude, for refusing or warning before a run that cannot end.
struct EpsNetEstimate {
  double net_points = 0;    // about this many net points
  double dense_points = 0;  // and a dense sample of oversampling times that (before the caps)
  double eps_at_cap = 0;    // about the eps whose dense sample is max_dense points
};
EpsNetEstimate estimate_eps_net(const manifold::Manifold& manifold, const EpsNetOptions& options);
// Before an eps-net is sampled (sample, refine without points, and the Python module's): refuses
// (io::InputError on --eps) an eps whose net would need a dense sample beyond options.max_dense
// (the selection could not give an eps-net, and would run for hours), naming the smallest eps that
// fits; warns on stderr beyond 10^6 dense points. By estimate_eps_net (a pilot, seeded).
// The message (exit 2) names the cap and the smallest_eps_within_cap.
void check_eps_net_size(const manifold::Manifold& manifold, const EpsNetOptions& options);
// The eps check_eps_net_size suggests, as the decimal it prints: two significant digits, rounded
// up, and checked (by estimate_eps_net at both doubles the decimal may be read as) to pass
// check_eps_net_size, so that feeding it back as --eps is accepted.
std::string smallest_eps_within_cap(const manifold::Manifold& manifold, const EpsNetOptions& options);

// Farthest-point selection on a given point set: indices of the selected points, in order,
// starting from point 0, until the farthest remaining point is closer than eps. Also returns
// the final covering radius of the selection over `dense`. `on_select`, when given, is called
// with the number of points selected so far, after each one.
std::vector<std::size_t> farthest_point_selection(const io::PointSet& dense, double eps, double* covering_radius,
                                                  const std::function<void(std::size_t)>& on_select = {});

}  // namespace delcert::sampling
