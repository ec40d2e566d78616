#include "core/app/command.hpp"

#include "io/spec.hpp"

namespace delcert::app {

std::string manifold_option_help() {
  std::string s = "manifold spec: a JSON file or builtin:NAME (";
  auto names = io::builtin_spec_names();
  for (std::size_t i = 0; i < names.size(); ++i) s += (i ? ", " : "") + names[i];
  return s + ")";
}

}  // namespace delcert::app
