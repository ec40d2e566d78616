// libFuzzer target: the points reader (see readers.hpp for what counts as a failure).
#include <cstddef>
#include <cstdint>

#include "fuzz/readers.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return delcert::fuzz::run_one("fuzz_points", delcert::fuzz::points, data, size);
}
