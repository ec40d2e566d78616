// Build a triangulation of a manifold with the producer's API (core/) and prove it correct with
// the checker's API (certify/), as `delcert refine` followed by `delcert-certify --claims` does.
//
//   refine_and_certify
//
// The flat (Clifford) torus in R^4: an eps-net, refined until its tangential Delaunay complex is
// thick, protected and consistent, then certified with the refiner's own claims. Prints the
// counts and the verdict; exit status 0 only when the verdict is CERTIFIED. Under a second.
#include <stdlib.h>  // mkdtemp

#include <cstdio>
#include <exception>
#include <filesystem>
#include <stdexcept>
#include <string>

#include "certify/certify.hpp"
#include "core/manifold/manifold.hpp"
#include "core/refine/refine_output.hpp"
#include "core/refine/refiner.hpp"
#include "core/sampling/sampling.hpp"
#include "exact/interval.hpp"
#include "io/spec.hpp"

int main() try {
  using namespace delcert;

  // 1. The manifold: a spec compiled into the library (a JSON file path works the same way).
  manifold::Manifold torus(io::read_spec("builtin:clifford-torus-2"));

  // 2. An eps-net: points of M at least eps apart, within eps of every point of M.
  sampling::EpsNetOptions net_options;
  net_options.eps = 0.25;
  net_options.seed = 1;  // same seed, same points
  sampling::EpsNetResult net = sampling::eps_net(torus, net_options);

  // 3. Refine: insert points until every star is thick, protected and small. The constants are
  //    exact rationals (Gamma0, alpha, beta and delta0 keep their defaults).
  refine::RefineParameters params;
  params.constants.eps = refine::ExactParameter::parse("0.25");
  params.seed = 1;
  refine::RefineResult refined = refine::refine(torus, net.points, params);
  std::printf("points     %zu in the eps-net, %zu after refinement\n", net.points.size(), refined.points.size());
  std::printf("complex    %zu triangles, converged: %s\n", refined.complex.simplices.size(),
              refined.converged ? "yes" : "no");

  // 4. Write points.txt, complex.txt and claims.json (and report.json), as `delcert refine` does.
  std::string dir = (std::filesystem::temp_directory_path() / "delcert-example-XXXXXX").string();
  if (mkdtemp(dir.data()) == nullptr) throw std::runtime_error("cannot create a temporary directory");
  refine::write_refine_output(dir, refined, {torus.spec().name, torus.spec().source, "eps-net, eps 0.25, seed 1"});

  // 5. Certify those files with the independent checker, claims included. Its enclosures rely on
  //    directed rounding, so check first that it works in this build.
  if (!exact::directed_rounding_failure().empty()) throw std::runtime_error("directed rounding does not work here");
  certify::CertifyOptions check;
  check.manifold = "builtin:clifford-torus-2";
  check.points = dir + "/points.txt";
  check.complex = dir + "/complex.txt";
  check.claims = dir + "/claims.json";
  certify::Certificate certificate = certify::run_certify(check);
  std::filesystem::remove_all(dir);

  const certify::Verdict verdict = certificate.overall();
  std::printf("verdict: %s\n", certify::to_string(verdict));
  return verdict == certify::Verdict::certified ? 0 : 1;
} catch (const std::exception& e) {
  std::fprintf(stderr, "refine_and_certify: %s\n", e.what());
  return 2;
}
