// delcert-certify: the independent checker (docs/design.md §1, §5, §9).
//
//   delcert-certify --manifold SPEC --points POINTS [--complex COMPLEX] [--kind tangential|restricted|intrinsic]
//                   [--complex-format auto|delcert|off|obj|ply|stl|gudhi] [--residual-tolerance T]
//                   [--claims CLAIMS.json] [--out CERTIFICATE.json] [--threads T] [--no-times]
//                   [--skip-restricted] [--report REPORT.html] [--fix-out MESH] [--halo H]   (MPI: design.md §4.11)
//
// Prints one line per check ([claimed] or [not claimed]), the claims that decided the verdict and, last,
// "verdict: CERTIFIED|REFUTED|UNDECIDED".
// Exit status: 0 CERTIFIED, 1 REFUTED, 3 UNDECIDED, 2 bad input or usage (no certificate written).
#include <CLI/CLI.hpp>

#include <cfloat>
#include <charconv>
#include <cstdio>
#include <iostream>
#include <regex>
#include <thread>

#include "certify/certify.hpp"
#include "exact/interval.hpp"
#include "io/atomic_file.hpp"
#include "io/input_error.hpp"
#include "io/progress.hpp"
#include "io/spec.hpp"
#include "certify/detail/sha256.hpp"
#include "certify/detail/world.hpp"
#include "io/mesh_feedback.hpp"  // presentation only: a mesh's edges in its file's numbering, --fix-out
#include "report/html_report.hpp"  // presentation only: reads the finished certificate

int main(int argc, char** argv) {
  using namespace delcert;
  // An MPI job when started by mpirun and built with -DDELCERT_MPI=ON (docs/design.md §4.11): every
  // rank runs this program on the same arguments; rank 0 alone prints and writes.
  const std::unique_ptr<certify::detail::World> world = certify::detail::make_world(argc, argv);
  const bool root = world->rank() == 0;
  if (!root && !std::freopen("/dev/null", "w", stdout)) return 3;  // (--help and --version: once, from rank 0)
  CLI::App app{"delcert-certify: exact certificates for tangential Delaunay complexes of manifolds.\n"
               "Verdict on the last line: CERTIFIED (exit 0), REFUTED (1), UNDECIDED (3); bad input or usage: 2."};
  app.set_version_flag("--version", "delcert-certify " DELCERT_VERSION, "print \"delcert-certify VERSION\" and exit");
  certify::CertifyOptions o;
  o.threads = 0;  // one per hardware thread, the default of every command
  std::string out;
  bool no_times = false;
  std::string builtins;
  for (const auto& n : io::builtin_spec_names()) builtins += (builtins.empty() ? "" : ", ") + n;
  app.add_option("--manifold", o.manifold, "manifold spec: a JSON file or builtin:NAME (" + builtins + ")")->required();
  app.add_option("--points", o.points, "point set (delcert-points v1, OFF, nOFF, or an OBJ/PLY/STL mesh's vertices)")->required();
  app.add_option("--complex", o.complex, "complex to verify (delcert-complex v1, OFF, OBJ, PLY, STL, GUDHI simplex list); without it the tangential complex of the points is computed and audited");
  app.add_option("--complex-format", o.complex_format, "format of --complex (default auto: detected; docs/formats.md)")
      ->check(CLI::IsMember({"auto", "delcert", "off", "obj", "ply", "stl", "gudhi"}));
  app.add_option("--residual-tolerance", o.residual_tolerance, "largest |F_i(p)| accepted for an input point, replacing the spec's residual_tolerance (a positive decimal or fraction, read exactly; recorded in the certificate)");
  std::string kind;
  app.add_option("--kind", kind, "what the complex is claimed to be: tangential (Del_TM, the default for delcert-complex files), restricted (Del_RM, the default for OFF/OBJ/PLY/STL: a surface mesher's output) or intrinsic (Del_M)")
      ->check(CLI::IsMember({"tangential", "restricted", "intrinsic"}));
  app.add_option("--claims", o.claims, "claims.json (delcert-claims v2: star_radius, covering, sparsity, gamma0, power_protection; v1 read too)");
  app.add_flag("--skip-restricted", o.skip_restricted, "do not compute the restricted Voronoi diagram and Del_M (checks 11-15): the certificate is about Del_TM only");
  app.add_option("--out", out, "certificate JSON path (written atomically)");
  std::string report_path, fix_out;
  app.add_option("--report", report_path, "also write the certificate as a self-contained HTML page (verdicts, margins, a 3D view of the complex with the witnesses); written atomically with --out");
  app.add_option("--fix-out", fix_out, "surface meshes (--complex OFF, OBJ, PLY or STL; m = 2): when check 12 proves Del_RM(P) complete and pure, write its triangles to this file in the format and vertex numbering of --complex, to replace the mesh; written atomically with --out; not written otherwise (the exit status is the verdict's)");
  app.add_option("--threads", o.threads, "worker threads: 0 (the default) = one per hardware thread, or 1 to 256; the certificate does not depend on it")
      ->check(CLI::Range(0, 256))->capture_default_str();
  app.add_option("--halo", o.halo, "MPI runs: the distance around its own points up to which each rank but 0 holds the others; a point whose searches need more is UNDECIDED (default: automatic, widened as needed)")
      ->check(CLI::Validator([](std::string& v) {
        double h = 0;
        const auto [end, ec] = std::from_chars(v.data(), v.data() + v.size(), h);
        return ec == std::errc() && end == v.data() + v.size() && h > 0 && h <= DBL_MAX ? std::string() : "not a positive distance: " + v;
      }, "POSITIVE"));
  app.add_flag("--no-times", no_times, "leave wall-clock times out of the certificate (byte-identical reruns)");
  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& e) {  // --help, --version: exit 0
    return app.exit(e);
  } catch (const CLI::ParseError& e) {  // CLI11 echoes the value: a number of 300 digits is cut to 20
    std::cerr << std::regex_replace(e.what(), std::regex("([0-9]{20})[0-9]{5,}"), "$1...") << "\n"
              << "Run with --help for more information.\n";
    return 2;
  }
  o.fixed_halo = app.count("--halo") > 0;
  if (!kind.empty())
    o.kind = kind == "restricted" ? certify::ComplexKind::restricted : kind == "intrinsic" ? certify::ComplexKind::intrinsic : certify::ComplexKind::tangential;
  if ((!kind.empty() || o.complex_format != "auto") && o.complex.empty()) {
    std::cerr << "delcert-certify: --kind and --complex-format need --complex (they describe the given complex)\n";
    return 2;
  }
  if (const std::string why = exact::directed_rounding_failure(); !why.empty()) {
    std::cerr << "delcert-certify: internal error: directed rounding does not work on this machine or build (" << why
              << "); no enclosure could be trusted\n";
    std::printf("verdict: UNDECIDED\n");
    return 3;
  }
  if (o.threads == 0)  // (the ranks of an MPI job on one machine share its cores)
    o.threads = std::max(1, static_cast<int>(std::thread::hardware_concurrency()) / world->ranks_on_this_machine());
  try {
    // --out must not be (the same file as) an input, nor unwritable: checked before any work.
    if (!out.empty()) io::check_output_path(out, "--out", {o.manifold, o.points, o.complex, o.claims});
    if (!report_path.empty() && !report::viewer_available())
      return std::cerr << "delcert-certify: " << report::viewer_missing_message() << "\n", 2;
    if (!report_path.empty()) io::check_output_path(report_path, "--report", {o.manifold, o.points, o.complex, o.claims}, {out});
    if (!fix_out.empty()) io::check_fix_out(fix_out, o.manifold, o.complex, o.complex_format, {o.manifold, o.points, o.complex, o.claims}, {out, report_path});
    io::ProgressLine progress = io::ProgressLine::on_stderr();  // on a terminal only; cleared before any output
    o.progress = root ? &progress : nullptr;
    o.world = world.get();
    certify::Certificate cert = certify::run_certify(o);
    if (!root) return std::stoi(world->broadcast({}));  // rank 0's exit status, so that mpirun's is the verdict's
    // A surface mesh: its non-Delaunay edges in its file's numbering, --fix-out's mesh (presentation, io/mesh_feedback.hpp).
    const io::MeshReport mesh = io::report_mesh(cert.inputs, cert.parameters["kind"] == "restricted", cert.restricted_complex,
                                                cert.checks[11].details.value("reason", cert.checks[11].summary), fix_out, certify::detail::Sha256::hex);
    if (!mesh.json.is_null()) cert.inputs["complex"]["mesh_feedback"] = mesh.json;
    std::vector<std::pair<std::string, std::string>> files;
    if (mesh.fixed_mesh) files.emplace_back(fix_out, *mesh.fixed_mesh);
    if (!out.empty()) files.emplace_back(out, cert.to_text(!no_times));
    if (!report_path.empty())
      files.emplace_back(report_path, report::format_html_report(cert.to_json(!no_times), o.points, o.complex));
    io::write_files_atomically(files);
    // Each check says whether it is a claim of this input; a check that is not one is reported (REPORT, its own
    // decision in parentheses) and never turns the verdict.
    for (const auto& c : cert.checks) {
      const std::string decision = c.details.is_object() && c.details.contains("decision")
                                       ? " (" + c.details["decision"].get<std::string>() + ")" : "";
      std::printf("check %-2d %-28s %-10s %-13s %s%s\n", c.number(), c.name(), certify::to_string(c.verdict),
                  c.claimed ? "[claimed]" : "[not claimed]", c.summary.c_str(), decision.c_str());
    }
    for (const auto& line : mesh.lines) std::printf("%s\n", line.c_str());  // (--fix-out's last)
    if (!out.empty()) std::printf("certificate        %s\n", out.c_str());
    if (!report_path.empty()) std::printf("report             %s\n", report_path.c_str());
    certify::Verdict v = cert.overall();
    std::printf("decided by the claims: %s\n", cert.decided_by().c_str());
    std::printf("verdict: %s\n", certify::to_string(v));
    std::fflush(stdout);
    const int status = v == certify::Verdict::certified ? 0 : v == certify::Verdict::refuted ? 1 : 3;
    if (world->size() > 1) world->broadcast(std::to_string(status));
    return status;
  } catch (const io::InputError& e) {
    // On every rank alike, before any exchange (run_certify's contract): each exits, rank 0 says why.
    if (root) std::cerr << "delcert-certify: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    // Not bad input: an internal failure. Nothing was certified. The other ranks are stopped.
    std::cerr << "delcert-certify: internal error" << (world->size() > 1 ? " on rank " + std::to_string(world->rank()) : "")
              << ": " << e.what() << "\n";
    if (root) std::printf("verdict: UNDECIDED\n"), std::fflush(stdout);
    world->abort(3);
    return 3;
  }
}
