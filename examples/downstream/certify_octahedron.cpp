// A downstream program linking delcert::certify (examples/downstream/CMakeLists.txt):
//
//   certify_octahedron POINTS COMPLEX
//
// certifies that COMPLEX is the tangential Delaunay complex of POINTS on the unit sphere
// (builtin:sphere-2, compiled into delcert::io) and prints the verdict; exit status 0 only when it
// is CERTIFIED.
#include <cstdio>
#include <exception>
#include <string>

#include "certify/certificate.hpp"
#include "certify/certify.hpp"
#include "exact/interval.hpp"

int main(int argc, char** argv) {
  using namespace delcert;
  if (argc != 3) {
    std::fprintf(stderr, "usage: certify_octahedron POINTS COMPLEX\n");
    return 2;
  }
  // Every enclosure relies on directed rounding: check once that it works in this build.
  if (const std::string why = exact::directed_rounding_failure(); !why.empty()) {
    std::fprintf(stderr, "certify_octahedron: directed rounding does not work here (%s)\n", why.c_str());
    return 3;
  }
  certify::CertifyOptions options;
  options.manifold = "builtin:sphere-2";
  options.points = argv[1];
  options.complex = argv[2];
  try {
    const certify::Certificate certificate = certify::run_certify(options);
    const certify::Verdict verdict = certificate.overall();
    std::printf("verdict: %s\n", certify::to_string(verdict));
    return verdict == certify::Verdict::certified ? 0 : 1;
  } catch (const std::exception& e) {  // io::InputError on bad input, naming file and line
    std::fprintf(stderr, "certify_octahedron: %s\n", e.what());
    return 2;
  }
}
