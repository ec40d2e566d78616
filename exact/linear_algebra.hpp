// Small dense linear algebra, written once for every number type of the project.
//
// The templates use only +, -, * (and, in cramer_solve, one division by a determinant the caller
// has shown to be non-zero), so one formula serves:
//  * an exact type (CGAL::Mpzf inside exact/, mpq_class anywhere): the exact value;
//  * interval arithmetic under upward rounding (exact/interval_arithmetic.hpp): an enclosure of
//    the exact value for every choice of the entries within their enclosures;
//  * double: the plain floating-point evaluation (unverified; used for fast guesses only).
// The operations and their order are fixed by the size alone (not by the values), so interval
// results are reproducible bit for bit; changing that order would change interval widths, hence
// how often the filtered predicates of exact/ fall back to exact arithmetic, hence the counts a
// certificate reports. Do not reorder.
//
// Matrices are row-major arrays. The rational routines (solve, inverse) use Gaussian elimination
// over mpq_class and report a singular matrix instead of dividing by zero.
#pragma once

#include <gmpxx.h>

#include <array>
#include <bit>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace delcert::exact {

// Largest n of the run-time sized routines (determinant(a, n), cramer_solve, adjugate).
inline constexpr int kMaxLinearSize = 8;

namespace detail {

// The non-empty column sets of at most Rows columns out of Cols, ordered by size (so every set
// comes after its subsets), with their sizes: computed at compile time.
template <int Rows, int Cols>
struct MinorMasks {
  static constexpr int count = [] {
    int n = 0;
    for (unsigned mask = 1; mask < (1u << Cols); ++mask) n += std::popcount(mask) <= Rows;
    return n;
  }();
  struct Entry {
    unsigned mask;
    int size;
  };
  static constexpr std::array<Entry, count> entries = [] {
    std::array<Entry, count> out{};
    int n = 0;
    for (int r = 1; r <= Rows; ++r)
      for (unsigned mask = 1; mask < (1u << Cols); ++mask)
        if (std::popcount(mask) == r) out[n++] = {mask, r};
    return out;
  }();
};

// One entry of the minor table (see minor_table), with the column loop unrolled at compile time.
template <int Rows, int Cols, unsigned Mask, class NT>
inline void minor_entry(const NT* a, NT* table) {
  constexpr int r = std::popcount(Mask);
  const NT* row = a + (Rows - r) * Cols;
  if constexpr (r == 1) {
    table[Mask] = row[std::countr_zero(Mask)];
  } else {
    NT acc(0);
    [&]<int... J>(std::integer_sequence<int, J...>) {
      int pos = 0;
      (
          [&] {
            if constexpr (((Mask >> J) & 1u) != 0) {
              constexpr unsigned sub = Mask ^ (1u << J);
              if (pos == 0) acc = row[J] * table[sub];
              else if (pos % 2 == 1) acc = acc - row[J] * table[sub];
              else acc = acc + row[J] * table[sub];
              ++pos;
            }
          }(),
          ...);
    }(std::make_integer_sequence<int, Cols>{});
    table[Mask] = acc;
  }
}

}  // namespace detail

// Minors by Laplace expansion memoised over column subsets.
// a is Rows x Cols, row-major. On return, for every column set `mask` with popcount(mask) <= Rows,
// table[mask] is the determinant of the square submatrix formed by the LAST popcount(mask) rows
// of a and the columns in mask (increasing order); table[0] = 1. table has 2^Cols entries.
// Each entry expands along the top row of its submatrix: det = sum_k (-1)^k a[top][c_k] *
// minor(mask \ c_k), where k is the position of c_k within mask, the first term assigned and
// the others added or subtracted in increasing column order. Ring operations only.
template <int Rows, int Cols, class NT>
void minor_table(const NT* a, NT* table) {
  static_assert(1 <= Rows && Rows <= Cols && Cols <= 12);
  table[0] = NT(1);
  if constexpr (Cols <= 5) {
    // Small tables (the hot tangential predicates): straight-line code.
    constexpr auto& entries = detail::MinorMasks<Rows, Cols>::entries;
    [&]<std::size_t... I>(std::index_sequence<I...>) {
      (detail::minor_entry<Rows, Cols, entries[I].mask>(a, table), ...);
    }(std::make_index_sequence<detail::MinorMasks<Rows, Cols>::count>{});
  } else {
    for (const auto& [mask, r] : detail::MinorMasks<Rows, Cols>::entries) {
      const NT* row = a + (Rows - r) * Cols;
      if (r == 1) {
        table[mask] = row[std::countr_zero(mask)];
        continue;
      }
      int pos = 0;
      NT acc(0);
      for (int j = 0; j < Cols; ++j) {
        if (!((mask >> j) & 1u)) continue;
        const unsigned sub = mask ^ (1u << j);
        if (pos == 0) acc = row[j] * table[sub];
        else if (pos % 2 == 1) acc = acc - row[j] * table[sub];
        else acc = acc + row[j] * table[sub];
        ++pos;
      }
      table[mask] = acc;
    }
  }
}

// Determinant of an N x N row-major matrix (N >= 1), division-free.
template <int N, class NT>
NT determinant(const NT* a) {
  NT table[1u << N];
  minor_table<N, N>(a, table);
  return table[(1u << N) - 1];
}

// The same for a size known at run time, 0 <= n <= kMaxLinearSize (the empty determinant is 1).
template <class NT>
NT determinant(const NT* a, int n) {
  switch (n) {
    case 0: return NT(1);
    case 1: return determinant<1>(a);
    case 2: return determinant<2>(a);
    case 3: return determinant<3>(a);
    case 4: return determinant<4>(a);
    case 5: return determinant<5>(a);
    case 6: return determinant<6>(a);
    case 7: return determinant<7>(a);
    case 8: return determinant<8>(a);
    default:
      throw std::invalid_argument("determinant: matrix size " + std::to_string(n) + " outside 0.." +
                                  std::to_string(kMaxLinearSize));
  }
}

// Cramer's rule for the n x n system A y = h given d = det(A) (the caller decides that d is
// non-zero, in its own number type): y_j = det(A_j) / d, A_j = A with column j replaced by h.
// One division per unknown; in interval arithmetic y encloses the solution for every A, h in the
// enclosures with det A in d.
template <class NT>
void cramer_solve(const NT* A, const NT* h, const NT& d, int n, NT* y) {
  std::array<NT, kMaxLinearSize * kMaxLinearSize> Aj;
  for (int j = 0; j < n; ++j) {
    for (int k = 0; k < n * n; ++k) Aj[k] = A[k];
    for (int i = 0; i < n; ++i) Aj[i * n + j] = h[i];
    y[j] = determinant(Aj.data(), n) / d;
  }
}

// The adjugate adj(A) = det(A) A^{-1} of an n x n matrix, 1 <= n <= kMaxLinearSize + 1:
// adj[a n + k] = (-1)^(a + k) det(A without row k and column a). Division-free.
template <class NT>
void adjugate(const NT* A, int n, NT* adj) {
  if (n == 1) {
    adj[0] = NT(1);
    return;
  }
  std::array<NT, kMaxLinearSize * kMaxLinearSize> minor;
  for (int a = 0; a < n; ++a)
    for (int k = 0; k < n; ++k) {
      int t = 0;
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j)
          if (i != k && j != a) minor[t++] = A[i * n + j];
      const NT mk = determinant(minor.data(), n - 1);
      adj[a * n + k] = (a + k) % 2 ? NT(-mk) : mk;
    }
}

// Exact solution of the n x n rational system A y = h (Gaussian elimination with the first
// non-zero pivot); nothing when A is singular.
std::optional<std::vector<mpq_class>> solve(std::vector<mpq_class> A, std::vector<mpq_class> h, int n);

// Exact inverse of an n x n rational matrix; nothing when A is singular.
std::optional<std::vector<mpq_class>> inverse(const std::vector<mpq_class>& A, int n);

}  // namespace delcert::exact
