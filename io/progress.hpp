// A progress line for long phases (issue 13 §5): drawn on a terminal, silent otherwise.
//
// Presentation only. It writes to its own stream (stderr in the programs), never to stdout or a
// file, and nothing reads it back: every output of delcert and delcert-certify, the certificate
// included, is the same byte for byte with and without a terminal. Redraws are throttled by counts,
// never by the clock: with a total, when the whole percentage grows; without one, when the first
// two digits of the count change (1, 2, ..., 99, 100, 110, ..., 990, 1000, 1100, ...). A line is
// cut to kWidth columns, so that '\r' can redraw it on any terminal at least that wide.
#pragma once

#include <cstddef>
#include <cstdio>
#include <mutex>
#include <string>

namespace delcert::io {

class ProgressLine {
 public:
  static constexpr std::size_t kWidth = 79;

  // Draws on `out` only when `terminal`; otherwise every call does nothing.
  ProgressLine(std::FILE* out, bool terminal);
  // On stderr, when stderr is a terminal (isatty).
  static ProgressLine on_stderr();
  ~ProgressLine();  // clear()
  ProgressLine(const ProgressLine&) = delete;
  ProgressLine& operator=(const ProgressLine&) = delete;

  bool terminal() const { return terminal_; }

  // A new phase named `label`, of `total` steps (0: not counted); drawn at once with count 0.
  void phase(const std::string& label, std::size_t total = 0);
  // The phase's count is `done` (a smaller count than the last is ignored), or `total` changes
  // (the count starting again). Any thread may call these.
  void update(std::size_t done);
  void update(std::size_t done, std::size_t total);
  void add(std::size_t steps = 1);
  // Erases the line (before ordinary output, and at the end).
  void clear();

  // How many times the line was drawn (for tests of the throttle).
  std::size_t draws() const { return draws_; }

 private:
  void set_locked(std::size_t done);
  void draw_locked();

  std::FILE* out_;
  bool terminal_;
  std::mutex mutex_;
  std::string label_;
  std::size_t total_ = 0, done_ = 0, shown_ = 0;  // shown_: the percentage or two-digit count drawn
  std::size_t drawn_width_ = 0, draws_ = 0;
};

}  // namespace delcert::io
