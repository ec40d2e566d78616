#include "exact/interval.hpp"

#include <CGAL/FPU.h>
#include <CGAL/Interval_nt.h>

#include <cfloat>

namespace delcert::exact {

UpwardRounding::UpwardRounding() : saved_(CGAL::FPU_get_cw()), changed_(saved_ != CGAL_FE_UPWARD) {
  if (changed_) CGAL::FPU_set_cw(CGAL_FE_UPWARD);
}

UpwardRounding::~UpwardRounding() {
  if (changed_) CGAL::FPU_set_cw(static_cast<CGAL::FPU_CW_t>(saved_));
}

NearestRounding::NearestRounding() : saved_(CGAL::FPU_get_cw()), changed_(saved_ != CGAL_FE_TONEAREST) {
  if (changed_) CGAL::FPU_set_cw(CGAL_FE_TONEAREST);
}

NearestRounding::~NearestRounding() {
  if (changed_) CGAL::FPU_set_cw(static_cast<CGAL::FPU_CW_t>(saved_));
}

bool rounding_is_upward() { return CGAL::FPU_get_cw() == CGAL_FE_UPWARD; }
bool rounding_is_nearest() { return CGAL::FPU_get_cw() == CGAL_FE_TONEAREST; }

std::string directed_rounding_failure() {
  volatile double one = 1.0, tiny = 0x1.0p-60, big = DBL_MAX, two = 2.0;
  std::string why;
  {
    UpwardRounding up;
    if (!rounding_is_upward()) return "the FPU did not switch to upward rounding";
    const double a = one + tiny;
    const double b = -one - tiny;
    const double c = -big * two;
    if (!(a > 1.0)) why += "1 + 2^-60 rounded upward is not above 1; ";
    if (!(b == -1.0)) why += "-1 - 2^-60 rounded upward is not -1; ";
    if (!(c == -DBL_MAX)) why += "-DBL_MAX * 2 rounded upward is not -DBL_MAX; ";
    using IA = CGAL::Interval_nt_advanced;
    const IA s = IA(static_cast<double>(one)) + IA(static_cast<double>(tiny));
    if (!(s.inf() == 1.0 && s.sup() > 1.0)) why += "CGAL interval [1,1] + [2^-60,2^-60] is not [1, 1 + ulp]; ";
  }
  {
    NearestRounding nearest;
    const double a = one + tiny;
    if (!(a == 1.0)) why += "1 + 2^-60 rounded to nearest is not 1; ";
  }
  if (!why.empty()) why.resize(why.size() - 2);
  return why;
}

}  // namespace delcert::exact
