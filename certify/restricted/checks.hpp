// The checks the driver (certify.cpp) runs on Del_RM(P): checks 11, 12 and 13, each taking the inputs it needs
// and returning its certificate entry (docs/design.md §4.9), and the witnesses and helpers check 15 shares.
#pragma once

#include <optional>
#include <set>
#include <string>
#include <vector>

#include "certify/certificate.hpp"
#include "certify/detail/grid.hpp"
#include "certify/restricted/coverage.hpp"
#include "certify/restricted/restricted.hpp"
#include "certify/restricted/restricted_recheck.hpp"
#include "certify/tangential/checks.hpp"
#include "exact/number_types.hpp"
#include "io/complex.hpp"
#include "io/points.hpp"
#include "io/spec.hpp"

namespace delcert::certify::detail {

// The witness of a certified restricted Voronoi vertex (checks 11, 12, 13 and 15).
nlohmann::json vertex_witness(const RestrictedSimplex& s);

// Check 11 with a per-point covering claim: the cells whose bound the shared covering target left loose,
// analysed again on their own (the argument is in checks.cpp).
void sharpen_per_point_cells(RestrictedDelaunay& R, const std::vector<mpq_class>& eps, const exact::ImplicitSystem& system,
                             const io::PointSet& P, const detail::PointGrid& grid, const RestrictedCellOptions& options,
                             int threads);

// Check 11: the certified covering radius (P is an eps-sample of M), against the covering claim.
CheckEntry check_covering(const RestrictedDelaunay& R, const CoverageProof& coverage, const std::optional<mpq_class>& claim,
                          const io::ManifoldSpec& spec, const std::vector<mpq_class>* per_point = nullptr,
                          const std::string& per_point_file = {});

// The m-simplices of a complex, each sorted.
std::set<Simplex> top_simplices(const io::Complex& K, int m);

// "a = b", "a != b" or "a = b not decided", by the verdict.
std::string equality(Verdict v, const std::string& a, const std::string& b);

// Check 12: Del_RM(P) computed and, with --kind restricted, compared with the given complex.
CheckEntry check_restricted(const RestrictedDelaunay& R, const std::optional<io::Complex>& given, bool claimed, int m,
                            const RecheckInput& recheck);

// Check 13: Del_TM(P) = Del_RM(P) on m-simplices, decided either way with witnesses.
CheckEntry check_tangential_equals_restricted(const Stars& st, const RestrictedDelaunay& R);

}  // namespace delcert::certify::detail
