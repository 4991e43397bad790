// `roving measure`: the run from options to report (measure.h): the models loaded (a large REF
// as a stream of face blocks), measured, and the outputs written each whole or not at all.
#include "measure.h"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <charconv>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <future>
#include <limits>
#include <memory>
#include <tuple>

#include "html_output.h"
#include "merge.h"
#include "provenance.h"
#include "roving/core/error.h"
#include "roving/formats/files/atomic_file.h"
#include "roving/formats/files/file_bytes.h"
#include "roving/formats/files/file_hash.h"
#include "roving/formats/outputs/distance_cloud_writer.h"
#include "roving/formats/outputs/heatmap.h"
#include "roving/formats/outputs/sample_output.h"
#include "roving/measurement/figure_families.h"
#include "roving/measurement/gates.h"
#include "roving/pictures/heatmap_picture.h"
#include "roving/pictures/precision_recall_chart.h"

namespace roving {
namespace {

std::string file_name(const std::string& path) {
  return std::filesystem::path(path).filename().string();
}

}  // namespace

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
                      args.samples_csv_path.empty() &&
                      (plan.sample_spec.kind == SampleSpec::Kind::Faces ||
                       (plan.sample_spec.kind == SampleSpec::Kind::Vertices && !plan.shard)) &&
                      plan.method->independent_run() > 0 &&
                      (!plan.reference_type || *plan.reference_type == ModelType::Mesh);
  return wanted ? open_triangle_stream(args.reference_path, plan.chunk_faces) : nullptr;
}

// The model a streamed REF stands as in the report: what its whole mesh would say of itself; and,
// from the same pass, its vertex sums in `streamed` where its vertices are the samples.
std::unique_ptr<Model> streamed_model(ReferenceStream& streamed, std::size_t chunk_faces, const ProgressFn& progress,
                                      bool with_vertex_sums) {
  TriangleStream& stream = streamed.file;
  StreamedReference summary = summarise(stream, chunk_faces, progress, with_vertex_sums);
  streamed.vertex_sums = std::move(summary.vertex_sums);
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
  std::optional<ReferenceStream> streamed;
  if (given_a) {
    run.a = std::move(given_a);
  } else if (stream) {
    stage = fmt::format("reading the reference {} {} faces at a time", args.reference_path, plan.chunk_faces);
    progress.stage("reading " + file_name(args.reference_path));
    streamed.emplace(ReferenceStream{*stream, std::nullopt});
    // REF's faces are read on another thread (mostly one core's parsing) while TEST is loaded and
    // the method built for it on this one (the GL methods' contexts live here).
    auto reading = std::async(std::launch::async, [&] {
      auto model = streamed_model(*streamed, plan.chunk_faces, progress.callback(),
                                  plan.sample_spec.kind == SampleSpec::Kind::Vertices);
      report.load_seconds[0] = watch.seconds();  // REF's own, beside TEST's loading and the build
      return model;
    });
    try {
      run.b = given_b ? std::move(given_b) : test_load.get();
      if (run.b->type == ModelType::Mesh) plan.method_built_seconds = plan.method->build(test_surface(*run.b));
    } catch (...) {
      run.a = reading.get();  // where both fail, the reference's error is the one reported
      throw;
    }
    run.a = reading.get();
  } else {
    stage = fmt::format("loading the reference {}", args.reference_path);
    progress.stage("loading " + file_name(args.reference_path));
    run.a = std::make_unique<Model>(load(args.reference_path, plan.reference_type, true));
  }
  if (!stream) report.load_seconds[0] = watch.seconds();
  if (!run.b) {  // else loaded beside a streamed REF
    if (given_b) {
      run.b = std::move(given_b);
    } else {
      stage = fmt::format("loading the test {}", args.test_path);
      progress.stage("loading " + file_name(args.test_path));
      run.b = test_load.get();
    }
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
                 reference_only_sampled(args, plan) ? &a : nullptr, streamed ? &*streamed : nullptr, &protocol);
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
  const auto write_samples = [&](std::FILE* out) {
    for (const DirectionReport& d : report.directions) {
      write_samples_csv(out, d.samples, d.result, d.label, &d == &report.directions.front(),
                        d.colour_pairs ? &*d.colour_pairs : nullptr, d.correspondences ? &*d.correspondences : nullptr);
    }
  };
  const bool samples_to_stdout = args.samples_csv_path == "-";
  if (!args.samples_csv_path.empty() && !samples_to_stdout) {
    outputs.push_back(std::make_unique<AtomicFile>(args.samples_csv_path));
    write_samples(outputs.back()->stream());
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
                                     to_json(report), run.plan.heatmap_of));
    outputs.back()->close_stream();
  }
  for (const auto& output : outputs) output->commit();
  if (samples_to_stdout) {  // after the files, which are then whole whatever becomes of the pipe
    stage = "writing the samples to standard output";
    write_samples(stdout);
    if (std::fflush(stdout) != 0 || std::ferror(stdout)) {
      throw Error(fmt::format("--samples-out -: writing to standard output failed ({})", std::strerror(errno)));
    }
  }
}

int run_measure(const MeasureArguments& args, std::string& stage) {
  Progress progress(args.quiet);
  // Standard output carries the text report, or what --json - or --samples-out - asks for alone.
  const bool samples_to_stdout = args.samples_csv_path == "-";
  const bool text_to_stdout = args.json_path != "-" && !samples_to_stdout;
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
  if (!samples_to_stdout) write_stdout(text_to_stdout ? format_body(report) : to_json(report).dump(2) + "\n");

  return apply_gates(run.plan.gates, gate_values(report), run.plan.gate_on);
}

}  // namespace roving