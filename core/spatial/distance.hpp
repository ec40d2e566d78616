// Squared Euclidean distance of two points given as spans of equal length.
#pragma once

#include <cstddef>
#include <span>

namespace delcert::spatial {

inline double squared_distance(std::span<const double> a, std::span<const double> b) {
  double s = 0;
  for (std::size_t j = 0; j < a.size(); ++j) {
    const double e = a[j] - b[j];
    s += e * e;
  }
  return s;
}

}  // namespace delcert::spatial
