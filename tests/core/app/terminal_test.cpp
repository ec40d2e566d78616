// The progress line (issue 13 §5) through the built binary: with stderr on a terminal, each
// command draws its phases there; without one it is silent; and either way stdout and every
// file written are the same bytes.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "tests/terminal_support.hpp"

namespace delcert::app {
namespace {

using test::binary;

std::string q(const std::string& s) { return "'" + s + "'"; }

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// stdout without the lines that hold wall-clock times (`delcert refine` prints its run time and
// each rule's, "(... 0.012 s)").
std::string without_times(const std::string& text) {
  std::string out, line;
  for (char c : text) {
    line.push_back(c);
    if (c != '\n') continue;
    if (line.rfind("time ", 0) != 0 && line.find(" s)") == std::string::npos) out += line;
    line.clear();
  }
  return out + line;
}

// Runs `args` (with OUT standing for an output prefix) twice: once with stdout and stderr in files,
// once with stderr on a terminal. Checks the outputs named by `files` (relative to OUT) and stdout
// are identical, and that stderr was silent off the terminal. Returns what the terminal showed.
std::string run_both(const test::TempDir& dir, const std::string& args, const std::vector<std::string>& files) {
  auto command = [&](const std::string& tag) {
    std::string c = binary("delcert") + " " + args;
    for (std::size_t at; (at = c.find("OUT")) != std::string::npos;) c.replace(at, 3, dir.file(tag));
    return c + " > " + q(dir.file(tag + ".stdout"));
  };
  const auto plain = test::run("(" + command("plain") + " 2> " + q(dir.file("plain.stderr")) + ")");
  EXPECT_EQ(plain.status, 0) << test::slurp(dir.file("plain.stderr"));
  EXPECT_EQ(test::slurp(dir.file("plain.stderr")), "");
  const auto tty = test::run_on_terminal(command("tty"));
  EXPECT_EQ(tty.status, 0) << tty.output;
  std::string plain_stdout = test::slurp(dir.file("plain.stdout"));  // names the outputs: OUT is plain there
  for (std::size_t at; (at = plain_stdout.find(dir.file("plain"))) != std::string::npos;)
    plain_stdout.replace(at, dir.file("plain").size(), dir.file("tty"));
  EXPECT_EQ(without_times(plain_stdout), without_times(test::slurp(dir.file("tty.stdout"))));
  for (const auto& f : files) {
    const std::string a = test::slurp(dir.file("plain" + f)), b = test::slurp(dir.file("tty" + f));
    EXPECT_FALSE(a.empty()) << f;
    EXPECT_EQ(a, b) << f;
  }
  // The line is erased at the end: the terminal is left with blanks after the last '\r'.
  EXPECT_EQ(tty.output.find_first_not_of(' ', tty.output.rfind('\r') + 1), std::string::npos) << tty.output;
  return tty.output;
}

TEST(Terminal, EveryCommandDrawsItsPhasesOnATerminalOnlyAndWritesTheSameBytes) {
  test::TempDir dir("terminal");
  const std::string net = dir.file("plain.net");
  std::string shown = run_both(dir, "sample --manifold builtin:sphere-2 --eps 0.3 --seed 3 --out OUT.net", {".net"});
  EXPECT_TRUE(contains(shown, "dense sample, pass 1")) << shown;
  EXPECT_TRUE(contains(shown, "net extraction, pass 1")) << shown;

  shown = run_both(dir,
                   "tangential --manifold builtin:sphere-2 --points " + q(net) + " --out OUT.complex --threads 2",
                   {".complex"});
  EXPECT_TRUE(contains(shown, "stars 100% (")) << shown;

  shown = run_both(dir, "refine --manifold builtin:sphere-2 --points " + q(net) + " --eps 0.3 --threads 2 --out OUT.refined",
                   {".refined/points.txt", ".refined/complex.txt", ".refined/claims.json"});
  EXPECT_TRUE(contains(shown, "stars of the ")) << shown;
  EXPECT_TRUE(contains(shown, "round 0: ")) << shown;

  shown = run_both(dir, "refine --manifold builtin:sphere-2 --eps 0.3 --seed 3 --out OUT.from-eps",
                   {".from-eps/points.txt", ".from-eps/complex.txt", ".from-eps/claims.json"});
  EXPECT_TRUE(contains(shown, "net extraction, pass 1")) << shown;
}

}  // namespace
}  // namespace delcert::app
