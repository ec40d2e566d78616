// delcert-certify: the independent checker (DESIGN §1, §4, §5b).
// Until the certifier lands it only prints its usage; every other invocation is a usage error.
#include <CLI/CLI.hpp>

#include <iostream>

int main(int argc, char** argv) {
  CLI::App app{"delcert-certify: exact certificates for Delaunay complexes of manifolds.\n"
               "Verdict on the last line: CERTIFIED (exit 0), REFUTED (1), UNDECIDED (3); bad input or usage: 2."};
  std::string manifold, points, complex, claims, out;
  int threads = 1;
  app.add_option("--manifold", manifold, "manifold spec file or builtin:NAME")->required();
  app.add_option("--points", points, "point set (delcert-points v1, OFF, nOFF)")->required();
  app.add_option("--complex", complex, "complex to verify (delcert-complex v1, OFF)");
  app.add_option("--claims", claims, "claims.json written by a producer");
  app.add_option("--out", out, "certificate JSON path (written atomically)");
  app.add_option("--threads", threads, "worker threads");
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return 2;
  }
  std::cerr << "delcert-certify: the certifier is not implemented in this build; nothing was checked.\n";
  return 2;
}
