// `roving measure`: load, sample, measure (one direction or both), report, gate.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace roving {

struct MeasureArguments {
  std::string reference_path, test_path;
  std::string method = "embree";
  std::string semantics;  // empty: the method's own default (closest with --symmetric)
  std::string samples = "faces";
  std::optional<std::uint64_t> seed;  // area:N only
  std::string max_error = "5%";
  std::string json_path, samples_csv_path, heatmap_path;
  std::size_t histogram_bins = 64;
  std::string views = "24x12", backend = "osmesa";
  std::string reference_type, test_type;  // empty: by extension
  int resolution = 1024;
  bool symmetric = false;
  bool quiet = false;
  std::vector<std::string> gates;  // --fail-above METRIC=LIMIT
  std::string command_line;
};

// Runs the measurement and writes its outputs; returns the exit code (0, or kGateExitCode when a
// gate is breached). Throws roving::Error (bad input) and std::bad_alloc, after `stage` was set
// to what the run was doing.
int run_measure(const MeasureArguments& args, std::string& stage);

}  // namespace roving
