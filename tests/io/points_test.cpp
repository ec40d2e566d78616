#include "io/points.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <random>

#include "io/input_error.hpp"
#include "tests/io/expect_input_error.hpp"
#include "tests/test_support.hpp"

namespace delcert::io {
namespace {

using test::fixture;

PointSet awkward_points(int dim, std::size_t n) {
  // Doubles that are hard to print: subnormals, huge and tiny magnitudes, random mantissas.
  // (std::mt19937_64 is fully specified by the standard: the same numbers on every platform.)
  std::mt19937_64 rng(7);
  auto uniform = [&] { return static_cast<double>(rng() >> 11) * 0x1p-53; };
  PointSet ps;
  ps.dimension = dim;
  for (std::size_t i = 0; i < n; ++i)
    for (int j = 0; j < dim; ++j) {
      double x = (uniform() - 0.5) * std::ldexp(1.0, static_cast<int>(rng() % 200) - 100);
      ps.coordinates.push_back(x);
    }
  ps.coordinates[0] = std::numeric_limits<double>::denorm_min();
  ps.coordinates[1] = -std::numeric_limits<double>::max();
  ps.coordinates[2] = 0.1;
  return ps;
}

bool bit_identical(const PointSet& a, const PointSet& b) {
  return a.dimension == b.dimension && a.coordinates.size() == b.coordinates.size() &&
         std::memcmp(a.coordinates.data(), b.coordinates.data(), a.coordinates.size() * sizeof(double)) == 0;
}

TEST(Points, RoundTripIsBitExactInEveryFormat) {
  for (auto [format, dim] : {std::pair{PointFormat::delcert, 5}, std::pair{PointFormat::off, 3},
                             std::pair{PointFormat::noff, 9}}) {
    PointSet ps = awkward_points(dim, 300);
    std::string text = format_points(ps, format);
    PointSet back = parse_points(text, "mem");
    EXPECT_TRUE(bit_identical(ps, back)) << static_cast<int>(format);
    EXPECT_EQ(format_points(back, format), text);
  }
  EXPECT_THROW(format_points(awkward_points(4, 3), PointFormat::off), std::invalid_argument);
}

// Every point's line, in each format and wherever the header's numbers sit: comments and blank
// lines before or inside the header, OFF counts on the tag's line, nOFF numbers sharing lines.
TEST(Points, ParserGivesTheLineOfEveryPoint) {
  struct Case {
    const char* text;
    std::vector<long> lines;
  };
  const Case cases[] = {
      {"delcert-points v1\n1 2\n0.5\n\n# c\n1.5\n", {3, 6}},
      {"# comment\n\ndelcert-points v1\n# c\n1 2\n0.5\n1.5\n", {6, 7}},
      {"OFF\n2 0 0\n1 0 0\n0 1 0\n", {3, 4}},
      {"OFF 2 0 0\n1 0 0\n0 1 0\n", {2, 3}},
      {"# comment\nOFF 2 0 0\n1 0 0\n0 1 0\n", {3, 4}},
      {"# comment\nnOFF\n2\n2 0 0\n1 0\n0 1\n", {5, 6}},
      {"nOFF 2\n2 0 0\n1 0\n\n0 1\n", {3, 5}},
      {"nOFF 2 2 0 0\n1 0\n0 1\n", {2, 3}},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.text);
    PointsFile f = parse_points_file(c.text, "mem");
    EXPECT_EQ(f.lines, c.lines);
    EXPECT_EQ(f.points.size(), c.lines.size());
    EXPECT_TRUE(bit_identical(f.points, parse_points(c.text, "mem")));
  }
}

TEST(Points, WriteIsAtomicAndReadable) {
  test::TempDir dir("points");
  PointSet ps = awkward_points(4, 50);
  write_points(dir.file("p.txt"), ps);
  EXPECT_TRUE(bit_identical(read_points(dir.file("p.txt")), ps));
  // No temporary file is left behind.
  std::size_t files = 0;
  for (auto& e : std::filesystem::directory_iterator(dir.path())) files += e.is_regular_file();
  EXPECT_EQ(files, 1u);
  EXPECT_THROW(write_points(dir.file("missing/dir/p.txt"), ps), InputError);
}

TEST(Points, ReadsOffAndNoffFixtures) {
  PointSet oct = read_points(fixture("points/octahedron.off"));
  EXPECT_EQ(oct.dimension, 3);
  EXPECT_EQ(oct.size(), 6u);
  EXPECT_EQ(oct.point(5)[2], -1.0);
  PointSet sq = read_points(fixture("points/clifford-square.noff"));
  EXPECT_EQ(sq.dimension, 4);
  EXPECT_EQ(sq.size(), 4u);
  EXPECT_EQ(sq.point(3)[3], -1.0);
}

// Each malformed case fails with "file:line: <message>" naming the right line.
struct BadCase {
  const char* file;
  long line;
  const char* message_part;
  int expected_dimension = 0;
};

class BadPoints : public ::testing::TestWithParam<BadCase> {};

TEST_P(BadPoints, ReportsFileLineAndProblem) {
  const BadCase& c = GetParam();
  test::expect_input_error([&](const std::string& path) { read_points(path, PointReadOptions{c.expected_dimension, true}); },
                           fixture(std::string("bad/") + c.file), c.line, c.message_part);
}

INSTANTIATE_TEST_SUITE_P(
    Malformed, BadPoints,
    ::testing::Values(BadCase{"points-malformed-number.txt", 4, "malformed number '1.0x'"},
                      BadCase{"points-nan.txt", 4, "not a finite number"},
                      BadCase{"points-inf.txt", 4, "not a finite number"},
                      BadCase{"points-count-short.txt", 4, "announces 3"},
                      BadCase{"points-count-extra.txt", 4, "extra data"},
                      BadCase{"points-wrong-dimension.txt", 4, "has 2 coordinates, expected 3"},
                      BadCase{"points-duplicate.txt", 5, "duplicate point: identical to point 0 on line 3"},
                      BadCase{"points-unknown-version.txt", 1, "unsupported points format version"},
                      BadCase{"points-unknown-tag.txt", 1, "unknown points format 'xyz-points'"},
                      BadCase{"points-dimension-4.txt", 1, "dimension 4 but the manifold lives in R^3", 3}));

TEST(Points, EmptyAndMissingFiles) {
  EXPECT_THROW(parse_points("", "empty.txt"), InputError);
  EXPECT_THROW(read_points("/nonexistent/file.txt"), InputError);
  EXPECT_THROW(parse_points("delcert-points v1\n0 1\n\n", "zero-dim.txt"), InputError);
  EXPECT_THROW(parse_points("delcert-points v1\n3 -1\n", "neg.txt"), InputError);
}

}  // namespace
}  // namespace delcert::io
