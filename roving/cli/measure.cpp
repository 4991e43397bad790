// `roving measure`: the run from options to report.
#include "measure.h"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <charconv>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <future>
#include <limits>
#include <memory>
#include <tuple>

#include "figure_families.h"
#include "checks.h"
#include "gates.h"
#include "html_output.h"
#include "merge.h"
#include "progress.h"
#include "provenance.h"
#include "report.h"
#include "roving/core/error.h"
#include "roving/formats/files/atomic_file.h"
#include "roving/formats/outputs/distance_cloud_writer.h"
#include "roving/formats/files/file_bytes.h"
#include "roving/formats/files/file_hash.h"
#include "roving/formats/outputs/heatmap.h"
#include "roving/formats/meshes/ply_reader.h"
#include "roving/formats/points_voxels_patches/point_cloud_io.h"
#include "roving/formats/outputs/sample_output.h"
#include "roving/formats/meshes/triangle_stream.h"
#include "roving/mpeg/mmetric_sampling.h"
#include "roving/mpeg/mpeg_points.h"
#include "roving/mpeg/surface_psnr.h"
#include "roving/pictures/heatmap_picture.h"
#include "roving/pictures/precision_recall_chart.h"
#include "roving/registry/method_registry.h"
#include "roving/reference_embree/certified_hausdorff.h"
#include "roving/streaming/mesh_blocks.h"

namespace roving {
namespace {

// h bounded by what the models and Embree's float rays can represent: the view volume need
// reach no farther than both models' extent, and beyond it the rays' float origins lose the
// precision the distances need (h = 1e10 on a unit model gave SiAD 2.5e9 instead of 0).
void require_representable(double max_error, const BoundingBox& both, const std::string& given) {
  const double extent = both.diagonal();
  if (!(max_error <= extent)) {
    throw Error(
        fmt::format("--max-error: expected at most the diagonal of both models' bounding box ({:.6g}), found "
                    "{} ({:.6g}); a view volume reaches nothing farther",
                    extent, given, max_error));
  }
}

// A length or P% of the diagonal, for `option`: --max-error's rules under another name.
MaxErrorSpec parse_length(const std::string& option, const std::string& text) {
  try {
    return parse_max_error(text);
  } catch (const Error& e) {
    const std::string message = e.what();
    throw Error(option + message.substr(message.find(':')));
  }
}

std::string file_name(const std::string& path) {
  return std::filesystem::path(path).filename().string();
}

void require_writable_paths(const MeasureArguments& args) {
  std::vector<std::pair<std::string, std::string>> outputs = {
      {"--json", args.json_path}, {"--samples-out", args.samples_csv_path}, {"--html", args.html_path}};
  for (const auto& [option, given] :
       {std::pair{"--heatmap", args.heatmap_path}, {"--heatmap-png", args.heatmap_png_path}}) {
    if (given.empty()) continue;
    for (const std::string& path : heatmap_paths(given, args.symmetric)) outputs.emplace_back(option, path);
  }
  for (const auto& [option, path] : outputs) {
    std::error_code error;
    if (!path.empty() && path != "-" && std::filesystem::is_directory(path, error)) {
      throw Error(fmt::format("{}: expected a file to write, found the directory '{}'", option, path));
    }
  }
}

// A protocol's input file: one that opens, and not a folder (which opens, then fails to read with
// a message naming nothing).
void require_readable_file(const std::string& option, const std::string& path) {
  std::error_code error;
  if (std::filesystem::is_directory(path, error)) {
    throw Error(fmt::format("{}: expected a file to read, found the directory '{}'", option, path));
  }
  if (!std::ifstream(path)) throw Error(fmt::format("{}: cannot read '{}'", option, path));
}

}  // namespace

// Every value a gate can check: each direction's statistics, and the two-sided summary.
std::vector<MetricValue> gate_values(const MeasureReport& report) {
  std::vector<MetricValue> values;
  // The range of |mean| an interval [lower, upper] of a signed mean allows.
  const auto magnitudes = [](MetricValue& v, const MeanInterval& m) {
    v.low = m.lower <= 0 && 0 <= m.upper ? 0.0 : std::min(std::abs(m.lower), std::abs(m.upper));
    v.high = std::max(std::abs(m.lower), std::abs(m.upper));
  };
  for (const DirectionReport& d : report.directions) {
    const Statistics& s = d.statistics;
    const nlohmann::json statistics = statistics_json(s);
    for (const auto& [name, value] : statistics.items()) {
      MetricValue v{name, d.label, value.get<double>(), report.diagonal};
      if (d.intervals) {  // area:N samples: the plain and area-weighted means are the same estimate
        if (name == "siad" || name == "siad_area") magnitudes(v, d.intervals->siad);
        if (name == "usiad" || name == "usiad_area") magnitudes(v, d.intervals->usiad);
        if (name == "rms" || name == "rms_area") magnitudes(v, d.intervals->rms);
      }
      values.push_back(v);
    }
    values.push_back(
        {"no_hits", d.label, static_cast<double>(s.no_hit_count), static_cast<double>(s.sample_count)});
    if (d.colour) {
      // P% of a colour limit: of the peak (255) for an RMS, of L*'s range (100) for a delta E.
      const nlohmann::json colour = colour_json(*d.colour);
      for (const auto& [name, value] : colour.items()) {
        if (name.rfind("delta_e_", 0) == 0) values.push_back({name, d.label, value.get<double>(), 100.0});
        if (name == "colour_rms_y") values.push_back({name, d.label, value.get<double>(), kColourPeak});
      }
    }
  }
  if (report.mpeg) {  // MPEG's PSNRs, the worse direction's (--fail-below)
    const MpegFigures& f = report.mpeg->figures;
    const MpegDirection worse_direction = f.symmetric();
    values.push_back({"mpeg_d1_psnr", "", geometry_psnr(worse_direction.d1_mse, f.peak), 0});
    if (f.d2) values.push_back({"mpeg_d2_psnr", "", geometry_psnr(worse_direction.d2_mse, f.peak), 0});
    if (f.colour) values.push_back({"mpeg_y_psnr", "", colour_psnr(worse_direction.ycbcr_mse[0], 1), 0});
    if (report.mpeg->surface) {
      const SurfaceFigures both = worse((*report.mpeg->surface)[0], (*report.mpeg->surface)[1]);
      const auto psnr = [&](const char* name, double mse, const std::optional<Interval>& interval) {
        if (std::isnan(mse)) return;  // D2 without faces (a nearest-vertex method)
        MetricValue v{name, "", geometry_psnr(mse, f.peak), 0};
        if (interval) {
          v.low = geometry_psnr(interval->upper, f.peak);
          v.high = geometry_psnr(interval->lower, f.peak);
        }
        values.push_back(v);
      };
      psnr("mpeg_surface_d1_psnr", both.d1_mse, both.d1_mse_interval);
      psnr("mpeg_surface_d2_psnr", both.d2_mse, both.d2_mse_interval);
    }
  }
  if (report.symmetric()) {
    const TwoSided t = report.two_sided();
    MetricValue hausdorff{"hausdorff", "", t.max_abs, report.diagonal};
    if (t.certified) hausdorff.low = t.hausdorff_lower, hausdorff.high = t.hausdorff_upper;
    values.push_back(hausdorff);
    values.push_back({"mean_both", "", t.mean_abs, report.diagonal});
    values.push_back({"rms_both", "", t.rms, report.diagonal});
  }
  return values;
}

namespace {

// The protocol alone reports its figures: no per-sample files, pictures or pages.
void refuse_outputs_without_symmetric(const MeasureArguments& args, const MeasurePlan& plan) {
  if (!plan.protocol_only) return;
  for (const auto& [option, given] :
       {std::pair<const char*, bool>{"--ibsm", args.ibsm}, {"--samples-out", !args.samples_csv_path.empty()},
        {"--heatmap", !args.heatmap_path.empty()}, {"--heatmap-png", !args.heatmap_png_path.empty()},
        {"--html", !args.html_path.empty()}}) {
    if (given) {
      throw Error(fmt::format("{}: --protocol alone gives the protocol's figures; add --symmetric for the exact "
                              "measurement and its outputs beside them",
                              option));
    }
  }
}

// --protocol tanks-and-temples: the crop file, tau by scene or given, the alignment and curves.
TanksAndTemplesPlan plan_tanks_and_temples(const MeasureArguments& args) {
  TanksAndTemplesPlan tnt;
  if (args.tnt_crop.empty()) throw Error("--protocol tanks-and-temples: needs --tnt-crop (the data set's <scene>.json)");
  for (const auto& [option, path] : {std::pair{"--tnt-crop", args.tnt_crop}, {"--tnt-alignment", args.tnt_alignment}}) {
    if (!path.empty()) require_readable_file(option, path);
  }
  tnt.crop = args.tnt_crop;
  tnt.alignment = args.tnt_alignment;
  if (args.tnt_scene.empty() == !args.tnt_tau) {
    throw Error("--protocol tanks-and-temples: needs one of --tnt-scene (tau as the toolbox's config.py sets it) and "
                "--tnt-tau (tau itself)");
  }
  if (args.tnt_tau) {
    if (!(std::isfinite(*args.tnt_tau) && *args.tnt_tau > 0)) {
      throw Error(fmt::format("--tnt-tau: expected a length > 0 in the models' units (metres), found {}", *args.tnt_tau));
    }
    tnt.options.tau = *args.tnt_tau;
  } else {
    const std::optional<double> tau = tanks_and_temples_tau(args.tnt_scene);
    if (!tau) {
      throw Error(fmt::format("--tnt-scene: '{}' has no tau in the toolbox's config.py; expected one of {}, or --tnt-tau",
                              args.tnt_scene, tanks_and_temples_scenes()));
    }
    tnt.scene = args.tnt_scene;
    tnt.options.tau = *tau;
  }
  tnt.options.voxel_size = tnt.options.tau / 2.0;  // run.py's dTau / 2.0
  tnt.curves_png = args.tnt_curves;
  tnt.plys = args.tnt_plys;
  if (args.tnt_trajectory.empty() != args.tnt_reference_trajectory.empty()) {
    throw Error("--tnt-trajectory: run.py's registration needs both the reconstruction's trajectory and "
                "--tnt-reference-trajectory (the scene's <scene>_COLMAP_SfM.log)");
  }
  if (args.tnt_trajectory.empty()) {
    if (!args.tnt_mapping.empty()) throw Error("--tnt-mapping: only with --tnt-trajectory");
    return tnt;
  }
  if (args.tnt_alignment.empty()) {
    throw Error("--tnt-trajectory: run.py's registration starts from the scene's alignment; expected --tnt-alignment "
                "(<scene>_trans.txt)");
  }
  for (const auto& [option, path] : {std::pair{"--tnt-trajectory", args.tnt_trajectory},
                                     {"--tnt-reference-trajectory", args.tnt_reference_trajectory},
                                     {"--tnt-mapping", args.tnt_mapping}}) {
    if (!path.empty() && !std::ifstream(path)) throw Error(fmt::format("{}: cannot read '{}'", option, path));
  }
  tnt.trajectory = args.tnt_trajectory;
  tnt.reference_trajectory = args.tnt_reference_trajectory;
  tnt.mapping = args.tnt_mapping;
  // Open3D's utility.random.seed takes an int: every run's seed must be one.
  const std::uint32_t highest = 2147483647u - static_cast<std::uint32_t>(std::max(args.protocol_runs, 1) - 1);
  std::uint32_t seed = 0;
  const char* end = args.protocol_seed.data() + args.protocol_seed.size();
  const auto [last, error] = std::from_chars(args.protocol_seed.data(), end, seed);
  if (args.protocol_seed.empty() || error != std::errc() || last != end || seed > highest) {
    throw Error(fmt::format("--protocol-seed: RANSAC's draws need a seed, a whole number from 0 to {} with "
                            "--protocol-runs {}; found '{}'",
                            highest, args.protocol_runs, args.protocol_seed));
  }
  tnt.first_seed = seed;
  tnt.runs = args.protocol_runs;
  return tnt;
}

// --protocol and its options; the data set's files must exist now (they are read before the models).
void plan_protocol(const MeasureArguments& args, MeasurePlan& plan) {
  const bool dtu_given = args.protocol == "dtu", tnt_given = args.protocol == "tanks-and-temples";
  for (const auto& [option, given] : {std::pair{"--dtu-obs-mask", args.dtu_obs_mask}, {"--dtu-plane", args.dtu_plane}}) {
    if (!given.empty() && !dtu_given) throw Error(fmt::format("{}: only with --protocol dtu", option));
  }
  for (const auto& [option, given] :
       {std::pair{"--tnt-crop", !args.tnt_crop.empty()}, {"--tnt-alignment", !args.tnt_alignment.empty()},
        {"--tnt-trajectory", !args.tnt_trajectory.empty()},
        {"--tnt-reference-trajectory", !args.tnt_reference_trajectory.empty()},
        {"--tnt-mapping", !args.tnt_mapping.empty()},
        {"--tnt-scene", !args.tnt_scene.empty()}, {"--tnt-tau", args.tnt_tau.has_value()},
        {"--tnt-curves", !args.tnt_curves.empty()}, {"--tnt-plys", !args.tnt_plys.empty()}}) {
    if (given && !tnt_given) throw Error(fmt::format("{}: only with --protocol tanks-and-temples", option));
  }
  if (args.protocol.empty()) return;
  if (args.pcc) throw Error("--protocol: not with --pcc; run MPEG's figures and the protocol as two measurements");
  if (tnt_given) {
    plan.tnt = plan_tanks_and_temples(args);
    plan.protocol_only = !args.symmetric;
    refuse_outputs_without_symmetric(args, plan);
    return;
  }
  DtuPlan dtu;
  for (const auto& [option, path, target] :
       {std::tuple{"--dtu-obs-mask", args.dtu_obs_mask, &dtu.obs_mask}, {"--dtu-plane", args.dtu_plane, &dtu.plane}}) {
    if (path.empty()) {
      throw Error(fmt::format("--protocol dtu: needs {} (the data set's ObsMask/{}.mat)", option,
                              std::string(option) == "--dtu-plane" ? "Plane<scan>" : "ObsMask<scan>_10"));
    }
    require_readable_file(option, path);
    *target = path;
  }
  for (const auto& [option, value, positive] :
       {std::tuple{"--dtu-density", args.dtu_density, true}, {"--dtu-patch", args.dtu_patch, false},
        {"--dtu-max-dist", args.dtu_max_dist, true}}) {
    if (!(std::isfinite(value) && (positive ? value > 0 : value >= 0))) {
      throw Error(fmt::format("{}: expected a length {} 0 in the models' units (DTU's are mm), found {}", option,
                              positive ? ">" : ">=", value));
    }
  }
  dtu.options.density = args.dtu_density;
  dtu.options.patch = args.dtu_patch;
  dtu.options.max_dist = args.dtu_max_dist;
  dtu.options.runs = args.protocol_runs;
  if (args.protocol_seed == "none") {
    dtu.options.first_seed.reset();
  } else {
    std::uint64_t seed = 0;
    const char* end = args.protocol_seed.data() + args.protocol_seed.size();
    const auto [last, error] = std::from_chars(args.protocol_seed.data(), end, seed);
    if (args.protocol_seed.empty() || error != std::errc() || last != end) {
      throw Error(fmt::format("--protocol-seed: expected an unsigned integer or 'none', found '{}'", args.protocol_seed));
    }
    dtu.options.first_seed = seed;
  }
  plan.dtu = dtu;
  plan.protocol_only = !args.symmetric;
  refuse_outputs_without_symmetric(args, plan);
}

// --shard and --shard-out: one slice of each direction's samples, by a method whose answer at a
// sample is the sample's alone, with the figures a merge can rebuild from the per-sample arrays.
void plan_shard(const MeasureArguments& args, MeasurePlan& plan) {
  if (args.shard.empty()) {
    if (!args.shard_out.empty()) throw Error("--shard-out: only with --shard I/N");
    return;
  }
  plan.shard = parse_shard("--shard", args.shard);
  if (args.shard_out.empty()) throw Error("--shard: needs --shard-out FILE, where the shard's part is written");
  const std::pair<const char*, bool> refused[] = {
      {"--pcc", args.pcc},
      {"--protocol", !args.protocol.empty()},
      {"--ibsm", args.ibsm},
      {"--samples area:auto", plan.sample_spec.automatic},
      {"--samples-out", !args.samples_csv_path.empty()},
      {"--heatmap", !args.heatmap_path.empty()},
      {"--heatmap-png", !args.heatmap_png_path.empty()},
      {"--html", !args.html_path.empty()},
  };
  for (const auto& [option, given] : refused) {
    if (given) {
      throw Error(fmt::format("{}: not with --shard, whose part holds the distance and reconstruction figures; "
                              "measure without --shard for it (roving merge reports the shards' figures)",
                              option));
    }
  }
  if (plan.method->independent_run() == 0) {
    throw Error(fmt::format("--shard: the GL method {} draws its views for all samples at once, so a part would "
                            "not be measured as within the whole; shard roving (exact roving), embree, cgal or a "
                            "vertex baseline",
                            args.method));
  }
}

}  // namespace

MeasurePlan plan_measurement(const MeasureArguments& args) {
  MeasurePlan plan;
  parse_views(args.views, plan.gl);
  plan.gl.backend = parse_gl_backend(args.backend);
  if (args.camera_geometry != "cpu" && args.camera_geometry != "gpu") {
    throw Error(fmt::format("--camera-geometry: expected cpu or gpu, found '{}'", args.camera_geometry));
  }
  plan.gl.gpu_cameras = args.camera_geometry == "gpu";
  plan.gl.resolution = args.resolution;
  plan.method = make_method(args.method, plan.gl);
  if (args.ibsm)
    plan.image_based = ImageBasedOptions{plan.gl.backend, args.ibsm_views, args.ibsm_resolution, true};
  plan.sample_spec = parse_sample_spec(args.samples);
  if (args.seed) {
    if (plan.sample_spec.kind != SampleSpec::Kind::Area) {
      throw Error(fmt::format("--seed: only --samples area:N is random; found --samples {}", args.samples));
    }
    plan.sample_spec.seed = *args.seed;
  }
  plan.max_error = parse_max_error(args.max_error);
  if (args.heatmap_of != "d" && args.heatmap_of != "delta-e") {
    throw Error(fmt::format("--heatmap-of: expected d or delta-e, found '{}'", args.heatmap_of));
  }
  if (args.heatmap_of == "delta-e") {
    plan.heatmap_of = HeatmapQuantity::DeltaE;
    if (!args.heatmap_range.empty()) {
      const MaxErrorSpec range = parse_length("--heatmap-range", args.heatmap_range);
      if (range.percent_of_diagonal) {
        throw Error(fmt::format(
            "--heatmap-range: with --heatmap-of delta-e, expected a delta E > 0 (e.g. 5), found '{}'",
            args.heatmap_range));
      }
      plan.heatmap_delta_e_range = range.value;
    }
  } else if (!args.heatmap_range.empty()) {
    plan.heatmap_range = parse_length("--heatmap-range", args.heatmap_range);
  }
  plan.max_error_text = args.max_error;
  if (!args.semantics.empty()) {
    plan.options.semantics = parse_semantics(args.semantics);
  } else {
    // Metro's two-sided figures are closest-point ones: the default wherever the method has it.
    plan.options.semantics = (args.symmetric || args.pcc) && plan.method->supports(Semantics::Closest)
                                 ? Semantics::Closest
                                 : plan.method->supported_semantics().front();
  }
  plan.options.max_error = 1;  // placeholder until the diagonal is known; checked for support now
  validate_options(*plan.method, plan.options);
  for (const std::string& text : args.gates) {
    plan.gates.push_back(parse_gate(text, args.symmetric));
    if (plan.gates.back().metric == "hausdorff" && plan.options.semantics != Semantics::Closest) {
      throw Error(fmt::format("--fail-above {}: the Hausdorff distance needs --semantics closest, found {}",
                              text, to_string(plan.options.semantics)));
    }
  }
  for (const std::string& text : args.floors) plan.gates.push_back(parse_gate(text, args.symmetric, true));
  const auto type = [](const std::string& text, const char* option) {
    return text.empty() ? std::nullopt : std::optional<ModelType>(parse_model_type(text, option));
  };
  plan.reference_type = type(args.reference_type, "--ref-type");
  plan.test_type = type(args.test_type, "--test-type");
  // --pcc on meshes sets the surfaces' own figures beside mmetric's: both directions.
  plan.symmetric = args.symmetric || args.pcc;
  plan.histogram_bins = args.histogram_bins;
  if (plan.sample_spec.automatic) {
    try {
      plan.precision = parse_max_error(args.precision);  // P% here is of USiAD itself
    } catch (const Error&) {
      throw Error(
          fmt::format("--precision: expected a length > 0 or a percentage of USiAD in (0%, 100%], found '{}'",
                      args.precision));
    }
  }
  if (args.gate_on != "estimate" && args.gate_on != "upper") {
    throw Error(fmt::format("--gate-on: expected 'estimate' or 'upper', found '{}'", args.gate_on));
  }
  plan.gate_on = args.gate_on == "upper" ? GateOn::Upper : GateOn::Estimate;
  // The certified Hausdorff interval wherever the Hausdorff distance is what is asked about: under
  // closest semantics, or --symmetric (Metro's summary).
  if (args.hausdorff_bound != "none") {
    const MaxErrorSpec bound = parse_length("--hausdorff-bound", args.hausdorff_bound);  // checked either way
    if (plan.symmetric || plan.options.semantics == Semantics::Closest) plan.hausdorff_bound = bound;
  }
  // The reconstruction figures need both directions; normal consistency the faces at the hits.
  for (const std::string& text : args.thresholds)
    plan.thresholds.push_back(parse_length("--threshold", text));
  if (!plan.thresholds.empty() && !plan.symmetric) {
    throw Error("--threshold: precision, recall and F-score need both directions; add --symmetric");
  }
  plan.certify_thresholds = args.certify_thresholds;
  if (plan.certify_thresholds) {
    if (plan.thresholds.empty()) throw Error("--certify-thresholds: bounds precision and recall at each --threshold; give one");
    if (plan.options.semantics != Semantics::Closest) {
      throw Error(fmt::format("--certify-thresholds: bounds closest-point shares; found --semantics {}",
                              to_string(plan.options.semantics)));
    }
    if (!plan.hausdorff_bound) {
      throw Error("--certify-thresholds: splits the surfaces down to --hausdorff-bound's length; not with none");
    }
  }
  // Python's per_sample and --samples-out show them; --pcc's surface D2 is computed from them.
  plan.correspondences = args.correspondences || !args.samples_csv_path.empty() || args.pcc;
  plan.options.faces = plan.symmetric || plan.correspondences;
  // Read in single precision, as pc_error reads --resolution: a peak below the least normal float
  // would become 0 or lose its digits, and every geometry PSNR infinite.
  if (args.pcc_resolution && !(*args.pcc_resolution >= std::numeric_limits<float>::min() &&
                               *args.pcc_resolution <= std::numeric_limits<float>::max())) {
    throw Error(fmt::format("--pcc-resolution: expected a peak > 0 that single precision holds, from {:g} to {:g} "
                            "(e.g. 1023 for 10-bit voxels), found {}",
                            std::numeric_limits<float>::min(), std::numeric_limits<float>::max(),
                            *args.pcc_resolution));
  }
  plan.pcc_resolution = args.pcc_resolution;
  plan.pcc_normals = args.pcc_normals;
  plan.pcc_only = args.pcc;
  if (args.pcc) {
    // --pcc's outputs are MPEG's figures in the report: no per-sample files, pictures or pages.
    if (plan.options.semantics != Semantics::Closest) {
      throw Error(fmt::format("--semantics {}: --pcc's surface figures are closest-point ones; leave "
                              "--semantics out, or use a method that has closest semantics",
                              to_string(plan.options.semantics)));
    }
    for (const auto& [option, given] :
         {std::pair<const char*, bool>{"--ibsm", args.ibsm},
          {"--threshold", !args.thresholds.empty()},
          {"--samples-out", !args.samples_csv_path.empty()}, {"--heatmap", !args.heatmap_path.empty()},
          {"--heatmap-png", !args.heatmap_png_path.empty()}, {"--html", !args.html_path.empty()}}) {
      if (given) {
        throw Error(fmt::format("{}: not with --pcc, whose figures are MPEG's (both directions already); "
                                "leave out --pcc for the other figures",
                                option));
      }
    }
  }
  plan_protocol(args, plan);
  plan_shard(args, plan);
  plan.chunk_faces = args.chunk;
  return plan;
}

MeasurePlan plan_command_line(const MeasureArguments& args) {
  try {
    MeasurePlan plan = plan_measurement(args);
    require_writable_paths(args);
    return plan;
  } catch (const UsageError&) {
    throw;
  } catch (const Error& e) {
    throw UsageError(e.what());
  }
}

// Which element of the reference's surface carries each sample's value in the heat map.
HeatmapLayout heatmap_layout(const Model& reference, const SampleSet& samples) {
  if (reference.type == ModelType::Mesh && samples.kind == "faces") return {HeatmapElement::Faces, 1};
  if (reference.type == ModelType::Mesh && samples.kind == "vertices") return {HeatmapElement::Vertices, 1};
  if (reference.type == ModelType::Voxels && samples.kind == "voxel faces") return {HeatmapElement::Faces, 2};
  return {HeatmapElement::Points, 1};  // area:N, Bezier parameter cells, point clouds
}

std::vector<std::string> heatmap_paths(const std::string& path, bool symmetric) {
  if (!symmetric) return {path};
  const std::filesystem::path p(path);
  const auto named = [&](const char* direction) {
    return (p.parent_path() / (p.stem().string() + direction + p.extension().string())).string();
  };
  return {named(".A-to-B"), named(".B-to-A")};
}

bool has_colour(const Model& model) {
  if (model.type == ModelType::Points) return !model.points.colours.empty();
  return model.type == ModelType::Mesh && model.mesh.mesh.has_colour();
}

// REF's colour at each sample: a point cloud's at its points, a mesh's by the colour rule.
std::vector<Colour> reference_colours(const Model& reference, const SampleSet& samples) {
  if (reference.type != ModelType::Points) return sample_colours(reference.mesh.mesh, samples);
  std::vector<Colour> colours;
  colours.reserve(samples.size());
  for (const std::size_t point : samples.elements) colours.push_back(reference.points.colours[point]);
  return colours;
}

void describe_pair(const Model& a, const Model& b, MeasurePlan& plan, MeasureReport& report) {
  if (!plan.pcc_normals.empty() && !(a.type == ModelType::Points && b.type == ModelType::Points)) {
    if (plan.pcc_only) {
      throw Error(fmt::format("--pcc-normals: pc_error's --inputNorm, for two point clouds; {} is a mesh "
                              "(measured by mmetric's rules, which read no normals file)",
                              (a.type == ModelType::Mesh ? a : b).path()));
    }
    throw Error(fmt::format("--pcc-normals: gives A's normals for MPEG's point-cloud figures, which two point "
                            "clouds get (or --pcc); found {} and {}",
                            to_string(a.type), to_string(b.type)));
  }
  // A point cloud's surfels are made (and its points checked) before the long work.
  test_surface(b);
  if (plan.symmetric) test_surface(a);
  report.method = plan.method->name();
  report.semantics = plan.options.semantics;
  plan.options.colour = has_colour(a) && has_colour(b);
  if (plan.heatmap_of == HeatmapQuantity::DeltaE && !plan.options.colour) {
    throw Error(fmt::format("--heatmap-of delta-e: needs colour on both models; {} has none",
                            has_colour(a) ? b.path() : a.path()));
  }
  if (!plan.options.colour) {  // a colour gate fails before the long work, not after it
    std::vector<Gate> colour_gates;
    std::copy_if(plan.gates.begin(), plan.gates.end(), std::back_inserter(colour_gates),
                 [](const Gate& gate) { return is_colour_metric(gate.metric); });
    require_gate_values(colour_gates, {});
  }
  report.max_error_text = plan.max_error.to_string();
  report.seed = plan.sample_spec.seed;
  BoundingBox both = a.bounding_box();
  both.extend(b.bounding_box().min);
  both.extend(b.bounding_box().max);
  report.diagonal_of_both = plan.symmetric;
  report.diagonal = plan.symmetric ? both.diagonal() : a.bounding_box().diagonal();
  plan.options.max_error = plan.max_error.resolve(report.diagonal);
  report.max_error = plan.options.max_error;
  if (plan.hausdorff_bound) report.hausdorff_bound = plan.hausdorff_bound->resolve(report.diagonal);
  require_representable(plan.options.max_error, both, plan.max_error_text);
}

namespace {

// `path`'s point cloud as pc_error holds it: a binary PLY's records read where the file lies,
// straight into single precision, any other file through read_point_cloud (normals as it has them).
MpegPoints read_mpeg_points(const std::string& path, bool with_normals, bool average_normals) {
  if (read_as_ply(path)) {
    const FileBytes file(path, "a .ply point cloud");
    if (const std::optional<PackedPointCloud> packed = ply_packed_points(path, file.bytes())) {
      return mpeg_points(*packed, path, with_normals, average_normals);
    }
  }
  return mpeg_points(read_point_cloud(path, false), path, with_normals, average_normals);
}

}  // namespace

MpegReport mpeg_report(const Model& a, const Model& b, std::optional<double> resolution,
                       const std::string& normals_path) {
  const Stopwatch watch;
  MpegReport report;
  MpegRules rules;
  rules.resolution = resolution;
  rules.mmetric = a.type == ModelType::Mesh || b.type == ModelType::Mesh;
  const auto points_of = [&](const Model& model, bool normals, double& read_seconds) {
    if (model.type == ModelType::Mesh) {
      return mpeg_points(mmetric_samples(model.mesh.mesh, model.path()), model.path(), true, true);
    }
    if (model.points_in_file) {
      const Stopwatch read;
      MpegPoints points = read_mpeg_points(model.path(), normals, rules.mmetric);
      read_seconds = read.seconds();
      return points;
    }
    return mpeg_points(model.points, model.path(), normals && !model.normals_estimated, rules.mmetric);
  };
  MpegPoints a_points, b_points, normals;
  tbb::parallel_invoke([&] { a_points = points_of(a, normals_path.empty(), report.read_seconds[0]); },
                       [&] { b_points = points_of(b, rules.mmetric, report.read_seconds[1]); },
                       [&] {
                         if (normals_path.empty()) return;
                         // Merged as A's are: under mmetric's rules, duplicates' normals averaged.
                         normals = mpeg_points(load_point_cloud(normals_path), normals_path, true, rules.mmetric);
                       });
  if (!normals_path.empty()) use_normals_of(a_points, normals, normals_path);
  report.figures = mpeg_point_cloud_figures(a_points, b_points, rules, a.path());
  report.normals_from = normals_path;
  report.a_sampled = a.type == ModelType::Mesh;
  report.points_read[0] = a_points.points_read;
  report.points_read[1] = b_points.points_read;
  report.points[0] = a_points.size();
  report.points[1] = b_points.size();
  report.coloured[0] = !a_points.colours.empty();
  report.coloured[1] = !b_points.colours.empty();
  report.normals[0] = !a_points.normals.empty();
  report.normals[1] = !b_points.normals.empty();
  // The clouds were read side by side: their reading is the run's loading, not the figures'.
  report.seconds = watch.seconds() - std::max(report.read_seconds[0], report.read_seconds[1]);
  return report;
}

namespace {

// A binary PLY mesh's vertices alone (open_triangle_stream reads them, checked, before any face);
// nullopt for any other file.
std::optional<Model> mesh_vertices(const std::string& path) {
  if (!read_as_ply(path)) return std::nullopt;
  const std::unique_ptr<TriangleStream> stream = open_triangle_stream(path, 0);
  if (!stream) return std::nullopt;
  if (stream->position_count() == 0) throw Error(fmt::format("{}: no vertices; expected a mesh", path));
  Model model;
  model.type = ModelType::Points;
  model.mesh.path = path;
  model.mesh_vertices_only = true;
  model.points.positions.resize(stream->position_count());
  for (std::size_t i = 0; i < model.points.positions.size(); ++i) {
    model.points.positions[i] = stream->position(static_cast<int>(i));
  }
  return model;
}

}  // namespace

Model load_for(const MeasurePlan& plan, const std::string& path, std::optional<ModelType> type, bool reference) {
  const bool raw = plan.pcc_only || plan.protocol_only;  // clouds as their files have them
  const ModelType found = type ? *type : model_type_of(path);
  if (plan.protocol_only && found == ModelType::Mesh && (plan.tnt || (plan.dtu && reference))) {
    if (std::optional<Model> vertices = mesh_vertices(path)) return std::move(*vertices);
  }
  if (!raw || found != ModelType::Points) return load_model(path, type);
  Model model;
  model.type = ModelType::Points;
  model.mesh.path = path;
  if (plan.pcc_only) {
    model.points_in_file = true;  // read by MPEG's figures, straight into their single precision
  } else {
    model.points = load_point_cloud(path, type);
  }
  return model;
}

void measure_point_clouds(const Model& a, const Model& b, const MeasurePlan& plan, MeasureReport& report,
                          Progress& progress, std::string& stage, const WarnFn& warn) {
  for (const Model* model : {&a, &b}) {
    if (model->type != ModelType::Points && model->type != ModelType::Mesh) {
      throw Error(fmt::format("{}: --pcc measures point clouds and meshes; found a {} model", model->path(),
                              to_string(model->type)));
    }
  }
  report.pcc_only = true;
  stage = fmt::format("computing MPEG's point-cloud figures of {} and {}", a.path(), b.path());
  progress.stage("MPEG point-cloud figures");
  report.mpeg = mpeg_report(a, b, plan.pcc_resolution, plan.pcc_normals);
  progress.clear();
  for (int side = 0; side < 2; ++side) report.load_seconds[side] += report.mpeg->read_seconds[side];
  const bool* coloured = report.mpeg->coloured;
  if (coloured[0] != coloured[1]) {
    warn({fmt::format("colour: {} has colour but {} has none; no colour figures", (coloured[0] ? a : b).path(),
                      (coloured[0] ? b : a).path())});
  }
}

namespace {

// One direction with REF read a block of faces at a time (streamed_measurement.h), `a` its summary.
// A shard measures its slice of the samples (`slice`) and bounds its share of the triangles, as it
// would with REF whole, keeping what its part holds.
void measure_streamed_direction(const Model& a, const TriangleMesh& test_mesh, TriangleStream& stream,
                                MeasurePlan& plan, double hausdorff_bound, const std::optional<SampleRange>& slice,
                                Progress& progress, std::string& stage, DirectionReport& d) {
  stage = fmt::format("measuring {} {} faces at a time against {} triangles with {}", a.path(), plan.chunk_faces,
                      test_mesh.triangle_count(), plan.method->name());
  progress.stage("measuring");
  validate_options(*plan.method, plan.options);
  d.result.build_seconds = plan.method->build(test_mesh);
  const TriangleMesh& m = a.mesh.mesh;
  StreamedResult streamed = measure_streamed(
      stream, *plan.method, plan.options, plan.histogram_bins, plan.chunk_faces,
      slice ? slice->last - slice->first : m.triangle_count() - m.degenerate_triangle_count(), progress.callback(),
      slice);
  plan.method->release();
  d.samples = std::move(streamed.samples);
  if (slice) {  // what the part holds: the slice's figures, and the count of the whole's skipped faces
    d.result.signed_distance = std::move(streamed.slice.signed_distance);
    d.result.hit = std::move(streamed.slice.hit);
    d.samples.skipped_degenerate_faces = m.degenerate_triangle_count();
  }
  d.result.query_seconds = streamed.query_seconds;
  d.result.gl = std::move(streamed.gl);
  d.statistics = streamed.statistics;
  d.signs = streamed.signs;
  d.heatmap_range = streamed.heatmap_range;
  d.chunk_faces = plan.chunk_faces;
  d.chunks = streamed.chunks;
  if (plan.hausdorff_bound) {  // a pass of its own: TEST's closest-point structure, REF's blocks as meshes
    stage = fmt::format("bounding the Hausdorff distance from {} to {}, {} faces at a time", a.path(),
                        d.test->path(), plan.chunk_faces);
    progress.stage("certified Hausdorff");
    CertifiedHausdorff bound(test_mesh, hausdorff_bound);
    MeshBlocks blocks(stream, plan.chunk_faces);
    const ProgressFn tell = progress.callback();
    const auto [first, last] =  // of REF's triangles
        plan.shard ? plan.shard->range(m.triangle_count()) : std::pair{std::size_t{0}, m.triangle_count()};
    TriangleMesh block;
    for (std::size_t before = 0; before < last && blocks.next(block); before += block.triangle_count()) {
      const std::size_t from = std::max(first, before), to = std::min(last, before + block.triangle_count());
      if (from < to) bound.add(block, from - before, to - before);
      if (tell) tell("faces", blocks.faces_read(), stream.face_count());
    }
    d.hausdorff = bound.interval();
  }
}

}  // namespace

void measure_models(const Model& a, const Model& b, MeasurePlan& plan, MeasureReport& report,
                    Progress& progress, std::string& stage, const WarnFn& warn, const SampleSet* samples_of_a,
                    Model* releasable_a, TriangleStream* streamed_a, ProtocolInputs* protocol) {
  warn(a.mesh.warnings);
  if (&b != &a) warn(b.mesh.warnings);
  warn(alignment_warnings(a, b, plan.options.max_error));
  if (has_colour(a) != has_colour(b)) {
    const Model& coloured = has_colour(a) ? a : b;
    const Model& plain = has_colour(a) ? b : a;
    warn({fmt::format("colour: {} has colour but {} has none; no colour figures", coloured.path(),
                      plain.path())});
  }
  if (!streamed_a) warn(orientation_warnings(a));  // it reads every triangle at once
  if (plan.symmetric) warn(orientation_warnings(b));

  if (plan.shard) report.shard = ShardSlice{*plan.shard, report.warnings};  // the models' warnings alone
  plan.method->set_progress(progress.callback());
  std::vector<double> thresholds;  // --threshold in model units
  for (const MaxErrorSpec& tau : plan.thresholds) thresholds.push_back(tau.resolve(report.diagonal));
  const std::vector<std::pair<const Model*, const Model*>> pairs =
      plan.symmetric ? std::vector<std::pair<const Model*, const Model*>>{{&a, &b}, {&b, &a}}
                     : std::vector<std::pair<const Model*, const Model*>>{{&a, &b}};
  for (const auto& [reference, test] : pairs) {
    DirectionReport& d = report.directions.emplace_back();
    d.reference = reference;
    d.test = test;
    d.reference_json = model_json(*reference);
    d.test_json = model_json(*test);
    if (plan.symmetric) d.label = reference == &a ? "A -> B" : "B -> A";
    stage = fmt::format("sampling {} ({})", reference->path(), plan.sample_spec.to_string());
    progress.stage(fmt::format("{}sampling", d.label.empty() ? "" : d.label + ": "));
    const TriangleMesh& test_mesh = test_surface(*test);
    SampleSpec spec = plan.sample_spec;
    if (spec.automatic) {
      spec.count = kAutoFirstSamples;
      d.auto_sampling.emplace();
    }
    // A shard's slice of `total` samples, beginning at a whole run of the method's (exact
    // roving's camera batches); never empty.
    const auto slice = [&](std::size_t total) {
      const std::size_t run = plan.method->independent_run();
      const auto [first, last] = plan.shard->range(total, run);
      if (first == last) {
        const std::size_t most = std::max<std::size_t>(1, total / run);
        throw Error(fmt::format("--shard {}/{}: this slice of {}'s {} samples is empty; use at most {} shard{}{}",
                                plan.shard->index, plan.shard->count, reference->path(), total, most,
                                most == 1 ? "" : "s",
                                run > 1 ? fmt::format(" ({} cuts at multiples of {} samples)", plan.method->name(), run)
                                        : ""));
      }
      return std::pair{first, last};
    };
    if (plan.shard && spec.kind == SampleSpec::Kind::Area) {  // a mesh draws only its slice
      std::tie(spec.first, spec.last) = slice(spec.count);
    }
    const bool streamed = reference == &a && streamed_a;
    if (streamed) {  // REF a block of faces at a time, its certified bound too
      std::optional<SampleRange> samples;
      if (plan.shard) {
        const TriangleMesh& m = a.mesh.mesh;
        d.slice_total = m.triangle_count() - m.degenerate_triangle_count();
        const auto [first, last] = slice(d.slice_total);
        d.slice_first = first;
        samples = SampleRange{first, last};
      }
      measure_streamed_direction(a, test_mesh, *streamed_a, plan, report.hausdorff_bound, samples, progress, stage,
                                 d);
    } else {
      // area:auto measures again with more samples until USiAD's interval is as narrow as asked.
      for (int round = 1;; ++round) {
        if (reference == &a && samples_of_a && !spec.automatic) {
          d.samples = *samples_of_a;
        } else if (reference == releasable_a && !spec.automatic) {
          d.samples = reference_samples_releasing(*releasable_a, spec);
        } else {
          d.samples = reference_samples(*reference, spec);
        }
        if (plan.shard) {  // this shard's slice of the pair's samples: the same samples whatever N
          const std::size_t total = spec.kind == SampleSpec::Kind::Area ? spec.count : d.samples.size();
          const auto [first, last] = slice(total);
          d.slice_first = first;
          d.slice_total = total;
          // A mesh's area samples come drawn as the slice already; all others are sliced here.
          if (d.samples.size() != last - first) d.samples = d.samples.slice(first, last);
        }
        stage = fmt::format("measuring {} samples against {} triangles with {}", d.samples.size(),
                            test_mesh.triangle_count(), plan.method->name());
        progress.stage(fmt::format("{}measuring", d.label.empty() ? "" : d.label + ": "));
        d.result = measure_distances(*plan.method, test_mesh, d.samples, plan.options);
        d.statistics = compute_statistics(d.result.signed_distance, d.result.hit, d.samples.weights,
                                          plan.options.max_error, plan.histogram_bins);
        if (d.samples.kind.rfind("area:", 0) == 0 && d.samples.size() >= 2) {
          d.intervals = sampling_intervals(d.result.signed_distance, d.result.hit, plan.options.max_error);
        }
        if (!spec.automatic) break;
        auto& aim = *d.auto_sampling;
        aim.rounds = round;
        aim.target = plan.precision->percent_of_diagonal
                         ? plan.precision->value / 100 * d.intervals->usiad.estimate
                         : plan.precision->value;
        aim.reached = (d.intervals->usiad.upper - d.intervals->usiad.lower) / 2;
        aim.met = aim.reached <= aim.target;
        if (aim.met || spec.count >= kAutoMaxSamples || round == 5) break;
        // The half-width shrinks as 1 / sqrt(N): the N that reaches the target, with 10% to spare.
        const double ratio = aim.target > 0 ? aim.reached / aim.target : 10.0;
        spec.count = static_cast<std::size_t>(
            std::min<double>(kAutoMaxSamples, std::ceil(spec.count * ratio * ratio * 1.1)));
      }
      d.signs = sign_counts(d.result);
      d.heatmap_range = plan.heatmap_range ? plan.heatmap_range->resolve(report.diagonal)
                                           : default_heatmap_range(d.result, report.max_error);
    }
    if (plan.hausdorff_bound && reference->type != ModelType::Points && !streamed) {
      stage = fmt::format("bounding the Hausdorff distance from {} to {}", reference->path(), test->path());
      progress.stage(fmt::format("{}certified Hausdorff", d.label.empty() ? "" : d.label + ": "));
      const TriangleMesh& surface = test_surface(*reference);
      if (plan.shard) {  // this shard's slice of the reference's triangles
        const auto [first, last] = plan.shard->range(surface.triangle_count());
        d.hausdorff = certified_hausdorff(surface, test_mesh, report.hausdorff_bound, first, last);
      } else {
        d.hausdorff = certified_hausdorff(surface, test_mesh, report.hausdorff_bound);
      }
      if (plan.certify_thresholds && test->type != ModelType::Points) {
        stage = fmt::format("bounding the share of {} within each threshold of {}", reference->path(), test->path());
        progress.stage(fmt::format("{}certified precision and recall", d.label + ": "));
        const auto [first, last] =
            plan.shard ? plan.shard->range(surface.triangle_count()) : std::pair{std::size_t{0}, surface.triangle_count()};
        d.area_within = certified_area_within(surface, test_mesh, thresholds, report.hausdorff_bound, first, last);
      }
    }
    if (plan.correspondences)
      d.correspondences = correspondences(d.samples, test_mesh, d.result, plan.options.semantics);
    if (plan.options.colour && d.result.hit_face.empty() && d.result.hit_colour.empty()) {
      if (&d == &report.directions.front()) warn({no_colour_warning(plan.method->name())});
    } else if (plan.options.colour) {
      stage = "comparing colours";
      d.colour_pairs = colour_pairs(reference_colours(*reference, d.samples), d.samples, test_mesh, d.result,
                                    plan.options.semantics);
      d.colour = compute_colour_statistics(*d.colour_pairs, d.result.hit);
    }
    std::vector<std::string> found = result_warnings(d.statistics, plan.options.semantics);
    for (std::string& line : found) line = (d.label.empty() ? "" : d.label + ": ") + line;
    warn(found);
  }
  FamilyInputs inputs{a, b, plan, protocol, progress, stage, warn};
  for (const FigureFamily& family : figure_families()) {
    if (family.asked(plan, a, b)) family.compute(inputs, report);
  }
  progress.clear();
}

nlohmann::json input_json(const std::string& role, const std::string& path, const std::string& sha256) {
  if (sha256.empty()) return {{"role", role}, {"path", path}, {"bytes", nullptr}, {"sha256", nullptr}};
  return {{"role", role}, {"path", path}, {"bytes", std::filesystem::file_size(path)}, {"sha256", sha256}};
}

namespace {

// Whether nothing after sampling reads REF's geometry: one direction, sampled once, and no figure
// or output that measures or draws REF itself (colour, IBSM, heat maps, the web page, and unless
// `blocks_bound_it`, the certified Hausdorff bound, which a streamed REF's blocks give).
bool reference_only_sampled(const MeasureArguments& args, const MeasurePlan& plan, bool blocks_bound_it = false) {
  return !plan.symmetric && !plan.sample_spec.automatic && (!plan.hausdorff_bound || blocks_bound_it) &&
         !plan.certify_thresholds && !plan.options.colour &&
         !plan.image_based && args.heatmap_path.empty() && args.heatmap_png_path.empty() &&
         args.html_path.empty();
}

// REF's file, to be read a block of faces at a time, where it is a binary PLY of plain triangles, a
// binary STL or a plain OBJ with more faces than --chunk and nothing asked for needs it whole: one direction of
// face samples by a method whose answers do not depend on every sample at once (not the GL methods
// that draw views: independent_run()), and no output that reads REF or every sample after the
// measurement. A shard's part is such an output for its slice alone: a shard streams too.
std::unique_ptr<TriangleStream> reference_stream(const MeasureArguments& args, const MeasurePlan& plan) {
  const bool wanted = plan.chunk_faces > 0 && reference_only_sampled(args, plan, true) && !plan.pcc_only && !plan.dtu &&
                      !plan.tnt && !plan.correspondences && plan.thresholds.empty() &&
                      args.samples_csv_path.empty() && plan.sample_spec.kind == SampleSpec::Kind::Faces &&
                      plan.method->independent_run() > 0 &&
                      (!plan.reference_type || *plan.reference_type == ModelType::Mesh);
  return wanted ? open_triangle_stream(args.reference_path, plan.chunk_faces) : nullptr;
}

// The model a streamed REF stands as in the report: what its whole mesh would say of itself.
std::unique_ptr<Model> streamed_model(TriangleStream& stream, std::size_t chunk_faces, const ProgressFn& progress) {
  StreamedReference summary = summarise(stream, chunk_faces, progress);
  auto model = std::make_unique<Model>();
  model->type = ModelType::Mesh;
  model->mesh.path = stream.path();
  model->mesh.mesh = std::move(summary.summary);
  model->mesh.dropped_repeated_vertex_faces = summary.dropped_repeated_vertex_faces;
  model->mesh.triangulated_polygons = summary.triangulated_polygons;
  return model;
}

}  // namespace

MeasureRun measure_run(const MeasureArguments& args, std::string& stage, Progress& progress,
                       const std::function<void(const MeasureRun&)>& on_described,
                       std::unique_ptr<Model> given_a, std::unique_ptr<Model> given_b) {
  const Stopwatch total;
  MeasureRun run;
  // Parse every option before the (slow) loads, so a typo fails at once.
  run.plan = plan_command_line(args);
  MeasurePlan& plan = run.plan;
  MeasureReport& report = run.report;
  const auto hash = [](bool given, const std::string& path) {
    return given ? std::async(std::launch::deferred, [] { return std::string(); })
                 : std::async(std::launch::async, file_sha256, path);
  };
  const auto load = [&](const std::string& path, std::optional<ModelType> type, bool reference) {
    return load_for(plan, path, type, reference);
  };
  ProtocolInputs protocol;  // the data set's files before the models: a wrong one fails at once
  if (plan.dtu) {
    stage = fmt::format("reading the DTU data set's files {} and {}", plan.dtu->obs_mask, plan.dtu->plane);
    protocol.dtu = read_dtu_files(*plan.dtu);
  }
  std::optional<TanksAndTemplesFiles>& tnt_files = protocol.tnt;
  if (plan.tnt) {
    stage = fmt::format("reading the Tanks and Temples scene's files {}{}", plan.tnt->crop,
                        plan.tnt->alignment.empty() ? "" : " and " + plan.tnt->alignment);
    tnt_files = read_tanks_and_temples_files(*plan.tnt);
  }
  // The inputs' hashes on another core while they load.
  if (plan.shard && (given_a || given_b)) {
    throw UsageError("--shard: the models must be files (a shard's part names them by path and hash for the merge)");
  }
  auto reference_hash = hash(given_a != nullptr, args.reference_path);
  auto test_hash = hash(given_b != nullptr, args.test_path);
  // The test loads on another core while the reference does; where both fail, the reference's
  // error is the one reported (the test's future is waited for and dropped).
  std::future<std::unique_ptr<Model>> test_load;
  if (!given_b) {
    test_load = std::async(std::launch::async, [&] {
      const Stopwatch watch;
      auto model = std::make_unique<Model>(load(args.test_path, plan.test_type, false));
      report.load_seconds[1] = watch.seconds();
      return model;
    });
  }
  const Stopwatch watch;
  const std::unique_ptr<TriangleStream> stream = given_a ? nullptr : reference_stream(args, plan);
  if (given_a) {
    run.a = std::move(given_a);
  } else if (stream) {
    stage = fmt::format("reading the reference {} {} faces at a time", args.reference_path, plan.chunk_faces);
    progress.stage("reading " + file_name(args.reference_path));
    run.a = streamed_model(*stream, plan.chunk_faces, progress.callback());
  } else {
    stage = fmt::format("loading the reference {}", args.reference_path);
    progress.stage("loading " + file_name(args.reference_path));
    run.a = std::make_unique<Model>(load(args.reference_path, plan.reference_type, true));
  }
  report.load_seconds[0] = watch.seconds();
  if (given_b) {
    run.b = std::move(given_b);
  } else {
    stage = fmt::format("loading the test {}", args.test_path);
    progress.stage("loading " + file_name(args.test_path));
    run.b = test_load.get();
  }
  if (tnt_files && tnt_files->trajectories) {
    stage = fmt::format("registering the test {} to the reference {} as run.py does (its trajectory {})",
                        run.b->path(), run.a->path(), plan.tnt->trajectory);
    progress.stage("Tanks and Temples registration");
    const Stopwatch watch;
    protocol.tnt_registrations = register_tanks_and_temples(*run.a, *run.b, *plan.tnt, *tnt_files, progress.callback());
    protocol.tnt_registration_seconds = watch.seconds();
    progress.clear();
  }
  if (tnt_files) {
    stage = fmt::format("aligning the test {} by {}", run.b->path(),
                        tnt_files->trajectories ? "run.py's registration" : plan.tnt->alignment);
    align_test_model(*run.b, tnt_files->alignment);  // as the toolbox moves the reconstruction, before all else
  }
  Model& a = *run.a;
  const Model& b = *run.b;
  // The run's end: provenance (the hashes, computed meanwhile on other threads) and the gates.
  const auto finish = [&] {
    report.provenance = {
        {"tool", tool_json()},
        {"command_line", args.command_line},
        {"inputs",
         {input_json(args.symmetric || args.pcc ? "A" : "reference", a.path(), reference_hash.get()),
          input_json(args.symmetric || args.pcc ? "B" : "test", b.path(), test_hash.get())}}};
    require_gate_values(plan.gates, gate_values(report));
    report.total_seconds = total.seconds();
  };

  const auto warn = [&](const std::vector<std::string>& lines) {
    if (lines.empty()) return;
    progress.clear();
    for (const std::string& line : lines) {
      if (!args.quiet && args.warnings_to_stderr) std::fprintf(stderr, "roving: warning: %s\n", line.c_str());
      report.warnings.push_back(line);
    }
  };
  // --pcc: point clouds (one at least) get MPEG's figures alone; two meshes the surface
  // measurement too, for the exact figures beside mmetric's.
  if (plan.pcc_only && !(a.type == ModelType::Mesh && b.type == ModelType::Mesh)) {
    report.pcc_only = true;
    measure_point_clouds(a, b, plan, report, progress, stage, warn);
    if (on_described) on_described(run);  // after: a cloud is read as it is measured (points_in_file)
    finish();
    return run;
  }
  if (plan.protocol_only) {
    report.protocol_only = true;
    // The header is written now, before the protocol's figures exist: it names the protocol asked.
    report.protocol = plan.dtu ? "dtu" : "tanks-and-temples";
    if (on_described) on_described(run);
    FamilyInputs inputs{a, b, plan, &protocol, progress, stage, warn};
    for (const FigureFamily& family : figure_families()) {
      if (family.protocol && family.asked(plan, a, b)) family.compute(inputs, report);
    }
    finish();
    return run;
  }
  describe_pair(a, b, plan, report);
  if (on_described) on_described(run);
  measure_models(a, b, plan, report, progress, stage, warn, nullptr,
                 reference_only_sampled(args, plan) ? &a : nullptr, stream.get(), &protocol);
  finish();
  return run;
}

void write_measure_outputs(const MeasureArguments& args, const MeasureRun& run, std::string& stage) {
  const MeasurePlan& plan = run.plan;
  const MeasureReport& report = run.report;
  // Every output file is written whole to a temporary file first; only when all succeeded are
  // they moved into place, so a failed run changes none of them.
  stage = "writing the outputs";
  std::vector<std::unique_ptr<AtomicFile>> outputs;
  if (!args.samples_csv_path.empty()) {
    outputs.push_back(std::make_unique<AtomicFile>(args.samples_csv_path));
    for (const DirectionReport& d : report.directions) {
      write_samples_csv(outputs.back()->stream(), d.samples, d.result, d.label,
                        &d == &report.directions.front(), d.colour_pairs ? &*d.colour_pairs : nullptr,
                        d.correspondences ? &*d.correspondences : nullptr);
    }
    outputs.back()->close_stream();
  }
  // One heat map per direction, each on its own reference (under --symmetric, A's then B's).
  for (std::size_t i = 0; i < report.directions.size(); ++i) {
    if (args.heatmap_path.empty() && args.heatmap_png_path.empty()) break;
    const DirectionReport& d = report.directions[i];
    const Model& reference = *d.reference;
    const TriangleMesh* surface = reference.type == ModelType::Points ? nullptr : &reference.mesh.mesh;
    const HeatmapLayout layout = heatmap_layout(reference, d.samples);
    const bool delta_e = plan.heatmap_of == HeatmapQuantity::DeltaE;
    const std::vector<float> per_sample =
        delta_e ? sample_delta_e(*d.colour_pairs, d.result.hit) : distances_or_nan(d.result);
    const HeatmapScale scale{
        plan.heatmap_of,
        delta_e ? plan.heatmap_delta_e_range.value_or(percentile_99(per_sample, 1)) : d.heatmap_range};
    if (!args.heatmap_path.empty()) {
      outputs.push_back(
          std::make_unique<AtomicFile>(heatmap_paths(args.heatmap_path, report.symmetric())[i]));
      write_heatmap_ply(outputs.back()->stream(), surface, layout, d.samples, per_sample, scale);
      outputs.back()->close_stream();
    }
    if (!args.heatmap_png_path.empty()) {
      stage = "rendering the heat-map picture";
      Picture picture;
      picture.title = fmt::format("{} (REF) against {} (TEST){}", file_name(reference.path()),
                                  file_name(d.test->path()), d.label.empty() ? "" : ", " + d.label);
      if (delta_e) {
        picture.subtitle = fmt::format(
            "colour difference by {} ({} semantics), {} samples ({}); CIEDE2000 mean {:.3g}, p95 {:.3g}, "
            "{} no-hits without a colour",
            report.method, to_string(report.semantics), d.samples.size(), d.samples.kind,
            d.colour->delta_e_mean, d.colour->delta_e_p95, d.colour->no_hit);
        picture.legend.no_value_label = "no hit: no colour";
      } else {
        picture.subtitle = fmt::format(
            "d by {}, {} semantics, {} samples ({}); USiAD {:.4g} ({:.3g}% of the diagonal), {} no-hits",
            report.method, to_string(report.semantics), d.samples.size(), d.samples.kind, d.statistics.usiad,
            100 * d.statistics.usiad / report.diagonal, d.statistics.no_hit_count);
      }
      picture.legend.quantity = plan.heatmap_of;
      picture.legend.range = scale.range;
      picture.legend.diagonal = report.diagonal;
      const std::vector<float> values = heatmap_values(surface, layout, d.samples, per_sample);
      outputs.push_back(
          std::make_unique<AtomicFile>(heatmap_paths(args.heatmap_png_path, report.symmetric())[i]));
      write_picture_png(outputs.back()->stream(), plan.gl.backend,
                        coloured_surface(surface, layout, d.samples, heatmap_colours(values, scale)),
                        picture);
      outputs.back()->close_stream();
    }
  }
  if (report.tnt && !report.tnt->curves_png.empty()) {
    stage = "drawing the precision and recall curves";
    const TanksAndTemplesReport& t = *report.tnt;
    PrecisionRecallChart chart;
    chart.title = fmt::format("Precision and recall: {}, F-score {:.2f}%", t.scene.empty() ? file_name(run.b->path()) : t.scene,
                              100 * t.figures.fscore);
    chart.subtitle = fmt::format("Tanks and Temples' EvaluateHisto: tau {:.6g}, precision {:.2f}%, recall {:.2f}%",
                                 t.figures.options.tau, 100 * t.figures.precision, 100 * t.figures.recall);
    chart.tau = t.figures.options.tau;
    chart.plot_stretch = t.figures.options.plot_stretch;
    chart.edges = t.figures.edges;
    chart.cumulative_precision = t.figures.cumulative_precision;
    chart.cumulative_recall = t.figures.cumulative_recall;
    if (t.exact) {
      const auto exact = [](const Estimate& e) { return PrecisionRecallChart::Exact{e.value, e.lower, e.upper}; };
      chart.exact_precision = exact(t.exact->accuracy.within.front());
      chart.exact_recall = exact(t.exact->completeness.within.front());
    }
    outputs.push_back(std::make_unique<AtomicFile>(t.curves_png));
    write_precision_recall_png(outputs.back()->stream(), chart);
    outputs.back()->close_stream();
  }
  if (report.tnt && report.tnt->clouds) {
    stage = "writing the viewing files";
    const TanksAndTemplesReport& t = *report.tnt;
    const double max_distance = 3 * t.figures.options.tau;  // the toolbox's 3 * threshold
    for (const auto& [suffix, points, distances] :
         {std::tuple{".precision.ply", &t.clouds->reconstruction, &t.clouds->precision_distances},
          std::tuple{".recall.ply", &t.clouds->ground_truth, &t.clouds->recall_distances}}) {
      outputs.push_back(std::make_unique<AtomicFile>(t.plys + suffix));
      write_distance_cloud_ply(outputs.back()->stream(), *points, *distances, max_distance);
      outputs.back()->close_stream();
    }
  }
  if (!args.shard_out.empty()) {
    outputs.push_back(std::make_unique<AtomicFile>(args.shard_out));
    write_shard_part(outputs.back()->stream(), args, run);
    outputs.back()->close_stream();
  }
  if (!args.json_path.empty() && args.json_path != "-") {
    const std::string json = to_json(report).dump(2) + "\n";
    outputs.push_back(std::make_unique<AtomicFile>(args.json_path));
    std::fputs(json.c_str(), outputs.back()->stream());
    outputs.back()->close_stream();
  }
  if (!args.html_path.empty()) {
    stage = "writing the web page";
    outputs.push_back(std::make_unique<AtomicFile>(args.html_path));
    write_html_page(outputs.back()->stream(),
                    measurement_page(report, format_header(*run.a, *run.b, report) + format_body(report),
                                     to_json(report)));
    outputs.back()->close_stream();
  }
  for (const auto& output : outputs) output->commit();
}

int run_measure(const MeasureArguments& args, std::string& stage) {
  Progress progress(args.quiet);
  const bool text_to_stdout = args.json_path != "-";
  const MeasureRun run = measure_run(args, stage, progress, [&](const MeasureRun& described) {
    if (!text_to_stdout) return;  // the header as soon as the models are known
    progress.clear();
    write_stdout(format_header(*described.a, *described.b, described.report));
  });
  write_measure_outputs(args, run, stage);
  const MeasureReport& report = run.report;
  if (report.shard) {  // a slice's figures are not the pair's: roving merge reports them, and gates them
    if (!text_to_stdout) {
      write_stdout(to_json(report).dump(2) + "\n");
      return 0;
    }
    std::vector<std::string> slices;
    for (const DirectionReport& d : report.directions) {
      slices.push_back(fmt::format("{}samples {} to {} of {}", d.label.empty() ? "" : d.label + ": ", d.slice_first,
                                   d.slice_first + d.statistics.sample_count - 1, d.slice_total));
    }
    write_stdout(fmt::format("shard {}/{}: {} measured in {:.3g} s; part written to {} (roving merge gives the "
                             "figures)\n",
                             report.shard->shard.index, report.shard->shard.count, fmt::join(slices, "; "),
                             report.total_seconds, args.shard_out));
    return 0;
  }
  write_stdout(text_to_stdout ? format_body(report) : to_json(report).dump(2) + "\n");

  return apply_gates(run.plan.gates, gate_values(report), run.plan.gate_on);
}

}  // namespace roving
