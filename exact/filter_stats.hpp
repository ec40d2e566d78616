// Per-predicate counters of the filtered evaluation, and the context object every filtered
// predicate takes.
//
// A filtered predicate first evaluates its sign in interval arithmetic; when the interval
// contains zero (the "filter fails") it re-evaluates exactly. The certificate reports how often
// that happened, so each predicate call counts itself in the FilterContext it is given. There is
// no global state: give each thread its own FilterContext and merge the statistics at the end.
#pragma once

#include <array>
#include <cstdint>
#include <string_view>

namespace delcert::exact {

enum class PredicateKind : int {
  tangent_orientation = 0,  // orientation of m + 1 points in T_p (also a cell's own orientation)
  power,                    // sign of |c - q|^2 - |c - p|^2 for a star cell's centre c in T_p
  power_threshold,          // the same minus a rational threshold (power protection)
  thickness,                // Upsilon(t) compared with a rational Gamma (via squares)
  squared_distance,         // |a - b|^2 against |c - d|^2 or against a rational
  ambient_power,            // sign of |x - q|^2 - |x - p|^2 for an exactly given x
};
inline constexpr int kNumPredicateKinds = 6;

// Stable lower-case names ("tangent_orientation", "power", ...) for reports.
std::string_view predicate_name(PredicateKind kind);

struct PredicateCounter {
  std::uint64_t calls = 0;            // every call
  std::uint64_t filter_failures = 0;  // calls decided by the exact fallback
  std::uint64_t zero_results = 0;     // calls whose exact answer was 0 (degenerate / on the sphere)
};

struct FilterStats {
  std::array<PredicateCounter, kNumPredicateKinds> counters{};

  PredicateCounter& operator[](PredicateKind k) { return counters[static_cast<int>(k)]; }
  const PredicateCounter& operator[](PredicateKind k) const { return counters[static_cast<int>(k)]; }
  void merge(const FilterStats& other);
  std::uint64_t total_calls() const;
  std::uint64_t total_failures() const;
};

// Passed by reference to every filtered predicate. Not thread-safe: one per thread.
struct FilterContext {
  FilterStats stats;
  // Skip the interval filter and always evaluate exactly. For tests and benchmarks; the answers
  // are the same either way.
  bool force_exact = false;
};

}  // namespace delcert::exact
