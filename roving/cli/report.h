// The `roving measure` report: what was measured, every statistic, timings, provenance and
// warnings; as text or JSON. One direction (REF -> TEST), or both with --symmetric.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "roving/core/distance_method.h"
#include "roving/core/statistics.h"
#include "roving/representations/model.h"

namespace roving {

// The JSON layout's version: raised whenever a field changes meaning or goes away (adding
// fields keeps it). Documented in docs/report-json.md.
constexpr int kReportSchemaVersion = 2;

// One direction: the samples of `reference` measured against `test`.
struct DirectionReport {
  const Model* reference = nullptr;
  const Model* test = nullptr;
  SampleSet samples;
  DistanceResult result;
  Statistics statistics;
  std::string label;  // "A -> B" with --symmetric, empty otherwise
};

// Metro's two-sided summary, over both directions' samples (closest-point semantics make the
// maximum the Hausdorff distance).
struct TwoSided {
  double max_abs = 0;    // the larger direction's max |d| over hits
  double mean_abs = 0;   // area-weighted mean |d| over both sample sets
  double rms = 0;        // area-weighted RMS over both
};

struct MeasureReport {
  std::vector<DirectionReport> directions;  // 1, or 2 with --symmetric
  std::string method;
  Semantics semantics = Semantics::FirstHit;
  double max_error = 0;
  std::string max_error_text;  // as the user gave it, e.g. "5%"
  double diagonal = 0;         // every relative figure's denominator
  bool diagonal_of_both = false;  // of both models' box (--symmetric), else the reference's
  std::uint64_t seed = 0;
  nlohmann::json provenance;  // tool, command line, inputs
  std::vector<std::string> warnings;
  double load_seconds[2] = {0, 0};  // A (the reference), B (the test)
  double total_seconds = 0;

  bool symmetric() const { return directions.size() == 2; }
  TwoSided two_sided() const;
};

// The models, the sampling and the method: known before the long work, printed at once.
std::string format_header(const Model& a, const Model& b, const MeasureReport& report);

// Metro-style plain text: each statistic in model units and relative to the diagonal (one
// column pair per direction), no-hits apart, what the semantics' no-hit means, the two-sided
// summary with --symmetric, GL observations and times.
std::string format_body(const MeasureReport& report);

// The statistics by their report (and --fail-above) names.
nlohmann::json statistics_json(const Statistics& statistics);

// Everything as JSON (layout in docs/report-json.md).
nlohmann::json to_json(const MeasureReport& report);

}  // namespace roving
