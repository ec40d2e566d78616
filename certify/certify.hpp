// delcert-certify's driver: reads each input once, runs checks 1-15 (one function each; their
// numbers and names are CheckId in certificate.hpp) and assembles the certificate.
//
//   1 input_sanity       points near M (exact residuals, certified distance), right component, full-rank Jacobian
//   2 sparsity           exact minimum distance and its pair; the sparsity claim
//   3 stars              the complex is exactly the tangential Delaunay complex Del_TM(P)
//   4 consistency        every simplex is in the star of each of its vertices
//   5 thickness          Upsilon of every simplex and face against gamma0; flakes
//   6 power_protection   every star simplex power-protected (beyond the claim); ties refuted
//   7 secure_simplices   paper Definition 3.1 in each vertex's local Euclidean metric, eps the certified
//                        covering radius (a claim with "secure": true, else report)
//   8 topology           pure closed pseudomanifold, sphere links, Euler, Betti over Z/2, Z/3
//   9 theorem            Theorem 3.3's hypotheses from the measured values (report)
//  10 star_radius        every star simplex has R_p(s) < eps (the star_radius claim)
//  11 covering           certified covering radius: P is an eps-sample of M (the covering claim)
//  12 restricted_delaunay Del_RM(P) from the certified restricted Voronoi diagram; with --kind
//                        restricted, the complex is exactly Del_RM(P)
//  13 tangential_equals_restricted  Del_TM(P) = Del_RM(P), either way with witnesses
//  14 intrinsic_delaunay Del_M(P) for a closed-form metric (certify/intrinsic.hpp); with --kind
//                        intrinsic, the complex is exactly Del_M(P)
//  15 restricted_equals_intrinsic   Del_RM(P) = Del_M(P), either way with witnesses
#pragma once

#include <string>

#include "certify/certificate.hpp"
#include "io/claims.hpp"
#include "io/input_error.hpp"
#include "io/progress.hpp"

namespace delcert::certify {

namespace detail {
class World;
}  // namespace detail

// What the given complex is claimed to be. automatic: restricted for an OFF file (a surface
// mesher's output), tangential otherwise. intrinsic: Del_M (check 14 compares).
enum class ComplexKind { automatic, tangential, restricted, intrinsic };

// What the input claims, by mode: the verdict and the exit status answer exactly that
// (docs/certificate.md, "What is claimed"). Audit (no complex) and tangential: every check that decides (the
// refiner's promise Del_TM = Del_RM = Del_M), check 7 with "secure": true. Restricted / intrinsic: check 1, the
// complex's own check (12: it is Del_RM(P) / 14: it is Del_M(P)) and the checks of the claims present (2 sparsity,
// 5 gamma0, 6 power_protection, 7 secure, 10 star_radius, 11 covering). Check 9 is never a claim. A check that is no
// claim is computed and reported: verdict REPORT, its decision in details.decision.
enum class Mode { audit, tangential, restricted, intrinsic };
bool is_claimed(CheckId id, Mode mode, const io::Claims& claims);

struct CertifyOptions {
  std::string manifold;  // spec path or builtin:NAME
  std::string points;
  std::string complex;   // empty: audit the point set (compute Del_TM)
  std::string claims;    // empty: no claims
  std::string complex_format = "auto";  // io::complex_format_from_name: auto, delcert, off, obj, ply, stl, gudhi
  std::string residual_tolerance;       // empty: the spec's; else replaces it (io::parse_residual_tolerance)
  ComplexKind kind = ComplexKind::automatic;
  // Checks 11-15 are not computed (their entries say so, verdict REPORT): the certificate is then
  // about Del_TM(P) only. Not allowed with kind restricted or intrinsic.
  bool skip_restricted = false;
  // Checks 14-15 on a manifold without a closed-form metric: the general engine
  // (certify/intrinsic/general.hpp). false: Del_M not computed there (the refiner's own final check
  // does so: its repair rule does not use the general engine yet, docs/refinement.md).
  bool general_del_m = true;
  int threads = 1;
  // Every exact/ predicate skips its interval filter and decides exactly (and check 7 decides
  // every cell in exact rationals). For differential tests: the certificate must be the same
  // apart from the filter statistics and the times.
  bool force_exact = false;
  io::ProgressLine* progress = nullptr;  // a line on a terminal: the phases (presentation, never read back)
  // The ranks of an MPI job (certify/detail/world.hpp), or null: this process alone. Every rank
  // calls run_certify with the same options; rank 0's certificate is the single-process one (byte
  // for byte), the other ranks' is empty.
  const detail::World* world = nullptr;
  // An MPI job: every rank but 0 holds, besides its own points, those within `halo` of them on
  // the grid's first axis (a slab of cells; 0: 16 typical point spacings). With fixed_halo a point
  // whose star search or check-7 neighbourhood needs more is UNDECIDED (with the reason); else the
  // halo is widened until every search is held (docs/design.md §4.11). No effect in one process.
  double halo = 0;
  bool fixed_halo = false;
};

// Throws io::InputError on bad input (exit status 2); never writes anything. In an MPI job, every
// io::InputError is thrown before the ranks first exchange data, on every rank alike.
Certificate run_certify(const CertifyOptions& options);

}  // namespace delcert::certify
