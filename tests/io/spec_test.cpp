#include "io/spec.hpp"

#include <gtest/gtest.h>

#include "io/input_error.hpp"
#include "tests/io/expect_input_error.hpp"
#include "tests/test_support.hpp"

namespace delcert::io {
namespace {

using test::fixture;

TEST(Spec, EveryBuiltinParsesAndMatchesItsFixtureFile) {
  auto names = builtin_spec_names();
  std::vector<std::string> expected{"clifford-torus-2", "clifford-torus-3", "so3", "sphere-2", "sphere-3",
                                    "torus-of-revolution"};
  EXPECT_EQ(names, expected);
  for (const auto& n : names) {
    ManifoldSpec a = read_spec("builtin:" + n);
    ManifoldSpec b = read_spec(fixture("manifolds/" + n + ".json"));
    EXPECT_EQ(a.name, n);
    EXPECT_EQ(a.equations.size(), static_cast<std::size_t>(a.ambient_dimension - a.intrinsic_dimension));
    ASSERT_EQ(a.equations.size(), b.equations.size());
    for (std::size_t i = 0; i < a.equations.size(); ++i) EXPECT_EQ(a.equations[i], b.equations[i]);
    ASSERT_TRUE(a.reach.has_value()) << n;
    ASSERT_TRUE(a.parametrization.has_value()) << n;
    EXPECT_TRUE(a.expected.euler_characteristic.has_value());
  }
}

TEST(Spec, KnownValues) {
  ManifoldSpec so3 = read_spec("builtin:so3");
  EXPECT_EQ(so3.intrinsic_dimension, 3);
  EXPECT_EQ(so3.ambient_dimension, 9);
  EXPECT_TRUE(so3.selector.has_value());
  EXPECT_EQ(so3.reach->squared, 2);  // reach sqrt(2)
  EXPECT_EQ(so3.metric->kind, ShapeSpec::Kind::so3);
  EXPECT_EQ(so3.expected.betti_z2, (std::vector<long>{1, 1, 1, 1}));
  EXPECT_EQ(so3.expected.betti_z3, (std::vector<long>{1, 0, 0, 1}));
  ManifoldSpec t = read_spec("builtin:torus-of-revolution");
  EXPECT_FALSE(t.metric.has_value());
  EXPECT_EQ(t.parametrization->major_radius, 2);
  EXPECT_EQ(t.reach->squared, 1);
  ManifoldSpec c = read_spec("builtin:clifford-torus-3");
  EXPECT_EQ(c.metric->radii.size(), 3u);
  EXPECT_EQ(c.residual_tolerance, mpq_class(1, 1000000000));
}

struct BadCase {
  const char* file;
  long line;
  const char* message_part;
};

class BadSpec : public ::testing::TestWithParam<BadCase> {};

TEST_P(BadSpec, NamesFileAndField) {
  const BadCase& c = GetParam();
  test::expect_input_error([](const std::string& path) { read_spec(path); }, fixture(std::string("bad/") + c.file),
                           c.line, c.message_part);
}

// Every message names the line of the field (the JSON reader keeps them).
INSTANTIATE_TEST_SUITE_P(
    Malformed, BadSpec,
    ::testing::Values(BadCase{"spec-equation-count.json", 6, "field 'equations': has 1 equations but a 2-manifold in R^4 needs N - m = 2"},
                      BadCase{"spec-bad-polynomial.json", 6, "field 'equations[0]': variable x4 out of range x1..x3"},
                      BadCase{"spec-unknown-version.json", 2, "field 'format': expected \"delcert-manifold v1\""},
                      BadCase{"spec-invalid-json.json", 5, "invalid JSON"},
                      BadCase{"spec-float-literal.json", 6, "field 'reach.value'"},
                      BadCase{"spec-duplicate-key.json", 8, "duplicate key \"value\" (first at line 7 in 'reach')"},
                      BadCase{"spec-unknown-key.json", 8, "unknown key 'expeted'"},
                      BadCase{"spec-unknown-nested-key.json", 8, "unknown key 'metric.centre'; known here: type, center, radius"},
                      BadCase{"spec-huge-integer.json", 8,
                              "field 'expected.euler_characteristic': 18446744073709551618 is out of range"},
                      BadCase{"spec-two-slashes.json", 8, "field 'parametrization.radius': not a rational number"}));

// The soundness cases of fixtures/soundness/: each spec meant something other than it was read as.
INSTANTIATE_TEST_SUITE_P(
    Soundness, BadSpec,
    ::testing::Values(BadCase{"../soundness/parse/spec-exponent-wrap.json", 6, "exponent 4096 too large"},
                      BadCase{"../soundness/parse/spec-varindex.json", 7, "variable x0000000031: leading zeros"},
                      BadCase{"../soundness/hang/spec-exponent-hang.json", 6, "exponent 9999 too large"}));

// Specs given as text; `line` is where the message must point.
void expect_spec_error(const std::string& text, long line, const std::string& part) {
  try {
    parse_spec(text, "s.json");
    ADD_FAILURE() << "accepted: " << text;
  } catch (const InputError& e) {
    EXPECT_EQ(e.line(), line) << e.what();
    EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
    EXPECT_EQ(std::string(e.what()).rfind("s.json:" + std::to_string(line) + ": ", 0), 0u) << e.what();
  }
}

// A valid sphere spec with `extra` spliced in as the last top-level members (one per line).
std::string sphere_with(const std::string& extra) {
  return "{\"format\": \"delcert-manifold v1\",\n"
         "\"intrinsic_dimension\": 2,\n"
         "\"ambient_dimension\": 3,\n"
         "\"equations\": [\"x1^2 + x2^2 + x3^2 - 1\"],\n"
         "\"bounding_box\": [[\"-1\", \"1\"], [\"-1\", \"1\"], [\"-1\", \"1\"]]" +
         (extra.empty() ? "" : ",\n" + extra) + "}";
}

TEST(Spec, SphereWithParsesAsIs) {
  ManifoldSpec s = parse_spec(sphere_with("\"expected\": {\"euler_characteristic\": -3}"), "s.json");
  EXPECT_EQ(s.expected.euler_characteristic, -3);
}

TEST(Spec, DuplicateKeysAreRefusedAtEveryLevel) {
  expect_spec_error(sphere_with("\"ambient_dimension\": 4"), 6, "duplicate key \"ambient_dimension\" (first at line 3");
  expect_spec_error(sphere_with("\"reach\": {\"value\": \"1\",\n\"kind\": \"exact\", \"kind\": \"lower_bound\"}"), 7,
                    "duplicate key \"kind\"");
  expect_spec_error(sphere_with("\"expected\": {\"betti_z2\": [1, 0, 1],\n\n\"betti_z2\": [1, 1, 1]}"), 8,
                    "in 'expected'");
  // Inside an array: the keys of each object are counted separately, and a repeat is still found.
  expect_spec_error(sphere_with("\"expected\": {\"betti_z3\": [{\"a\": 1, \"b\": 2}, {\"a\": 1,\n \"a\": 2}]}"), 7,
                    "in 'expected.betti_z3[1]'");
}

TEST(Spec, UnknownKeysAreRefusedAtEveryLevel) {
  expect_spec_error(sphere_with("\"expeted\": {\"euler_characteristic\": 2}"), 6, "unknown key 'expeted'");
  expect_spec_error(sphere_with("\"reach\": {\"value\": \"1\",\n \"knd\": \"lower_bound\"}"), 7, "unknown key 'reach.knd'");
  expect_spec_error(sphere_with("\"metric\": {\"type\": \"sphere\", \"radius\": \"1\", \"radii\": [\"1\"]}"), 6,
                    "unknown key 'metric.radii'");
  expect_spec_error(sphere_with("\"parametrization\": {\"name\": \"sphere\", \"radius\": \"1\",\n\"centre\": [\"0\"]}"), 7,
                    "unknown key 'parametrization.centre'");
  expect_spec_error(sphere_with("\"expected\": {\"euler\": 2}"), 6, "unknown key 'expected.euler'");
  expect_spec_error(sphere_with("\"Reach\": {\"value\": \"1\"}"), 6, "unknown key 'Reach'");
}

// A product metric (issue 12): factors on disjoint coordinate blocks covering x1..xN, their
// dimensions adding up to m; each mistake named at its line.
std::string s2_x_s1(const std::string& factors) {
  return "{\"format\": \"delcert-manifold v1\",\n"
         "\"intrinsic_dimension\": 3, \"ambient_dimension\": 5,\n"
         "\"equations\": [\"x1^2 + x2^2 + x3^2 - 1\", \"x4^2 + x5^2 - 4\"],\n"
         "\"bounding_box\": [[\"-1\", \"1\"], [\"-1\", \"1\"], [\"-1\", \"1\"], [\"-2\", \"2\"], [\"-2\", \"2\"]],\n"
         "\"metric\": {\"type\": \"product\", \"factors\": [\n" + factors + "]}}";
}

TEST(Spec, ProductMetric) {
  const ManifoldSpec s = parse_spec(s2_x_s1("{\"type\": \"sphere\", \"coordinates\": [1, 2, 3], \"radius\": \"1\"},\n"
                                            "{\"type\": \"sphere\", \"coordinates\": [4, 5], \"radius\": \"2\"}"),
                                    "s.json");
  ASSERT_TRUE(s.metric.has_value());
  ASSERT_EQ(s.metric->kind, ShapeSpec::Kind::product);
  ASSERT_EQ(s.metric->factors.size(), 2u);
  EXPECT_EQ(s.metric->factors[0].coordinates, (std::vector<int>{0, 1, 2}));
  EXPECT_EQ(s.metric->factors[0].dimension(), 2);
  EXPECT_EQ(s.metric->factors[1].radius, 2);
  const std::string a = "{\"type\": \"sphere\", \"coordinates\": [1, 2, 3], \"radius\": \"1\"},\n";
  expect_spec_error(s2_x_s1(a + "{\"type\": \"sphere\", \"coordinates\": [3, 4, 5], \"radius\": \"2\"}"), 7,
                    "coordinate x3 is already in a factor");
  expect_spec_error(s2_x_s1(a + "{\"type\": \"sphere\", \"coordinates\": [4], \"radius\": \"2\"}"), 7,
                    "a sphere factor needs at least 2 coordinates");
  expect_spec_error(s2_x_s1("{\"type\": \"sphere\", \"coordinates\": [1, 2, 3, 4], \"radius\": \"1\"}"), 5,
                    "coordinate x5 is in no factor");
  expect_spec_error(s2_x_s1(a + "{\"type\": \"so3\", \"coordinates\": [4, 5]}"), 7, "an so3 factor needs 9 coordinates");
  expect_spec_error(s2_x_s1(a + "{\"type\": \"torus\", \"coordinates\": [4, 5]}"), 7,
                    "unknown factor type 'torus'; known: sphere, so3");
  expect_spec_error(s2_x_s1(a + "{\"type\": \"sphere\", \"coordinates\": [4, 6], \"radius\": \"2\"}"), 7,
                    "between 1 and 5");
  expect_spec_error(s2_x_s1(a + "{\"type\": \"sphere\", \"coordinates\": [4, 5], \"radius\": \"0\"}"), 7,
                    "must be positive");
  // S^4 on the five coordinates: dimension 4, not 3.
  expect_spec_error(s2_x_s1("{\"type\": \"sphere\", \"coordinates\": [1, 2, 3, 4, 5], \"radius\": \"1\"}"), 5,
                    "the factors' dimensions add up to 4, not the intrinsic dimension 3");
}

// JSON integers were converted with get<long>(): 2^64 - 1 became -1. They are read exactly as
// written, and refused when out of range.
TEST(Spec, IntegersAreReadExactlyOrRefused) {
  expect_spec_error(sphere_with("\"expected\": {\"euler_characteristic\": 18446744073709551615}"), 6,
                    "18446744073709551615 is out of range");
  expect_spec_error(sphere_with("\"expected\": {\"euler_characteristic\": -9223372036854775809}"), 6, "out of range");
  expect_spec_error(sphere_with("\"expected\": {\"betti_z2\": [1, 0,\n -1]}"), 7, "field 'expected.betti_z2[2]'");
  expect_spec_error(sphere_with("\"expected\": {\"euler_characteristic\": 2.0}"), 6, "expected an integer");
  expect_spec_error(sphere_with("\"expected\": {\"euler_characteristic\": 2e0}"), 6, "expected an integer");
  // ambient_dimension 2^64 + 3 would wrap to 3.
  std::string t = sphere_with("");
  t.replace(t.find("\"ambient_dimension\": 3"), 22, "\"ambient_dimension\": 18446744073709551619");
  expect_spec_error(t, 3, "field 'ambient_dimension': 18446744073709551619 is out of range");
  // A JSON integer where a rational is expected: exact at any size.
  ManifoldSpec s = parse_spec(sphere_with("\"parametrization\": {\"name\": \"sphere\", \"radius\": 100000000000000000000001}"),
                              "s.json");
  EXPECT_EQ(s.parametrization->radius, mpq_class("100000000000000000000001"));
  expect_spec_error(sphere_with("\"residual_tolerance\": 1e-9"), 6, "exact rational");
}

TEST(Spec, RationalsWithTwoSlashesAreRefused) {
  expect_spec_error(sphere_with("\"reach\": {\"value\": \"1/2/3\"}"), 6, "not a rational number");
  std::string t = sphere_with("");
  t.replace(t.find("[\"-1\", \"1\"]]"), 12, "[\"-1\", \"1/2/3\"]]");
  expect_spec_error(t, 5, "field 'bounding_box[2][1]': not a rational number");
  expect_spec_error(sphere_with("\"residual_tolerance\": \"1/2/3\""), 6, "not a rational number");
}

TEST(Spec, PolynomialLimitsAreReportedWithTheLine) {
  std::string t = sphere_with("");
  t.replace(t.find("x1^2 + x2^2"), 11, "(x1+x2+x3+1)^200 + x2^2");
  expect_spec_error(t, 4, "field 'equations[0]': polynomial too large");
  t = sphere_with("\"selector\": \"" + std::string(40000, '(') + "x1" + std::string(40000, ')') + "\"");
  expect_spec_error(t, 6, "too deeply nested");
}

// A JSON document nested 100,000 deep is refused before any recursion can overflow the stack.
TEST(Spec, DeepJsonIsRefused) {
  expect_spec_error(sphere_with("\"expected\": " + std::string(100000, '[') + std::string(100000, ']')), 6,
                    "nested too deeply");
}

// Every spec in the repository that is meant to be valid still reads under the strict rules.
TEST(Spec, EveryValidFixtureSpecReads) {
  for (const char* f : {"specs/ellipsoid.json", "certify/sphere-4.json", "soundness/hang/spec-plane.json",
                        "soundness/overflow/spec.json", "certify/spec-bad-field.json"}) {
    SCOPED_TRACE(f);
    if (std::string(f) == "certify/spec-bad-field.json") {  // valid JSON, one bad value, at its line
      test::expect_input_error([](const std::string& p) { read_spec(p); }, fixture(f), 7, "field 'reach.value'");
      continue;
    }
    EXPECT_NO_THROW(read_spec(fixture(f)));
  }
  // The 300-digit coefficients of the overflow case are read exactly.
  ManifoldSpec o = read_spec(fixture("soundness/overflow/spec.json"));
  EXPECT_EQ(o.equations[0].degree(), 4);
}

// The text read_spec parses is what a caller hashes: the file's bytes or the compiled-in text.
TEST(Spec, ReadSpecTextIsWhatIsParsed) {
  EXPECT_EQ(read_spec_text("builtin:sphere-2"), std::string(builtin_spec_text("sphere-2")));
  const std::string path = fixture("manifolds/sphere-2.json");
  EXPECT_EQ(parse_spec(read_spec_text(path), path).equations, read_spec(path).equations);
}

TEST(Spec, UnknownBuiltinListsTheKnownOnes) {
  try {
    read_spec("builtin:klein-bottle");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("known: clifford-torus-2"), std::string::npos);
  }
}

}  // namespace
}  // namespace delcert::io

namespace delcert::io {
namespace {

// delcert-certify --residual-tolerance: a positive rational, read exactly; anything else is refused
// naming the option (exit status 2 in the binary).
// Codimension above what the exact tangent bases support: refused at reading (exit 2), naming the
// limit and the line, not an internal error halfway through a run.
TEST(Spec, CodimensionAboveTheSupportedMaximumIsRefused) {
  test::expect_input_error([](const std::string& p) { read_spec(p); }, fixture("soundness/scale/sphere-codim9.json"), 4,
                           "exceeds the supported maximum 8");
}

// Equations are read at their canonical scale: the sphere times 10^-400 is the sphere.
TEST(Spec, EquationsAreReadAtTheirCanonicalScale) {
  const ManifoldSpec plain = read_spec(fixture("soundness/scale/sphere-plain.json"));
  for (const char* f : {"sphere-tiny.json", "sphere-10p400.json", "sphere-2p1000.json", "sphere-2m1000.json"}) {
    const ManifoldSpec s = read_spec(fixture(std::string("soundness/scale/") + f));
    ASSERT_EQ(s.equations.size(), 1u);
    EXPECT_EQ(s.equations[0], plain.equations[0]) << f;
    EXPECT_NE(s.equation_text[0], plain.equation_text[0]) << f;  // the text as written is kept
  }
}

TEST(ResidualTolerance, PositiveRationalsOnly) {
  EXPECT_EQ(parse_residual_tolerance("1e-6"), mpq_class(1, 1000000));
  EXPECT_EQ(parse_residual_tolerance("1/3"), mpq_class(1, 3));
  EXPECT_EQ(parse_residual_tolerance("0.1"), mpq_class(1, 10));  // exactly 1/10, not the double
  for (const char* bad : {"0", "-1e-6", "abc", "inf", "nan", "", "1/0", "1e-6x"}) {
    try {
      parse_residual_tolerance(bad);
      ADD_FAILURE() << "accepted '" << bad << "'";
    } catch (const InputError& e) {
      EXPECT_EQ(e.file(), "--residual-tolerance");
      EXPECT_EQ(std::string(e.what()).rfind("--residual-tolerance: ", 0), 0u) << e.what();
    }
  }
}

}  // namespace
}  // namespace delcert::io
