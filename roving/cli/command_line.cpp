// The options of `roving measure` and `roving batch` (command_line.h).
#include "command_line.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>

#include "roving/registry/method_registry.h"

namespace roving {
namespace {

// Edit distance, for "did you mean" on a mistyped subcommand or option.
std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] != b[j - 1])});
      diagonal = above;
    }
  }
  return row[b.size()];
}

// " (did you mean 'X'?)" for the nearest candidate within a few edits, or nothing.
std::string suggestion(const std::string& given, const std::vector<std::string>& candidates) {
  const std::string best = nearest_name(given, candidates);
  return best.empty() ? "" : fmt::format(" (did you mean '{}'?)", best);
}

// The first argument that names no subcommand or no option of the subcommand given, with a
// suggestion; empty when every one is known (the parse error is then about something else).
std::string unknown_argument(const std::vector<std::string>& arguments, const CLI::App& app) {
  std::vector<std::string> subcommands, options;
  for (const CLI::App* sub : app.get_subcommands({})) subcommands.push_back(sub->get_name());
  if (arguments.empty()) return "";
  const std::string& first = arguments[0];
  const bool option_first = !first.empty() && first[0] == '-';
  if (!option_first && std::find(subcommands.begin(), subcommands.end(), first) == subcommands.end()) {
    return fmt::format("unknown command '{}'{}; expected one of: {}", first, suggestion(first, subcommands),
                       fmt::join(subcommands, ", "));
  }
  const CLI::App& given = option_first ? app : *app.get_subcommand(first);
  for (const CLI::Option* option : given.get_options()) {
    for (const std::string& name : option->get_lnames()) options.push_back("--" + name);
  }
  for (std::size_t i = option_first ? 0 : 1; i < arguments.size(); ++i) {
    const std::string& argument = arguments[i];
    if (argument == "--") break;
    if (argument.rfind("--", 0) != 0) continue;
    const std::string name = argument.substr(0, argument.find('='));
    if (std::find(options.begin(), options.end(), name) == options.end()) {
      return fmt::format("unknown option '{}'{}", name, suggestion(name, options));
    }
  }
  return "";
}

// The options that say how to measure, shared by `measure` and `batch`.
void add_measurement_options(CLI::App& app, MeasureArguments& args, bool& trust_references, bool& strict_materials) {
  app.add_flag("--trust-references", trust_references,
               "let files a model names (glTF buffers) lie outside the model's folder: absolute paths, '..', "
               "symbolic links out (by default refused, for models from elsewhere)");
  app.add_flag("--strict-materials", strict_materials,
               "refuse an OBJ whose material library (mtllib) or texture (map_Kd) is not there (by default "
               "a warning, and the geometry measured without the materials' colour)");
  app.add_option("--method", args.method, fmt::format("distance method: {}", fmt::join(method_names(), ", ")))
      ->capture_default_str();
  app.add_option("--semantics", args.semantics,
                 "first-hit (paper), nearest (on the normal line) or closest (Metro); "
                 "default: the method's own, closest with --symmetric where the method has it");
  app.add_flag("--symmetric", args.symmetric,
               "measure REF -> TEST and TEST -> REF, with Metro's two-sided summary (Hausdorff, mean, RMS) "
               "relative to the diagonal of both models' box");
  app.add_option("--samples", args.samples,
                 "faces, vertices, area:N, or area:auto (as many random samples as --precision needs)")
      ->capture_default_str();
  app.add_option(
         "--precision", args.precision,
         "with --samples area:auto: the half-width asked of USiAD's 95% interval, P% of USiAD or a length; "
         "samples are drawn (from 10,000, at most 20,000,000) until it is reached")
      ->capture_default_str();
  app.add_option("--seed", args.seed, "seed of area:N sampling (default 12345; reported either way)");
  app.add_option("--max-error", args.max_error,
                 "h, the view volume's half-height: a length or P% of the diagonal")
      ->capture_default_str();
  app.add_option("--ref-type", args.reference_type, "mesh, points, voxels or bezier (default: by extension)");
  app.add_option("--test-type", args.test_type, "mesh, points, voxels or bezier (default: by extension)");
  app.add_option(
         "--views", args.views,
         "viewpoint sampling: H x V directions; for cooperative also auto or auto:HxV (a view only where "
         "it costs less than the cameras it saves)")
      ->capture_default_str();
  app.add_option("--resolution", args.resolution, "viewpoint sampling: view side in pixels")
      ->check(CLI::Range(1, 16384))
      ->capture_default_str();
  app.add_option("--backend", args.backend,
                 "GL backend: osmesa or egl (default: $ROVING_GL_BACKEND, else osmesa)");
  app.add_option(
         "--camera-geometry", args.camera_geometry,
         "roving and cooperative: where each per-sample camera's triangles are put in its frame and their "
         "edges widened: cpu, or gpu (in a compute shader; the same answers); or compute (each camera's "
         "depth in a compute pass over TEST's grid, nothing drawn)")
      ->capture_default_str();
  app.add_option("--view-culling", args.view_culling,
                 "viewpoint and cooperative: footprint (each view draws only the triangles that can cover the "
                 "pixels its samples read, found on the CPU) or none (each view drawn whole: no per-view CPU "
                 "work, the better trade on a GPU); the same answers")
      ->check(CLI::IsMember({"footprint", "none"}))
      ->capture_default_str();
  app.add_option(
         "--hausdorff-bound", args.hausdorff_bound,
         "with --symmetric or --semantics closest: the Hausdorff distance is also bounded over every point "
         "of the surfaces, as a certified interval [lower, upper] at most this wide (a length or P% of the "
         "diagonal), or none")
      ->capture_default_str();
  app.add_flag(
      "--ibsm", args.ibsm,
      "also compare the models image by image as MPEG's IBSM does (mmetric): both drawn unlit from "
      "--ibsm-views orthographic cameras on a Fibonacci sphere, back faces culled; colour PSNR (R'G'B', "
      "Y'CbCr 6:1:1) and depth PSNR over the pixels both cover, and the unmatched pixels' share");
  app.add_option("--ibsm-views", args.ibsm_views, "with --ibsm: cameras on the Fibonacci sphere")
      ->check(CLI::Range(2, 1000))
      ->capture_default_str();
  app.add_option("--ibsm-resolution", args.ibsm_resolution, "with --ibsm: each camera's image side in pixels")
      ->check(CLI::Range(16, 16384))
      ->capture_default_str();
  app.add_option(
      "--threshold", args.thresholds,
      "with --symmetric: precision, recall and F-score at this distance tau (a length or P% of the "
      "diagonal), as reconstruction benchmarks report them; repeatable");
  app.add_flag(
      "--certify-thresholds", args.certify_thresholds,
      "with --threshold and closest semantics: precision and recall also as certified bounds, the shares of "
      "area surely and possibly within tau over every point of the surfaces (can take 100x the measurement's "
      "time: docs/reconstruction.md)");
  app.add_flag(
      "--pcc", args.pcc,
      "MPEG's point-cloud figures alone, as its pc_error computes them: D1 and D2 MSE and PSNR, their "
      "Hausdorff forms, colour PSNR, per direction and the worse of the two (two point clouds; given "
      "without --pcc for two point clouds too, beside the surface figures); on meshes, as mmetric's "
      "compare --mode pcc, each mesh sampled as mmetric samples it");
  app.add_option("--pcc-resolution", args.pcc_resolution,
                 "the geometry PSNR's peak p in 10 log10(3 p^2 / MSE), pc_error's --resolution (e.g. 1023 "
                 "for 10-bit voxels); default (or 0, as pc_error's -r 0): the largest nearest-neighbour spacing "
                 "within A, as pc_error's (on meshes the diagonal of A's box, as mmetric's)");
  app.add_option("--pcc-normals", args.pcc_normals,
                 "A's normals for D2 from this file, pc_error's --inputNorm: a point cloud of A's points "
                 "(in any order, duplicates merged as A's) with normals; they replace any A has");
  app.add_option("--pcc-dropdups", args.pcc_dropdups,
                 "pc_error's (and, on meshes, mmetric's --dropDuplicates): points of one cloud at one position 0 all "
                 "kept, 1 the first kept, 2 merged into one, their colours averaged")
      ->check(CLI::Range(0, 2))
      ->capture_default_str();
  app.add_option("--pcc-neighbors-proc", args.pcc_neighbors_proc,
                 "pc_error's (and, on meshes, mmetric's) --neighborsProc: the colour of the other cloud's points "
                 "tied nearest, 0 the first its "
                 "search finds, 1 their mean, 2 their mean weighted by the points each merged, 3 the nearest in RGB, "
                 "4 the farthest in RGB")
      ->check(CLI::Range(0, 4))
      ->capture_default_str();
  app.add_option("--pcc-average-normals", args.pcc_average_normals,
                 "pc_error's --averageNormals: 1 D2 averaged over the points tied nearest, 0 the first found alone")
      ->check(CLI::Range(0, 1))
      ->capture_default_str();
  app.add_option("--pcc-mse-space", args.pcc_mse_space,
                 "pc_error's --mseSpace: 8 adds YCoCg-R's colour PSNRs; 0 (RGB) and 1 (BT.709 Y'CbCr) are both "
                 "always given")
      ->check(CLI::IsMember({0, 1, 8}))
      ->capture_default_str();
  app.add_option("--pcc-normal-calc-modification", args.pcc_normal_calc_modification,
                 "mmetric's --normalCalcModificationEnable, on meshes: true, D2 from A to B along B's own normals "
                 "(its samples' faces'); false, along A's carried onto B as pc_error carries them")
      ->capture_default_str();
  app.add_option("--protocol", args.protocol,
                 "a benchmark's own evaluation, step by step, on REF (its ground truth) and TEST (the "
                 "reconstruction): dtu, as DTUeval-python's eval.py computes it (needs --dtu-obs-mask and "
                 "--dtu-plane); tanks-and-temples, as its toolbox's EvaluateHisto computes it (needs --tnt-crop "
                 "and --tnt-scene or --tnt-tau); alone, or beside the exact figures with --symmetric")
      ->check(CLI::IsMember({"dtu", "tanks-and-temples"}));
  app.add_option("--dtu-obs-mask", args.dtu_obs_mask,
                 "with --protocol dtu: the scan's observation mask, the data set's ObsMask/ObsMask<scan>_10.mat");
  app.add_option("--dtu-plane", args.dtu_plane,
                 "with --protocol dtu: the scan's ground plane, the data set's ObsMask/Plane<scan>.mat");
  app.add_option("--dtu-density", args.dtu_density,
                 "with --protocol dtu: the mesh sampling step and thinning radius (eval.py's downsample_density)")
      ->capture_default_str();
  app.add_option("--dtu-patch", args.dtu_patch,
                 "with --protocol dtu: the margin around the mask's box (eval.py's patch_size)")
      ->capture_default_str();
  app.add_option("--dtu-max-dist", args.dtu_max_dist,
                 "with --protocol dtu: distances at or beyond it are left out of the means (eval.py's max_dist)")
      ->capture_default_str();
  app.add_option("--tnt-crop", args.tnt_crop,
                 "with --protocol tanks-and-temples: the scene's crop volume, the data set's <scene>.json");
  app.add_option("--tnt-alignment", args.tnt_alignment,
                 "with --protocol tanks-and-temples: the 4 x 4 matrix (four rows of four numbers, as run.py's "
                 "<scene>_trans.txt) that takes TEST onto REF, applied before everything; default: none");
  app.add_option("--tnt-trajectory", args.tnt_trajectory,
                 "with --protocol tanks-and-temples: the reconstruction's camera trajectory (.log); run.py's "
                 "registration then refines --tnt-alignment (the scene's _trans.txt) by RANSAC on the cameras and "
                 "three rounds of ICP (needs --tnt-reference-trajectory)");
  app.add_option("--tnt-reference-trajectory", args.tnt_reference_trajectory,
                 "with --tnt-trajectory: the scene's reference cameras, <scene>_COLMAP_SfM.log");
  app.add_option("--tnt-mapping", args.tnt_mapping,
                 "with --tnt-trajectory: the scene's <scene>_mapping_reference.txt (run.py reads it where the "
                 "trajectory has more than 1,600 cameras)");
  app.add_option("--tnt-scene", args.tnt_scene,
                 "with --protocol tanks-and-temples: the scene whose tau the toolbox's config.py sets (Barn, "
                 "Caterpillar, Church, Courthouse, Ignatius, Meetingroom, Truck)");
  app.add_option("--tnt-tau", args.tnt_tau,
                 "with --protocol tanks-and-temples: tau itself, in the models' units (metres), for another scene");
  app.add_option("--tnt-curves", args.tnt_curves,
                 "with --protocol tanks-and-temples: write the precision and recall curves as PNG here");
  app.add_option("--tnt-plys", args.tnt_plys,
                 "with --protocol tanks-and-temples: write the toolbox's viewing files PREFIX.precision.ply and "
                 "PREFIX.recall.ply (the thinned clouds coloured by distance, hot_r up to 3 tau)");
  app.add_option("--protocol-seed", args.protocol_seed,
                 "with --protocol dtu: the first seed of the shuffle before thinning (eval.py's is unseeded), or "
                 "none for the points' own order; with --tnt-trajectory: the first seed of RANSAC's draws (run.py's "
                 "are unseeded)")
      ->capture_default_str();
  app.add_option("--protocol-runs", args.protocol_runs,
                 "with --protocol dtu or --tnt-trajectory: runs with seeds --protocol-seed, +1, ...; reported: "
                 "DTU's first, the registration whose figures the most runs give; the spread of all beside it")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  app.add_option("--histogram-bins", args.histogram_bins, "bins of the signed-d histogram")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  app.add_flag(
      "--quiet", args.quiet,
      "no progress and no warnings on stderr (progress is shown only on a terminal anyway; warnings stay in "
      "the report and the JSON); errors are always printed");
}

// The words of measure's command line that decide its figures: REF, TEST and each option given,
// in the order declared, but those that only name outputs (or the shard).
std::vector<std::string> figure_arguments(const CLI::App& measure) {
  const std::vector<std::string> outputs = {"json", "samples-out", "heatmap", "heatmap-png",
                                            "html", "quiet",       "shard",   "shard-out"};
  std::vector<std::string> words;
  for (const CLI::Option* option : measure.get_options()) {
    if (option->count() == 0) continue;
    if (option->get_lnames().empty()) {  // REF, TEST
      words.insert(words.end(), option->results().begin(), option->results().end());
      continue;
    }
    const std::string& name = option->get_lnames().front();
    if (std::find(outputs.begin(), outputs.end(), name) != outputs.end()) continue;
    for (const std::string& value : option->results()) {
      words.push_back("--" + name);
      if (option->get_expected_max() != 0) words.push_back(value);  // a flag takes none
    }
  }
  return words;
}

}  // namespace

std::string nearest_name(const std::string& given, const std::vector<std::string>& candidates) {
  std::string best;
  std::size_t best_distance = std::max<std::size_t>(3, given.size() / 3) + 1;
  for (const std::string& candidate : candidates) {
    const std::size_t distance = edit_distance(given, candidate);
    if (distance < best_distance) {
      best = candidate;
      best_distance = distance;
    }
  }
  return best;
}

std::unique_ptr<CommandLine> make_command_line() {
  auto line = std::make_unique<CommandLine>();
  CLI::App& app = line->app;
  MeasureArguments& args = line->args;
  BatchArguments& batch_args = line->batch_args;
  bool& trust_references = line->trust_references;
  bool& strict_materials = line->strict_materials;
  app.description(
      "surface roving: shape dissimilarity between 3D models (Z-buffer surface roving, "
      "with exact CPU references and classic baselines)");
  app.require_subcommand(0, 1);
  app.add_flag("--version", line->version, "print the version and the commit built, and exit");
  CLI::App* measure = line->measure = app.add_subcommand(
      "measure",
      "measure distances from REF's samples to TEST (exit 0; 1 on an error; 2 on a usage error; 3 when a "
      "--fail-above gate is breached)");
  measure
      ->add_option("REF", args.reference_path,
                   "reference model M_R: mesh (.obj .ply .off .stl .gltf .glb .3mf), Bezier patches (.bpt), "
                   "point cloud "
                   "(.ply without faces, .xyz) or voxels (.binvox)")
      ->required();
  measure
      ->add_option(
          "TEST", args.test_path,
          "test model M_C: mesh (.obj .ply .off .stl .gltf .glb .3mf), Bezier patches (.bpt), voxels "
          "(.binvox) or point cloud (.ply without faces, .xyz; drawn as surfels)")
      ->required();
  add_measurement_options(*measure, args, trust_references, strict_materials);
  measure->add_option("--fail-above", args.gates,
                      fmt::format("METRIC=LIMIT (a length, or P% of the diagonal; no_hits: a count or P% of "
                                  "the samples): exit 3 if METRIC's magnitude exceeds LIMIT; repeatable. "
                                  "Metrics: {}",
                                  fmt::join(gate_metrics(true), ", ")));
  measure->add_option("--fail-below", args.floors,
                      fmt::format("METRIC=FLOOR in dB: exit 3 if METRIC, a PSNR (the worse direction's), is below "
                                  "FLOOR; repeatable. Metrics: {}",
                                  fmt::join(floor_metrics(), ", ")));
  measure
      ->add_option(
          "--gate-on", args.gate_on,
          "estimate (default) or upper: what --fail-above compares where a figure has an interval "
          "(area:N means, the certified Hausdorff distance): the figure, or its interval's upper end")
      ->capture_default_str();
  measure->add_option("--json", args.json_path, "write the report as JSON to FILE, or - for stdout");
  measure->add_option(
      "--shard", args.shard,
      "I/N: measure only the I-th (0-based) of N contiguous slices of REF's samples (the same samples whatever "
      "N; exact roving's slices cut at multiples of its 4096-camera batches), e.g. "
      "$SLURM_ARRAY_TASK_ID/$SLURM_ARRAY_TASK_COUNT, into --shard-out; roving merge gives the report one process "
      "gives");
  measure->add_option("--shard-out", args.shard_out,
                      "with --shard: the part to write (17 bytes per sample per direction, 25 with --symmetric, 24 more for colour; and the models' description)");
  measure->add_option(
             "--chunk", args.chunk,
             "a binary PLY or STL, or OBJ, REF with more faces than this is read, sampled and measured this many faces at a time, "
             "in bounded memory with the same figures, where nothing asked for needs it whole (one direction, face "
             "samples, an exact, nearest-point or exact roving (GL cameras) method, no threshold, per-sample output or picture; the certified "
             "Hausdorff interval is bounded block by block); 0: always read whole")
      ->capture_default_str();
  measure->add_option("--samples-out", args.samples_csv_path, "write one CSV row per sample (-: standard output, instead of the text report)");
  measure->add_option(
      "--heatmap", args.heatmap_path,
      "write REF coloured by d as PLY (per face or vertex on a mesh or voxels; points otherwise); with "
      "--symmetric one file per direction, FILE's name + .A-to-B / .B-to-A");
  measure->add_option(
      "--heatmap-png", args.heatmap_png_path,
      "render REF coloured by d from the front, side and top, with a colour bar, as PNG; with --symmetric "
      "one picture per direction, named as for --heatmap");
  measure->add_option(
      "--html", args.html_path,
      "write one self-contained web page (opens offline in a browser): REF in 3D coloured by d as for "
      "--heatmap-png, to turn and zoom, a sample's d on hover or click, the figures, histogram, "
      "warnings and provenance; both directions with --symmetric");
  measure
      ->add_option(
          "--heatmap-of", args.heatmap_of,
          "what --heatmap and --heatmap-png show: d (signed distance, diverging map) or delta-e (the "
          "CIEDE2000 colour difference at each sample, 0 to the range; both models coloured)")
      ->capture_default_str();
  measure->add_option(
      "--heatmap-range", args.heatmap_range,
      "the colour map's half-range: a length or P% of the diagonal (default: the 99th percentile of "
      "|d| over the hits); with --heatmap-of delta-e, a delta E (default: the 99th percentile of "
      "delta E)");

  CLI::App* batch = line->batch = app.add_subcommand("batch",
                                                     "measure many pairs: one JSON report per pair in --out, "
                                                     "and --out/summary.csv (exit 0; 4 when some pair "
                                                     "failed, each recorded with its error)");
  batch->add_option(
      "PAIRS", batch_args.inputs,
      "a manifest (.csv with a header naming reference, test and optional per-pair columns "
      "method, semantics, samples, seed, max_error, views, resolution, backend, camera_geometry, "
      "view_culling; or .jsonl with those keys), or REF_FOLDER TEST_FOLDER paired by file name");
  batch->add_option("--out", batch_args.out, "folder of the per-pair reports and summary.csv")
      ->capture_default_str();
  batch->add_option("--shard", batch_args.shard,
                    "I/N: only the I-th (0-based) of N contiguous slices of the pairs, e.g. "
                    "$SLURM_ARRAY_TASK_ID/$SLURM_ARRAY_TASK_COUNT; pairs already in --out are skipped");
  batch->add_flag("--merge", batch_args.merge_only, "only rebuild --out/summary.csv from the reports there");
  batch->add_flag(
      "--html", batch_args.html,
      "also write a web page per pair (as measure --html) and --out/index.html, a sortable table of the "
      "pairs linking to them");
  batch->add_flag(
      "--skip-unpaired", batch_args.skip_unpaired,
      "with REF_FOLDER TEST_FOLDER: measure the files found in both and list the others on stderr "
      "(without it, a file with no partner of the same name is an error)");
  add_measurement_options(*batch, batch_args.defaults, trust_references, strict_materials);

  MergeArguments& merge_args = line->merge_args;
  CLI::App* merge = line->merge = app.add_subcommand(
      "merge",
      "merge the parts of one pair's shards (measure --shard I/N --shard-out PART) into the report one process "
      "gives, with the shards' gates (exit as measure)");
  merge->add_option("PARTS", merge_args.parts, "every part of the N shards, in any order")->required();
  merge->add_option("--json", merge_args.json_path, "write the report as JSON to FILE, or - for stdout");
  merge->add_flag("--quiet", merge_args.quiet, "no warnings on stderr");

  return line;
}

std::string parse_command_line(CommandLine& line, std::vector<std::string> arguments) {
  std::vector<std::string> reversed(arguments.rbegin(), arguments.rend());  // CLI11 takes them reversed
  try {
    line.app.parse(reversed);
    if (line.measure->parsed()) line.args.figure_arguments = figure_arguments(*line.measure);
    return "";
  } catch (const CLI::CallForHelp&) {
    throw;
  } catch (const CLI::CallForAllHelp&) {
    throw;
  } catch (const CLI::ParseError& e) {
    const std::string unknown = unknown_argument(arguments, line.app);
    return unknown.empty() ? e.what() : unknown;
  }
}

}  // namespace roving
