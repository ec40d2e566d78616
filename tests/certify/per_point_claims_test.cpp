// Checks 10 and 11 against a per-point ε(p) (claims version 3, io/claims.hpp): CERTIFIED when every
// point's ε is above its stars' radii and its cell's covering bound, REFUTED with the point as
// witness when one ε is shrunk below them, and bad input when the file does not have one value per
// point. The uniform and per-point claims of a sample agree.
#include "exact/polynomial.hpp"
#include "io/claims.hpp"
#include "support.hpp"

namespace delcert::certify::test {
namespace {

Certificate certify_with(const TempDir& dir, const io::PointSet& P, const std::string& claims) {
  CertifyOptions o;
  o.manifold = "builtin:sphere-2";
  o.points = dir.file("points.txt");
  io::write_points(o.points, P);
  o.claims = dir.file("claims.json");
  write_text(o.claims, claims);
  return run_certify(o);
}

std::string per_point_file(const std::vector<std::string>& values) {
  std::string s;
  for (const auto& v : values) s += v + "\n";
  return s;
}

const char* kClaims = R"({"format": "delcert-claims v3", "star_radius_per_point": "eps.txt", "covering_per_point": "eps.txt"})";

TEST(PerPointClaims, CertifiedThenRefutedAtTheShrunkPoint) {
  TempDir dir("per-point");
  const io::PointSet P = fibonacci_sphere(150);
  // An audit with a uniform claim: the largest star radius and the covering radius.
  const Certificate audit = certify_with(dir, P, R"({"format": "delcert-claims v2", "star_radius": "1"})");
  const double r2 = std::stod(check(audit, CheckId::star_radius).margin["max_radius_squared"]["certified_upper_bound"].get<std::string>());
  const double c = std::stod(check(audit, CheckId::covering).margin["covering_radius"]["certified_upper_bound"].get<std::string>());
  char bound[64];
  std::snprintf(bound, sizeof bound, "%.6f", 1.05 * std::max(std::sqrt(r2), c));
  // Every ε(p) above both, alternately the bound and twice it (a field, not one number).
  const mpq_class b = exact::parse_rational(bound);
  std::vector<std::string> eps;
  for (std::size_t p = 0; p < P.size(); ++p) eps.push_back(exact::rational_to_string(p % 2 ? b : mpq_class(2 * b)));
  write_text(dir.file("eps.txt"), per_point_file(eps));
  const Certificate good = certify_with(dir, P, kClaims);
  EXPECT_EQ(check(good, CheckId::star_radius).verdict, Verdict::certified) << check(good, CheckId::star_radius).summary;
  EXPECT_EQ(check(good, CheckId::covering).verdict, Verdict::certified) << check(good, CheckId::covering).summary;
  EXPECT_EQ(check(good, CheckId::star_radius).claim["star_radius_per_point"], "eps.txt");
  EXPECT_EQ(good.inputs["claims"]["star_radius_per_point"]["path"], dir.file("eps.txt"));

  // Point 17's ε shrunk to a thousandth of its neighbours' distance: both checks REFUTED, naming it.
  eps[17] = "1/100000";
  write_text(dir.file("eps.txt"), per_point_file(eps));
  const Certificate bad = certify_with(dir, P, kClaims);
  const CheckEntry& radius = check(bad, CheckId::star_radius);
  EXPECT_EQ(radius.verdict, Verdict::refuted) << radius.summary;
  ASSERT_FALSE(radius.witnesses.empty());
  for (const auto& w : radius.witnesses) {
    EXPECT_EQ(w["at_vertex"], 17);
    EXPECT_EQ(w["eps_at_vertex"], "0.00001");
  }
  const CheckEntry& covering = check(bad, CheckId::covering);
  EXPECT_EQ(covering.verdict, Verdict::refuted) << covering.summary;
  ASSERT_FALSE(covering.witnesses.empty());
  for (const auto& w : covering.witnesses) EXPECT_EQ(w["point"], 17);
  EXPECT_EQ(bad.overall(), Verdict::refuted);

  // One value too few: bad input naming the file and what to write.
  eps.pop_back();
  write_text(dir.file("eps.txt"), per_point_file(eps));
  try {
    certify_with(dir, P, kClaims);
    ADD_FAILURE() << "a short per-point file was accepted";
  } catch (const io::InputError& e) {
    EXPECT_EQ(e.file(), dir.file("eps.txt"));
    EXPECT_NE(std::string(e.what()).find("one eps(p) per point"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace delcert::certify::test
