#include "exact/filter_stats.hpp"

namespace delcert::exact {

std::string_view predicate_name(PredicateKind kind) {
  switch (kind) {
    case PredicateKind::tangent_orientation: return "tangent_orientation";
    case PredicateKind::power: return "power";
    case PredicateKind::power_threshold: return "power_threshold";
    case PredicateKind::thickness: return "thickness";
    case PredicateKind::squared_distance: return "squared_distance";
    case PredicateKind::ambient_power: return "ambient_power";
  }
  return "unknown";
}

void FilterStats::merge(const FilterStats& other) {
  for (int k = 0; k < kNumPredicateKinds; ++k) {
    counters[k].calls += other.counters[k].calls;
    counters[k].filter_failures += other.counters[k].filter_failures;
    counters[k].zero_results += other.counters[k].zero_results;
  }
}

std::uint64_t FilterStats::total_calls() const {
  std::uint64_t n = 0;
  for (const auto& c : counters) n += c.calls;
  return n;
}

std::uint64_t FilterStats::total_failures() const {
  std::uint64_t n = 0;
  for (const auto& c : counters) n += c.filter_failures;
  return n;
}

}  // namespace delcert::exact
