// The points a star search at p looks at (checks 3, 4, 6, 7 and 10): their indices and the interval rows b(x) =
// U^T (x - p), s(x) = |x - p|^2 in the exact tangent basis U of T_p. Shared by star.cpp (the star of p) and
// secure.cpp (check 7).
#pragma once

#include <algorithm>
#include <array>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "certify/tangential/star.hpp"
#include "exact/interval_arithmetic.hpp"
#include "exact/linear_algebra.hpp"
#include "exact/tangent_predicates.hpp"

namespace delcert::certify::detail {

// Interval arithmetic for enclosures only (never for a decision: signs come from exact/).
// IntervalNumber assumes upward rounding, which analyse_star holds for its whole body.
using IA = exact::IntervalNumber;
constexpr int kMaxM = exact::kMaxTangentDimension;
static_assert(kMaxM <= exact::kMaxLinearSize);
using List = std::array<int, kMaxM + 1>;  // local indices of a cell, [0] = p, the rest increasing

// Growth when the radius was too small: to a little more than what was needed (a margin over
// the floating-point distances and enclosures it was computed from, so that the next run does
// not ask for the same radius again), and at least by a quarter (so that the number of runs is
// logarithmic in the final radius).
constexpr double kNeededRadiusMargin = 1.0625;
constexpr double kMinRadiusGrowth = 1.25;

// The points tested at p: every point within distance `radius` of p (and possibly more).
struct Local {
  int m = 0, N = 0;
  std::vector<int> global;  // local -> global, global[0] = p; the rest increasing
  const io::PointSet* points = nullptr;
  const exact::TangentSpace* space = nullptr;          // null: built on first use from `system`
  const exact::ImplicitSystem* system = nullptr;
  mutable std::optional<exact::TangentSpace> own_space_;
  mutable std::optional<exact::TangentChart> chart_;  // built on first use
  std::vector<IA> rows;       // (m + 1) per local: b = U^T (x - p), s = |x - p|^2 (enclosures)
  std::vector<double> drows;  // midpoints, for the floating-point gift-wrapping
  std::vector<IA> gram;       // m x m enclosure of G = U^T U
  double radius = 0;
  bool all = false;
  bool covered = true;  // the grid held every point within `radius` (false only on an MPI rank's part)

  const IA* row(int l) const { return rows.data() + static_cast<std::size_t>(l) * (m + 1); }
  const double* drow(int l) const { return drows.data() + static_cast<std::size_t>(l) * (m + 1); }
  int size() const { return static_cast<int>(global.size()); }
  const exact::TangentChart& chart() const {
    if (!chart_) {
      std::vector<const double*> ptrs;
      for (std::size_t i = 1; i < global.size(); ++i) ptrs.push_back(points->point(global[i]).data());
      if (!space && !own_space_) own_space_.emplace(*system, points->point(global[0]));
      chart_.emplace(space ? *space : *own_space_, std::span<const double* const>(ptrs));
    }
    return *chart_;
  }
  int local_of(int g) const {
    if (g == global[0]) return 0;
    auto it = std::lower_bound(global.begin() + 1, global.end(), g);
    return it != global.end() && *it == g ? static_cast<int>(it - global.begin()) : -1;
  }
};

// Enclosure of the Gram matrix G = U^T U of the exact basis (m x m).
std::vector<IA> gram_enclosure(const exact::TangentSpace& T, int m);

// The Local of the points `glob` (glob[0] = p, the rest increasing). T may be null (the exact
// tangent space is then built only if the chart is needed). tangent_only: only the enclosures of
// b(x) (check 7); s(x) is left 0 and drows empty. coords: when given, coords[l] holds the
// coordinates of glob[l] (equal to the points', e.g. the grid's copy, read in sequence).
Local make_local_of(const StarSettings& S, const exact::TangentSpace* T, const std::vector<IA>& U, const std::vector<IA>& gram,
                    std::vector<int> glob, double radius, bool tangent_only,
                    const std::vector<const double*>* coords = nullptr);

// The Local of p and the points `near` ((index, coordinates) pairs, in any order, possibly with
// repeats; p itself left out): sorted by index, each once. Clears `near`.
Local make_local_of_near(const StarSettings& S, const exact::TangentSpace* T, const std::vector<IA>& U, const std::vector<IA>& gram,
                         int p, std::vector<std::pair<int, const double*>>& near, double radius, bool tangent_only);

// The Local of every point within `radius` of p (and possibly more: the grid's superset).
Local make_local(const StarSettings& S, const exact::TangentSpace* T, const std::vector<IA>& U, const std::vector<IA>& gram,
                 int p, double radius);

}  // namespace delcert::certify::detail
