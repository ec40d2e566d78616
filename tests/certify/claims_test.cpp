#include <gtest/gtest.h>

#include "certify/claims.hpp"
#include "core/io/input_error.hpp"

namespace delcert::certify {
namespace {

TEST(Claims, ParsesExactRationals) {
  Claims c = parse_claims(R"({"format": "delcert-claims v1", "eps": "0.1", "sparsity": "1/30",
                              "gamma0": 1, "power_protection": "2.5e-3"})",
                          "c.json");
  ASSERT_TRUE(c.eps && c.sparsity && c.gamma0 && c.power_protection);
  EXPECT_EQ(*c.eps, mpq_class(1, 10));  // "0.1" is exactly 1/10, not the double
  EXPECT_EQ(*c.sparsity, mpq_class(1, 30));
  EXPECT_EQ(*c.gamma0, mpq_class(1));
  EXPECT_EQ(*c.power_protection, mpq_class(1, 400));
  Claims none = parse_claims(R"({"format": "delcert-claims v1"})", "c.json");
  EXPECT_FALSE(none.any());
}

void expect_error(const std::string& text, long line, const std::string& fragment) {
  try {
    parse_claims(text, "c.json");
    FAIL() << "accepted: " << text;
  } catch (const io::InputError& e) {
    EXPECT_EQ(e.line(), line) << e.what();
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
    EXPECT_EQ(std::string(e.what()).rfind("c.json:" + std::to_string(line) + ":", 0), 0u) << e.what();
  }
}

TEST(Claims, RefusesMalformedInput) {
  expect_error("{\"format\": \"delcert-claims v1\",\n \"eps\": 0.1}", 2, "exact rational");
  expect_error("{\"format\": \"delcert-claims v1\",\n\n \"protection\": \"1\"}", 3, "unknown claim");
  expect_error("{\"format\": \"delcert-claims v2\"}", 1, "version 1");
  expect_error("{\"format\": \"delcert-claims v1\",\n \"sparsity\": \"-1\"}", 2, "non-negative");
  expect_error("{\"format\": \"delcert-claims v1\",\n \"gamma0\": \"1.5\"}", 2, "(0, 1]");
  expect_error("{\"format\": \"delcert-claims v1\",\n \"eps\": \"0\"}", 2, "positive");
  expect_error("{\"format\": \"delcert-claims v1\",\n \"eps\": \"abc\"}", 2, "eps");
  expect_error("{\"format\": \"delcert-claims v1\",\n \"eps\": \"0.1\"\n \"gamma0\": \"0.2\"}", 3, "invalid JSON");
  expect_error("[1, 2]", 1, "JSON object");
}

}  // namespace
}  // namespace delcert::certify
