// What `delcert refine` writes (docs/design.md §9): DIR/points.txt, DIR/complex.txt, DIR/report.json
// and DIR/claims.json, each atomically.
//
// claims.json ("delcert-claims v2", io/claims.hpp) holds only what the output keeps,
// by the producer's own measure, every value an exact rational string:
//   eps               every star simplex has R_p(σ) < ε               (when no star cell is big)
//   sparsity          every two points are farther apart than this:  μ0 ε_min = ε_min/9 when that
//                     holds, otherwise a rational just below the smallest distance (a random
//                     input, or a reported sparsity violation)
//   gamma0            every simplex of the complex is Γ0-good          (when every star simplex is)
//   power_protection  δ̌^2 = δ0^2 (ε_min/9)^2: every star simplex is power-protected by more than
//                     that                                              (when the margin says so)
// ε_min = ε / 2^eps_level is the smallest local ε of the practical mode (ε without local sites;
// docs/refinement.md, "Local ε"); the star radius is claimed with ε, the largest.
// Under --sizing curvature, claims.json is "delcert-claims v3": instead of "star_radius" it names
// DIR/eps.txt in "star_radius_per_point" and "covering_per_point", ε(p) per point (io/claims.hpp).
// A claim that does not hold is left out and report.json says why. points.txt, complex.txt and
// claims.json are byte-identical for the same inputs and seed; report.json differs only in its
// "seconds" fields.
#pragma once

#include <gmpxx.h>

#include <string>
#include <utility>
#include <vector>

#include "core/refine/refiner.hpp"

namespace delcert::refine {

struct OutputContext {
  std::string manifold;      // spec name
  std::string manifold_source;
  std::string input;         // the --points path, or a description of the generated ε-net
};

struct ClaimsOutcome {
  std::string json;  // the claims.json text
  std::vector<mpq_class> per_point;  // eps.txt's values (curvature sizing, when claimed), else empty
  std::vector<std::pair<std::string, std::string>> omitted;  // (claim, why)
};

// The claims, from the exact constants of result.parameters (not from the rounded doubles).
ClaimsOutcome make_claims(const RefineResult& result);

std::string make_report(const RefineResult& result, const OutputContext& context, const ClaimsOutcome& claims);

// Paper mode: one plain sentence on what Algorithm 1 achieved (report.json "assessment", the
// summary's "assessment" line). At realistic ε its rules often run out with the complex still
// inconsistent or unprotected, or before inserting anything, and the sentence says so, with the
// hypothesis bound on ε and the advice to use the practical mode. Empty in practical mode.
std::string paper_mode_assessment(const RefineResult& result);

// Creates `dir` if missing and writes the four files atomically (claims and report last).
void write_refine_output(const std::string& dir, const RefineResult& result, const OutputContext& context);

}  // namespace delcert::refine
