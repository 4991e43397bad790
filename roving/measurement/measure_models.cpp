// Measuring a loaded pair (measure_models.h): the pair described, each direction sampled and
// measured, the families of figures computed from what the directions measured.
#include "measure_models.h"

#include <fmt/format.h>
#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <cmath>
#include <memory>

#include "checks.h"
#include "figure_families.h"
#include "measure_direction.h"
#include "roving/core/error.h"
#include "roving/core/stopwatch.h"
#include "roving/formats/files/file_bytes.h"
#include "roving/formats/meshes/ply_reader.h"
#include "roving/formats/meshes/triangle_stream.h"
#include "roving/formats/points_voxels_patches/point_cloud_io.h"
#include "roving/mpeg/mmetric_sampling.h"
#include "roving/mpeg/mpeg_points.h"

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

bool has_colour(const Model& model) {
  if (model.type == ModelType::Points) return !model.points.colours.empty();
  return model.type == ModelType::Mesh && model.mesh.mesh.has_colour();
}

}  // namespace

namespace {

// pc_error's options apply to MPEG's figures of two point clouds; of them, mmetric 1.1.7 offers
// --dropDuplicates and --neighborsProc on meshes too (compared with its output; it has neither
// --averageNormals nor --mseSpace), and its own --normalCalcModificationEnable.
void require_mpeg_options_apply(const MeasurePlan& plan, const Model& a, const Model& b) {
  const bool mesh = a.type == ModelType::Mesh || b.type == ModelType::Mesh;
  const bool mpeg = plan.pcc_only || (a.type == ModelType::Points && b.type == ModelType::Points);
  const PcErrorOptions& o = plan.pcc_options;
  const bool pc_error_only = !o.average_normals || o.ycocg;
  const bool mpeg_only = pc_error_only || o.dropdups != 2 || o.neighbors_proc != 1;
  if (!mpeg && mpeg_only) {
    throw Error(fmt::format("--pcc-dropdups, --pcc-neighbors-proc, --pcc-average-normals, --pcc-mse-space: "
                            "pc_error's options, for MPEG's figures (--pcc, or two point clouds); found {} and {}",
                            to_string(a.type), to_string(b.type)));
  }
  if (mesh && pc_error_only) {
    throw Error(fmt::format("--pcc-average-normals, --pcc-mse-space: pc_error's options, for MPEG's figures of two "
                            "point clouds; found {} and {} (a mesh is measured as mmetric's compare --mode pcc "
                            "measures it, which has --dropDuplicates and --neighborsProc but neither of these)",
                            to_string(a.type), to_string(b.type)));
  }
  if (!plan.pcc_b_own_normals && (!mpeg || !mesh)) {
    throw Error(fmt::format("--pcc-normal-calc-modification: mmetric's option, for MPEG's figures of a mesh "
                            "(--pcc); found {} and {} (pc_error's D2 always carries A's normals onto B)",
                            to_string(a.type), to_string(b.type)));
  }
}

}  // namespace

void describe_pair(const Model& a, const Model& b, MeasurePlan& plan, MeasureReport& report) {
  require_mpeg_options_apply(plan, a, b);
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
MpegPoints read_mpeg_points(const std::string& path, const MpegReading& reading) {
  if (read_as_ply(path)) {
    const FileBytes file(path, "a .ply point cloud");
    if (const std::optional<PackedPointCloud> packed = ply_packed_points(path, file.bytes())) {
      return mpeg_points(*packed, path, reading);
    }
  }
  return mpeg_points(read_point_cloud(path, false), path, reading);
}

}  // namespace

MpegReport mpeg_report(const Model& a, const Model& b, const MeasurePlan& plan) {
  const Stopwatch watch;
  MpegReport report;
  MpegRules rules;
  rules.resolution = plan.pcc_resolution;
  rules.mmetric = a.type == ModelType::Mesh || b.type == ModelType::Mesh;
  rules.options = plan.pcc_options;
  rules.b_own_normals = plan.pcc_b_own_normals;
  // How each cloud is held: merged as pc_error's --dropdups says (mmetric's own merging for
  // meshes' samples); NaN normals kept, as pc_error computes on with them.
  MpegReading reading;
  reading.average_normals = rules.mmetric;
  reading.dropdups = plan.pcc_options.dropdups;
  reading.merged_counts = plan.pcc_options.neighbors_proc == 2 && plan.pcc_options.dropdups == 2;
  reading.nan_normals = !rules.mmetric;
  const auto points_of = [&](const Model& model, bool normals, double& read_seconds) {
    MpegReading r = reading;
    r.normals = normals;
    if (model.type == ModelType::Mesh) {
      MpegReading samples;  // mmetric's removeDuplicatePoints: pc_error's merging, normals averaged
      samples.average_normals = true;
      samples.dropdups = reading.dropdups;
      samples.merged_counts = reading.merged_counts;
      return mpeg_points(mmetric_samples(model.mesh.mesh, model.path()), model.path(), samples);
    }
    if (model.points_in_file) {
      const Stopwatch read;
      MpegPoints points = read_mpeg_points(model.path(), r);
      read_seconds = read.seconds();
      return points;
    }
    r.normals = normals && !model.normals_estimated;
    return mpeg_points(model.points, model.path(), r);
  };
  // pc_error reads colour only as uchar: a cloud whose file stores float colours has none for it,
  // and none in MPEG's figures here.
  const auto float_colours = [](const Model& model) {
    return model.type == ModelType::Points && read_as_ply(model.path()) && ply_colours_are_floats(model.path());
  };
  const bool uncoloured[2] = {float_colours(a), float_colours(b)};
  for (int side = 0; side < 2; ++side) {
    if (!uncoloured[side]) continue;
    report.warnings.push_back(fmt::format(
        "colour: {} stores its colours as floats; pc_error reads colour only as uchar (0-255) and gives no "
        "colour figures for it, nor do MPEG's figures here (store them as uchar to have them)",
        (side == 0 ? a : b).path()));
  }
  const std::string& normals_path = plan.pcc_normals;
  MpegPoints a_points, b_points, normals;
  tbb::parallel_invoke([&] { a_points = points_of(a, normals_path.empty(), report.read_seconds[0]); },
                       [&] { b_points = points_of(b, rules.mmetric, report.read_seconds[1]); },
                       [&] {
                         if (normals_path.empty()) return;
                         // Merged as A's are.
                         normals = mpeg_points(load_point_cloud(normals_path), normals_path, reading);
                       });
  if (uncoloured[0]) a_points.colours.clear();
  if (uncoloured[1]) b_points.colours.clear();
  if (!normals_path.empty()) use_normals_of(a_points, normals, normals_path);
  if (a_points.nan_normals > 0) {
    report.warnings.push_back(fmt::format(
        "normals: {} of {}'s normals are NaN, the first its point {} in file order; as pc_error, D2 takes "
        "the sum of the coordinates' differences (unsquared) for a nearest point with a NaN normal (the squared "
        "distance under --pcc-average-normals 0)",
        a_points.nan_normals, normals_path.empty() ? a.path() : normals_path, a_points.first_nan_normal));
  }
  report.figures = mpeg_point_cloud_figures(a_points, b_points, rules, a.path());
  report.normals_from = normals_path;
  report.options = plan.pcc_options;
  report.b_own_normals = plan.pcc_b_own_normals;
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
  } else if (plan.tnt) {
    // The toolbox crops every cloud before it uses it, and its crop leaves out NaN and infinite
    // points (Open3D's polygon test fails on them): so does its protocol here. DTU's script
    // crashes on them, and is refused with the first one named.
    model.points = read_point_cloud_finite(path, model.non_finite_dropped);
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
  require_mpeg_options_apply(plan, a, b);
  report.pcc_only = true;
  stage = fmt::format("computing MPEG's point-cloud figures of {} and {}", a.path(), b.path());
  progress.stage("MPEG point-cloud figures");
  report.mpeg = mpeg_report(a, b, plan);
  progress.clear();
  warn(report.mpeg->warnings);
  for (int side = 0; side < 2; ++side) report.load_seconds[side] += report.mpeg->read_seconds[side];
  const bool* coloured = report.mpeg->coloured;
  if (coloured[0] != coloured[1]) {
    warn({fmt::format("colour: {} has colour but {} has none; no colour figures", (coloured[0] ? a : b).path(),
                      (coloured[0] ? b : a).path())});
  }
}

void measure_models(const Model& a, const Model& b, MeasurePlan& plan, MeasureReport& report,
                    Progress& progress, std::string& stage, const WarnFn& warn, const SampleSet* samples_of_a,
                    Model* releasable_a, ReferenceStream* streamed_a, ProtocolInputs* protocol) {
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
    const DirectionSource source =
        reference == &a ? DirectionSource{samples_of_a, releasable_a, streamed_a} : DirectionSource{};
    measure_direction(*reference, *test, source, plan, report, thresholds, progress, stage, warn, d);
  }
  FamilyInputs inputs{a, b, plan, protocol, progress, stage, warn};
  for (const FigureFamily& family : figure_families()) {
    if (family.asked(plan, a, b)) family.compute(inputs, report);
  }
  progress.clear();
}

}  // namespace roving
