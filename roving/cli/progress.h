// Progress on stderr for a person watching a terminal: the stage, then counts as they move
// ("views 12/288", "samples 45%"), redrawn in place at most ten times a second. Silent when
// stderr is not a terminal (pipes, CI logs) or when the user asked for --quiet.
#pragma once

#include <chrono>
#include <cstddef>
#include <mutex>
#include <string>

#include "roving/core/distance_method.h"

namespace roving {

class Progress {
 public:
  explicit Progress(bool quiet);
  ~Progress() { clear(); }

  // A new stage ("loading bunny.obj"): shown at once.
  void stage(const std::string& text);
  // How far the current stage has got; thread-safe, throttled.
  void update(const char* what, std::size_t done, std::size_t total);
  // A callback for DistanceMethod::set_progress, forwarding to update().
  ProgressFn callback();
  // Erases the line, so that what follows starts clean.
  void clear();

 private:
  void draw(const std::string& line);

  bool enabled_;
  std::mutex mutex_;
  std::string stage_;
  std::size_t drawn_width_ = 0;
  std::chrono::steady_clock::time_point last_draw_{};
};

}  // namespace roving
