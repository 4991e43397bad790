// DTU's evaluation (`--protocol dtu`) on a pair, as DTUeval-python computes it
// (roving/reconstruction/dtu_protocol.h), from the data set's own files: the scan's observation
// mask and ground plane; and the report's section of it (docs/report-json.md's `dtu_protocol`).
#pragma once

#include <array>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "roving/reconstruction/dtu_protocol.h"
#include "roving/reconstruction/reconstruction_figures.h"
#include "roving/representations/model.h"

namespace roving {

struct DtuPlan {
  DtuOptions options;
  std::string obs_mask, plane;  // ObsMask<scan>_10.mat, Plane<scan>.mat
};

struct DtuReport {
  DtuFigures figures;
  std::string obs_mask, plane;
  double seconds = 0;
  // With --symmetric, the exact figures where the protocol measures: accuracy over TEST's samples
  // within the box and observed, completeness over REF's above the plane, every distance counted;
  // the same with the protocol's cap (the distances below max_dist only); how many samples each
  // direction counted (below the cap: the figures' hits), of how many.
  std::optional<ReconstructionFigures> exact, exact_below_cap;
  std::size_t exact_test_counted = 0, exact_test_samples = 0, exact_reference_counted = 0,
              exact_reference_samples = 0;
};

// The data set's files for one scan: its observation mask and ground plane.
struct DtuFiles {
  DtuObservationMask mask;
  std::array<double, 4> plane{};
};

// Reads them, before the models (a wrong file fails at once). Throws roving::Error naming the file
// and variable that is missing or malformed.
DtuFiles read_dtu_files(const DtuPlan& plan);

// The protocol with `ground_truth` (REF: DTU's STL points, or a mesh's vertices) and
// `reconstruction` (TEST: a mesh, sampled as the script samples it, or a point cloud). Throws
// roving::Error naming a model that is neither a mesh nor a point cloud. `progress` hears the runs'
// steps.
DtuReport dtu_report(const Model& ground_truth, const Model& reconstruction, const DtuPlan& plan,
                     const DtuFiles& files, const ProgressFn& progress = {});

// Sets report.exact (every distance) and report.exact_below_cap (those below max_dist) from the two
// directions' correspondences (REF's samples measured against TEST, TEST's against REF), as
// reconstruction_figures takes them, restricted to the protocol's region, and the samples counted.
void set_exact_within_region(DtuReport& report, const DtuPlan& plan, const DtuFiles& files,
                             const CorrespondenceSet& reference_to_test,
                             const CorrespondenceSet& test_to_reference,
                             const std::vector<double>& thresholds, bool area_uniform);

nlohmann::json dtu_json(const DtuReport& report);
// The text section: the protocol's figures (and their spread over the runs' seeds), then the exact
// figures where the protocol measures.
std::string dtu_lines(const DtuReport& report);

}  // namespace roving
