// Progress on a terminal's stderr.
#include "progress.h"

#include <fmt/format.h>
#include <sys/ioctl.h>
#include <unistd.h>

#include <cstdio>

namespace roving {

Progress::Progress(bool quiet) : enabled_(!quiet && ::isatty(STDERR_FILENO)) {}

void Progress::stage(const std::string& text) {
  if (!enabled_ && !listener_) return;
  const std::lock_guard<std::mutex> lock(mutex_);
  stage_ = text;
  if (enabled_) draw(stage_ + " ...");
  if (listener_) hear("", 0, 0);
}

void Progress::update(const char* what, std::size_t done, std::size_t total) {
  if (!enabled_ && !listener_) return;
  const std::lock_guard<std::mutex> lock(mutex_);
  const auto now = std::chrono::steady_clock::now();
  const auto due = [&](std::chrono::steady_clock::time_point& last) {
    if (done < total && now - last < std::chrono::milliseconds(100)) return false;
    last = now;
    return true;
  };
  if (enabled_ && due(last_draw_)) {
    const double percent = total ? 100.0 * done / total : 100.0;
    draw(fmt::format("{}: {} {}/{} ({:.0f}%)", stage_, what, done, total, percent));
  }
  if (listener_ && due(last_heard_)) hear(what, done, total);
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
