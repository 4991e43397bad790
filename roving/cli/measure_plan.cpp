// `roving measure`'s options planned (measure.h): every value and combination checked, and the
// files a protocol reads found, before any model is read.
#include "measure.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <charconv>
#include <filesystem>
#include <fstream>
#include <limits>

#include "roving/core/error.h"
#include "roving/registry/method_registry.h"

namespace roving {
namespace {

// A length or P% of the diagonal, for `option`: --max-error's rules under another name.
MaxErrorSpec parse_length(const std::string& option, const std::string& text) {
  try {
    return parse_max_error(text);
  } catch (const Error& e) {
    const std::string message = e.what();
    throw Error(option + message.substr(message.find(':')));
  }
}

void require_writable_paths(const MeasureArguments& args) {
  std::vector<std::pair<std::string, std::string>> outputs = {
      {"--json", args.json_path}, {"--samples-out", args.samples_csv_path}, {"--html", args.html_path}};
  for (const auto& [option, given] :
       {std::pair{"--heatmap", args.heatmap_path}, {"--heatmap-png", args.heatmap_png_path}}) {
    if (given.empty()) continue;
    for (const std::string& path : heatmap_paths(given, args.symmetric)) outputs.emplace_back(option, path);
  }
  if (args.json_path == "-" && args.samples_csv_path == "-") {
    throw Error("--json - and --samples-out -: only one of them can write to standard output; give the other a file");
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
  plan.gl.camera_geometry = parse_camera_geometry(args.camera_geometry);
  plan.gl.cull_views = args.view_culling != "none";
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
  // would become 0 or lose its digits, and every geometry PSNR infinite. 0 itself is pc_error's
  // "none given" (its default, and what `-r 0` asks for): the default peak.
  const bool default_peak = args.pcc_resolution && *args.pcc_resolution == 0;
  if (args.pcc_resolution && !default_peak &&
      !(*args.pcc_resolution >= std::numeric_limits<float>::min() &&
        *args.pcc_resolution <= std::numeric_limits<float>::max())) {
    throw Error(fmt::format("--pcc-resolution: expected a peak > 0 that single precision holds, from {:g} to {:g} "
                            "(e.g. 1023 for 10-bit voxels), or 0 for the default peak, found {}",
                            std::numeric_limits<float>::min(), std::numeric_limits<float>::max(),
                            *args.pcc_resolution));
  }
  plan.pcc_resolution = default_peak ? std::nullopt : args.pcc_resolution;
  if (!args.pcc_normals.empty()) require_readable_file("--pcc-normals", args.pcc_normals);
  plan.pcc_normals = args.pcc_normals;
  plan.pcc_options.dropdups = args.pcc_dropdups;
  plan.pcc_options.neighbors_proc = args.pcc_neighbors_proc;
  plan.pcc_options.average_normals = args.pcc_average_normals != 0;
  plan.pcc_options.ycocg = args.pcc_mse_space == 8;
  plan.pcc_b_own_normals = args.pcc_normal_calc_modification;
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

}  // namespace roving
