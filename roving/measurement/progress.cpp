// Progress on a terminal's stderr.
#include "progress.h"

#include <fmt/format.h>
#include <sys/ioctl.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>

namespace roving {

namespace {

// A rate with SI prefixes ("1.23 M/s") and a duration as h:mm:ss or m:ss.
std::string rate_text(double per_second) {
  if (per_second >= 1e6) return fmt::format("{:.3g} M/s", per_second / 1e6);
  if (per_second >= 1e3) return fmt::format("{:.3g} k/s", per_second / 1e3);
  return fmt::format("{:.3g}/s", per_second);
}

std::string duration_text(double seconds) {
  const long s = std::lround(seconds);
  if (s >= 3600) return fmt::format("{}:{:02}:{:02}", s / 3600, s / 60 % 60, s % 60);
  return fmt::format("{}:{:02}", s / 60, s % 60);
}

}  // namespace

Progress::Progress(bool quiet, bool log_lines, double log_after)
    : enabled_(!quiet && ::isatty(STDERR_FILENO)), log_lines_(!quiet && log_lines && !enabled_), log_after_(log_after) {}

std::string Progress::count_text(std::size_t done, std::size_t total, double seconds) const {
  std::string text = fmt::format("{}: {} {}/{} ({:.0f}%)", stage_, what_, done, total,
                                 total ? 100.0 * double(done) / double(total) : 100.0);
  if (seconds > 0.5 && done > 0 && done < total) {
    const double rate = double(done) / seconds;
    text += fmt::format(", {}, about {} left", rate_text(rate), duration_text(double(total - done) / rate));
  }
  return text;
}

void Progress::stage(const std::string& text) {
  if (!enabled_ && !log_lines_ && !listener_) return;
  const std::lock_guard<std::mutex> lock(mutex_);
  stage_ = text;
  what_.clear();
  if (enabled_) draw(stage_ + " ...");
  if (listener_) hear("", 0, 0);
}

void Progress::update(const char* what, std::size_t done, std::size_t total) {
  if (!enabled_ && !log_lines_ && !listener_) return;
  const std::lock_guard<std::mutex> lock(mutex_);
  const auto now = std::chrono::steady_clock::now();
  if (what_ != what) {  // a new count: its rate and tenths start here
    what_ = what;
    counting_since_ = now;
    next_tenth_ = 1;
  }
  const double seconds = std::chrono::duration<double>(now - counting_since_).count();
  const auto due = [&](std::chrono::steady_clock::time_point& last, std::chrono::milliseconds every) {
    if (done < total && now - last < every) return false;
    last = now;
    return true;
  };
  if (enabled_ && due(last_draw_, std::chrono::milliseconds(1000))) draw(count_text(done, total, seconds));
  if (log_lines_ && total > 0 && done * 10 >= next_tenth_ * total) {
    next_tenth_ = int(done * 10 / total) + 1;
    if (seconds >= log_after_) std::fprintf(stderr, "roving: %s\n", count_text(done, total, seconds).c_str());
  }
  if (listener_ && due(last_heard_, std::chrono::milliseconds(100))) hear(what, done, total);
}

void Progress::hear(const char* what, std::size_t done, std::size_t total) {
  try {
    listener_(stage_, what, done, total);
  } catch (...) {
    stopped_ = true;
    throw;
  }
}

ProgressFn Progress::callback() {
  return [this](const char* what, std::size_t done, std::size_t total) { update(what, done, total); };
}

void Progress::clear() {
  if (!enabled_) return;
  const std::lock_guard<std::mutex> lock(mutex_);
  draw("");
}

void Progress::draw(const std::string& text) {
  // One terminal line at most, or the carriage return would no longer reach its start.
  winsize size{};
  const std::size_t width =
      ::ioctl(STDERR_FILENO, TIOCGWINSZ, &size) == 0 && size.ws_col > 1 ? size.ws_col : 80;
  const std::string line = text.size() < width ? text : text.substr(0, width - 4) + "...";
  // Carriage return, the line, and blanks over whatever longer line was there before.
  const std::size_t pad = drawn_width_ > line.size() ? drawn_width_ - line.size() : 0;
  std::fprintf(stderr, "\r%s%*s\r%s", line.c_str(), static_cast<int>(pad), "", line.c_str());
  std::fflush(stderr);
  drawn_width_ = line.size();
}

}  // namespace roving
