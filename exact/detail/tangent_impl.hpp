// Private data of ImplicitSystem, TangentSpace and TangentChart. Include only from exact/*.cpp.
#pragma once

#include <mutex>
#include <vector>

#include "exact/detail/cgal_number_types.hpp"
#include "exact/interval.hpp"
#include "exact/polynomial.hpp"
#include "exact/tangent_predicates.hpp"
#include "exact/tangent_space.hpp"

namespace delcert::exact {

struct ImplicitSystem::Impl {
  int N = 0;  // ambient dimension
  int k = 0;  // codimension
  std::vector<Polynomial> equations;
  std::vector<Polynomial> derivatives;  // dF_i/dx_j, k x N row-major (jacobian_exact)
  // J_i,j = d(D_i F_i)/dx_j with D_i the common denominator of F_i's coefficients: integer
  // coefficients (row scaling does not change ker J). k x N row-major.
  std::vector<Polynomial> jacobian;
  std::vector<std::vector<detail::EX>> jacobian_coefficients;  // exact, aligned with terms()
  std::vector<DoublePolynomial> jacobian_double;              // for pivot selection
  std::vector<Polynomial> scaled;                             // S_i = D_i F_i, integer coefficients
  std::vector<std::vector<detail::EX>> scaled_coefficients;   // exact, aligned with terms()
  std::vector<Interval> denominators;                         // enclosures of D_i > 0

  // Exact J at x (x already converted to EX), k x N row-major.
  std::vector<detail::EX> jacobian_at(const std::vector<detail::EX>& x) const;
};

struct TangentSpace::Impl {
  int N = 0, m = 0, k = 0;
  std::vector<double> p;              // N
  std::vector<detail::EX> p_exact;    // N
  std::vector<detail::EX> U_exact;    // N x m row-major
  std::vector<detail::IA> U_interval; // N x m row-major, enclosures of U_exact
  std::vector<double> U_mid;          // N x m: a double inside each enclosure
  std::vector<double> U_rad;          // N x m: |U_exact - U_mid| <= U_rad (rounded up)
  std::vector<double> U_err;          // N x m: error weights of the fast chart rows (see
                                      // interval_row in tangent_predicates.cpp)
  std::vector<Interval> U_tight;     // N x m: the tightest double enclosures of U_exact
  std::vector<detail::EX> G_exact;   // m x m: G = U^T U
  std::vector<Interval> G_tight;     // m x m: the tightest double enclosures of G_exact
  // U and G as rationals, converted on first use (exact fallbacks, reports); thread-safe.
  const std::vector<mpq_class>& U_rational() const;
  const std::vector<mpq_class>& gram() const;
  mutable std::once_flag rational_once;
  mutable std::vector<mpq_class> U_rational_, gram_;
  std::vector<detail::EX> adj_gram_exact;     // adj(G) = det(G) G^{-1}, m x m (faces)
  std::vector<detail::IA> adj_gram_interval;  // enclosures of adj_gram_exact
  std::vector<int> pivots, frees;
};

struct TangentChart::Impl {
  std::shared_ptr<const TangentSpace::Impl> space_impl;
  TangentSpace space;
  int N = 0, m = 0, count = 0;
  std::vector<double> coords;               // count x N, row 0 = p
  // Rows are computed on first use: a star's cells read those of their vertices and of the few
  // points their power filters leave open, not all of the chart's.
  mutable std::vector<detail::IA> rows;        // count x (m + 1)
  mutable std::vector<unsigned char> have_row;
  mutable std::vector<detail::EX> exact_rows;  // count x (m + 1), allocated on first use
  mutable std::vector<unsigned char> have_exact;

  explicit Impl(const TangentSpace& s) : space(s) {}
  const detail::IA* row(int i) const {
    if (!have_row[i]) compute_row(i);
    return rows.data() + static_cast<std::size_t>(i) * (m + 1);
  }
  void compute_row(int i) const;
  const detail::EX* exact_row(int i) const;
  void check_index(int i) const;
};

namespace detail {
struct ExactCellData {
  std::array<EX, kMaxTangentDimension + 1> coef;
  EX k0;
};

// A face through p (see TangentFace): coef_0..coef_k of the bordered determinant and the k x m
// matrix DA = D adj(G) mapping b(q) to the bordered row, in intervals and (lazily) exactly.
struct FaceData {
  const TangentChart::Impl* chart = nullptr;
  int k = 0, m = 0;
  std::vector<int> vertices;  // as given
  std::vector<int> others;    // the k vertices other than p, in internal order
  std::vector<IA> coef, DA;
  bool usable = false;
  int det_sign = 0;
  mutable bool have_exact = false;
  mutable std::vector<EX> coef_exact, DA_exact;
};
}  // namespace detail

}  // namespace delcert::exact
