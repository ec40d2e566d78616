#include "certify/tangential/topology.hpp"

#include <algorithm>
#include <array>
#include <map>
#include <numeric>
#include <stdexcept>
#include <string>

#include "certify/detail/parallel.hpp"
#include "topology/three_sphere.hpp"

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
  if (static_cast<std::size_t>(k) < first.size() && !first[k].empty()) {  // faces starting with face[0] only
    if (face[0] < 0 || static_cast<std::size_t>(face[0]) + 1 >= first[k].size()) return -1;
    lo = static_cast<std::size_t>(first[k][face[0]]), hi = static_cast<std::size_t>(first[k][face[0] + 1]);
  }
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

FaceLattice face_lattice(const std::vector<std::vector<int>>& maximal, int threads) {
  FaceLattice L;
  for (const auto& s : maximal) {
    if (s.size() > static_cast<std::size_t>(kMaxLatticeVertices))
      throw std::invalid_argument("face_lattice: a simplex with " + std::to_string(s.size()) + " vertices (at most " +
                                  std::to_string(kMaxLatticeVertices) + ")");
    L.dimension = std::max(L.dimension, static_cast<int>(s.size()) - 1);
  }
  L.flat.assign(std::max(0, L.dimension + 1), {});
  for (auto s : maximal) {
    std::sort(s.begin(), s.end());
    const int n = static_cast<int>(s.size());
    for (unsigned mask = 1; mask < (1u << n); ++mask) {
      int k = __builtin_popcount(mask) - 1;
      for (int i = 0; i < n; ++i)
        if (mask >> i & 1) L.flat[k].push_back(s[i]);
    }
  }
  // One sort per dimension, the largest first, on the threads (the result does not depend on them).
  std::vector<int> dims(std::max(0, L.dimension + 1));
  std::iota(dims.begin(), dims.end(), 0);
  std::stable_sort(dims.begin(), dims.end(), [&](int a, int b) { return L.flat[a].size() > L.flat[b].size(); });
  detail::parallel_for(dims.size(), threads, [&](std::size_t i, int) { L.flat[dims[i]] = sorted_unique_records(L.flat[dims[i]], dims[i] + 1); });
  L.first.assign(std::max(0, L.dimension + 1), {});
  for (int k = 0; k <= L.dimension; ++k) {
    const std::size_t n = L.count(k);
    if (n == 0 || L.flat[k][0] < 0) continue;  // (negative vertex ids: keep the plain search)
    const int vmax = L.flat[k][(n - 1) * (k + 1)];  // faces are sorted: the last has the largest first vertex
    auto& F = L.first[k];
    F.assign(static_cast<std::size_t>(vmax) + 2, 0);
    for (std::size_t j = 0; j < n; ++j) ++F[L.flat[k][j * (k + 1)] + 1];
    for (std::size_t v = 1; v < F.size(); ++v) F[v] += F[v - 1];
  }
  return L;
}

namespace {

// For k = 2..D: the index of each k-face's boundary (k-1)-faces, of[k][j * (k + 1) + i] = the
// face without its vertex i. Built once and shared by the reductions over Z/2 and Z/3.
struct FaceIndex {
  std::vector<std::vector<long>> of;
};

FaceIndex face_index(const FaceLattice& L, int threads = 1) {
  FaceIndex I;
  const int D = L.dimension;
  I.of.resize(std::max(D + 1, 0));
  constexpr long kBlock = 4096;  // faces per task
  for (int k = 2; k <= D; ++k) {
    const long n = static_cast<long>(L.count(k));
    I.of[k].resize(static_cast<std::size_t>(n) * (k + 1));
    detail::parallel_for((n + kBlock - 1) / kBlock, threads, [&](std::size_t b, int) {
      std::array<int, kMaxLatticeVertices> face{};
      for (long j = static_cast<long>(b) * kBlock; j < std::min(n, static_cast<long>(b + 1) * kBlock); ++j) {
        const int* s = &L.flat[k][j * (k + 1)];
        for (int i = 0; i <= k; ++i) {
          for (int t = 0, u = 0; t <= k; ++t)
            if (t != i) face[u++] = s[t];
          I.of[k][j * (k + 1) + i] = L.find(k - 1, face.data());
        }
      }
    });
  }
  return I;
}

// rank of d_D for a closed D-pseudomanifold (every ridge in exactly two facets), by a spanning
// forest of the dual graph: over Z/2, and over Z/p when every component is orientable, the
// boundaries of the facets other than one root per component are independent (in the order of
// discovery, the ridge through which a facet was reached lies otherwise only in its parent, an
// earlier facet: restricted to those ridges the system is triangular with a non-zero diagonal)
// and span im d_D (a component's oriented sum is a cycle), so rank d_D = #facets - #components. The ridges of the
// forest then index coordinates on which im d_D projects isomorphically, so d_(D-1) has the same
// rank on the other ridges alone ("clearing"). Returns false when the shortcut does not apply.
bool top_rank_by_forest(const FaceLattice& L, const FaceIndex& I, int p, long& rank, std::vector<char>& tree_ridge) {
  const int D = L.dimension;
  const long F = static_cast<long>(L.count(D)), R = static_cast<long>(L.count(D - 1));
  std::vector<std::array<long, 2>> cof(R, {-1, -1});   // the two facets of each ridge
  std::vector<std::array<int, 2>> pos(R, {0, 0});       // the ridge's position in each facet
  const std::vector<long>& ridge_of = I.of[D];
  for (long j = 0; j < F; ++j) {
    for (int i = 0; i <= D; ++i) {
      long r = ridge_of[j * (D + 1) + i];
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

static std::vector<long> boundary_ranks(const FaceLattice& L, const FaceIndex& I, int p) {
  const int D = L.dimension;
  std::vector<long> rank(std::max(D + 2, 1), 0);
  std::vector<char> cleared_above;  // k-faces already known to reduce to zero (pivots of d_{k+1})
  int top = D;
  long forest_rank = 0;
  std::vector<char> forest;
  if (D >= 2 && top_rank_by_forest(L, I, p, forest_rank, forest)) {
    rank[D] = forest_rank;
    cleared_above.swap(forest);
    top = D - 1;
  }
  // rank d_1 = #vertices - #components, over any field, by a spanning forest of the 1-skeleton.
  if (D >= 1) {
    UnionFind uf(L.count(0));
    for (std::size_t e = 0; e < L.count(1); ++e)
      rank[1] += uf.unite(L.find(0, &L.flat[1][2 * e]), L.find(0, &L.flat[1][2 * e + 1]));
  }
  using Column = std::vector<std::pair<long, int>>;  // (row, coefficient mod p), rows increasing
  for (int k = top; k >= 2; --k) {
    const long rows = static_cast<long>(L.count(k - 1)), cols = static_cast<long>(L.count(k));
    auto row_of = [&](long j, int i) { return I.of[k][j * (k + 1) + i]; };
    // Peeling first (elementary collapses): a row with one non-zero entry left, in column j, adds
    // 1 to the rank, and the rest of the matrix keeps its rank without that row and column j (row
    // operations with the row clear the rest of column j and touch no other entry). Repeated, this
    // removes all of d_k on the spheres we met; the rest, a core with its entries unchanged, is
    // reduced below. Cleared for d_(k-1): the peeled rows and the core's pivots. Each is a row of
    // a cycle (column j; a reduced column, a combination of whole columns of the core) with a
    // non-zero entry there, and these cycles are triangular on the cleared rows: column j holds
    // no row peeled before it (such a row had its one live column elsewhere while j lived), a
    // core column no peeled row at all, a reduced column no pivot above its own. So d_(k-1)
    // keeps its rank without the columns of the cleared rows.
    std::vector<int> row_n(rows, 0);  // the live columns of each row
    std::vector<char> col_dead(cols, 0), row_dead(rows, 0), cleared_here(rows, 0);
    for (long j = 0; j < cols; ++j) {
      col_dead[j] = !cleared_above.empty() && cleared_above[j];
      for (int i = 0; i <= k && !col_dead[j]; ++i) ++row_n[row_of(j, i)];
    }
    std::vector<long> row_start(rows + 1, 0);
    for (long r = 0; r < rows; ++r) row_start[r + 1] = row_start[r] + row_n[r];
    std::vector<long> row_cols(row_start[rows]), fill(row_start.begin(), row_start.end() - 1);
    for (long j = 0; j < cols; ++j)
      for (int i = 0; i <= k && !col_dead[j]; ++i) row_cols[fill[row_of(j, i)]++] = j;
    std::vector<long> stack;
    for (long r = rows - 1; r >= 0; --r)
      if (row_n[r] == 1) stack.push_back(r);
    while (!stack.empty()) {
      const long r = stack.back();
      stack.pop_back();
      if (row_dead[r] || row_n[r] != 1) continue;
      long j = -1;
      for (long t = row_start[r]; t < row_start[r + 1]; ++t)
        if (!col_dead[row_cols[t]]) j = row_cols[t];
      ++rank[k];
      cleared_here[r] = 1;
      col_dead[j] = row_dead[r] = 1;
      for (int i = 0; i <= k; ++i) {
        const long q = row_of(j, i);
        if (q != r && !row_dead[q] && --row_n[q] == 1) stack.push_back(q);
      }
    }
    // The core: column reduction (columns in order, the pivot of a column its largest row).
    std::vector<long> pivot_col(rows, -1);
    std::vector<Column> reduced(cols);
    Column sum;  // scratch of the column additions (its buffer is swapped with the column's)
    for (long j = 0; j < cols; ++j) {
      if (col_dead[j]) continue;
      Column col;
      for (int i = 0; i <= k; ++i) {  // the face without vertex i, coefficient (-1)^i
        const long row = row_of(j, i);
        if (!row_dead[row]) col.emplace_back(row, (i % 2 == 0) ? 1 : p - 1);
      }
      std::sort(col.begin(), col.end());
      while (!col.empty() && pivot_col[col.back().first] >= 0) {
        const Column& other = reduced[pivot_col[col.back().first]];
        int factor = col.back().second * inverse_mod(other.back().second, p) % p;  // col -= factor * other
        sum.clear();
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
  return rank;
}

namespace {

std::vector<long> betti_from_ranks(const FaceLattice& L, const std::vector<long>& rank) {
  std::vector<long> b;
  for (int k = 0; k <= L.dimension; ++k)
    b.push_back(static_cast<long>(L.count(k)) - rank[k] - (k + 1 <= L.dimension ? rank[k + 1] : 0));
  return b;
}

}  // namespace

std::vector<long> boundary_ranks(const FaceLattice& L, int p) { return boundary_ranks(L, face_index(L), p); }

std::vector<long> betti_numbers(const FaceLattice& L, int p) { return betti_from_ranks(L, boundary_ranks(L, p)); }

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
  for (auto s : simplices) {
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
    return Tri::yes;
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
    // Here d >= 3: only a link proven not to be a sphere changes the answer (below).
    if (is_sphere(link, d - 1, &w) == Tri::no)
      return fail("the link of vertex " + std::to_string(v) + " is not a sphere: " + w);
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
  if (d == 3) {  // a homology 3-sphere: Regina's S^3 recognition decides (docs/design.md §5, a link check)
    auto r = topology::recognise_3_sphere(simplices, why);
    return r == topology::SphereAnswer::yes ? Tri::yes : r == topology::SphereAnswer::no ? Tri::no : Tri::unknown;
  }
  if (why) *why = "a homology " + std::to_string(d) + "-sphere over Z/2 and Z/3 (recognising S^" + std::to_string(d) + " is not attempted)";
  return Tri::unknown;
}

namespace {

// A fast sufficient test that the triangles `tris` (global vertex ids) form a 2-sphere, by the
// same conditions as is_sphere(.., 2, ..): every edge in exactly two triangles, connected, every
// vertex link one cycle, Euler characteristic 2. True only when is_sphere would answer yes; on
// false the caller asks is_sphere (which names the problem). No allocation after warm-up.
struct LinkScratch {
  std::vector<int> verts, edges, parent, start, ring;
};

bool link_is_2_sphere(const std::vector<std::array<int, 3>>& tris, LinkScratch& W) {
  if (tris.empty()) return false;
  W.verts.clear();
  for (const auto& t : tris) W.verts.insert(W.verts.end(), t.begin(), t.end());
  std::sort(W.verts.begin(), W.verts.end());
  W.verts.erase(std::unique(W.verts.begin(), W.verts.end()), W.verts.end());
  const int V = static_cast<int>(W.verts.size());
  auto local = [&](int v) { return static_cast<int>(std::lower_bound(W.verts.begin(), W.verts.end(), v) - W.verts.begin()); };
  W.edges.clear();  // edge (a < b) as a * V + b, once per triangle side
  for (const auto& t : tris) {
    int a = local(t[0]), b = local(t[1]), c = local(t[2]);
    if (a == b || b == c || a == c) return false;
    W.edges.push_back(std::min(a, b) * V + std::max(a, b));
    W.edges.push_back(std::min(b, c) * V + std::max(b, c));
    W.edges.push_back(std::min(a, c) * V + std::max(a, c));
  }
  std::sort(W.edges.begin(), W.edges.end());
  for (std::size_t i = 0; i < W.edges.size(); i += 2)
    if (i + 1 >= W.edges.size() || W.edges[i] != W.edges[i + 1] || (i + 2 < W.edges.size() && W.edges[i + 2] == W.edges[i]))
      return false;
  const long E = static_cast<long>(W.edges.size() / 2);
  W.parent.resize(V);
  for (int i = 0; i < V; ++i) W.parent[i] = i;
  auto find = [&](int x) {
    while (W.parent[x] != x) x = W.parent[x] = W.parent[W.parent[x]];
    return x;
  };
  int comps = V;
  for (std::size_t i = 0; i < W.edges.size(); i += 2) {
    int a = find(W.edges[i] / V), b = find(W.edges[i] % V);
    if (a != b) W.parent[std::max(a, b)] = std::min(a, b), --comps;
  }
  if (comps != 1) return false;
  if (static_cast<long>(V) - E + static_cast<long>(tris.size()) != 2) return false;
  // Vertex links: the opposite edges of the triangles at v, as pairs in ring[start[v]..].
  W.start.assign(V + 1, 0);
  for (const auto& t : tris)
    for (int v : t) ++W.start[local(v) + 1];
  for (int v = 0; v < V; ++v) W.start[v + 1] += W.start[v];
  W.ring.assign(2 * static_cast<std::size_t>(W.start[V]), -1);
  W.parent.assign(V, 0);  // reused: fill position per vertex
  for (const auto& t : tris)
    for (int i = 0; i < 3; ++i) {
      int v = local(t[i]), k = W.start[v] + W.parent[v]++;
      W.ring[2 * k] = local(t[(i + 1) % 3]), W.ring[2 * k + 1] = local(t[(i + 2) % 3]);
    }
  for (int v = 0; v < V; ++v) {  // one cycle through all W.start[v+1] - W.start[v] edges
    const int b = W.start[v], n = W.start[v + 1] - b;
    int first = W.ring[2 * b], cur = W.ring[2 * b + 1], prev_edge = 0, steps = 1;
    while (cur != first && steps <= n) {
      int next_edge = -1;
      for (int k = 0; k < n; ++k)
        if (k != prev_edge && (W.ring[2 * (b + k)] == cur || W.ring[2 * (b + k) + 1] == cur)) {
          next_edge = k;
          break;
        }
      if (next_edge < 0) return false;
      cur = W.ring[2 * (b + next_edge)] == cur ? W.ring[2 * (b + next_edge) + 1] : W.ring[2 * (b + next_edge)];
      prev_edge = next_edge;
      ++steps;
    }
    if (cur != first || steps != n) return false;
  }
  return true;
}

}  // namespace

TopologyReport analyse_topology(const io::Complex& K, int m, const FaceLattice* lattice, int threads) {
  TopologyReport R;
  R.m = m;
  bool too_big = false;
  // Ridges of the m-simplices (numbered 0, 1, ... in file order) and the strongly connected components across them.
  std::vector<std::pair<std::array<int, 8>, long>> ridge_of;  // (ridge padded with -1, simplex)
  ridge_of.reserve(m <= 8 ? K.simplices.size() * (m + 1) : 0);
  long tops = 0;
  for (auto s : K.simplices) {
    std::sort(s.begin(), s.end());
    if (static_cast<int>(s.size()) != m + 1) {
      if (R.pure) R.impure_example = s;
      R.pure = false;
      too_big = too_big || static_cast<int>(s.size()) > m + 1;
      continue;
    }
    for (int i = 0; i <= m && m <= 8; ++i) {
      std::array<int, 8> r;
      r.fill(-1);
      for (int t = 0, n = 0; t <= m; ++t)
        if (t != i) r[n++] = s[t];
      ridge_of.emplace_back(r, tops);
    }
    ++tops;
  }
  std::sort(ridge_of.begin(), ridge_of.end());
  UnionFind uf(tops);
  R.strong_components = tops;
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
  decltype(ridge_of)().swap(ridge_of);  // freed before the links and Betti numbers
  // Vertex links.
  std::vector<std::vector<long>> incident(K.num_vertices);
  for (std::size_t j = 0; j < K.simplices.size(); ++j)
    for (int v : K.simplices[j]) incident[v].push_back(static_cast<long>(j));
  // The m = 3 fast path (m = 2: is_sphere) for every vertex in parallel (its answer depends only on
  // the vertex); the vertices it does not accept then go, in increasing order, through is_sphere.
  std::vector<char> settled(K.num_vertices, 0);
  if (m == 3) {
    std::vector<LinkScratch> scratch(std::max(1, threads));
    std::vector<std::vector<std::array<int, 3>>> tris_of(std::max(1, threads));
    detail::parallel_for(K.num_vertices, threads, [&](std::size_t v, int w) {
      auto& tris = tris_of[w];
      tris.clear();
      for (long j : incident[v]) {
        const auto& s = K.simplices[j];
        if (s.size() != 4) return;
        std::array<int, 3> t{};
        int n = 0;
        for (int x : s)
          if (x != static_cast<int>(v) && n < 3) t[n++] = x;
        if (n != 3) return;
        tris.push_back(t);
      }
      settled[v] = !incident[v].empty() && link_is_2_sphere(tris, scratch[w]);  // is_sphere would say yes
    });
  } else if (m == 2) {  // is_sphere itself (a cycle test) in parallel; its answer depends only on the vertex
    detail::parallel_for(K.num_vertices, threads, [&](std::size_t v, int) {
      std::vector<std::vector<int>> link;
      link.reserve(incident[v].size());
      for (long j : incident[v]) {
        link.emplace_back().reserve(2);
        for (int x : K.simplices[j])
          if (x != static_cast<int>(v)) link.back().push_back(x);
      }
      settled[v] = !link.empty() && is_sphere(link, 1, nullptr) == Tri::yes;
    });
  }
  for (std::size_t v = 0; v < K.num_vertices; ++v) {
    if (incident[v].empty()) {
      ++R.uncovered_vertices;
      continue;
    }
    if (settled[v]) continue;
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
    std::optional<FaceLattice> own;
    if (!lattice) own = face_lattice(K.simplices, threads);
    const FaceLattice& L = lattice ? *lattice : *own;
    for (int k = 0; k <= L.dimension; ++k) {
      R.f.push_back(static_cast<long>(L.count(k)));
      R.euler += (k % 2 ? -1 : 1) * R.f.back();
    }
    const FaceIndex I = face_index(L, threads);  // shared by both fields
    std::vector<long> ranks[2];
    detail::parallel_for(2, threads, [&](std::size_t f, int) { ranks[f] = boundary_ranks(L, I, f ? 3 : 2); });
    R.betti_z2 = betti_from_ranks(L, ranks[0]);
    R.betti_z3 = betti_from_ranks(L, ranks[1]);
  }
  return R;
}

}  // namespace delcert::certify
