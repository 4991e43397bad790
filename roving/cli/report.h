// The `roving measure` report: what was measured, every statistic, timings; as text or JSON.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "roving/core/distance_method.h"
#include "roving/core/statistics.h"
#include "roving/representations/model.h"

namespace roving {

struct MeasureReport {
  const Model* reference = nullptr;
  const Model* test = nullptr;
  const SampleSet* samples = nullptr;
  std::string method;
  Semantics semantics = Semantics::FirstHit;
  double max_error = 0;
  std::string max_error_text;  // as the user gave it, e.g. "5%"
  Statistics statistics;
  double load_reference_seconds = 0, load_test_seconds = 0;
  double build_seconds = 0, query_seconds = 0, total_seconds = 0;
  const GlReport* gl = nullptr;  // GL methods: observations and precision
};

// Metro-style plain text: counts, diagonal, each statistic in model units and relative to the
// reference's bounding-box diagonal, no-hits, and load / build / query times.
std::string format_text(const MeasureReport& report);

// The same fields as JSON.
nlohmann::json to_json(const MeasureReport& report);

}  // namespace roving
