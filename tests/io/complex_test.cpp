#include "io/complex.hpp"

#include <gtest/gtest.h>

#include "io/input_error.hpp"
#include "tests/io/expect_input_error.hpp"
#include "tests/test_support.hpp"

namespace delcert::io {
namespace {

using test::fixture;

TEST(Complex, RoundTripIsExact) {
  Complex c;
  c.num_vertices = 10;
  c.simplices = {{0, 1, 2, 3}, {4, 5, 6}, {7, 8}, {9}, {3, 2, 9, 8}};
  std::string text = format_complex(c);
  ComplexFile back = parse_complex(text, "mem");
  EXPECT_EQ(back.complex.num_vertices, c.num_vertices);
  EXPECT_EQ(back.complex.simplices, c.simplices);
  EXPECT_FALSE(back.embedded_points.has_value());
  EXPECT_EQ(format_complex(back.complex), text);
}

TEST(Complex, OffSurfaceRoundTrip) {
  ComplexFile oct = read_complex(fixture("complexes/octahedron.off"));
  ASSERT_TRUE(oct.embedded_points.has_value());
  EXPECT_EQ(oct.complex.num_vertices, 6u);
  EXPECT_EQ(oct.complex.simplices.size(), 8u);
  std::string text = format_off(*oct.embedded_points, oct.complex);
  ComplexFile back = parse_complex(text, "mem.off");
  EXPECT_EQ(back.complex.simplices, oct.complex.simplices);
  EXPECT_EQ(back.embedded_points->coordinates, oct.embedded_points->coordinates);
  EXPECT_EQ(format_off(*back.embedded_points, back.complex), text);
}

// The line of the vertex count and of each embedded point, for the certifier's messages.
TEST(Complex, ParserGivesTheLinesOfTheCountsAndOfEmbeddedPoints) {
  ComplexFile c = parse_complex("# comment\ndelcert-complex v1\n\n3 1\n0 1 2\n", "mem");
  EXPECT_EQ(c.counts_line, 4);
  EXPECT_TRUE(c.embedded_point_lines.empty());
  ComplexFile off = parse_complex("OFF\n# c\n3 1 0\n0 0 1\n0 1 0\n\n1 0 0\n3 0 1 2\n", "mem.off");
  EXPECT_EQ(off.counts_line, 3);
  EXPECT_EQ(off.embedded_point_lines, (std::vector<long>{4, 5, 7}));
  ComplexFile one_line = parse_complex("# c\nOFF 3 1 0\n0 0 1\n0 1 0\n1 0 0\n3 0 1 2\n", "mem.off");
  EXPECT_EQ(one_line.counts_line, 2);
  EXPECT_EQ(one_line.embedded_point_lines, (std::vector<long>{3, 4, 5}));
}

struct BadCase {
  const char* file;
  long line;
  const char* message_part;
};

class BadComplex : public ::testing::TestWithParam<BadCase> {};

TEST_P(BadComplex, ReportsFileLineAndProblem) {
  const BadCase& c = GetParam();
  test::expect_input_error([](const std::string& path) { read_complex(path); }, fixture(std::string("bad/") + c.file),
                           c.line, c.message_part);
}

INSTANTIATE_TEST_SUITE_P(
    Malformed, BadComplex,
    ::testing::Values(BadCase{"complex-out-of-range.txt", 4, "vertex index 4 out of range"},
                      BadCase{"complex-repeated-index.txt", 4, "vertex 3 repeated"},
                      BadCase{"complex-count-mismatch.txt", 4, "announces 3 simplices but the file has 2"},
                      BadCase{"complex-duplicate-simplex.txt", 4, "simplex listed twice (first on line 3)"},
                      BadCase{"complex-negative-index.txt", 3, "expected a vertex index"},
                      BadCase{"complex-unknown-version.txt", 1, "unsupported complex format version"},
                      BadCase{"complex-off-quad.off", 7, "face has 4 vertices"},
                      BadCase{"complex-66-vertices.txt", 4, "a simplex with 66 vertices; at most 65"}));

// With several repeated simplices, the one reported is the first line that repeats an earlier one,
// with the line it repeats (the reader sorts the simplices; the answer is the file's order).
TEST(Complex, TheFirstRepeatInTheFileIsReported) {
  auto error_of = [](const std::string& text) {
    try {
      parse_complex(text, "mem");
    } catch (const InputError& e) {
      return std::to_string(e.line()) + ": " + e.what();
    }
    return std::string("accepted");
  };
  const std::string head = "delcert-complex v1\n5 4\n";  // simplices on lines 3, 4, 5, 6
  EXPECT_NE(error_of(head + "0 1 2\n1 2 3\n3 2 1\n2 1 0\n").find("5: "), std::string::npos);
  EXPECT_NE(error_of(head + "0 1 2\n1 2 3\n3 2 1\n2 1 0\n").find("first on line 4"), std::string::npos);
  EXPECT_NE(error_of(head + "0 1 2\n1 2 3\n2 1 0\n3 2 1\n").find("first on line 3"), std::string::npos);
  EXPECT_NE(error_of(head + "0 1 2\n1 2 3\n2 1 0\n3 2 1\n").find("5: "), std::string::npos);
  EXPECT_NE(error_of(head + "0 1 2\n0 2 1\n1 0 2\n2 3 4\n").find("4: "), std::string::npos);
  EXPECT_NE(error_of(head + "0 1 2\n0 2 1\n1 0 2\n2 3 4\n").find("first on line 3"), std::string::npos);
  EXPECT_EQ(error_of(head + "0 1 2\n1 2 3\n2 3 4\n0 1 3\n"), "accepted");
}

// The largest simplex the reader accepts: 65 vertices (ambient dimension 64 + 1).
TEST(Complex, SimplexSizeLimit) {
  std::string text = "delcert-complex v1\n65 1\n";
  for (int i = 0; i < 65; ++i) text += std::to_string(i) + (i < 64 ? " " : "\n");
  EXPECT_EQ(parse_complex(text, "mem").complex.simplices.at(0).size(), kMaxSimplexVertices);
}

// Vertex indices are ints downstream: a vertex count beyond INT_MAX is refused, so that an index
// such as 2147483648 can never wrap to a negative one (found by fuzzing, fuzz/regressions/complex).
TEST(Complex, VertexCountBeyondIntIsRefused) {
  try {
    parse_complex("delcert-complex v1\n3000000000 1\n0 1 2147483648\n", "mem");
    FAIL() << "accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.line(), 2);
    EXPECT_NE(std::string(e.what()).find("exceeds 2147483647"), std::string::npos) << e.what();
  }
  EXPECT_EQ(parse_complex("delcert-complex v1\n2147483647 1\n0 1 2147483646\n", "mem").complex.simplices.at(0).at(2),
            2147483646);
}

}  // namespace
}  // namespace delcert::io
