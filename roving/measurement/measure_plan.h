// What a measurement of a pair is to do: everything the options decide, parsed and checked before
// any file is read (the command line's, the Python module's and a batch's options all become one).
#pragma once

#include <cstddef>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "gates.h"
#include "shard.h"
#include "roving/mpeg/point_cloud_psnr.h"
#include "roving/core/distance_method.h"
#include "roving/formats/outputs/heatmap.h"
#include "roving/gl_methods/gl_methods.h"
#include "roving/gl_methods/image_based.h"
#include "roving/protocols/dtu_evaluation.h"
#include "roving/protocols/tanks_and_temples_evaluation.h"
#include "roving/streaming/streamed_measurement.h"

namespace roving {

// Everything the options decide, parsed and checked before any file is read.
struct MeasurePlan {
  GlMethodOptions gl;
  std::unique_ptr<DistanceMethod> method;
  SampleSpec sample_spec;
  MaxErrorSpec max_error;
  std::string max_error_text;  // as given, for messages
  DistanceOptions options;     // max_error resolved per pair
  std::vector<Gate> gates;
  std::optional<ModelType> reference_type, test_type;
  bool symmetric = false;
  std::size_t histogram_bins = 64;
  std::optional<MaxErrorSpec> hausdorff_bound;  // set where the certified Hausdorff interval is computed
  GateOn gate_on = GateOn::Estimate;
  std::optional<MaxErrorSpec> precision;      // area:auto only; P% is of USiAD itself
  std::optional<MaxErrorSpec> heatmap_range;  // --heatmap-range; unset: the 99th percentile of |d|
  HeatmapQuantity heatmap_of = HeatmapQuantity::Distance;
  std::optional<double> heatmap_delta_e_range;   // --heatmap-range with --heatmap-of delta-e
  std::optional<ImageBasedOptions> image_based;  // --ibsm
  std::vector<MaxErrorSpec> thresholds;          // --threshold, resolved per pair
  bool certify_thresholds = false;               // --certify-thresholds
  bool pcc_only = false;                         // --pcc: MPEG's point-cloud figures, nothing else
  std::optional<double> pcc_resolution;          // --pcc-resolution
  std::string pcc_normals;                       // --pcc-normals
  PcErrorOptions pcc_options;                    // --pcc-dropdups, -neighbors-proc, -average-normals, -mse-space
  bool pcc_b_own_normals = true;                 // --pcc-normal-calc-modification (mmetric's, on meshes)
  std::optional<DtuPlan> dtu;                    // --protocol dtu
  std::optional<TanksAndTemplesPlan> tnt;        // --protocol tanks-and-temples
  bool protocol_only = false;                    // --protocol without --symmetric: its figures alone
  bool correspondences = false;                  // each direction's Correspondences kept
  std::optional<Shard> shard;                    // --shard: one slice of the samples
  std::size_t chunk_faces = kDefaultChunkFaces;  // --chunk
  // Set where `method` was built for TEST already, beside a streamed REF's reading: its seconds.
  std::optional<double> method_built_seconds;
};

// --samples area:auto: the first round's samples, and the most it may take.
constexpr std::size_t kAutoFirstSamples = 10000;
constexpr std::size_t kAutoMaxSamples = 20000000;

// Where a measurement's warnings go as they are found.
using WarnFn = std::function<void(const std::vector<std::string>&)>;

}  // namespace roving
