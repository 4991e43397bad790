// Progress on stderr. On a terminal: the stage, then counts as they move with their rate and the
// time left ("measuring: samples 450000/1000000 (45%), 1.2 M/s, about 0:05 left"), redrawn in place
// at most once a second. In a log (stderr not a terminal: a pipe, a batch job's file): one line per
// 10% of a stage that has run 5 s or more, so short runs stay silent. Nothing with --quiet; a
// listener hears it either way.
#pragma once

#include <atomic>
#include <chrono>
#include <cstddef>
#include <functional>
#include <mutex>
#include <string>

#include "roving/core/distance_method.h"

namespace roving {

class Progress {
 public:
  // `log_lines`: the 10% lines when stderr is not a terminal (off for the Python module, whose
  // progress= callback is how a notebook hears it), for counts that have run `log_after` seconds.
  explicit Progress(bool quiet, bool log_lines = true, double log_after = 5);
  ~Progress() { clear(); }

  // A new stage ("loading bunny.obj"): shown at once.
  void stage(const std::string& text);
  // How far the current stage has got; thread-safe, throttled.
  void update(const char* what, std::size_t done, std::size_t total);
  // A callback for DistanceMethod::set_progress, forwarding to update().
  ProgressFn callback();
  // Erases the line, so that what follows starts clean.
  void clear();

  // Also hands each stage (what empty, 0 of 0) and the updates, at most every 0.1 s, to
  // `listener`, terminal or not: the Python module's progress callback and its Ctrl-C check. The
  // listener may throw to stop the measurement; nothing is written then.
  using Listener =
      std::function<void(const std::string& stage, const char* what, std::size_t done, std::size_t total)>;
  void listen(Listener listener) { listener_ = std::move(listener); }
  // Whether the listener has thrown: the run is being stopped, not one of its parts failing (a
  // batch goes on past a failed pair, never past this).
  bool stopped() const { return stopped_; }

 private:
  void draw(const std::string& line);

  bool enabled_;    // a terminal's line, redrawn
  bool log_lines_;  // a log's 10% lines
  double log_after_;
  std::mutex mutex_;
  std::string stage_;
  // The count being made: what, since when, and the next tenth a log line is due at.
  std::string what_;
  std::chrono::steady_clock::time_point counting_since_{};
  int next_tenth_ = 1;
  std::size_t drawn_width_ = 0;
  std::chrono::steady_clock::time_point last_draw_{}, last_heard_{};
  Listener listener_;
  std::atomic<bool> stopped_{false};

  void hear(const char* what, std::size_t done, std::size_t total);
  // "samples 450000/1000000 (45%), 1.2 M/s, about 0:05 left"
  std::string count_text(std::size_t done, std::size_t total, double seconds) const;
};

}  // namespace roving
