#include "core/io/spec.hpp"

#include <gtest/gtest.h>

#include "core/io/input_error.hpp"
#include "tests/core/io/expect_input_error.hpp"
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

INSTANTIATE_TEST_SUITE_P(
    Malformed, BadSpec,
    ::testing::Values(BadCase{"spec-equation-count.json", 0, "field 'equations': has 1 equations but a 2-manifold in R^4 needs N - m = 2"},
                      BadCase{"spec-bad-polynomial.json", 0, "field 'equations[0]': variable x4 out of range x1..x3"},
                      BadCase{"spec-unknown-version.json", 0, "field 'format': expected \"delcert-manifold v1\""},
                      BadCase{"spec-invalid-json.json", 5, "invalid JSON"},
                      BadCase{"spec-float-literal.json", 0, "field 'reach.value'"}));

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
