#include "io/progress.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <thread>
#include <vector>

namespace delcert::io {
namespace {

// A temporary file standing in for stderr; text() reads back what was written.
class Sink {
 public:
  Sink() : file_(std::tmpfile()) {}
  ~Sink() {
    if (file_) std::fclose(file_);
  }
  std::FILE* file() const { return file_; }
  std::string text() const {
    std::fflush(file_);
    std::rewind(file_);
    std::string s;
    for (int c; (c = std::fgetc(file_)) != EOF;) s.push_back(static_cast<char>(c));
    return s;
  }

 private:
  std::FILE* file_;
};

// The last redraw: the text after the last '\r', without the blanks that erase a longer line.
std::string last_line(const std::string& text) {
  const std::size_t r = text.rfind('\r');
  std::string line = r == std::string::npos ? text : text.substr(r + 1);
  return line.erase(line.find_last_not_of(' ') + 1);
}

TEST(ProgressLine, NotATerminalWritesNothing) {
  Sink sink;
  {
    ProgressLine p(sink.file(), false);
    EXPECT_FALSE(p.terminal());
    p.phase("stars", 1000);
    for (int i = 0; i < 1000; ++i) p.add();
    p.update(5, 10);
    p.phase("net extraction");
    p.update(123456);
    p.clear();
    EXPECT_EQ(p.draws(), 0u);
  }
  EXPECT_EQ(sink.text(), "");
}

TEST(ProgressLine, CountedPhaseRedrawsOncePerPercent) {
  Sink sink;
  ProgressLine p(sink.file(), true);
  p.phase("stars", 100000);
  for (int i = 0; i < 100000; ++i) p.add();
  EXPECT_EQ(p.draws(), 101u);  // 0% when the phase starts, then 1% ... 100%
  EXPECT_EQ(last_line(sink.text()), "stars 100% (100000/100000)");
  // Smaller counts than the last are ignored (workers may report out of order).
  p.update(10);
  EXPECT_EQ(p.draws(), 101u);
}

TEST(ProgressLine, SmallTotalsRedrawAtEveryStep) {
  Sink sink;
  ProgressLine p(sink.file(), true);
  p.phase("cells", 3);
  p.update(1), p.update(2), p.update(3);
  EXPECT_EQ(p.draws(), 4u);
  EXPECT_EQ(last_line(sink.text()), "cells 100% (3/3)");
}

TEST(ProgressLine, UncountedPhaseRedrawsWhenTheFirstTwoDigitsChange) {
  Sink sink;
  ProgressLine p(sink.file(), true);
  p.phase("net extraction");
  EXPECT_EQ(last_line(sink.text()), "net extraction");
  for (std::size_t i = 1; i <= 1000000; ++i) p.update(i);
  // 1 (the phase) + 99 (1..99) + 90 per decade for 100..999, ..., 100000..999999, + 1 (1000000).
  EXPECT_EQ(p.draws(), 1u + 99u + 4u * 90u + 1u);
  EXPECT_EQ(last_line(sink.text()), "net extraction: 1000000");
}

TEST(ProgressLine, ANewTotalStartsTheCountAgain) {
  Sink sink;
  ProgressLine p(sink.file(), true);
  p.phase("round 1", 0);
  p.update(50, 100);
  EXPECT_EQ(last_line(sink.text()), "round 1 50% (50/100)");
  p.update(10, 20);  // the next batch of the same phase
  EXPECT_EQ(last_line(sink.text()), "round 1 50% (10/20)");
}

TEST(ProgressLine, ShorterLinesOverwriteLongerOnesAndClearErases) {
  Sink sink;
  ProgressLine p(sink.file(), true);
  p.phase("a long label here");
  p.phase("short");
  EXPECT_EQ(sink.text(), "\ra long label here\rshort            ");
  p.clear();
  EXPECT_EQ(sink.text(), "\ra long label here\rshort            \r     \r");
  p.clear();  // nothing drawn since: nothing written
  EXPECT_EQ(sink.text(), "\ra long label here\rshort            \r     \r");
}

TEST(ProgressLine, LinesAreCutToTheWidth) {
  Sink sink;
  ProgressLine p(sink.file(), true);
  p.phase(std::string(200, 'x'), 10);
  EXPECT_EQ(last_line(sink.text()), std::string(ProgressLine::kWidth, 'x'));
}

TEST(ProgressLine, TheDestructorClearsTheLine) {
  Sink sink;
  {
    ProgressLine p(sink.file(), true);
    p.phase("topology");
  }
  EXPECT_EQ(sink.text(), "\rtopology\r        \r");
}

TEST(ProgressLine, ManyThreadsCountEveryStep) {
  Sink sink;
  ProgressLine p(sink.file(), true);
  p.phase("stars", 4000);
  std::vector<std::thread> pool;
  for (int t = 0; t < 4; ++t)
    pool.emplace_back([&p] {
      for (int i = 0; i < 1000; ++i) p.add();
    });
  for (auto& t : pool) t.join();
  EXPECT_EQ(p.draws(), 101u);
  EXPECT_EQ(last_line(sink.text()), "stars 100% (4000/4000)");
}

}  // namespace
}  // namespace delcert::io
