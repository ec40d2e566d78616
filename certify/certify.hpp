// delcert-certify's driver: reads each input once, runs checks 1-10 (one function each; their
// numbers and names are CheckId in certificate.hpp) and assembles the certificate.
//
//   1 input_sanity       points near M (exact residuals, certified distance), right component, full-rank Jacobian
//   2 sparsity           exact minimum distance and its pair; the sparsity claim
//   3 stars              the complex is exactly the tangential Delaunay complex Del_TM(P)
//   4 consistency        every simplex is in the star of each of its vertices
//   5 thickness          Upsilon of every simplex and face against gamma0; flakes
//   6 power_protection   every star simplex power-protected (beyond the claim); ties refuted
//   7 secure_simplices   paper Definition 3.1 in each vertex's local Euclidean metric (report)
//   8 topology           pure closed pseudomanifold, sphere links, Euler, Betti over Z/2, Z/3
//   9 theorem            Theorem 3.3's hypotheses from the measured values (report)
//  10 star_radius        every star simplex has R_p(s) < eps (the eps claim)
#pragma once

#include <string>

#include "certify/certificate.hpp"
#include "io/input_error.hpp"

namespace delcert::certify {

struct CertifyOptions {
  std::string manifold;  // spec path or builtin:NAME
  std::string points;
  std::string complex;   // empty: audit the point set (compute Del_TM)
  std::string claims;    // empty: no claims
  int threads = 1;
  // Every exact/ predicate skips its interval filter and decides exactly (and check 7 decides
  // every cell in exact rationals). For differential tests: the certificate must be the same
  // apart from the filter statistics and the times.
  bool force_exact = false;
};

// Throws io::InputError on bad input (exit status 2); never writes anything.
Certificate run_certify(const CertifyOptions& options);

}  // namespace delcert::certify
