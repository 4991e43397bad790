// The `roving measure` report: what was measured, every statistic, timings, provenance and
// warnings; as text (report_text.cpp) or JSON (measure_report.cpp). One direction (REF -> TEST),
// or both with --symmetric.
#pragma once

#include <array>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "shard.h"
#include "roving/core/colour_statistics.h"
#include "roving/core/confidence.h"
#include "roving/core/correspondence.h"
#include "roving/core/distance_method.h"
#include "roving/core/statistics.h"
#include "roving/gl_methods/image_based.h"
#include "roving/mpeg/mpeg_report.h"
#include "roving/protocols/dtu_evaluation.h"
#include "roving/protocols/tanks_and_temples_evaluation.h"
#include "roving/reconstruction/reconstruction_figures.h"
#include "roving/reference_embree/certified_area_within.h"
#include "roving/reference_embree/certified_hausdorff.h"
#include "roving/representations/model.h"

namespace roving {

// The JSON layout's version: raised whenever a field changes meaning or goes away (adding
// fields keeps it). Documented in docs/report-json.md.
constexpr int kReportSchemaVersion = 3;

// One direction: the samples of `reference` measured against `test`.
struct DirectionReport {
  const Model* reference = nullptr;
  const Model* test = nullptr;
  SampleSet samples;
  DistanceResult result;
  Statistics statistics;
  SignCounts signs;   // of the hits' d
  std::string label;  // "A -> B" with --symmetric, empty otherwise
  // Where REF was read, sampled and measured a block of faces at a time (streamed_measurement.h):
  // its faces per block and the blocks; 0 where it was read whole.
  std::size_t chunk_faces = 0, chunks = 0;
  // The certified one-sided Hausdorff distance of the reference's surface from the test's, where
  // asked (closest semantics, or --symmetric) and the reference is a surface.
  std::optional<HausdorffInterval> hausdorff;
  // The certified shares of the reference's area within each --threshold of the test, where both
  // directions are measured with closest semantics between surfaces (precision and recall).
  std::optional<AreaWithin> area_within;
  // 95% intervals of SiAD, USiAD and RMS as estimates of the surface means, for area:N samples.
  std::optional<SamplingIntervals> intervals;
  // area:auto: the half-width asked of USiAD's interval, the one reached, and whether it was met
  // (or the sample cap was).
  struct AutoSampling {
    double target = 0, reached = 0;
    int rounds = 0;
    bool met = false;
  };
  std::optional<AutoSampling> auto_sampling;
  // The heat maps' colour range [-range, range]: --heatmap-range, or the 99th percentile of |d|.
  double heatmap_range = 0;
  // Each sample's two colours and their statistics, where both models have colour and the
  // method reports the faces its hits lie on (README "Colour").
  std::optional<ColourPairs> colour_pairs;
  std::optional<ColourStatistics> colour;
  // Each sample's point on TEST and its barycentric coordinates, where asked (per-sample outputs).
  std::optional<Correspondences> correspondences;
  // The reference and the test as the report describes them (model_json), taken before sampling
  // (which may release the reference's geometry); a merge of shards reports them without models.
  nlohmann::json reference_json, test_json;
  // Under --shard: this direction's slice starts at sample `slice_first` of `slice_total`.
  std::size_t slice_first = 0, slice_total = 0;
};

// measure --shard: which slice one run measured, for `roving merge` (merge.h).
struct ShardSlice {
  Shard shard;
  std::vector<std::string> model_warnings;  // the warnings about the models, before any figure's
};

// Metro's two-sided summary, over both directions' samples (closest-point semantics make the
// maximum the Hausdorff distance).
struct TwoSided {
  double max_abs = 0;   // the larger direction's max |d| over hits
  double mean_abs = 0;  // area-weighted mean |d| over both sample sets
  double rms = 0;       // area-weighted RMS over both
  // The certified Hausdorff distance, max of both directions' intervals, where both were computed.
  bool certified = false;
  double hausdorff_lower = 0, hausdorff_upper = 0;
};

struct MeasureReport {
  std::vector<DirectionReport> directions;  // 1, or 2 with --symmetric
  std::string method;
  Semantics semantics = Semantics::FirstHit;
  double max_error = 0;
  std::string max_error_text;     // as the user gave it, e.g. "5%"
  double hausdorff_bound = 0;     // the certified interval's largest width, in model units
  double diagonal = 0;            // every relative figure's denominator
  bool diagonal_of_both = false;  // of both models' box (--symmetric), else the reference's
  std::uint64_t seed = 0;
  nlohmann::json provenance;  // tool, command line, inputs
  std::vector<std::string> warnings;
  std::optional<ImageBasedResult> image_based;  // --ibsm
  // With --symmetric: the reconstruction figures, REF the ground truth and TEST the reconstruction.
  std::optional<ReconstructionFigures> reconstruction;
  // For two point clouds: MPEG's figures; with --pcc (pcc_only) nothing else is measured.
  std::optional<MpegReport> mpeg;
  bool pcc_only = false;
  // --protocol dtu: the benchmark's own figures; with protocol_only nothing else is measured.
  std::optional<DtuReport> dtu;
  std::optional<TanksAndTemplesReport> tnt;  // --protocol tanks-and-temples
  bool protocol_only = false;
  std::string protocol;  // "dtu" or "tanks-and-temples" where one was asked for, known before its figures
  std::optional<ShardSlice> shard;  // a shard's run: its figures are its slice's alone
  double load_seconds[2] = {0, 0};  // A (the reference), B (the test)
  double total_seconds = 0;

  bool symmetric() const { return directions.size() == 2; }
  TwoSided two_sided() const;
};

// What a semantics' d and no-hit mean, as the text report explains them and the JSON carries them.
const char* semantics_note(Semantics semantics);

// The textures a mesh's materials use, each once (the JSON's and the text's model descriptions).
std::vector<const Texture*> textures_of(const TriangleMesh& m);

// A model as the report's JSON describes it (paths, counts, area, box, colour, representation).
nlohmann::json model_json(const Model& model);

// The models, the sampling and the method: known before the long work, printed at once.
std::string format_header(const Model& a, const Model& b, const MeasureReport& report);

// Metro-style plain text: each statistic in model units and relative to the diagonal (one
// column pair per direction), no-hits apart, what the semantics' no-hit means, the two-sided
// summary with --symmetric, GL observations and times.
std::string format_body(const MeasureReport& report);

// The statistics by their report (and --fail-above) names.
nlohmann::json statistics_json(const Statistics& statistics);

// The colour statistics by their report names (gates use delta_e_mean, delta_e_p95, delta_e_max
// and colour_rms_y).
nlohmann::json colour_json(const ColourStatistics& colour);

// A GL method's observations, precision and times by their report names (a shard's part carries
// them too, and the merge adds them up: gl_report_of).
nlohmann::json gl_json(const GlReport& g);
GlReport gl_report_of(const nlohmann::json& json);

// Everything as JSON (layout in docs/report-json.md).
nlohmann::json to_json(const MeasureReport& report);

}  // namespace roving
