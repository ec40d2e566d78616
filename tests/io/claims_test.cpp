#include <gtest/gtest.h>

#include "io/claims.hpp"

#include "exact/polynomial.hpp"
#include "io/input_error.hpp"
#include "tests/test_support.hpp"

#include <fstream>

namespace delcert::io {
namespace {

TEST(Claims, ParsesExactRationals) {
  Claims c = parse_claims(R"({"format": "delcert-claims v1", "eps": "0.1", "sparsity": "1/30",
                              "gamma0": 1, "power_protection": "2.5e-3"})",
                          "c.json");
  ASSERT_TRUE(c.star_radius && c.sparsity && c.gamma0 && c.power_protection);
  EXPECT_FALSE(c.covering);                     // version 1's eps is the star radius
  EXPECT_EQ(*c.star_radius, mpq_class(1, 10));  // "0.1" is exactly 1/10, not the double
  EXPECT_EQ(*c.sparsity, mpq_class(1, 30));
  EXPECT_EQ(*c.gamma0, mpq_class(1));
  EXPECT_EQ(*c.power_protection, mpq_class(1, 400));
  Claims none = parse_claims(R"({"format": "delcert-claims v1"})", "c.json");
  EXPECT_FALSE(none.any());
  Claims v2 = parse_claims(R"({"format": "delcert-claims v2", "star_radius": "0.3", "covering": "1/4"})", "c.json");
  ASSERT_TRUE(v2.star_radius && v2.covering);
  EXPECT_EQ(*v2.star_radius, mpq_class(3, 10));
  EXPECT_EQ(*v2.covering, mpq_class(1, 4));
}

void expect_error(const std::string& text, long line, const std::string& fragment) {
  try {
    parse_claims(text, "c.json");
    FAIL() << "accepted: " << text;
  } catch (const InputError& e) {
    EXPECT_EQ(e.line(), line) << e.what();
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
    EXPECT_EQ(std::string(e.what()).rfind("c.json:" + std::to_string(line) + ":", 0), 0u) << e.what();
  }
}

// Version 2 splits version 1's "eps" into two different promises and refuses the old name.
TEST(Claims, Version2RefusesTheAmbiguousEps) {
  expect_error("{\"format\": \"delcert-claims v2\",\n \"eps\": \"0.1\"}", 2, "star_radius");
  expect_error("{\"format\": \"delcert-claims v1\",\n \"covering\": \"0.1\"}", 2, "unknown claim");
  expect_error("{\"format\": \"delcert-claims v2\",\n \"covering\": \"0\"}", 2, "positive");
}

TEST(Claims, RefusesMalformedInput) {
  expect_error("{\"format\": \"delcert-claims v1\",\n \"eps\": 0.1}", 2, "exact rational");
  expect_error("{\"format\": \"delcert-claims v1\",\n\n \"protection\": \"1\"}", 3, "unknown claim");
  expect_error("{\"format\": \"delcert-claims v4\"}", 1, "versions 1, 2 and 3");
  expect_error("{\"format\": \"delcert-claims v1\",\n \"sparsity\": \"-1\"}", 2, "non-negative");
  expect_error("{\"format\": \"delcert-claims v1\",\n \"gamma0\": \"1.5\"}", 2, "(0, 1]");
  expect_error("{\"format\": \"delcert-claims v1\",\n \"eps\": \"0\"}", 2, "positive");
  expect_error("{\"format\": \"delcert-claims v1\",\n \"eps\": \"abc\"}", 2, "eps");
  expect_error("{\"format\": \"delcert-claims v1\",\n \"eps\": \"0.1\"\n \"gamma0\": \"0.2\"}", 3, "invalid JSON");
  expect_error("[1, 2]", 1, "JSON object");
}

// {"eps": "0.5", "eps": "2"} was read as eps = 2: the false claim was dropped without a word.
TEST(Claims, DuplicateKeysAreRefused) {
  expect_error("{\"format\": \"delcert-claims v1\", \"eps\": \"0.5\",\n \"eps\": \"2\"}", 2,
               "duplicate key \"eps\" (first at line 1");
  expect_error("{\"format\": \"delcert-claims v1\",\n\"format\": \"delcert-claims v1\"}", 2, "duplicate key \"format\"");
  // Nested (claims have no nested values, but the duplicate is found before the type error).
  expect_error("{\"format\": \"delcert-claims v1\",\n \"eps\": {\"a\": 1,\n\n \"a\": 2}}", 4, "duplicate key \"a\"");
  // The fixture of the soundness case.
  try {
    read_claims(test::fixture("soundness/parse/claims-dupkey.json"));
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.line(), 1);
    EXPECT_NE(std::string(e.what()).find("duplicate key \"eps\""), std::string::npos) << e.what();
  }
}

// "1/2/3" was read as 1/(2/3) = 3/2.
TEST(Claims, TwoSlashesAreNotARational) {
  expect_error("{\"format\": \"delcert-claims v1\",\n \"eps\": \"1/2/3\"}", 2, "not a rational number");
}

// 18446744073709551615 was converted with get<long long>() and wrapped to -1. JSON integers are
// read exactly as written, at any size (docs/certificate.md: a value is a rational string or a
// JSON integer).
TEST(Claims, IntegersAreReadExactly) {
  Claims c = parse_claims(R"({"format": "delcert-claims v1", "sparsity": 18446744073709551615})", "c.json");
  EXPECT_EQ(*c.sparsity, mpq_class("18446744073709551615"));
  c = parse_claims(R"({"format": "delcert-claims v1", "eps": 100000000000000000000000000001})", "c.json");
  EXPECT_EQ(*c.star_radius, mpq_class("100000000000000000000000000001"));
  expect_error("{\"format\": \"delcert-claims v1\",\n \"sparsity\": -18446744073709551617}", 2, "non-negative");
  expect_error("{\"format\": \"delcert-claims v1\",\n \"eps\": 1e3}", 2, "found 1e3");
}

// The writer and the reader agree: what format_claims writes, parse_claims reads back to the same
// exact rationals, whether a value has a finite decimal expansion ("0.1") or not ("1/3"), is
// tiny, huge, zero or an integer, and whichever claims are left out.
TEST(Claims, WriteThenReadGivesTheSameRationals) {
  const mpq_class values[] = {mpq_class(1, 10), mpq_class(1, 3), mpq_class(1, 12960000), mpq_class(0),
                              mpq_class(1), exact::parse_rational("123456789012345678901234567891/7"),
                              exact::parse_rational("1e-300"), mpq_class(2, 3)};
  for (int mask = 0; mask < 64; ++mask)
    for (const mpq_class& v : values) {
      Claims c;
      mpq_class eps = v == 0 ? mpq_class(1, 7) : mpq_class(abs(v));  // eps must be positive
      if (mask & 1) c.star_radius = eps;
      if (mask & 16) c.covering = eps;
      if (mask & 2) c.sparsity = abs(v);
      if (mask & 4) c.gamma0 = mpq_class(1, 3);  // must lie in (0, 1]
      if (mask & 8) c.power_protection = abs(v) * abs(v);
      c.secure = (mask & 32) != 0;
      const std::string text = format_claims(c);
      const Claims back = parse_claims(text, "round-trip.json");
      EXPECT_EQ(back, c) << text;
      EXPECT_EQ(format_claims(back), text);
    }
}

// The writer's bytes, which claims.json files and their SHA-256 in certificates depend on.
TEST(Claims, WriterLayout) {
  Claims c;
  c.star_radius = mpq_class(1, 4);
  c.covering = mpq_class(1, 5);
  c.sparsity = mpq_class(1, 36);
  c.power_protection = mpq_class(1, 12960000);
  EXPECT_EQ(format_claims(c), "{\n  \"format\": \"delcert-claims v2\",\n  \"star_radius\": \"0.25\",\n  \"covering\": \"0.2\",\n"
                              "  \"sparsity\": \"1/36\",\n"
                              "  \"power_protection\": \"1/12960000\"\n}\n");
  EXPECT_EQ(format_claims(Claims{}), "{\n  \"format\": \"delcert-claims v2\"\n}\n");
}

// "secure" (check 7) is the one yes/no claim: a JSON boolean, version 2 only.
TEST(Claims, SecureIsABoolean) {
  EXPECT_TRUE(parse_claims(R"({"format": "delcert-claims v2", "secure": true})", "c.json").secure);
  const Claims no = parse_claims(R"({"format": "delcert-claims v2", "secure": false})", "c.json");
  EXPECT_FALSE(no.secure);
  EXPECT_FALSE(no.any());
  expect_error("{\"format\": \"delcert-claims v2\",\n \"secure\": \"yes\"}", 2, "true or false");
  expect_error("{\"format\": \"delcert-claims v2\",\n \"secure\": 1}", 2, "true or false");
  expect_error("{\"format\": \"delcert-claims v1\",\n \"secure\": true}", 2, "unknown claim");
  Claims c;
  c.secure = true;
  EXPECT_EQ(format_claims(c), "{\n  \"format\": \"delcert-claims v2\",\n  \"secure\": true\n}\n");
}

// Version 3: per-point bounds in a file next to claims.json, one exact rational per point.
void write(const std::string& path, const std::string& text) { std::ofstream(path, std::ios::binary) << text; }

TEST(Claims, Version3ReadsPerPointFiles) {
  test::TempDir dir("claims-v3");
  write(dir.file("eps.txt"), "# comment\n0.5\n1/4\n\n3e-1\n");
  const std::string text = R"({"format": "delcert-claims v3", "star_radius_per_point": "eps.txt",
                              "covering_per_point": "eps.txt", "sparsity": "0.01"})";
  const Claims c = parse_claims(text, dir.file("claims.json"));
  ASSERT_EQ(c.star_radius_per_point.size(), 3u);
  EXPECT_EQ(c.star_radius_per_point[1], mpq_class(1, 4));
  EXPECT_EQ(c.star_radius_per_point[2], mpq_class(3, 10));
  EXPECT_EQ(c.covering_per_point, c.star_radius_per_point);
  EXPECT_EQ(c.star_radius_per_point_file, "eps.txt");
  EXPECT_FALSE(c.star_radius);
  EXPECT_TRUE(c.any());
  // Written back: version 3, the file names after "covering"; the values by format_per_point.
  const std::string out = format_claims(c);
  EXPECT_NE(out.find("\"delcert-claims v3\""), std::string::npos) << out;
  EXPECT_NE(out.find("\"star_radius_per_point\": \"eps.txt\""), std::string::npos) << out;
  EXPECT_EQ(parse_per_point(format_per_point(c.star_radius_per_point), "x"), c.star_radius_per_point);
  // Without a per-point claim the writer stays at version 2 (byte-identical to before).
  Claims v2;
  v2.star_radius = mpq_class(1, 2);
  EXPECT_EQ(format_claims(v2), "{\n  \"format\": \"delcert-claims v2\",\n  \"star_radius\": \"0.5\"\n}\n");
}

TEST(Claims, Version3RefusesBadPerPointInput) {
  test::TempDir dir("claims-v3-bad");
  const std::string claims = dir.file("claims.json");
  write(dir.file("bad.txt"), "0.5\n0.1 0.2\n");
  write(dir.file("zero.txt"), "0.5\n\n0\n");
  write(dir.file("ok.txt"), "0.5\n");
  auto expect = [&](const std::string& text, const std::string& file, long line, const std::string& fragment) {
    try {
      parse_claims(text, claims);
      ADD_FAILURE() << "accepted: " << text;
    } catch (const InputError& e) {
      EXPECT_EQ(e.file(), file) << e.what();
      EXPECT_EQ(e.line(), line) << e.what();
      EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
    }
  };
  expect(R"({"format": "delcert-claims v3", "star_radius_per_point": "bad.txt"})", dir.file("bad.txt"), 2, "point 1");
  expect(R"({"format": "delcert-claims v3", "covering_per_point": "zero.txt"})", dir.file("zero.txt"), 3, "positive");
  expect(R"({"format": "delcert-claims v3", "covering_per_point": "missing.txt"})", dir.file("missing.txt"), 0, "");
  expect(R"({"format": "delcert-claims v3", "star_radius_per_point": 3})", claims, 1, "must name a file");
  expect("{\"format\": \"delcert-claims v3\",\n \"star_radius\": \"1\",\n \"star_radius_per_point\": \"ok.txt\"}", claims, 3,
         "not both");
  // Version 2 does not know the per-point claims: unknown keys stay an error.
  expect("{\"format\": \"delcert-claims v2\",\n \"star_radius_per_point\": \"ok.txt\"}", claims, 2, "unknown claim");
  expect("{\"format\": \"delcert-claims v3\",\n \"star_radius_per_pont\": \"ok.txt\"}", claims, 2, "unknown claim");
}

}  // namespace
}  // namespace delcert::io
