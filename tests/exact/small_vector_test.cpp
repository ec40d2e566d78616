// SmallVector (exact/small_vector.hpp, exact::Box): behaves as std::vector across the inline /
// heap boundary, for copies, moves, self-referencing operations and growth (ASan checks the
// memory in the sanitizer run).
#include "exact/small_vector.hpp"

#include <gtest/gtest.h>

#include <numeric>
#include <span>
#include <vector>

#include "exact/interval.hpp"

namespace delcert::exact {
namespace {

using V = SmallVector<int, 4>;

std::vector<int> as_vector(const V& v) { return {v.begin(), v.end()}; }

TEST(SmallVector, MatchesStdVectorAcrossTheInlineBoundary) {
  V v;
  std::vector<int> ref;
  for (int i = 0; i < 20; ++i) {
    v.push_back(i);
    ref.push_back(i);
    ASSERT_EQ(as_vector(v), ref) << i;
    // Copies and moves from both storages.
    V c = v;
    EXPECT_EQ(as_vector(c), ref);
    V m = std::move(c);
    EXPECT_EQ(as_vector(m), ref);
    EXPECT_TRUE(c.empty());
    V a{9, 9};
    a = m;
    EXPECT_EQ(as_vector(a), ref);
    a = std::move(m);
    EXPECT_EQ(as_vector(a), ref);
  }
  EXPECT_GE(v.capacity(), 20u);
  // push_back of its own element while growing.
  V g{1, 2, 3, 4};
  g.push_back(g[0]);
  EXPECT_EQ(as_vector(g), (std::vector<int>{1, 2, 3, 4, 1}));
  // assign from its own range (a prefix), resize, insert at the end and in the middle.
  g.assign(g.begin() + 1, g.begin() + 3);
  EXPECT_EQ(as_vector(g), (std::vector<int>{2, 3}));
  g.resize(6, 7);
  EXPECT_EQ(as_vector(g), (std::vector<int>{2, 3, 7, 7, 7, 7}));
  const std::vector<int> more{5, 6};
  g.insert(g.begin() + 1, more.begin(), more.end());
  EXPECT_EQ(as_vector(g), (std::vector<int>{2, 5, 6, 3, 7, 7, 7, 7}));
  g.insert(g.end(), more.begin(), more.end());
  EXPECT_EQ(g.size(), 10u);
  EXPECT_EQ(g.back(), 6);
  g.pop_back();
  EXPECT_EQ(g.back(), 5);
  g.assign(3, 1);
  EXPECT_EQ(as_vector(g), (std::vector<int>{1, 1, 1}));
  EXPECT_TRUE(g == (V{1, 1, 1}));
  EXPECT_FALSE(g == (V{1, 1}));
  g.clear();
  EXPECT_TRUE(g.empty());
  // Self-assignment keeps the contents.
  V s{4, 5, 6, 7, 8, 9};
  const V& alias = s;
  s = alias;
  EXPECT_EQ(as_vector(s), (std::vector<int>{4, 5, 6, 7, 8, 9}));
}

TEST(SmallVector, IsABoxUsableAsASpan) {
  Box b(3, Interval{0, 1});
  b.emplace_back(Interval{2, 3});
  const std::span<const Interval> s(b);
  ASSERT_EQ(s.size(), 4u);
  EXPECT_EQ(s[3].hi, 3.0);
  Box wide(12, Interval{-1, 1});  // on the heap
  Box copy(wide.begin() + 2, wide.end());
  EXPECT_EQ(copy.size(), 10u);
  EXPECT_EQ(copy[9].lo, -1.0);
}

}  // namespace
}  // namespace delcert::exact
