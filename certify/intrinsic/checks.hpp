// The checks the driver (certify.cpp) runs on Del_M(P): checks 14 and 15, each taking the inputs it needs and
// returning its certificate entry (docs/design.md §4.9).
#pragma once

#include <optional>

#include "certify/certificate.hpp"
#include "certify/intrinsic/intrinsic.hpp"
#include "certify/restricted/restricted.hpp"
#include "io/complex.hpp"

namespace delcert::certify::detail {

// Check 14: Del_M(P) computed and, with --kind intrinsic, compared with the given complex.
CheckEntry check_intrinsic(const IntrinsicDelaunay& D, const std::optional<io::Complex>& given, bool intrinsic_kind, int m);

// Check 15: Del_RM(P) = Del_M(P) on m-simplices, decided either way with witnesses.
CheckEntry check_restricted_equals_intrinsic(const RestrictedDelaunay* R, const IntrinsicDelaunay& D);

}  // namespace delcert::certify::detail
