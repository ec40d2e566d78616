// The soundness cases of an outside review (fixtures/soundness/README.md): inputs on which an
// earlier delcert-certify said CERTIFIED although the truth is REFUTED, or hung, or crashed. Each
// must end as the README requires. A hang is bounded by `timeout` (exit 124), so it fails the
// test instead of blocking it; the limit is generous (a wall-clock bound is not what is tested:
// the README's limits are met by orders of magnitude).
#include <regex>

#include "support.hpp"

namespace delcert::certify::test {
namespace {

std::string q(const std::string& s) { return "'" + s + "'"; }
std::string soundness(const std::string& f) { return q(fixture("soundness/" + f)); }
std::string octahedron() {
  return " --points " + q(fixture("points/octahedron.off")) + " --complex " + q(fixture("certify/octahedron.complex"));
}
RunResult certify_cmd(const std::string& args, const TempDir& dir, int seconds = 120) {
  return run("timeout " + std::to_string(seconds) + " " + binary() + " " + args, dir);
}
bool has(const std::string& text, const std::string& what) { return text.find(what) != std::string::npos; }

// Case "overflow": the filtered star of point 0 was {(0,1),(0,3)} (a chart row overflowed to
// -DBL_MAX under upward rounding); the exact star is {(0,1),(0,2)}, and point 2 lies inside the
// ball of [0,3].
TEST(Soundness, OverflowCaseIsRefutedWithTheWitness) {
  TempDir dir("sound-overflow");
  const std::string cert = dir.file("cert.json");
  RunResult r = certify_cmd("--manifold " + soundness("overflow/spec.json") + " --points " +
                                soundness("overflow/points.txt") + " --complex " + soundness("overflow/complex.txt") +
                                " --no-times --out " + q(cert),
                            dir);
  ASSERT_EQ(r.exit_code, 1) << r.out << r.err;
  EXPECT_EQ(last_line(r.out), "verdict: REFUTED");
  auto j = nlohmann::json::parse(read_text(cert));
  // Check 3 (stars) names the missing simplex [0,2] of star(0); check 4 (consistency) names the
  // simplex [0,3] and the point 2 strictly inside its ball (exact sign -1).
  bool missing = false, inside = false;
  for (const auto& c : j["checks"]) {
    if (c["id"] == 3) {
      EXPECT_EQ(c["verdict"], "REFUTED");
      for (const auto& w : c["witnesses"])
        missing = missing || (w["kind"] == "missing_simplex" && w["simplex"] == nlohmann::json({0, 2}));
    }
    if (c["id"] == 4) {
      EXPECT_EQ(c["verdict"], "REFUTED");
      for (const auto& w : c["witnesses"])
        inside = inside || (w["kind"] == "point_in_ball" && w["simplex"] == nlohmann::json({0, 3}) && w["point"] == 2 &&
                            w["exact_sign"] == -1);
    }
  }
  EXPECT_TRUE(missing) << j["checks"].dump(1);
  EXPECT_TRUE(inside) << j["checks"].dump(1);
  // No check may print a certified margin contradicting its verdict (the old run printed a power
  // margin of -4.32 next to CERTIFIED).
  for (const auto& c : j["checks"]) {
    if (c["name"] == "power_protection" && c["verdict"] == "CERTIFIED") {
      EXPECT_GE(std::stod(c["margin"]["min_power_margin"]["certified_lower_bound"].get<std::string>()), 0.0);
    }
  }

  // Audit mode (no --complex): never CERTIFIED.
  r = certify_cmd("--manifold " + soundness("overflow/spec.json") + " --points " + soundness("overflow/points.txt"), dir);
  EXPECT_TRUE(r.exit_code == 1 || r.exit_code == 3) << r.out << r.err;
  EXPECT_FALSE(has(r.out + r.err, "internal error")) << r.out << r.err;
}

struct BadCase {
  const char* name;
  std::string args;
  std::string message;  // expected in stderr
};

// The parse cases: each spec or claim means something else than it was read as; exit 2 with
// file:line and no certificate.
TEST(Soundness, ParseCasesAreRefusedWithFileAndLine) {
  const std::vector<BadCase> cases = {
      {"exponent wrap", "--manifold " + soundness("parse/spec-exponent-wrap.json") + octahedron(), "exponent"},
      {"variable index", "--manifold " + soundness("parse/spec-varindex.json") + octahedron(), "variable"},
      {"duplicate key", "--manifold builtin:sphere-2" + octahedron() + " --claims " + soundness("parse/claims-dupkey.json"),
       "duplicate"},
      {"slash", "--manifold builtin:sphere-2" + octahedron() + " --claims " + soundness("parse/claims-slash.json"),
       "rational"},
      {"exponent blow-up", "--manifold " + soundness("hang/spec-exponent-hang.json") + " --points " +
                               soundness("hang/pts-sphere6.txt"),
       "too large"},
  };
  for (const auto& c : cases) {
    TempDir dir("sound-parse");
    const std::string cert = dir.file("cert.json");
    RunResult r = certify_cmd(c.args + " --out " + q(cert), dir, 60);
    EXPECT_EQ(r.exit_code, 2) << c.name << ": " << r.out << r.err;
    EXPECT_TRUE(has(r.err, c.message)) << c.name << ": " << r.err;
    EXPECT_TRUE(std::regex_search(r.err, std::regex(R"(\.json:[0-9]+)"))) << c.name << ": no file:line in " << r.err;
    EXPECT_FALSE(std::filesystem::exists(cert)) << c.name;
  }
}

// A claim of 2^64 - 1 must be read exactly or refused, never wrapped.
TEST(Soundness, HugeJsonIntegerIsNeverWrapped) {
  TempDir dir("sound-u64");
  RunResult r = certify_cmd("--manifold builtin:sphere-2" + octahedron() + " --claims " + soundness("parse/claims-u64.json"),
                            dir, 60);
  EXPECT_TRUE(r.exit_code == 1 || r.exit_code == 2) << r.out << r.err;
}

// A 32-vertex simplex in a complex claimed for a 2-manifold: REFUTED (wrong dimension) or refused,
// at once, without enumerating 2^32 faces.
TEST(Soundness, HugeSimplexIsRejectedAtOnce) {
  TempDir dir("sound-32");
  RunResult r = certify_cmd("--manifold builtin:sphere-2 --points " + soundness("hang/fib40.txt") + " --complex " +
                                soundness("hang/complex-32simplex.txt"),
                            dir, 60);
  EXPECT_TRUE(r.exit_code == 1 || r.exit_code == 2) << r.out << r.err;
  EXPECT_FALSE(has(r.out + r.err, "internal error")) << r.out << r.err;
}

// Four points 5e-324 apart on a plane: the neighbour grid must work at any magnitude. The
// points are distinct doubles, so a verdict is owed (no internal error).
TEST(Soundness, SubnormalCoordinatesGetAVerdict) {
  TempDir dir("sound-subnormal");
  RunResult r = certify_cmd("--manifold " + soundness("hang/spec-plane.json") + " --points " +
                                soundness("hang/pts-subnormal.txt"),
                            dir, 60);
  EXPECT_TRUE(r.exit_code == 0 || r.exit_code == 1 || r.exit_code == 3) << r.out << r.err;
  EXPECT_FALSE(has(r.out + r.err, "internal error")) << r.out << r.err;
}

// Case "covering bound" (third round): the 16 vertices of a tesseract on S^3, whose covering
// radius is exactly 1 (the centre of a cell of the tesseract, (1, 0, 0, 0), is at distance 1 from
// every vertex, and no point of S^3 is farther). Check 11 printed a certified_upper_bound of
// 0.99253, computed over the decided boxes only, under UNDECIDED. Every certified bound printed
// must be a bound: an upper bound >= 1, a lower bound <= 1; under UNDECIDED no upper bound at all.
TEST(Soundness, CoveringBoundIsNeverBelowTheTruth) {
  TempDir dir("sound-cover");
  const std::string cert = dir.file("cert.json");
  RunResult r = certify_cmd("--manifold builtin:sphere-3 --points " + soundness("bounds/tesseract-s3.txt") +
                                " --no-times --out " + q(cert),
                            dir);
  ASSERT_TRUE(r.exit_code == 0 || r.exit_code == 1 || r.exit_code == 3) << r.out << r.err;
  EXPECT_FALSE(has(r.out + r.err, "internal error")) << r.out << r.err;
  auto j = nlohmann::json::parse(read_text(cert));
  bool seen = false;
  for (const auto& c : j["checks"]) {
    if (c["name"] != "covering") continue;
    seen = true;
    const auto& cr = c["margin"]["covering_radius"];
    if (c["verdict"] == "UNDECIDED") {
      EXPECT_FALSE(cr.contains("certified_upper_bound")) << c.dump(1);
    }
    if (cr.contains("certified_upper_bound")) {
      EXPECT_GE(std::stod(cr["certified_upper_bound"].get<std::string>()), 1.0);
    }
    ASSERT_TRUE(cr.contains("certified_lower_bound")) << c.dump(1);
    EXPECT_LE(std::stod(cr["certified_lower_bound"].get<std::string>()), 1.0);
    EXPECT_NE(c["summary"].get<std::string>().find("not certified"), std::string::npos) << c["summary"];
  }
  EXPECT_TRUE(seen);
}

// Case "codimension 9": a sphere in R^11 (nine equations). The exact tangent bases stop at eight;
// the spec is refused at reading, exit 2, naming the limit, the file and the line, no certificate.
TEST(Soundness, CodimensionNineIsRefusedNamingTheLimit) {
  TempDir dir("sound-codim");
  const std::string cert = dir.file("cert.json");
  RunResult r = certify_cmd("--manifold " + soundness("scale/sphere-codim9.json") + " --points " +
                                soundness("scale/fib30-r11.txt") + " --out " + q(cert),
                            dir, 60);
  EXPECT_EQ(r.exit_code, 2) << r.out << r.err;
  EXPECT_TRUE(has(r.err, "exceeds the supported maximum 8")) << r.err;
  EXPECT_TRUE(has(r.err, "sphere-codim9.json:4:")) << r.err;
  EXPECT_FALSE(has(r.out + r.err, "internal error")) << r.out << r.err;
  EXPECT_FALSE(std::filesystem::exists(cert));
}


// Case "off M, x1.3" (issue 39): a gmsh mesh of the unit sphere scaled by 1.3 (every vertex 0.3
// from M) or 1.2, claimed restricted. Scaling a radial sample of a sphere keeps its Voronoi cells
// (cones from the centre), so both meshes are Del_RM(P): 1.2 must certify; 1.3 may be CERTIFIED,
// UNDECIDED or refused, never REFUTED (it was, "820 not in Del_RM", on no witness: every first ball
// missed M, every cell was complete and empty, and the covering argument "held" with no anchor).
// Check 1 names the point farthest from M.
TEST(Soundness, OffManifoldScaledMeshIsNeverRefuted) {
  for (const std::string scale : {"1.2", "1.3"}) {
    TempDir dir("sound-off-manifold");
    const std::string mesh = soundness("off-manifold/sphere-mesh-scaled-" + scale + ".off");
    const std::string cert = dir.file("cert.json");
    RunResult r = certify_cmd("--manifold builtin:sphere-2 --points " + mesh + " --complex " + mesh +
                                  " --kind restricted --residual-tolerance 2 --no-times --out " + q(cert),
                              dir);
    EXPECT_TRUE(r.exit_code == 0 || r.exit_code == 2 || r.exit_code == 3) << scale << ": " << r.out << r.err;
    EXPECT_FALSE(has(r.out + r.err, "internal error")) << scale << ": " << r.err;
    if (scale == "1.2") {
      EXPECT_EQ(r.exit_code, 0) << r.out;
    }
    if (r.exit_code != 0) continue;
    const auto j = nlohmann::json::parse(read_text(cert));
    for (const auto& c : j["checks"]) {
      if (c["id"] == 1) {
        EXPECT_TRUE(has(c["summary"].get<std::string>(), "the farthest: point")) << c["summary"];
      }
      if (c["id"] == 12) {
        EXPECT_EQ(c["details"]["m_simplices"], 820) << scale;  // all of Del_RM(P): the mesh
      }
    }
  }
}

}  // namespace
}  // namespace delcert::certify::test
