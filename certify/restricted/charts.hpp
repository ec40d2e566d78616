// The pieces of the rational charts (param_cell.hpp: rational_chart, torus_chart; the charts are in charts.cpp)
// that the GEODESIC product chart of param_cell.cpp reuses.
#pragma once

#include <gmpxx.h>

#include <optional>
#include <span>
#include <vector>

#include "exact/interval_arithmetic.hpp"

namespace delcert::certify::detail {

// An Interval as an IntervalNumber (the same bounds).
exact::IntervalNumber ia(const exact::Interval& i);

// t = s / sqrt(1 - s^2) rounded up from an upper bound r' of the distance (s = r' / scale); 0 when s >= 1.
double half_width(const exact::IntervalNumber& r_prime, const exact::IntervalNumber& scale);

// sup |p - a| for a rational point a, enclosed from the exact doubles of p.
exact::IntervalNumber distance_to(std::span<const double> p, const std::vector<mpq_class>& a);

// A rational unit vector near the direction of u (none when u is 0 or not finite): with u
// normalised and k its largest coordinate (sign sk), the inverse stereographic image (pole
// -sk e_k) of the dyadic w_j = u_j / (1 + sk u_k), exactly unit. The sphere's n, each circle's n_i.
std::optional<std::vector<mpq_class>> rational_unit_near(std::vector<double> u);

// E (N x (N - 1)): the columns j != l of H = I - 2 a a^T / |a|^2, a = n + sgn(n_l) e_l
// (|a|^2 >= 2, l the largest |n_l|), which sends -sgn(n_l) e_l to the rational unit n:
// orthonormal, orthogonal to n, exactly.
std::vector<std::vector<mpq_class>> householder_frame(const std::vector<mpq_class>& n);

}  // namespace delcert::certify::detail
