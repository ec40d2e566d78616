// Hitting sets (paper Definition 4.7 and Algorithm 2, step 3).
//
// A set S of k <= m + 1 existing points hits a candidate x when x * S is a k-dimensional
// Γ0-flake and some elementary weight function ω on x * S has R(x * S, ω) < β R_p(σ) (the
// radius bound). Pick_valid rejects x when it is hit.
//
// Search. By Lemma 4.1 (2), Δ(x * S) <= 2 R(x * S, ω) / (1 - δ0^2), so every point of S lies
// within 2 β R_p / (1 - δ0^2) of x: those are the candidates. Every proper face of a flake is
// Γ0-good, so S grows one point at a time through Γ0-good simplices x * S' only (S' in canonical
// increasing order). A further necessary condition prunes the growth: by Lemma 4.1 (1), the
// restriction of ω to a face x * S' is an elementary weight function of that face (its weight
// range [0, δ0 L(x * S')] contains the value, as L(x * S') >= L(x * S)), with
// R(x * S', ω|) <= R(x * S, ω); so x * S' can lie under a hitting flake only if the minimum of
// R(x * S', ·) over its own elementary weight functions is below the bound too.
#pragma once

#include <cstddef>
#include <optional>
#include <span>
#include <vector>

#include "core/spatial/neighbour_index.hpp"
#include "io/points.hpp"

namespace delcert::refine {

struct HittingQuery {
  double radius_bound = 0;  // β R_p(σ)
  double gamma0 = 0.1;
  double delta0 = 0.1;
  int max_set_size = 3;     // m + 1
};

struct HittingSet {
  std::vector<std::size_t> points;  // S, sorted
  double radius2 = 0;               // min over ω of R(x * S, ω)^2 (< radius_bound^2)
  int weighted_vertex = 0;          // of a minimiser: 0 = x, i = S[i-1]
  double t = 0;                     // its ω^2
};

struct HittingStats {
  std::size_t candidates = 0;   // points within the candidate radius
  std::size_t simplices = 0;    // simplices x * S examined
  std::size_t flakes = 0;       // of which Γ0-flakes
};

// The first hitting set of x in canonical order (by size, then lexicographically), or nullopt
// when x is a good point. `index` must hold exactly the points of `points`.
std::optional<HittingSet> find_hitting_set(std::span<const double> x, const io::PointSet& points, const spatial::NeighbourIndex& index,
                                           const HittingQuery& query, HittingStats* stats = nullptr);

}  // namespace delcert::refine
