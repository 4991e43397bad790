// Progress on stderr for a person watching a terminal: the stage, then counts as they move
// ("views 12/288", "samples 45%"), redrawn in place at most ten times a second. Silent when
// stderr is not a terminal (pipes, CI logs) or when the user asked for --quiet; a listener hears
// it either way.
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

  bool enabled_;
  std::mutex mutex_;
  std::string stage_;
  std::size_t drawn_width_ = 0;
  std::chrono::steady_clock::time_point last_draw_{}, last_heard_{};
  Listener listener_;
  std::atomic<bool> stopped_{false};

  void hear(const char* what, std::size_t done, std::size_t total);
};

}  // namespace roving
