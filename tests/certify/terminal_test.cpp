// delcert-certify's progress line (issue 13 §5): drawn on a terminal only, and the certificate
// and stdout are the same bytes with and without one.
#include <gtest/gtest.h>

#include <string>

#include "tests/terminal_support.hpp"

namespace delcert::certify {
namespace {

std::string q(const std::string& s) { return "'" + s + "'"; }

TEST(Terminal, TheCertificateIsTheSameWithAndWithoutAProgressLine) {
  delcert::test::TempDir dir("certify-terminal");
  const std::string points = delcert::test::fixture("report/clifford-torus-net.txt");
  auto command = [&](const std::string& tag) {
    return delcert::test::binary("delcert-certify") + " --manifold builtin:clifford-torus-2 --points " + q(points) +
           " --threads 2 --no-times --out " + q(dir.file(tag + ".json")) + " > " + q(dir.file(tag + ".stdout"));
  };
  const auto plain = delcert::test::run("(" + command("plain") + " 2> " + q(dir.file("plain.stderr")) + ")");
  const auto tty = delcert::test::run_on_terminal(command("tty"));
  EXPECT_EQ(plain.status, tty.status) << tty.output;
  EXPECT_EQ(delcert::test::slurp(dir.file("plain.stderr")), "");
  const std::string certificate = delcert::test::slurp(dir.file("plain.json"));
  EXPECT_NE(certificate.find("delcert-certificate v1"), std::string::npos);
  EXPECT_EQ(certificate, delcert::test::slurp(dir.file("tty.json")));
  std::string plain_stdout = delcert::test::slurp(dir.file("plain.stdout"));  // "certificate  .../plain.json"
  plain_stdout.replace(plain_stdout.find(dir.file("plain.json")), dir.file("plain.json").size(), dir.file("tty.json"));
  EXPECT_EQ(plain_stdout, delcert::test::slurp(dir.file("tty.stdout")));
  for (const char* phase : {"check 1 input_sanity", "check 3 stars 100% (", "checks 11-13 restricted Voronoi cells",
                            "check 7 secure_simplices", "checks 14-15 intrinsic Delaunay"})
    EXPECT_NE(tty.output.find(phase), std::string::npos) << phase << "\n" << tty.output;
  // Erased before the program ends.
  EXPECT_EQ(tty.output.find_first_not_of(' ', tty.output.rfind('\r') + 1), std::string::npos) << tty.output;
}

}  // namespace
}  // namespace delcert::certify
