#include "exact/linear_algebra.hpp"

#include <utility>

namespace delcert::exact {

std::optional<std::vector<mpq_class>> solve(std::vector<mpq_class> A, std::vector<mpq_class> h, int n) {
  for (int c = 0; c < n; ++c) {
    int piv = c;
    while (piv < n && A[piv * n + c] == 0) ++piv;
    if (piv == n) return std::nullopt;
    if (piv != c) {
      for (int j = 0; j < n; ++j) std::swap(A[c * n + j], A[piv * n + j]);
      std::swap(h[c], h[piv]);
    }
    for (int i = c + 1; i < n; ++i) {
      if (A[i * n + c] == 0) continue;
      mpq_class f = A[i * n + c] / A[c * n + c];
      for (int j = c; j < n; ++j) A[i * n + j] -= f * A[c * n + j];
      h[i] -= f * h[c];
    }
  }
  std::vector<mpq_class> y(n);
  for (int i = n - 1; i >= 0; --i) {
    mpq_class acc = h[i];
    for (int j = i + 1; j < n; ++j) acc -= A[i * n + j] * y[j];
    y[i] = acc / A[i * n + i];
  }
  return y;
}

// Gauss-Jordan elimination on [A | I].
std::optional<std::vector<mpq_class>> inverse(const std::vector<mpq_class>& matrix, int n) {
  std::vector<mpq_class> A = matrix;
  std::vector<mpq_class> X(static_cast<std::size_t>(n) * n, mpq_class(0));
  for (int i = 0; i < n; ++i) X[i * n + i] = 1;
  for (int c = 0; c < n; ++c) {
    int piv = c;
    while (piv < n && A[piv * n + c] == 0) ++piv;
    if (piv == n) return std::nullopt;
    for (int j = 0; j < n; ++j) std::swap(A[c * n + j], A[piv * n + j]), std::swap(X[c * n + j], X[piv * n + j]);
    mpq_class inv = 1 / A[c * n + c];
    for (int j = 0; j < n; ++j) A[c * n + j] *= inv, X[c * n + j] *= inv;
    for (int i = 0; i < n; ++i) {
      if (i == c || A[i * n + c] == 0) continue;
      mpq_class f = A[i * n + c];
      for (int j = 0; j < n; ++j) A[i * n + j] -= f * A[c * n + j], X[i * n + j] -= f * X[c * n + j];
    }
  }
  return X;
}

}  // namespace delcert::exact
