#include "certify/topology.hpp"

#include <algorithm>
#include <array>
#include <map>
#include <numeric>

namespace delcert::certify {

namespace {

struct UnionFind {
  std::vector<long> parent;
  explicit UnionFind(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0L); }
  long find(long x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  }
  bool unite(long a, long b) {
    a = find(a), b = find(b);
    if (a == b) return false;
    parent[std::max(a, b)] = std::min(a, b);
    return true;
  }
};

// Sorts fixed-stride records lexicographically and removes duplicates.
template <int K>
std::vector<int> sorted_unique_fixed(const std::vector<int>& flat) {
  std::vector<std::array<int, K>> recs(flat.size() / K);
  for (std::size_t i = 0; i < recs.size(); ++i) std::copy(flat.begin() + i * K, flat.begin() + (i + 1) * K, recs[i].begin());
  std::sort(recs.begin(), recs.end());
  recs.erase(std::unique(recs.begin(), recs.end()), recs.end());
  std::vector<int> out;
  out.reserve(recs.size() * K);
  for (const auto& r : recs) out.insert(out.end(), r.begin(), r.end());
  return out;
}

std::vector<int> sorted_unique_records(const std::vector<int>& flat, std::size_t stride) {
  switch (stride) {
    case 1: return sorted_unique_fixed<1>(flat);
    case 2: return sorted_unique_fixed<2>(flat);
    case 3: return sorted_unique_fixed<3>(flat);
    case 4: return sorted_unique_fixed<4>(flat);
    case 5: return sorted_unique_fixed<5>(flat);
    case 6: return sorted_unique_fixed<6>(flat);
    case 7: return sorted_unique_fixed<7>(flat);
    case 8: return sorted_unique_fixed<8>(flat);
    default: break;
  }
  std::size_t n = flat.size() / stride;
  std::vector<std::size_t> idx(n);
  std::iota(idx.begin(), idx.end(), 0);
  auto rec = [&](std::size_t i) { return flat.begin() + static_cast<long>(i * stride); };
  std::sort(idx.begin(), idx.end(), [&](std::size_t a, std::size_t b) {
    return std::lexicographical_compare(rec(a), rec(a) + static_cast<long>(stride), rec(b), rec(b) + static_cast<long>(stride));
  });
  std::vector<int> out;
  out.reserve(flat.size());
  for (std::size_t k = 0; k < n; ++k) {
    if (k && std::equal(rec(idx[k]), rec(idx[k]) + static_cast<long>(stride), rec(idx[k - 1]))) continue;
    out.insert(out.end(), rec(idx[k]), rec(idx[k]) + static_cast<long>(stride));
  }
  return out;
}

int inverse_mod(int a, int p) {
  for (int x = 1; x < p; ++x)
    if (a * x % p == 1) return x;
  return 0;
}

}  // namespace

long FaceLattice::find(int k, const int* face) const {
  if (k < 0 || k > dimension) return -1;
  const auto& f = flat[k];
  std::size_t s = k + 1, lo = 0, hi = f.size() / s;
  while (lo < hi) {
    std::size_t mid = (lo + hi) / 2;
    if (std::lexicographical_compare(f.begin() + static_cast<long>(mid * s), f.begin() + static_cast<long>(mid * s + s), face, face + s))
      lo = mid + 1;
    else
      hi = mid;
  }
  if (lo < f.size() / s && std::equal(face, face + s, f.begin() + static_cast<long>(lo * s))) return static_cast<long>(lo);
  return -1;
}

FaceLattice face_lattice(const std::vector<std::vector<int>>& maximal) {
  FaceLattice L;
  for (const auto& s : maximal) L.dimension = std::max(L.dimension, static_cast<int>(s.size()) - 1);
  L.flat.assign(std::max(0, L.dimension + 1), {});
  for (const auto& s0 : maximal) {
    std::vector<int> s = s0;
    std::sort(s.begin(), s.end());
    const int n = static_cast<int>(s.size());
    for (unsigned mask = 1; mask < (1u << n); ++mask) {
      int k = __builtin_popcount(mask) - 1;
      for (int i = 0; i < n; ++i)
        if (mask >> i & 1) L.flat[k].push_back(s[i]);
    }
  }
  for (int k = 0; k <= L.dimension; ++k) L.flat[k] = sorted_unique_records(L.flat[k], k + 1);
  return L;
}

namespace {

// rank of d_D for a closed D-pseudomanifold (every ridge in exactly two facets), by a spanning
// forest of the dual graph: over Z/2, and over Z/p when every component is orientable, the
// boundaries of the facets other than one root per component are independent (in the order of
// discovery, the ridge through which a facet was reached lies otherwise only in its parent, an
// earlier facet: restricted to those ridges the system is triangular with a non-zero diagonal)
// and span im d_D (a component's oriented sum is a cycle), so rank d_D = #facets - #components. The ridges of the
// forest then index coordinates on which im d_D projects isomorphically, so d_(D-1) has the same
// rank on the other ridges alone ("clearing"). Returns false when the shortcut does not apply.
bool top_rank_by_forest(const FaceLattice& L, int p, long& rank, std::vector<char>& tree_ridge) {
  const int D = L.dimension;
  const long F = static_cast<long>(L.count(D)), R = static_cast<long>(L.count(D - 1));
  std::vector<std::array<long, 2>> cof(R, {-1, -1});   // the two facets of each ridge
  std::vector<std::array<int, 2>> pos(R, {0, 0});       // the ridge's position in each facet
  std::vector<long> ridge_of(F * (D + 1));
  std::vector<int> face(D);
  for (long j = 0; j < F; ++j) {
    const int* s = &L.flat[D][j * (D + 1)];
    for (int i = 0; i <= D; ++i) {
      for (int t = 0, u = 0; t <= D; ++t)
        if (t != i) face[u++] = s[t];
      long r = L.find(D - 1, face.data());
      ridge_of[j * (D + 1) + i] = r;
      int slot = cof[r][0] < 0 ? 0 : cof[r][1] < 0 ? 1 : 2;
      if (slot == 2) return false;
      cof[r][slot] = j, pos[r][slot] = i;
    }
  }
  for (long r = 0; r < R; ++r)
    if (cof[r][1] < 0) return false;
  std::vector<int> sign(F, 0);  // orientation of each facet (+-1), for p != 2
  tree_ridge.assign(R, 0);
  rank = 0;
  std::vector<long> queue;
  for (long root = 0; root < F; ++root) {
    if (sign[root]) continue;
    sign[root] = 1;
    queue.assign(1, root);
    for (std::size_t h = 0; h < queue.size(); ++h) {
      long a = queue[h];
      for (int i = 0; i <= D; ++i) {
        long r = ridge_of[a * (D + 1) + i];
        int k = cof[r][0] == a ? 1 : 0;
        long b = cof[r][k];
        // Coherent orientation: the ridge's coefficients in a and b must cancel.
        int want = -sign[a] * ((i + pos[r][k]) % 2 ? -1 : 1);
        if (!sign[b]) {
          sign[b] = want;
          tree_ridge[r] = 1;
          ++rank;
          queue.push_back(b);
        } else if (p != 2 && sign[b] != want) {
          return false;  // non-orientable: the shortcut does not apply over Z/p, p odd
        }
      }
    }
  }
  return true;
}

}  // namespace

std::vector<long> boundary_ranks(const FaceLattice& L, int p) {
  const int D = L.dimension;
  std::vector<long> rank(std::max(D + 2, 1), 0);
  std::vector<char> cleared_above;  // k-faces already known to reduce to zero (pivots of d_{k+1})
  int top = D;
  long forest_rank = 0;
  std::vector<char> forest;
  if (D >= 2 && top_rank_by_forest(L, p, forest_rank, forest)) {
    rank[D] = forest_rank;
    cleared_above.swap(forest);
    top = D - 1;
  }
  using Column = std::vector<std::pair<long, int>>;  // (row, coefficient mod p), rows increasing
  for (int k = top; k >= 2; --k) {
    const long rows = static_cast<long>(L.count(k - 1)), cols = static_cast<long>(L.count(k));
    std::vector<long> pivot_col(rows, -1);
    std::vector<Column> reduced(cols);
    std::vector<char> cleared_here(rows, 0);
    std::vector<int> face(k);
    for (long j = 0; j < cols; ++j) {
      if (!cleared_above.empty() && cleared_above[j]) continue;
      const int* s = &L.flat[k][j * (k + 1)];
      Column col;
      for (int i = 0; i <= k; ++i) {  // the face without vertex i, coefficient (-1)^i
        for (int t = 0, u = 0; t <= k; ++t)
          if (t != i) face[u++] = s[t];
        col.emplace_back(L.find(k - 1, face.data()), (i % 2 == 0) ? 1 : p - 1);
      }
      std::sort(col.begin(), col.end());
      while (!col.empty() && pivot_col[col.back().first] >= 0) {
        const Column& other = reduced[pivot_col[col.back().first]];
        int factor = col.back().second * inverse_mod(other.back().second, p) % p;  // col -= factor * other
        Column sum;
        sum.reserve(col.size() + other.size());
        std::size_t a = 0, b = 0;
        while (a < col.size() || b < other.size()) {
          if (b == other.size() || (a < col.size() && col[a].first < other[b].first)) {
            sum.push_back(col[a++]);
          } else if (a == col.size() || other[b].first < col[a].first) {
            sum.emplace_back(other[b].first, (p - factor * other[b].second % p) % p);
            ++b;
          } else {
            int c = ((col[a].second - factor * other[b].second) % p + p) % p;
            if (c) sum.emplace_back(col[a].first, c);
            ++a, ++b;
          }
        }
        col.swap(sum);
      }
      if (!col.empty()) {
        pivot_col[col.back().first] = j;
        cleared_here[col.back().first] = 1;
        reduced[j] = std::move(col);
        ++rank[k];
      }
    }
    cleared_above.swap(cleared_here);
  }
  if (D >= 1) {  // rank d_1 = #vertices - #components, over any field
    UnionFind uf(L.count(0));
    const std::size_t E = L.count(1);
    for (std::size_t e = 0; e < E; ++e) {
      long a = L.find(0, &L.flat[1][2 * e]), b = L.find(0, &L.flat[1][2 * e + 1]);
      rank[1] += uf.unite(a, b);
    }
  }
  return rank;
}

std::vector<long> betti_numbers(const FaceLattice& L, int p) {
  auto rank = boundary_ranks(L, p);
  std::vector<long> b;
  for (int k = 0; k <= L.dimension; ++k)
    b.push_back(static_cast<long>(L.count(k)) - rank[k] - (k + 1 <= L.dimension ? rank[k + 1] : 0));
  return b;
}

Tri is_sphere(const std::vector<std::vector<int>>& simplices, int d, std::string* why) {
  auto fail = [&](const std::string& w) {
    if (why) *why = w;
    return Tri::no;
  };
  for (const auto& s : simplices)
    if (static_cast<int>(s.size()) != d + 1) return fail("not pure of dimension " + std::to_string(d));
  if (d == 0) return simplices.size() == 2 ? Tri::yes : fail(std::to_string(simplices.size()) + " points instead of 2");
  if (simplices.empty()) return fail("empty");
  std::vector<int> verts;  // the vertices, sorted; local index = position
  for (const auto& s : simplices) verts.insert(verts.end(), s.begin(), s.end());
  std::sort(verts.begin(), verts.end());
  verts.erase(std::unique(verts.begin(), verts.end()), verts.end());
  auto local = [&](int v) { return static_cast<int>(std::lower_bound(verts.begin(), verts.end(), v) - verts.begin()); };
  if (d == 1) {  // a cycle: every vertex in exactly two edges, and one walk visits every edge
    std::vector<std::vector<int>> adj(verts.size());
    for (const auto& s : simplices) adj[local(s[0])].push_back(local(s[1])), adj[local(s[1])].push_back(local(s[0]));
    for (const auto& a : adj)
      if (a.size() != 2) return fail("a vertex lies in " + std::to_string(a.size()) + " edges, not 2");
    std::size_t steps = 0;
    for (int prev = -1, v = 0; steps == 0 || v != 0; ++steps) {
      int next = adj[v][0] != prev ? adj[v][0] : adj[v][1];
      prev = v, v = next;
      if (steps > simplices.size()) break;
    }
    return steps == simplices.size() ? Tri::yes : fail("more than one cycle");
  }
  // Every ridge in exactly two facets.
  if (d > 8) return fail("dimension above 8 is not supported");
  std::vector<std::array<int, 8>> ridges;
  for (const auto& s0 : simplices) {
    auto s = s0;
    std::sort(s.begin(), s.end());
    for (int i = 0; i <= d; ++i) {
      std::array<int, 8> r;
      r.fill(-1);
      for (int t = 0, n = 0; t <= d; ++t)
        if (t != i) r[n++] = s[t];
      ridges.push_back(r);
    }
  }
  std::sort(ridges.begin(), ridges.end());
  long distinct_ridges = 0;
  for (std::size_t a = 0; a < ridges.size();) {
    std::size_t b = a;
    while (b < ridges.size() && ridges[b] == ridges[a]) ++b;
    if (b - a != 2) return fail("a " + std::to_string(d - 1) + "-face lies in " + std::to_string(b - a) + " facets, not 2");
    ++distinct_ridges;
    a = b;
  }
  UnionFind uf(verts.size());
  long comps = static_cast<long>(verts.size());
  for (const auto& s : simplices)
    for (std::size_t i = 1; i < s.size(); ++i) comps -= uf.unite(local(s[0]), local(s[i]));
  if (comps != 1) return fail(std::to_string(comps) + " connected components");
  Tri result = Tri::yes;
  if (d == 2) {  // vertex links of a closed pseudo-surface are unions of cycles: check each is one cycle
    std::vector<std::vector<int>> around(verts.size());  // triangles at each vertex
    for (std::size_t j = 0; j < simplices.size(); ++j)
      for (int v : simplices[j]) around[local(v)].push_back(static_cast<int>(j));
    std::vector<std::pair<int, int>> edges;
    for (std::size_t v = 0; v < verts.size(); ++v) {
      edges.clear();
      for (int j : around[v]) {
        int e[2], n = 0;
        for (int w : simplices[j])
          if (w != verts[v]) e[n++] = w;
        edges.emplace_back(e[0], e[1]);
      }
      // Walk the cycle from the first edge; every step must find an unused edge at the current end.
      std::vector<char> used(edges.size(), 0);
      used[0] = 1;
      int start = edges[0].first, cur = edges[0].second;
      std::size_t steps = 1;
      while (cur != start) {
        std::size_t k = 0;
        while (k < edges.size() && (used[k] || (edges[k].first != cur && edges[k].second != cur))) ++k;
        if (k == edges.size()) break;
        used[k] = 1, ++steps;
        cur = edges[k].first == cur ? edges[k].second : edges[k].first;
      }
      if (cur != start || steps != edges.size())
        return fail("the link of vertex " + std::to_string(verts[v]) + " is not a sphere: more than one cycle");
    }
    long chi = static_cast<long>(verts.size()) - distinct_ridges + static_cast<long>(simplices.size());
    if (chi != 2) return fail("Euler characteristic " + std::to_string(chi) + ", a sphere has 2");
    return result;
  }
  for (int v : verts) {
    std::vector<std::vector<int>> link;
    for (const auto& s : simplices)
      if (std::find(s.begin(), s.end(), v) != s.end()) {
        std::vector<int> t;
        for (int w : s)
          if (w != v) t.push_back(w);
        link.push_back(t);
      }
    std::string w;
    Tri r = is_sphere(link, d - 1, &w);
    if (r == Tri::no) return fail("the link of vertex " + std::to_string(v) + " is not a sphere: " + w);
    if (r == Tri::unknown) result = Tri::unknown;
  }
  if (d == 2) {  // a closed connected surface with chi = V - E + F = 2 is a sphere
    long chi = static_cast<long>(verts.size()) - distinct_ridges + static_cast<long>(simplices.size());
    if (chi != 2) return fail("Euler characteristic " + std::to_string(chi) + ", a sphere has 2");
    return result;
  }
  FaceLattice L = face_lattice(simplices);
  long chi = 0;
  for (int k = 0; k <= d; ++k) chi += (k % 2 ? -1 : 1) * static_cast<long>(L.count(k));
  long sphere_chi = d % 2 ? 0 : 2;
  if (chi != sphere_chi) return fail("Euler characteristic " + std::to_string(chi) + ", a sphere has " + std::to_string(sphere_chi));
  for (int p : {2, 3}) {
    auto b = betti_numbers(L, p);
    for (int k = 0; k <= d; ++k)
      if (b[k] != ((k == 0 || k == d) ? 1 : 0)) return fail("not a homology sphere over Z/" + std::to_string(p));
  }
  if (why) *why = "a homology " + std::to_string(d) + "-sphere over Z/2 and Z/3 (recognising S^" + std::to_string(d) + " is not attempted)";
  return Tri::unknown;
}

TopologyReport analyse_topology(const io::Complex& K, int m) {
  TopologyReport R;
  R.m = m;
  std::vector<std::vector<int>> tops;
  bool too_big = false;
  for (const auto& s0 : K.simplices) {
    auto s = s0;
    std::sort(s.begin(), s.end());
    if (static_cast<int>(s.size()) != m + 1) {
      if (R.pure) R.impure_example = s;
      R.pure = false;
      too_big = too_big || static_cast<int>(s.size()) > m + 1;
    } else {
      tops.push_back(s);
    }
  }
  // Ridges of the m-simplices and the strongly connected components across them.
  std::vector<std::pair<std::array<int, 8>, long>> ridge_of;  // (ridge padded with -1, simplex)
  if (m <= 8)
    for (std::size_t j = 0; j < tops.size(); ++j)
      for (int i = 0; i <= m; ++i) {
        std::array<int, 8> r;
        r.fill(-1);
        for (int t = 0, n = 0; t <= m; ++t)
          if (t != i) r[n++] = tops[j][t];
        ridge_of.emplace_back(r, static_cast<long>(j));
      }
  std::sort(ridge_of.begin(), ridge_of.end());
  UnionFind uf(tops.size());
  R.strong_components = static_cast<long>(tops.size());
  for (auto a = ridge_of.begin(); a != ridge_of.end();) {
    auto b = std::find_if(a, ridge_of.end(), [&](const auto& r) { return r.first != a->first; });
    long c = static_cast<long>(b - a);
    if (c != 2) {
      (c == 1 ? R.boundary_ridges : R.singular_ridges)++;
      if (R.ridge_example.empty())
        R.ridge_example.assign(a->first.begin(), a->first.begin() + m), R.ridge_example_count = c;
    }
    for (auto t = a + 1; t < b; ++t) R.strong_components -= uf.unite(a->second, t->second);
    a = b;
  }
  // Vertex links.
  std::vector<std::vector<long>> incident(K.num_vertices);
  for (std::size_t j = 0; j < K.simplices.size(); ++j)
    for (int v : K.simplices[j]) incident[v].push_back(static_cast<long>(j));
  for (std::size_t v = 0; v < K.num_vertices; ++v) {
    if (incident[v].empty()) {
      ++R.uncovered_vertices;
      continue;
    }
    std::vector<std::vector<int>> link;
    for (long j : incident[v]) {
      std::vector<int> t;
      for (int w : K.simplices[j])
        if (w != static_cast<int>(v)) t.push_back(w);
      link.push_back(std::move(t));
    }
    std::string why;
    Tri r = is_sphere(link, m - 1, &why);
    if (r == Tri::no) {
      if (R.bad_link_example < 0) R.bad_link_example = static_cast<long>(v), R.bad_link_reason = why;
      ++R.bad_links;
    } else if (r == Tri::unknown) {
      if (R.unknown_links == 0 && R.bad_link_example < 0) R.bad_link_reason = why;
      ++R.unknown_links;
    }
  }
  if (!too_big) {
    FaceLattice L = face_lattice(K.simplices);
    for (int k = 0; k <= L.dimension; ++k) {
      R.f.push_back(static_cast<long>(L.count(k)));
      R.euler += (k % 2 ? -1 : 1) * R.f.back();
    }
    R.betti_z2 = betti_numbers(L, 2);
    R.betti_z3 = betti_numbers(L, 3);
  }
  return R;
}

}  // namespace delcert::certify
