// Elementary weight functions (paper §4.1.1, docs/design.md §3.4).
//
// An elementary weight function ω on τ = [v0..vk] gives one vertex v_i a weight ω(v_i) in
// [0, δ0 L(τ)] and every other vertex 0. C(τ, ω) is the point of aff(τ) with
//   ||C - v_u||^2 - ω(v_u)^2  equal for all u,
// and R(τ, ω)^2 is that common value. With t = ω(v_i)^2 and C = v0 + Σ_u λ_u (v_u - v0), the
// conditions read G λ = (h - t e_i) / 2 (i >= 1) or G λ = (h + t 1) / 2 (i = 0), where G is the
// Gram matrix of the edge vectors v_u - v0 and h_u = |v_u - v0|^2. So λ, hence C, is affine in t,
// and R^2 = λ^T G λ - [i = 0] t is a convex quadratic c0 + c1 t + c2 t^2 (c2 = d^T G^-1 d / 4 >= 0):
// its minimum over t in [0, δ0^2 L^2] is found in closed form.
//
// A degenerate τ (G singular to working precision) has no weighted centre in aff(τ) for
// general ω: the functions below report it as invalid / radius +inf ("hits nothing").
#pragma once

#include <Eigen/Core>

#include <optional>
#include <span>

#include "core/refine/simplex_measures.hpp"

namespace delcert::refine {

// R(τ, ω)^2 = c0 + c1 t + c2 t^2 for the weight t = ω(vertex)^2 on `vertex`; c0 = R(τ)^2.
struct WeightedRadiusQuadratic {
  double c0 = 0, c1 = 0, c2 = 0;
  double operator()(double t) const { return c0 + t * (c1 + t * c2); }
  // argmin and min over t in [0, t_max].
  double argmin(double t_max) const;
  double min(double t_max) const { return (*this)(argmin(t_max)); }
};

// nullopt when τ has fewer than 2 vertices or is degenerate (G not positive definite to
// working precision).
std::optional<WeightedRadiusQuadratic> weighted_radius_quadratic(const SimplexGeometry& tau, int vertex);

// R(τ, ω)^2 for the weight ω(vertex)^2 = t; +inf when τ is degenerate.
double weighted_radius2(const SimplexGeometry& tau, int vertex, double t);

// C(τ, ω) in ambient coordinates; nullopt when τ is degenerate. `vertices` as for SimplexGeometry.
std::optional<Eigen::VectorXd> weighted_centre(std::span<const std::span<const double>> vertices, int vertex, double t);

struct MinWeightedRadius {
  double radius2 = 0;  // min over elementary weight functions of R(τ, ω)^2 (+inf: degenerate)
  int vertex = -1;     // the weighted vertex of a minimiser
  double t = 0;        // its ω^2
};

// Minimum of R(τ, ω)^2 over all elementary weight functions with ω in [0, δ0 L(τ)] (every
// vertex, every admissible value; t = 0 is the circumradius).
MinWeightedRadius min_weighted_radius2(const SimplexGeometry& tau, double delta0);

}  // namespace delcert::refine
