// `roving`: measure the shape dissimilarity of a test model M_C from a reference model M_R.
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <new>

#include "report.h"
#include "roving/core/error.h"
#include "roving/core/memory_budget.h"
#include "roving/core/sample_set.h"
#include "roving/core/stopwatch.h"
#include "roving/formats/atomic_file.h"
#include "roving/formats/mesh_io.h"
#include "roving/formats/sample_output.h"
#include "roving/registry/method_registry.h"
#include "roving/representations/model.h"

namespace {

struct MeasureArguments {
  std::string reference_path, test_path;
  std::string method = "embree";
  std::string semantics;  // empty: the method's default
  std::string samples = "faces";
  std::string max_error = "5%";
  std::string json_path, samples_csv_path, heatmap_path;
  std::size_t histogram_bins = 64;
  std::string views = "24x12", backend = "osmesa";
  std::string reference_type, test_type;  // empty: by extension
  int resolution = 1024;
};

// What the run is doing, for the one-line message when memory runs out.
std::string current_stage = "starting";

// h bounded by what the models and Embree's float rays can represent: the view volume need
// reach no farther than both models' extent, and beyond it the rays' float origins lose the
// precision the distances need (h = 1e10 on a unit model gave SiAD 2.5e9 instead of 0).
void require_representable(double max_error, const roving::BoundingBox& both, const std::string& given) {
  const double extent = both.diagonal();
  if (!(max_error <= extent)) {
    throw roving::Error(
        fmt::format("--max-error: expected at most the diagonal of both models' bounding box ({:.6g}), found "
                    "{} ({:.6g}); "
                    "a view volume reaches nothing farther",
                    extent, given, max_error));
  }
}

int run_measure(const MeasureArguments& args) {
  using namespace roving;
  const Stopwatch total;
  // Parse every option before the (slow) loads, so a typo fails at once.
  GlMethodOptions gl;
  parse_views(args.views, gl.views_h, gl.views_v);
  gl.backend = parse_gl_backend(args.backend);
  gl.resolution = args.resolution;
  const auto method = make_method(args.method, gl);
  const SampleSpec sample_spec = parse_sample_spec(args.samples);
  const MaxErrorSpec max_error = parse_max_error(args.max_error);
  DistanceOptions options;
  options.semantics =
      args.semantics.empty() ? method->supported_semantics().front() : parse_semantics(args.semantics);
  options.max_error = 1;  // placeholder until the diagonal is known; checked for support now
  validate_options(*method, options);

  for (const auto& [option, path] :
       {std::pair{"--json", args.json_path}, std::pair{"--samples-out", args.samples_csv_path},
        std::pair{"--heatmap", args.heatmap_path}}) {
    std::error_code error;
    if (!path.empty() && path != "-" && std::filesystem::is_directory(path, error)) {
      throw Error(fmt::format("{}: expected a file to write, found the directory '{}'", option, path));
    }
  }

  MeasureReport report;
  Stopwatch watch;
  const auto type = [](const std::string& text, const char* option) {
    return text.empty() ? std::nullopt : std::optional<ModelType>(parse_model_type(text, option));
  };
  const auto reference_type = type(args.reference_type, "--ref-type");
  const auto test_type = type(args.test_type, "--test-type");
  if (test_type == ModelType::Points) {
    throw Error(
        "--test-type: a point cloud cannot be the test model: it has holes and records no surface to draw or "
        "intersect (the paper's limit); expected mesh or voxels, found 'points'");
  }
  current_stage = fmt::format("loading the reference {}", args.reference_path);
  const Model reference = load_model(args.reference_path, reference_type);
  report.load_reference_seconds = watch.seconds();
  watch = Stopwatch();
  current_stage = fmt::format("loading the test {}", args.test_path);
  const Model test = load_model(args.test_path, test_type);
  const TriangleMesh& test_mesh = test_surface(test);
  report.load_test_seconds = watch.seconds();

  current_stage = fmt::format("sampling the reference ({})", sample_spec.to_string());
  const SampleSet samples = reference_samples(reference, sample_spec);
  options.max_error = max_error.resolve(reference.bounding_box().diagonal());
  BoundingBox both = reference.bounding_box();
  both.extend(test_mesh.bounding_box().min);
  both.extend(test_mesh.bounding_box().max);
  require_representable(options.max_error, both, args.max_error);
  current_stage = fmt::format("measuring {} samples against {} triangles with {}", samples.size(),
                              test_mesh.triangle_count(), method->name());
  const DistanceResult result = measure_distances(*method, test_mesh, samples, options);

  report.reference = &reference;
  report.test = &test;
  report.samples = &samples;
  report.method = method->name();
  report.semantics = options.semantics;
  report.max_error = options.max_error;
  report.max_error_text = max_error.to_string();
  report.statistics = compute_statistics(result.signed_distance, result.hit, samples.weights,
                                         options.max_error, args.histogram_bins);
  report.build_seconds = result.build_seconds;
  report.gl = result.gl ? &*result.gl : nullptr;
  report.query_seconds = result.query_seconds;

  // Every output file is written whole to a temporary file first; only when all succeeded are
  // they moved into place, so a failed run changes none of them.
  current_stage = "writing the outputs";
  std::vector<std::unique_ptr<AtomicFile>> outputs;
  if (!args.samples_csv_path.empty()) {
    outputs.push_back(std::make_unique<AtomicFile>(args.samples_csv_path));
    write_samples_csv(outputs.back()->stream(), samples, result);
    outputs.back()->close_stream();
  }
  if (!args.heatmap_path.empty()) {
    outputs.push_back(std::make_unique<AtomicFile>(args.heatmap_path));
    const double range = std::max(report.statistics.max_abs, 1e-300);
    write_heatmap_ply(outputs.back()->stream(), samples, result, std::min(range, options.max_error));
    outputs.back()->close_stream();
  }
  report.total_seconds = total.seconds();
  const std::string json = args.json_path.empty() ? "" : to_json(report).dump(2) + "\n";
  if (!args.json_path.empty() && args.json_path != "-") {
    outputs.push_back(std::make_unique<AtomicFile>(args.json_path));
    std::fputs(json.c_str(), outputs.back()->stream());
    outputs.back()->close_stream();
  }
  for (const auto& output : outputs) output->commit();
  write_stdout(args.json_path == "-" ? json : format_text(report));
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "surface roving: shape dissimilarity between 3D models (Z-buffer surface roving, "
      "with exact CPU references and classic baselines)"};
  app.require_subcommand(1);
  MeasureArguments args;
  CLI::App* measure = app.add_subcommand("measure", "measure distances from REF's samples to TEST");
  measure
      ->add_option("REF", args.reference_path,
                   "reference model M_R: mesh (.obj .ply .off .stl), point cloud (.ply "
                   "without faces, .xyz) or voxels (.binvox)")
      ->required();
  measure->add_option("TEST", args.test_path, "test model M_C: mesh or voxels")->required();
  measure
      ->add_option("--method", args.method,
                   fmt::format("distance method: {}", fmt::join(roving::method_names(), ", ")))
      ->capture_default_str();
  measure->add_option("--semantics", args.semantics,
                      "first-hit (paper), nearest (on the normal line) or closest (Metro); "
                      "default: the method's own");
  measure->add_option("--samples", args.samples, "faces, vertices or area:N")->capture_default_str();
  measure
      ->add_option("--max-error", args.max_error,
                   "h, the view volume's half-height: a length or P% of the reference's diagonal")
      ->capture_default_str();
  measure->add_option("--json", args.json_path, "write the report as JSON to FILE, or - for stdout");
  measure->add_option("--samples-out", args.samples_csv_path, "write one CSV row per sample");
  measure->add_option("--heatmap", args.heatmap_path, "write the samples coloured by d as PLY");
  measure->add_option("--ref-type", args.reference_type, "mesh, points or voxels (default: by extension)");
  measure->add_option("--test-type", args.test_type, "mesh or voxels (default: by extension)");
  measure->add_option("--views", args.views, "viewpoint sampling: H x V directions")->capture_default_str();
  measure->add_option("--resolution", args.resolution, "viewpoint sampling: view side in pixels")
      ->check(CLI::Range(1, 16384))
      ->capture_default_str();
  measure->add_option("--backend", args.backend, "GL backend: osmesa or egl")->capture_default_str();
  measure->add_option("--histogram-bins", args.histogram_bins, "bins of the signed-d histogram")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::fprintf(stderr, "roving: error: %s (see roving %s--help)\n", e.what(),
                 measure->parsed() ? "measure " : "");
    return 2;
  }
  try {
    return run_measure(args);
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "roving: error: out of memory while %s (available: %.3g GiB)\n",
                 current_stage.c_str(), roving::available_memory() / (1024.0 * 1024 * 1024));
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "roving: error: %s\n", e.what());
    return 1;
  }
}
