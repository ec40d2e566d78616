#include "certify/distributed.hpp"

#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <type_traits>

#include "certify/detail/grid.hpp"

namespace delcert::certify {
namespace {

// Every message starts with these: a rank built differently (another binary, byte order or
// double format) is refused rather than misread.
constexpr std::uint64_t kMagic = 0x64656c6365727431;  // "delcert1"
constexpr double kProbe = -0x1.23456789abcdfp-1021;

class Writer {
 public:
  Writer() { put(kMagic), put(kProbe), put(sizeof(long)); }
  template <class T>
  void put(const T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    out.append(reinterpret_cast<const char*>(&v), sizeof v);
  }
  void put(const std::string& s) { put(std::uint64_t(s.size())), out += s; }
  void put(const mpq_class& q) { put(q.get_str(16)); }
  template <class T>
  void put(const std::vector<T>& v) {
    put(std::uint64_t(v.size()));
    for (const T& x : v) put(x);
  }
  void put(const CellReport& c) {
    put(c.simplex), put(c.conflict_power), put(c.radius2), put(c.margin), put(c.protection_power);
    for (int k : {c.conflict, c.tie, c.margin_point, c.protection_point, c.protection_sign, c.eps_sign}) put(k);
    put(c.degenerate);
  }
  std::string out;
};

class Reader {
 public:
  explicit Reader(const std::string& s) : s_(s) {
    std::uint64_t magic = 0;
    double probe = 0;
    std::size_t long_size = 0;
    get(magic), get(probe), get(long_size);
    if (magic != kMagic || std::memcmp(&probe, &kProbe, sizeof probe) != 0 || long_size != sizeof(long))
      throw std::runtime_error("distributed run: a rank's message is in another format (every rank must run the same "
                               "delcert-certify on the same kind of machine)");
  }
  template <class T>
  void get(T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    take(&v, sizeof v);
  }
  void get(std::string& s) {
    s.resize(size());
    take(s.data(), s.size());
  }
  void get(mpq_class& q) {
    std::string t;
    get(t);
    q.set_str(t, 16);
  }
  template <class T>
  void get(std::vector<T>& v) {
    v.resize(size());
    for (T& x : v) get(x);
  }
  void get(CellReport& c) {
    get(c.simplex), get(c.conflict_power), get(c.radius2), get(c.margin), get(c.protection_power);
    for (int* k : {&c.conflict, &c.tie, &c.margin_point, &c.protection_point, &c.protection_sign, &c.eps_sign}) get(*k);
    get(c.degenerate);
  }
  void finish() const {
    if (at_ != s_.size()) throw std::runtime_error("distributed run: a rank's message is longer than its contents");
  }

 private:
  std::size_t size() {
    std::uint64_t n = 0;
    get(n);
    if (n > s_.size() - at_) throw std::runtime_error("distributed run: a rank's message is truncated");
    return n;
  }
  void take(void* p, std::size_t k) {
    if (k > s_.size() - at_) throw std::runtime_error("distributed run: a rank's message is truncated");
    std::memcpy(p, s_.data() + at_, k), at_ += k;
  }
  const std::string& s_;
  std::size_t at_ = 0;
};

// A star report crosses without basis_enclosure and gram_enclosure: they are check 7's inputs at
// the report's own point, and check 7 runs where the star was computed (rank 0 reads them for its
// own block only). About 200 bytes a point less in the message and on rank 0.
void put(Writer& w, const StarReport& r) {
  w.put(r.p), w.put(r.state), w.put(r.reason), w.put(r.claimed_verified), w.put(r.star), w.put(r.claimed);
  w.put(r.link_problem), w.put(r.search_radius);
  w.put(r.searched_all), w.put(r.halo_needed), w.put(r.vertices);
  for (int k : {r.cells, r.min_margin_cell, r.min_margin_point, r.max_radius_cell}) w.put(k);
  w.put(r.min_margin), w.put(r.max_radius2);
}
void get(Reader& in, StarReport& r) {
  in.get(r.p), in.get(r.state), in.get(r.reason), in.get(r.claimed_verified), in.get(r.star), in.get(r.claimed);
  in.get(r.link_problem), in.get(r.search_radius);
  in.get(r.searched_all), in.get(r.halo_needed), in.get(r.vertices);
  for (int* k : {&r.cells, &r.min_margin_cell, &r.min_margin_point, &r.max_radius_cell}) in.get(*k);
  in.get(r.min_margin), in.get(r.max_radius2);
}
void put(Writer& w, const SecureReport& r) {
  w.put(r.secure), w.put(r.insecure), w.put(r.undecided), w.put(r.exact_fallbacks), w.put(r.halo_needed);
  w.put(std::uint64_t(r.failures.size()));
  for (const auto& [s, why] : r.failures) w.put(s), w.put(why);
}
void get(Reader& in, SecureReport& r) {
  in.get(r.secure), in.get(r.insecure), in.get(r.undecided), in.get(r.exact_fallbacks), in.get(r.halo_needed);
  std::uint64_t n = 0;
  in.get(n);
  if (n > (std::uint64_t(1) << 32)) throw std::runtime_error("distributed run: a rank's message is corrupt");
  r.failures.resize(n);
  for (auto& [s, why] : r.failures) in.get(s), in.get(why);
}

template <class R>
std::string encode_all(const std::vector<R>& reports) {
  Writer w;
  w.put(std::uint64_t(reports.size()));
  for (const R& r : reports) put(w, r);
  return std::move(w.out);
}
template <class R>
void decode_all(const std::string& bytes, const std::vector<int>& owned, std::vector<R>& reports) {
  Reader in(bytes);
  std::uint64_t n = 0;
  in.get(n);
  if (n != owned.size()) throw std::runtime_error("distributed run: a rank sent results for other points");
  for (int p : owned) get(in, reports[p]);
  in.finish();
}

}  // namespace

std::vector<int> owned_points(const detail::PointGrid& grid, int rank, int size) {
  const std::vector<int>& order = grid.order();
  const std::size_t n = order.size(), k = static_cast<std::size_t>(size), r = static_cast<std::size_t>(rank);
  std::vector<int> mine(order.begin() + r * n / k, order.begin() + (r + 1) * n / k);
  std::sort(mine.begin(), mine.end());
  return mine;
}

std::string encode(const std::vector<StarReport>& r) { return encode_all(r); }
void decode(const std::string& b, const std::vector<int>& owned, std::vector<StarReport>& r) { decode_all(b, owned, r); }
std::string encode(const std::vector<SecureReport>& r) { return encode_all(r); }
void decode(const std::string& b, const std::vector<int>& owned, std::vector<SecureReport>& r) { decode_all(b, owned, r); }

std::string encode_stats(const exact::FilterStats& stats) {
  Writer w;
  w.put(stats.counters);
  return std::move(w.out);
}
exact::FilterStats decode_stats(const std::string& bytes) {
  exact::FilterStats s;
  Reader in(bytes);
  in.get(s.counters);
  in.finish();
  return s;
}

std::string encode_measured(const Measured& m) {
  Writer w;
  w.put(m.min_distance), w.put(m.min_thickness), w.put(m.min_margin), w.put(m.max_radius_squared);
  for (const auto* q : {&m.eps, &m.covering}) {
    w.put(q->has_value());
    if (*q) w.put(**q);
  }
  return std::move(w.out);
}
Measured decode_measured(const std::string& bytes) {
  Measured m;
  Reader in(bytes);
  in.get(m.min_distance), in.get(m.min_thickness), in.get(m.min_margin), in.get(m.max_radius_squared);
  for (auto* q : {&m.eps, &m.covering}) {
    bool has = false;
    in.get(has);
    if (has) in.get(q->emplace());
  }
  in.finish();
  return m;
}

}  // namespace delcert::certify
