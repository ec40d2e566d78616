// Certify a complex through the library API of the checker (certify/), as delcert-certify does.
//
//   certify_complex [MANIFOLD POINTS COMPLEX [CLAIMS]]
//
// Without arguments (run from the repository root) it checks that the octahedron is the
// tangential Delaunay complex of its six vertices on the unit sphere S^2. Prints one line per
// check and the verdict; exit status 0 only when the verdict is CERTIFIED.
#include <cstdio>
#include <exception>
#include <string>

#include "certify/certificate.hpp"
#include "certify/certify.hpp"
#include "exact/interval.hpp"

int main(int argc, char** argv) {
  using namespace delcert;

  // The inputs are files (or builtin:NAME for a manifold compiled into the library).
  certify::CertifyOptions options;
  options.manifold = argc > 1 ? argv[1] : "builtin:sphere-2";
  options.points = argc > 2 ? argv[2] : "fixtures/points/octahedron.off";
  options.complex = argc > 3 ? argv[3] : "fixtures/certify/octahedron.complex";
  options.claims = argc > 4 ? argv[4] : "";  // optional: claims.json (star_radius, covering, sparsity, ...)

  // Every enclosure relies on directed rounding; check once that it works in this build.
  if (const std::string why = exact::directed_rounding_failure(); !why.empty()) {
    std::fprintf(stderr, "certify_complex: directed rounding does not work here (%s)\n", why.c_str());
    return 3;
  }

  certify::Certificate certificate;
  try {
    // Reads the inputs, runs the ten checks, never writes anything.
    certificate = certify::run_certify(options);
  } catch (const std::exception& e) {  // io::InputError on bad input, naming file and line
    std::fprintf(stderr, "certify_complex: %s\n", e.what());
    return 2;
  }

  // One entry per check, by CheckId: its verdict and a one-line summary.
  for (const certify::CheckEntry& check : certificate.checks)
    std::printf("check %-2d %-18s %-10s %s\n", check.number(), check.name(), certify::to_string(check.verdict),
                check.summary.c_str());
  // REPORT entries are informational; the overall verdict comes from the others.
  const certify::Verdict verdict = certificate.overall();
  std::printf("verdict: %s\n", certify::to_string(verdict));
  // certificate.to_text() is the JSON that delcert-certify --out writes (docs/certificate.md).
  return verdict == certify::Verdict::certified ? 0 : 1;
}
