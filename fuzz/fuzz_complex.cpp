// libFuzzer target: the complex reader (see readers.hpp for what counts as a failure).
#include <cstddef>
#include <cstdint>

#include "fuzz/readers.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return delcert::fuzz::run_one("fuzz_complex", delcert::fuzz::complex, data, size);
}
