#include "core/tangential/complex_topology.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <climits>
#include <numeric>
#include <stdexcept>

namespace delcert::tangential {

namespace {

std::size_t find_root(std::vector<std::size_t>& parent, std::size_t x) {
  while (parent[x] != x) x = parent[x] = parent[parent[x]];
  return x;
}

// K = dimension + 1: faces are stored as K ints padded with INT_MAX.
template <int K>
void analyze(const io::Complex& complex, ComplexTopology& t) {
  using Face = std::array<int, K>;
  const int D = K - 1;
  t.maximal_by_dimension.assign(D + 1, 0);
  t.faces_by_dimension.assign(D + 1, 0);
  std::vector<std::vector<Face>> faces(D + 1);
  std::vector<std::size_t> top;  // indices of the D-simplices
  std::vector<int> s;
  for (std::size_t i = 0; i < complex.simplices.size(); ++i) {
    s = complex.simplices[i];
    if (s.empty()) continue;
    std::sort(s.begin(), s.end());
    const int k = static_cast<int>(s.size());
    ++t.maximal_by_dimension[k - 1];
    if (k - 1 == D) top.push_back(i);
    for (unsigned mask = 1; mask < (1u << k); ++mask) {
      Face f;
      f.fill(INT_MAX);
      std::size_t c = 0;
      for (int j = 0; j < k; ++j)
        if (mask & (1u << j)) f[c++] = s[j];
      faces[std::popcount(mask) - 1].push_back(f);
    }
  }
  for (int d = 0; d <= D; ++d) {
    auto& v = faces[d];
    std::sort(v.begin(), v.end());
    v.erase(std::unique(v.begin(), v.end()), v.end());
    t.faces_by_dimension[d] = v.size();
    t.euler_characteristic += (d % 2 ? -1L : 1L) * static_cast<long>(v.size());
    std::vector<Face>().swap(faces[d]);
  }
  std::size_t nonempty = 0;
  for (const auto& x : complex.simplices) nonempty += !x.empty();
  t.pure = t.maximal_by_dimension[D] == nonempty;
  if (D < 1) return;
  // Ridges of the top simplices, with their owner, grouped by sorting.
  std::vector<std::pair<Face, std::size_t>> ridges;
  ridges.reserve(top.size() * K);
  for (std::size_t ti = 0; ti < top.size(); ++ti) {
    s = complex.simplices[top[ti]];
    std::sort(s.begin(), s.end());
    for (int drop = 0; drop <= D; ++drop) {
      Face f;
      f.fill(INT_MAX);
      int c = 0;
      for (int j = 0; j <= D; ++j)
        if (j != drop) f[c++] = s[j];
      ridges.emplace_back(f, ti);
    }
  }
  std::sort(ridges.begin(), ridges.end());
  std::vector<std::size_t> parent(top.size());
  std::iota(parent.begin(), parent.end(), std::size_t{0});
  for (auto it = ridges.begin(); it != ridges.end();) {
    const Face face = it->first;
    const std::size_t owner = it->second;
    std::size_t count = 0;
    for (; it != ridges.end() && it->first == face; ++it, ++count) {
      const std::size_t a = find_root(parent, owner), b = find_root(parent, it->second);
      if (a != b) parent[std::max(a, b)] = std::min(a, b);
    }
    ++t.ridges;
    if (count == 1) ++t.boundary_ridges;
    if (count > 2) ++t.singular_ridges;
  }
  for (std::size_t i = 0; i < top.size(); ++i) t.components += find_root(parent, i) == i;
  t.pseudomanifold = t.pure && t.boundary_ridges == 0 && t.singular_ridges == 0 && t.components == 1;
}

}  // namespace

ComplexTopology analyze_complex(const io::Complex& complex) {
  ComplexTopology t;
  for (const auto& s : complex.simplices) {
    if (s.size() > 8) throw std::invalid_argument("analyze_complex: simplices of dimension above 7 are not supported");
    t.dimension = std::max(t.dimension, static_cast<int>(s.size()) - 1);
  }
  switch (t.dimension) {
    case -1: break;
    case 0: analyze<1>(complex, t); break;
    case 1: analyze<2>(complex, t); break;
    case 2: analyze<3>(complex, t); break;
    case 3: analyze<4>(complex, t); break;
    case 4: analyze<5>(complex, t); break;
    case 5: analyze<6>(complex, t); break;
    case 6: analyze<7>(complex, t); break;
    default: analyze<8>(complex, t); break;
  }
  return t;
}

}  // namespace delcert::tangential
