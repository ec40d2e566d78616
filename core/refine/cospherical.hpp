// The quasi-cospherical complex cosph^{δ0}(p) (paper §4.1.2 eq. (cosph), docs/design.md §3.4).
//
// q * σ belongs to cosph^{δ0}(p) when σ ∈ star(p), R_p(σ) < ε, σ is Γ0-good, q ∉ σ and
//   0 <= ||c_p(σ) - q||^2 - R_p(σ)^2 <= δ0^2 L(q * σ)^2,
// i.e. the elementary weight function ω(q) = sqrt(||c_p(σ) - q||^2 - R_p(σ)^2) <= δ0 L(q * σ)
// puts c_p(σ) in the weighted normal space of q * σ. An empty cosph(p) means every star
// simplex at p is δ0^2 L^2-power-protected (paper Lemma 4.4).
//
// Two knobs serve the practical mode (the paper's definition is length_floor = 0,
// lower = 0, slack = 0):
//  - length_floor: the bound uses max(L(q * σ), length_floor); with length_floor = μ0 ε an
//    empty cosph implies the claimed δ̌^2 = δ0^2 (μ0 ε)^2 protection even where the input is
//    denser than μ0 ε (the paper assumes sparsity, random inputs are not sparse);
//  - lower = -inf: a point on or inside the ball (negative power, from a tie the star resolved
//    symbolically or from rounding) is unprotected too, not "outside cosph";
//  - slack: an absolute widening so that the double-precision decision errs on the side of
//    "unprotected" (the certifier decides the same inequality exactly).
#pragma once

#include <cstddef>
#include <limits>
#include <span>
#include <vector>

#include "core/spatial/neighbour_index.hpp"
#include "io/points.hpp"

namespace delcert::refine {

struct CosphOptions {
  double delta0 = 0.1;
  double length_floor = 0;
  double lower = 0;
  double slack = 0;
};

struct CosphMember {
  std::size_t q = 0;     // the apex point
  double power = 0;      // ||c - q||^2 - R^2
  double bound = 0;      // δ0^2 max(L(q * σ), length_floor)^2
};

// Is q * σ in cosph given σ's power centre and R_p(σ)^2? (σ ∈ star(p), Γ0-good and R_p < ε
// are the caller's preconditions; see cosph_test for the full definition.)
bool cosph_member(const io::PointSet& points, std::span<const int> cell, std::span<const double> centre, double radius2,
                  std::size_t q, const CosphOptions& options, CosphMember* out = nullptr);

// Every q ∉ σ with q * σ in cosph, sorted by q. Only points within
// sqrt(R^2 + δ0^2 max(L(σ), floor)^2 + slack) of c can qualify (L(q * σ) <= L(σ)); those come
// from `index`, which must hold exactly the points of `points`.
std::vector<CosphMember> cosph_members(const io::PointSet& points, const spatial::NeighbourIndex& index, std::span<const int> cell,
                                       std::span<const double> centre, double radius2, const CosphOptions& options);

// The whole definition, preconditions included: R_p(σ) < eps and σ Γ0-good (then the power
// bound). Returns false when a precondition fails.
bool cosph_test(const io::PointSet& points, std::span<const int> cell, std::span<const double> centre, double radius2,
                std::size_t q, double eps, double gamma0, const CosphOptions& options);

}  // namespace delcert::refine
