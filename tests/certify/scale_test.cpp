// Verdicts and work must not depend on multiplying an equation by a non-zero constant (issue 39,
// the "tiny coefficient" soundness case: the sphere's equation times 10^-400 underflowed every
// enclosure of its coefficients, and a 30-point audit took 14 s instead of 0.02 s). The spec reader
// keeps every equation at its canonical scale (exact::at_canonical_scale), so the sphere times
// 2^1000, 2^-1000, 10^400 and 10^-400 must give the plain sphere's certificate: the same verdict and
// summary for every check, and the same deterministic work counters (boxes of the restricted
// Voronoi cells, Krawczyk calls). No clock is read.
#include "support.hpp"

namespace delcert::certify::test {
namespace {

Certificate audit_with(const std::string& spec) {
  CertifyOptions o;
  o.manifold = fixture("soundness/scale/" + spec);
  o.points = fixture("soundness/scale/fib30.txt");
  return run_certify(o);
}

TEST(Scale, EquationTimesAnyConstantGivesThePlainCertificate) {
  const Certificate plain = audit_with("sphere-plain.json");
  ASSERT_NE(plain.overall(), Verdict::refuted) << plain.to_text(false);
  const CheckEntry& cov = check(plain, CheckId::covering);
  ASSERT_GT(cov.details["boxes"].get<long>(), 0);
  for (const char* spec : {"sphere-2p1000.json", "sphere-2m1000.json", "sphere-10p400.json", "sphere-tiny.json"}) {
    const Certificate scaled = audit_with(spec);
    EXPECT_EQ(scaled.overall(), plain.overall()) << spec;
    ASSERT_EQ(scaled.checks.size(), plain.checks.size());
    for (std::size_t i = 0; i < plain.checks.size(); ++i) {
      EXPECT_EQ(scaled.checks[i].verdict, plain.checks[i].verdict) << spec << " check " << plain.checks[i].number();
      EXPECT_EQ(scaled.checks[i].summary, plain.checks[i].summary) << spec << " check " << plain.checks[i].number();
      EXPECT_EQ(scaled.checks[i].margin, plain.checks[i].margin) << spec << " check " << plain.checks[i].number();
    }
    const CheckEntry& c = check(scaled, CheckId::covering);
    for (const char* counter : {"boxes", "krawczyk_calls", "krawczyk_failures"})
      EXPECT_EQ(c.details[counter], cov.details[counter]) << spec << " " << counter;
  }
}

}  // namespace
}  // namespace delcert::certify::test
