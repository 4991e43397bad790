// `roving measure`: its options planned, the models loaded and measured (measure_models.h), the
// report and the files it asks for written, the gates applied.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "roving/core/error.h"
#include "roving/measurement/measure_models.h"

namespace roving {

struct MeasureArguments {
  std::string reference_path, test_path;
  std::string method = "embree";
  std::string semantics;  // empty: the method's own default (closest with --symmetric)
  std::string samples = "faces";
  std::optional<std::uint64_t> seed;  // area:N only
  std::string max_error = "5%";
  std::string json_path, samples_csv_path, heatmap_path, heatmap_png_path, html_path;
  std::string heatmap_of = "d";           // or "delta-e": what --heatmap and --heatmap-png show
  std::string heatmap_range;              // empty: the 99th percentile of |d| (or delta E) over the hits
  std::string hausdorff_bound = "0.01%";  // the certified interval's width, or "none"
  std::string gate_on = "estimate";       // or "upper": gates compare an interval's upper end
  std::string precision = "1%";           // area:auto: USiAD's 95% half-width, relative (P%) or a length
  std::size_t histogram_bins = 64;
  std::string views = "24x12", backend;   // backend empty: default_gl_backend()
  std::string camera_geometry = "cpu";    // or "gpu", "compute": where exact roving's cameras are made
  std::string view_culling = "footprint";  // or "none": each view drawn whole
  std::string reference_type, test_type;  // empty: by extension
  int resolution = 1024;
  bool ibsm = false;  // the image-based comparison (image_based.h) beside the sample-based one
  int ibsm_views = 16, ibsm_resolution = 2048;
  bool symmetric = false;
  bool quiet = false;
  bool warnings_to_stderr = true;  // false: the caller hands them on (the Python module, to `warnings`)
  std::vector<std::string> gates;       // --fail-above METRIC=LIMIT
  std::vector<std::string> floors;      // --fail-below METRIC=FLOOR
  std::vector<std::string> thresholds;  // --threshold TAU: precision, recall, F-score at TAU
  bool certify_thresholds = false;      // --certify-thresholds: their certified bounds too
  bool pcc = false;                     // MPEG's point-cloud figures alone (pc_error's)
  std::optional<double> pcc_resolution;  // their PSNR peak; unset: pc_error's default
  std::string pcc_normals;               // A's normals from this file (pc_error's --inputNorm)
  int pcc_dropdups = 2;                  // pc_error's --dropdups, --neighborsProc, --averageNormals, --mseSpace
  int pcc_neighbors_proc = 1;
  int pcc_average_normals = 1;
  int pcc_mse_space = 1;
  bool pcc_normal_calc_modification = true;  // mmetric's --normalCalcModificationEnable
  std::string protocol;                  // "dtu", "tanks-and-temples": a benchmark's own evaluation (roving/protocols/)
  std::string dtu_obs_mask, dtu_plane;   // its data set's files
  double dtu_density = 0.2, dtu_patch = 60, dtu_max_dist = 20;
  std::string tnt_crop, tnt_alignment, tnt_scene, tnt_curves, tnt_plys;  // --protocol tanks-and-temples
  std::string tnt_trajectory, tnt_reference_trajectory, tnt_mapping;     // and run.py's registration
  std::optional<double> tnt_tau;
  std::string protocol_seed = "1";  // or "none": the points' own order
  int protocol_runs = 5;
  // Keep each sample's point on TEST and its barycentric coordinates (correspondence.h): Python's
  // per_sample asks for them; --samples-out always writes them. No option of its own.
  bool correspondences = false;
  // --shard I/N: only the I-th of N slices of the samples, written as a part to --shard-out for
  // `roving merge` (merge.h).
  std::string shard, shard_out;
  // --chunk FACES: a binary PLY or STL, or OBJ, REF with more faces than this is read, sampled and measured this
  // many faces at a time (where nothing asked for needs it whole); 0: always read whole.
  std::size_t chunk = kDefaultChunkFaces;
  // The words of the command line that decide the figures (REF, TEST and every option given but
  // the outputs'): a shard's part records them, and a merge plans from them. Set by the parse.
  std::vector<std::string> figure_arguments;
  std::string command_line;
};

// A bad option value or combination on the command line: the tool exits 2, as for a parse error.
class UsageError : public Error {
 public:
  using Error::Error;
};

// Throws roving::Error naming the option on any bad value.
MeasurePlan plan_measurement(const MeasureArguments& args);

// plan_measurement, and the output paths checked, for the command line's own options: any error
// is a UsageError.
MeasurePlan plan_command_line(const MeasureArguments& args);

// Where --heatmap FILE or --heatmap-png FILE writes each direction: FILE itself for one direction;
// FILE's stem + ".A-to-B" / ".B-to-A" + its extension under --symmetric.
std::vector<std::string> heatmap_paths(const std::string& path, bool symmetric);

// Which element of the reference's surface carries each sample's value in the heat maps.
HeatmapLayout heatmap_layout(const Model& reference, const SampleSet& samples);

// An entry of the report's `inputs`; with no `sha256`, a model given in memory (no file: bytes
// and hash null).
nlohmann::json input_json(const std::string& role, const std::string& path, const std::string& sha256);

// A measurement as `roving measure` makes it: the models (where the report's directions point),
// the plan and the report, before any output is written.
struct MeasureRun {
  MeasurePlan plan;
  std::unique_ptr<Model> a, b;
  MeasureReport report;
};

// Plans, loads (or takes `given_a`, `given_b`: models already in memory, whose paths name them),
// and measures; `on_described` is called once the pair is described (report header known).
// Throws roving::Error (bad input, UsageError for a bad option) and std::bad_alloc, after `stage`
// was set to what the run was doing.
MeasureRun measure_run(const MeasureArguments& args, std::string& stage, Progress& progress,
                       const std::function<void(const MeasureRun&)>& on_described = {},
                       std::unique_ptr<Model> given_a = nullptr, std::unique_ptr<Model> given_b = nullptr);

// Writes the files the arguments ask for (--samples-out, --heatmap, --heatmap-png, --json FILE,
// --html), each whole or none of them.
void write_measure_outputs(const MeasureArguments& args, const MeasureRun& run, std::string& stage);

// Runs the measurement, writes its outputs and the report on stdout; returns the exit code (0, or
// kGateExitCode when a gate is breached). Throws as measure_run does.
int run_measure(const MeasureArguments& args, std::string& stage);

}  // namespace roving
