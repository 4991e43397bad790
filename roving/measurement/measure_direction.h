// One direction of a pair: REF's samples (drawn, handed over, or streamed a block of faces at a
// time) measured against TEST; their statistics, the certified bounds asked for, the
// correspondences and the colour figures, into a DirectionReport.
#pragma once

#include <string>
#include <vector>

#include "measure_plan.h"
#include "measure_report.h"
#include "progress.h"
#include "roving/streaming/streamed_measurement.h"
#include "roving/representations/model.h"

namespace roving {

// What REF comes with beyond the model itself (measure_models' A direction; none for B's).
struct DirectionSource {
  const SampleSet* samples = nullptr;  // its samples already made (a batch reuses them)
  Model* releasable = nullptr;         // REF itself, whose geometry is released once sampled
  ReferenceStream* stream = nullptr;   // its file a block of faces at a time, REF its summary
};

// Fills `d` (an entry of report.directions, its label set) for `reference` against `test`:
// `report`'s diagonal, h and certified bounds' width as describe_pair set them; `thresholds`
// --threshold in model units.
void measure_direction(const Model& reference, const Model& test, const DirectionSource& source, MeasurePlan& plan,
                       const MeasureReport& report, const std::vector<double>& thresholds, Progress& progress,
                       std::string& stage, const WarnFn& warn, DirectionReport& d);

}  // namespace roving
