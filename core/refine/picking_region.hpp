// The picking region of a bad configuration (paper Definition 4.6): the m-ball
// B(c_p(σ), α R_p(σ)) ∩ T_p, sampled uniformly and mapped onto M by ψ_p.
#pragma once

#include <Eigen/Core>

#include <optional>
#include <span>

#include "core/manifold/manifold.hpp"
#include "core/sampling/random.hpp"

namespace delcert::refine {

struct PickingRegion {
  Eigen::VectorXd centre;   // c_p(σ) in T_p, ambient coordinates (N)
  double radius = 0;        // α R_p(σ)
  Eigen::MatrixXd tangent;  // N by m orthonormal basis of T_p
};

// A point uniform in the m-ball (ambient coordinates): a Gaussian direction times U^(1/m).
Eigen::VectorXd sample_picking_region(const PickingRegion& region, sampling::Random& random);

// y uniform in the region, then x = ψ_p(y) (Newton along the normal space of T_p, which must be
// `frame`'s), on the selected component. nullopt when ψ_p fails, or moves x farther than
// max_distance from y (0: no bound).
std::optional<Eigen::VectorXd> pick_in_region(const manifold::Manifold& manifold, std::span<const double> p, const manifold::Frame& frame,
                                              const PickingRegion& region, sampling::Random& random, double max_distance = 0,
                                              Eigen::VectorXd* y_out = nullptr);

}  // namespace delcert::refine
