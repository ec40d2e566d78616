#include "exact/interval.hpp"

#include <CGAL/FPU.h>

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

}  // namespace delcert::exact
