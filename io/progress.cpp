#include "io/progress.hpp"

#include <unistd.h>

#include <algorithm>

namespace delcert::io {

namespace {

// The throttle key of an uncounted phase: `n` with all but its first two digits zeroed.
std::size_t two_digits(std::size_t n) {
  std::size_t scale = 1;
  while (n >= 100) n /= 10, scale *= 10;
  return n * scale;
}

}  // namespace

ProgressLine::ProgressLine(std::FILE* out, bool terminal) : out_(out), terminal_(terminal && out) {}

ProgressLine ProgressLine::on_stderr() { return ProgressLine(stderr, ::isatty(STDERR_FILENO) == 1); }

ProgressLine::~ProgressLine() { clear(); }

void ProgressLine::phase(const std::string& label, std::size_t total) {
  if (!terminal_) return;
  std::lock_guard<std::mutex> lock(mutex_);
  label_ = label, total_ = total, done_ = 0, shown_ = 0;
  draw_locked();
}

void ProgressLine::update(std::size_t done) {
  if (!terminal_) return;
  std::lock_guard<std::mutex> lock(mutex_);
  set_locked(done);
}

void ProgressLine::update(std::size_t done, std::size_t total) {
  if (!terminal_) return;
  std::lock_guard<std::mutex> lock(mutex_);
  if (total != total_) total_ = total, done_ = 0, shown_ = 0;
  set_locked(done);
}

void ProgressLine::add(std::size_t steps) {
  if (!terminal_) return;
  std::lock_guard<std::mutex> lock(mutex_);
  set_locked(done_ + steps);
}

void ProgressLine::set_locked(std::size_t done) {
  if (done <= done_) return;
  done_ = done;
  const std::size_t key = total_ ? static_cast<std::size_t>(100.0 * static_cast<double>(std::min(done, total_)) /
                                                            static_cast<double>(total_))
                                 : two_digits(done);
  if (key == shown_) return;
  shown_ = key;
  draw_locked();
}

void ProgressLine::draw_locked() {
  std::string text = label_;
  if (total_)
    text += " " + std::to_string(shown_) + "% (" + std::to_string(std::min(done_, total_)) + "/" + std::to_string(total_) + ")";
  else if (done_)
    text += ": " + std::to_string(done_);
  if (text.size() > kWidth) text.resize(kWidth);
  const std::size_t width = text.size();
  if (width < drawn_width_) text.append(drawn_width_ - width, ' ');
  std::fprintf(out_, "\r%s", text.c_str());
  std::fflush(out_);
  drawn_width_ = width;
  ++draws_;
}

void ProgressLine::clear() {
  if (!terminal_) return;
  std::lock_guard<std::mutex> lock(mutex_);
  if (!drawn_width_) return;
  std::fprintf(out_, "\r%s\r", std::string(drawn_width_, ' ').c_str());
  std::fflush(out_);
  drawn_width_ = 0;
}

}  // namespace delcert::io
