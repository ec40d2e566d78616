// libFuzzer target: the points reader (see readers.hpp for what counts as a failure).
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <typeinfo>

#include "fuzz/readers.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    delcert::fuzz::points(std::string(reinterpret_cast<const char*>(data), size));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "delcert fuzz_points: undocumented exception %s: %s\n", typeid(e).name(), e.what());
    std::abort();
  }
  return 0;
}
