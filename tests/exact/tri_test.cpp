#include "exact/tri.hpp"

#include <gtest/gtest.h>

namespace delcert::exact {
namespace {

TEST(Tri, KleeneConjunctionAndNegation) {
  const Tri all[] = {Tri::no, Tri::yes, Tri::unknown};
  for (Tri a : all)
    for (Tri b : all) {
      Tri expected = (a == Tri::no || b == Tri::no)    ? Tri::no
                     : (a == Tri::yes && b == Tri::yes) ? Tri::yes
                                                        : Tri::unknown;
      EXPECT_EQ(a && b, expected);
      EXPECT_EQ(a && b, b && a);
    }
  EXPECT_EQ(!Tri::yes, Tri::no);
  EXPECT_EQ(!Tri::no, Tri::yes);
  EXPECT_EQ(!Tri::unknown, Tri::unknown);
  EXPECT_EQ(tri(true), Tri::yes);
  EXPECT_EQ(tri(false), Tri::no);
}

}  // namespace
}  // namespace delcert::exact
