// The checks the driver (certify.cpp) runs on the stars and on the complex: checks 3, 4, 6, 8 and 10, each taking
// the inputs it needs and returning its certificate entry (docs/design.md §4.9). Check 7 stays in the driver
// (its per-point loop is split between MPI ranks).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "certify/certificate.hpp"
#include "certify/tangential/star.hpp"
#include "certify/tangential/topology.hpp"
#include "exact/number_types.hpp"
#include "io/complex.hpp"
#include "io/spec.hpp"

namespace delcert::certify::detail {

// The stars of every point (read by checks 3, 4, 6, 7 and 10).
struct Stars {
  bool verify = false;                               // a complex was given (else: audit mode)
  std::vector<Simplex> wrong_dimension;              // given simplices of another dimension, sorted
  std::vector<StarReport> reports;                   // per point: star(p), exactly or why not
  io::Complex complex;                               // audit mode: the union of the stars, what the global checks look at
  std::vector<Simplex> sorted;                       // verify mode: the given m-simplices, each sorted, in file order,
  const std::vector<Simplex>* given_tops = nullptr;  // or the given simplices themselves when they are just that
  std::vector<long> first;                           // verify mode: tops()[at[i]], first[p] <= i < first[p + 1], contain p
  std::vector<int> at;
  // The m-simplices, each sorted (given: in file order; audit: sorted, unique)
  const std::vector<Simplex>& tops() const { return given_tops ? *given_tops : verify ? sorted : complex.simplices; }
  std::vector<Simplex> claimed(std::size_t p) const {  // the given m-simplices at p, in file order
    std::vector<Simplex> c;
    for (long i = first[p]; i < first[p + 1]; ++i) c.push_back(tops()[at[i]]);
    return c;
  }
};

// Three-valued (Kleene) disjunction: yes if either is yes, no if both are no, else unknown.
inline exact::Tri either(exact::Tri a, exact::Tri b) { return !(!a && !b); }

// Check 3: the complex is Del_TM(P).
CheckEntry check_stars(const Stars& st, int m);

// Check 4: every m-simplex is in the star of each of its vertices.
CheckEntry check_consistency(const Stars& st, const StarSettings& S, exact::FilterContext& ctx);

struct ProtectionResult {
  CheckEntry entry{CheckId::power_protection};
  long cells = 0;                                 // star cells seen (certified or not)
  exact::Interval min_margin{INFINITY, INFINITY};  // over the certified cells
  bool all_determined = true;                      // every star and star cell determined: min_margin bounds them all
};

// Check 6: every star simplex power-protected (beyond the claim, when given); exact ties refuted.
ProtectionResult check_power_protection(const Stars& st, const std::optional<mpq_class>& claim);

struct RadiusResult {
  CheckEntry entry{CheckId::star_radius};
  long cells = 0;                                 // star cells seen (certified or not)
  exact::Interval max_r2{-INFINITY, -INFINITY};   // of R_p(s)^2 over the certified cells
  bool all_determined = true;                     // every star determined: max_r2 bounds them all
};

// Check 10: every star simplex has R_p(s) < eps (the star_radius claim); without a claim, a report.
// With a per-point claim (claims v3) `per_point` holds eps(p) and `per_point_file` names the file.
RadiusResult check_star_radius(const Stars& st, const std::optional<mpq_class>& eps,
                               const std::vector<mpq_class>* per_point = nullptr, const std::string& per_point_file = {});

// Check 8: the complex is a closed pseudomanifold with sphere links, and the topology the spec expects.
CheckEntry check_topology(const io::Complex& K, int m, const FaceLattice& lattice, const io::ExpectedTopology& expect, int threads);

}  // namespace delcert::certify::detail
