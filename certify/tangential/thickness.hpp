// Check 5: thickness of every simplex of the complex and of its faces (paper §2.2), decided
// exactly against the claimed Gamma0 (a j-face t is thick enough iff Upsilon(t) >= Gamma0^j;
// a simplex is Gamma0-good iff all its faces are), flakes listed, certified minima reported.
#pragma once

#include <gmpxx.h>

#include <vector>

#include "certify/certificate.hpp"
#include "io/points.hpp"

namespace delcert::certify {

struct FaceLattice;

struct ThicknessResult {
  CheckEntry entry{CheckId::thickness};
  // Certified enclosure of min Upsilon over the m-simplices (for the theorem report); lo = -1
  // when there is no m-simplex.
  exact::Interval min_top{-1, -1};
};

// `lattice`: the faces of the complex (face_lattice of its simplices).
ThicknessResult check_thickness(const io::PointSet& points, const FaceLattice& lattice, int m, const mpq_class* gamma0,
                                int threads, exact::FilterStats& stats, bool force_exact = false);

}  // namespace delcert::certify
