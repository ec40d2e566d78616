// Links delcert::io alone (tests/install/consumer/): the built-in specs are compiled into the
// installed library, so builtin:NAME needs no file of delcert's sources.
#include <cstdio>
#include <exception>

#include "io/spec.hpp"

int main() {
  using namespace delcert;
  try {
    const io::ManifoldSpec spec = io::read_spec("builtin:sphere-2");
    if (spec.intrinsic_dimension != 2 || spec.ambient_dimension != 3 || spec.equations.size() != 1) {
      std::fprintf(stderr, "io_only: builtin:sphere-2 is not S^2 in R^3\n");
      return 1;
    }
    std::printf("io_only: builtin:sphere-2, %zu built-in specs\n", io::builtin_spec_names().size());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "io_only: %s\n", e.what());
    return 1;
  }
  return 0;
}
