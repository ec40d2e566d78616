// One entry point per file reader, shared by the libFuzzer targets (fuzz/fuzz_*.cpp) and the
// replay of fuzz/regressions/ in the ordinary test suite (tests/fuzz/fuzz_regression_test.cpp).
//
// Each function feeds one input to a reader exactly as the programs do and returns true when the
// reader accepted it, false when it refused it with the error that reader documents:
//   points, complex, spec, claims   io::InputError
//   polynomial                      PolynomialParseError (Polynomial::parse),
//                                   std::invalid_argument (parse_rational)
// Anything else escapes: another exception type, or RoundTripError when an accepted input does
// not survive its writer and the reader again (the writers promise a faithful round trip; for a
// polynomial, whose expanded text can outgrow the input, within the text limit). A
// crash, a sanitizer report or a hang is a bug as well; those the fuzzer and ctest see directly.
#pragma once

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <stdexcept>
#include <string>
#include <string_view>
#include <typeinfo>

#include "io/claims.hpp"
#include "exact/polynomial.hpp"
#include "io/complex.hpp"
#include "io/input_error.hpp"
#include "io/points.hpp"
#include "io/spec.hpp"

namespace delcert::fuzz {

// Not derived from any of the documented reader errors, so that nothing mistakes it for one.
struct RoundTripError : std::logic_error {
  using std::logic_error::logic_error;
};

namespace detail {

// Runs `again` (writer, then reader) and turns any exception into a RoundTripError.
template <class F>
auto round_trip(const char* what, F&& again) {
  try {
    return again();
  } catch (const std::exception& e) {
    throw RoundTripError(std::string(what) + ": the written text does not read back: " + e.what());
  }
}

inline bool same_points(const io::PointSet& a, const io::PointSet& b) {
  return a.dimension == b.dimension && a.coordinates.size() == b.coordinates.size() &&
         (a.coordinates.empty() ||
          std::memcmp(a.coordinates.data(), b.coordinates.data(), a.coordinates.size() * sizeof(double)) == 0);
}

inline bool same_complex(const io::Complex& a, const io::Complex& b) {
  return a.num_vertices == b.num_vertices && a.simplices == b.simplices;
}

}  // namespace detail

inline bool points(const std::string& text) {
  io::PointSet p;
  try {
    p = io::parse_points(text, "fuzz-input");
  } catch (const io::InputError&) {
    return false;
  }
  // Every format must round-trip bit for bit (points.hpp).
  auto back = [&](io::PointFormat f) {
    return detail::round_trip("points", [&] { return io::parse_points(io::format_points(p, f), "round-trip"); });
  };
  if (!detail::same_points(p, back(io::PointFormat::delcert)))
    throw RoundTripError("points: delcert-points v1 round trip changed the points");
  if (!detail::same_points(p, back(io::PointFormat::noff)))
    throw RoundTripError("points: nOFF round trip changed the points");
  if (p.dimension == 3 && !detail::same_points(p, back(io::PointFormat::off)))
    throw RoundTripError("points: OFF round trip changed the points");
  return true;
}

inline bool complex(const std::string& text) {
  io::ComplexFile c;
  try {
    c = io::parse_complex(text, "fuzz-input");
  } catch (const io::InputError&) {
    return false;
  }
  auto again = detail::round_trip("complex", [&] { return io::parse_complex(io::format_complex(c.complex), "round-trip"); });
  if (!detail::same_complex(c.complex, again.complex))
    throw RoundTripError("complex: delcert-complex v1 round trip changed the complex");
  if (c.embedded_points) {  // OFF: triangles and their points
    auto off = detail::round_trip("complex", [&] { return io::parse_complex(io::format_off(*c.embedded_points, c.complex), "round-trip"); });
    if (!detail::same_complex(c.complex, off.complex) || !off.embedded_points ||
        !detail::same_points(*c.embedded_points, *off.embedded_points))
      throw RoundTripError("complex: OFF round trip changed the mesh");
  }
  return true;
}

inline bool spec(const std::string& text) {
  try {
    io::parse_spec(text, "fuzz-input.json");
  } catch (const io::InputError&) {
    return false;
  }
  return true;
}

inline bool claims(const std::string& text) {
  try {
    io::parse_claims(text, "fuzz-input.json");
  } catch (const io::InputError&) {
    return false;
  }
  return true;
}

// Input: an optional prefix "N;" (N = 1..64 variables, as a spec's ambient dimension allows),
// then the polynomial text; without the prefix N = 9. The whole text (after the prefix) is also
// given to parse_rational, the parser of every rational literal in specs and claims.
inline bool polynomial(const std::string& data) {
  int n = 9;
  std::string_view text = data;
  if (auto semi = text.find(';'); semi != std::string_view::npos && semi >= 1 && semi <= 2) {
    int v = 0;
    bool digits = true;
    for (char ch : text.substr(0, semi)) digits = digits && ch >= '0' && ch <= '9', v = 10 * v + (ch - '0');
    if (digits && v >= 1 && v <= 64) n = v, text.remove_prefix(semi + 1);
  }
  bool accepted = false;
  try {
    mpq_class q = exact::parse_rational(text);
    accepted = true;
    mpq_class back = detail::round_trip("rational", [&] { return exact::parse_rational(exact::rational_to_string(q)); });
    if (back != q) throw RoundTripError("rational: rational_to_string round trip changed the value");
  } catch (const std::invalid_argument&) {
  }
  try {
    exact::Polynomial p = exact::Polynomial::parse(text, n);
    accepted = true;
    const std::string written = p.to_string();
    if (written.size() > exact::PolynomialLimits::max_text_length) {
      // The expansion is longer than the text limit: the reader must refuse it (documented error),
      // and there is nothing to compare.
      bool refused = false;
      try {
        exact::Polynomial::parse(written, n);
      } catch (const exact::PolynomialParseError&) {
        refused = true;
      }
      if (!refused) throw RoundTripError("polynomial: a written text beyond the text limit was accepted");
      return accepted;
    }
    exact::Polynomial back = detail::round_trip("polynomial", [&] { return exact::Polynomial::parse(written, n); });
    if (!(back == p)) throw RoundTripError("polynomial: to_string round trip changed the polynomial");
  } catch (const exact::PolynomialParseError&) {
  }
  return accepted;
}

// The body of every libFuzzer target: feed the input to `reader`; an escaping exception is a
// finding, reported with the target's name and turned into a crash that libFuzzer records.
inline int run_one(const char* target, bool (*reader)(const std::string&), const std::uint8_t* data, std::size_t size) {
  try {
    reader(std::string(reinterpret_cast<const char*>(data), size));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "delcert %s: undocumented exception %s: %s\n", target, typeid(e).name(), e.what());
    std::abort();
  }
  return 0;
}

}  // namespace delcert::fuzz
