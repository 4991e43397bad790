// Shards' parts of one pair, and their merge (merge.h).
#include "merge.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "roving/measurement/checks.h"
#include "roving/measurement/figure_families.h"
#include "command_line.h"
#include "roving/measurement/gates.h"
#include "provenance.h"
#include "roving/core/confidence.h"
#include "roving/core/error.h"
#include "roving/core/stopwatch.h"
#include "roving/formats/files/atomic_file.h"
#include "roving/formats/outputs/heatmap.h"
#include "roving/formats/outputs/shard_part.h"

namespace roving {
namespace {

nlohmann::json hausdorff_json(const HausdorffInterval& h) {
  const auto point = [](const Vec3& p) { return nlohmann::json{p.x(), p.y(), p.z()}; };
  return {{"lower", h.lower},
          {"upper", h.upper},
          {"lower_point", point(h.lower_point)},
          {"lower_closest", point(h.lower_closest)},
          {"distance_queries", h.distance_queries},
          {"triangles_split", h.triangles_split},
          {"seconds", h.seconds}};
}

HausdorffInterval hausdorff_of(const nlohmann::json& json) {
  const auto point = [](const nlohmann::json& p) {
    return Vec3(p.at(0).get<double>(), p.at(1).get<double>(), p.at(2).get<double>());
  };
  HausdorffInterval h;
  h.lower = json.at("lower").get<double>();
  h.upper = json.at("upper").get<double>();
  h.lower_point = point(json.at("lower_point"));
  h.lower_closest = point(json.at("lower_closest"));
  h.distance_queries = json.at("distance_queries").get<std::size_t>();
  h.triangles_split = json.at("triangles_split").get<std::size_t>();
  h.seconds = json.at("seconds").get<double>();
  return h;
}

// A shard's certified areas within each threshold: fixed-point sums, added exactly by the merge.
nlohmann::json area_within_json(const AreaWithin& w) {
  return {{"thresholds", w.thresholds},
          {"within", w.within},
          {"undecided", w.undecided},
          {"distance_queries", w.distance_queries},
          {"triangles_split", w.triangles_split},
          {"seconds", w.seconds}};
}

// Adds the part's areas `json` to `sum` (empty: the first part's are taken as they are).
void add_area_within(std::optional<AreaWithin>& sum, const nlohmann::json& json, const std::string& path) {
  AreaWithin w;
  w.thresholds = json.at("thresholds").get<std::vector<double>>();
  w.within = json.at("within").get<std::vector<std::uint64_t>>();
  w.undecided = json.at("undecided").get<std::vector<std::uint64_t>>();
  w.distance_queries = json.at("distance_queries").get<std::size_t>();
  w.triangles_split = json.at("triangles_split").get<std::size_t>();
  w.seconds = json.at("seconds").get<double>();
  if (w.within.size() != w.thresholds.size() || w.undecided.size() != w.thresholds.size()) {
    throw Error(fmt::format("{}: the certified areas have {} and {} values for {} thresholds", path, w.within.size(),
                            w.undecided.size(), w.thresholds.size()));
  }
  // A share of A's area cannot exceed it (2^60 units, with room for rounding): more, and the parts
  // do not belong together (checked as they are added, so that no sum can wrap around).
  constexpr std::uint64_t kMost = (std::uint64_t{1} << 60) + (std::uint64_t{1} << 40);
  for (std::size_t k = 0; k < w.thresholds.size(); ++k) {
    if (w.within[k] > kMost || w.undecided[k] > kMost || w.within[k] + w.undecided[k] > kMost) {
      throw Error(fmt::format("{}: its certified areas are more than the surface", path));
    }
  }
  if (!sum) {
    sum = std::move(w);
    return;
  }
  if (w.thresholds != sum->thresholds) throw Error(fmt::format("{}: its certified areas are for other thresholds", path));
  for (std::size_t k = 0; k < w.thresholds.size(); ++k) {
    sum->within[k] += w.within[k];
    sum->undecided[k] += w.undecided[k];
    if (sum->within[k] + sum->undecided[k] > kMost) {
      throw Error(fmt::format("{}: the certified areas add up to more than the surface", path));
    }
  }
  sum->distance_queries += w.distance_queries;
  sum->triangles_split += w.triangles_split;
  sum->seconds += w.seconds;
}

using Part = PartHeader;

// The fields every part of one measurement has alike.
constexpr const char* kAlike[] = {"tool", "arguments", "inputs", "method", "semantics", "diagonal"};

void check_alike(const Part& first, const Part& part) {
  for (const char* key : kAlike) {
    if (part.description.at(key) != first.description.at(key)) {
      throw Error(fmt::format("{} and {}: parts of different measurements (their {} differ); merge the parts of "
                              "one roving measure command",
                              first.path, part.path, key));
    }
  }
  if (part.description.at("shard").at("count") != first.description.at("shard").at("count")) {
    throw Error(fmt::format("{} and {}: parts of different shardings ({}/{} and {}/{})", first.path, part.path,
                            first.description["shard"]["index"].dump(), first.description["shard"]["count"].dump(),
                            part.description["shard"]["index"].dump(), part.description["shard"]["count"].dump()));
  }
  for (std::size_t i = 0; i < first.directions.size(); ++i) {
    const auto total = [&](const Part& p) { return p.description["directions"][i]["samples"]["total"]; };
    if (part.directions.size() != first.directions.size() || total(part) != total(first) ||
        part.directions[i].agreement != first.directions[i].agreement ||
        part.directions[i].colour != first.directions[i].colour) {
      throw Error(fmt::format("{} and {}: parts of different sample sets", first.path, part.path));
    }
  }
}

// The parts in shard order, each once, all there, each the slice its index names.
std::vector<Part> ordered_parts(const std::vector<std::string>& paths) {
  if (paths.empty()) throw Error("merge: expected the parts of one measurement's shards, found none");
  std::vector<Part> parts;
  for (const std::string& path : paths) parts.push_back(read_part_header(path));
  std::size_t count = 0, run = 1;
  try {
    count = parts[0].description.at("shard").at("count").get<std::size_t>();
    run = parts[0].description.at("shard").at("run").get<std::size_t>();  // alike in parts of one method
    if (run == 0) throw Error(fmt::format("{}: its shard's run is 0; expected 1 or more", parts[0].path));
    for (const Part& part : parts) check_alike(parts[0], part);
  } catch (const nlohmann::json::exception& e) {
    throw Error(fmt::format("merge: a part's description is incomplete: {}", e.what()));
  }
  std::vector<const Part*> by_index(count, nullptr);
  for (const Part& part : parts) {
    const std::size_t index = part.description["shard"]["index"].get<std::size_t>();
    if (index >= count) throw Error(fmt::format("{}: shard {} of {} is out of range", part.path, index, count));
    if (by_index[index]) {
      throw Error(fmt::format("{} and {}: both are shard {}/{}", by_index[index]->path, part.path, index, count));
    }
    by_index[index] = &part;
  }
  std::vector<std::string> missing;
  for (std::size_t i = 0; i < count; ++i) {
    if (!by_index[i]) missing.push_back(fmt::format("{}/{}", i, count));
  }
  if (!missing.empty()) {
    throw Error(fmt::format("merge: shard{} {} missing (run {} again, then merge all {} parts)",
                            missing.size() == 1 ? "" : "s", fmt::join(missing, ", "),
                            missing.size() == 1 ? "it" : "them", count));
  }
  std::vector<Part> ordered;
  for (std::size_t i = 0; i < count; ++i) {
    const Part& part = *by_index[i];
    for (std::size_t k = 0; k < part.directions.size(); ++k) {
      const std::size_t total = part.description["directions"][k]["samples"]["total"].get<std::size_t>();
      const auto [first, last] = Shard{i, count}.range(total, run);
      const PartDirection& d = part.directions[k];
      if (d.first != first || d.count != last - first) {
        throw Error(fmt::format("{}: shard {}/{} should hold samples [{}, {}) of {}; it holds {} from {}", part.path,
                                i, count, first, last, total, d.count, d.first));
      }
    }
    ordered.push_back(part);
  }
  return ordered;
}

// The arguments the shards were run with, parsed as measure parses them.
MeasureArguments shard_arguments(const nlohmann::json& words) {
  const std::unique_ptr<CommandLine> line = make_command_line();
  std::vector<std::string> arguments = {"measure"};
  for (const auto& word : words) arguments.push_back(word.get<std::string>());
  const std::string error = parse_command_line(*line, arguments);
  if (!error.empty()) throw Error("merge: the parts' arguments do not parse: " + error);
  return line->args;
}

}  // namespace

void write_shard_part(std::FILE* out, const MeasureArguments& args, const MeasureRun& run) {
  const MeasureReport& r = run.report;
  nlohmann::json directions = nlohmann::json::array();
  std::vector<std::vector<double>> agreement;
  for (const DirectionReport& d : r.directions) {
    // Normal consistency's term, for the reconstruction figures of both directions.
    agreement.push_back(r.symmetric() ? normal_agreement({&d.samples, &d.result, &test_surface(*d.test)})
                                      : std::vector<double>());
    directions.push_back(
        {{"label", d.label},
         {"samples",
          {{"kind", d.samples.kind},
           {"total", d.slice_total},
           {"first", d.slice_first},
           {"count", d.result.hit.size()},
           {"skipped_degenerate_faces", d.samples.skipped_degenerate_faces},
           {"skipped_unreferenced_vertices", d.samples.skipped_unreferenced_vertices},
           {"skipped_zero_normal_vertices", d.samples.skipped_zero_normal_vertices}}},
         {"reference", d.reference_json},
         {"test", d.test_json},
         {"seconds", {{"build", d.result.build_seconds}, {"query", d.result.query_seconds}}},
         {"hausdorff", d.hausdorff ? hausdorff_json(*d.hausdorff) : nlohmann::json(nullptr)},
         {"area_within", d.area_within ? area_within_json(*d.area_within) : nlohmann::json(nullptr)},
         {"normal_agreement", !agreement.back().empty()},
         {"colour", d.colour_pairs.has_value()},
         {"colour_source", d.result.colour_source},
         {"gl", d.result.gl ? gl_json(*d.result.gl) : nlohmann::json(nullptr)}});
  }
  const nlohmann::json description = {
      {"tool", r.provenance.at("tool")},
      {"arguments", args.figure_arguments},
      {"inputs", r.provenance.at("inputs")},
      {"command_line", args.command_line},
      // run: the method's independent run, at whose multiples the slices are cut (shard.h).
      {"shard",
       {{"index", r.shard->shard.index}, {"count", r.shard->shard.count}, {"run", run.plan.method->independent_run()}}},
      {"header", format_header(*run.a, *run.b, r)},
      {"method", r.method},
      {"semantics", to_string(r.semantics)},
      {"max_error", r.max_error},
      {"max_error_text", r.max_error_text},
      {"hausdorff_bound", r.hausdorff_bound},
      {"diagonal", r.diagonal},
      {"diagonal_of_both", r.diagonal_of_both},
      {"seed", r.seed},
      {"model_warnings", r.shard->model_warnings},
      {"colour_compared", run.plan.options.colour},
      {"directions", directions},
      {"seconds",
       {{"load_reference", r.load_seconds[0]}, {"load_test", r.load_seconds[1]}, {"total", r.total_seconds}}}};
  // Weights are per sample wherever samples are made; a set without them stands for equal areas.
  std::vector<std::vector<double>> weights;
  for (const DirectionReport& d : r.directions) {
    weights.push_back(d.samples.weights);  // a streamed REF's shard keeps no positions: counted by its hits
    weights.back().resize(d.result.hit.size(), d.samples.weights.empty() ? 1.0 : d.samples.weights.back());
  }
  std::vector<PartColumns> columns;
  for (std::size_t i = 0; i < r.directions.size(); ++i) {
    const DistanceResult& result = r.directions[i].result;
    const std::optional<ColourPairs>& colours = r.directions[i].colour_pairs;
    columns.push_back({&result.signed_distance, &result.hit, &weights[i], &agreement[i],
                       colours ? &colours->reference : nullptr, colours ? &colours->test : nullptr});
  }
  write_part(out, description, columns);
}

namespace {

// One direction's figures folded in part by part, in sample order: a merge of one direction without
// colour holds 8 bytes a sample (|d|, for the exact percentiles) and one part's arrays, rather than
// every part's 17 bytes a sample, and computes the same figures bit for bit.
struct FoldedDirection {
  FoldedDirection(double max_error, std::size_t histogram_bins, std::size_t samples)
      : statistics(max_error, histogram_bins, samples), intervals(max_error) {}
  void add(const DistanceResult& part, const std::vector<double>& weights) {
    for (std::size_t k = 0; k < part.hit.size(); ++k) {
      statistics.add(part.signed_distance[k], part.hit[k], weights[k]);
      intervals.add(part.signed_distance[k], part.hit[k]);
    }
    const SignCounts counts = sign_counts(part);
    signs.positive += counts.positive;
    signs.negative += counts.negative;
    signs.zero += counts.zero;
  }
  StatisticsAccumulator statistics;
  IntervalsAccumulator intervals;
  SignCounts signs;
};

}  // namespace

MergedReport merge_parts(const std::vector<std::string>& paths, const std::string& command_line) {
  const Stopwatch watch;
  const std::vector<Part> parts = ordered_parts(paths);
  MergedReport merged;
  const nlohmann::json& first = parts.front().description;
  MeasureReport& r = merged.report;
  std::vector<std::vector<double>> agreement(parts.front().directions.size());
  bool colour_compared = false;  // both models have colour
  std::optional<FoldedDirection> folded;
  try {
    colour_compared = first.at("colour_compared").get<bool>();
    merged.plan = plan_measurement(shard_arguments(first.at("arguments")));
    merged.header = first.at("header").get<std::string>();
    r.method = first.at("method").get<std::string>();
    r.semantics = parse_semantics(first.at("semantics").get<std::string>());
    r.max_error = first.at("max_error").get<double>();
    r.max_error_text = first.at("max_error_text").get<std::string>();
    r.hausdorff_bound = first.at("hausdorff_bound").get<double>();
    r.diagonal = first.at("diagonal").get<double>();
    r.diagonal_of_both = first.at("diagonal_of_both").get<bool>();
    r.seed = first.at("seed").get<std::uint64_t>();
    r.warnings = first.at("model_warnings").get<std::vector<std::string>>();
    std::vector<std::string> part_paths;
    for (const Part& part : parts) part_paths.push_back(part.path);
    r.provenance = {{"tool", tool_json()},
                    {"command_line", command_line},
                    {"inputs", first.at("inputs")},
                    {"merged_from", {{"parts", part_paths}, {"shard_command_line", first.at("command_line")}}}};
    const nlohmann::json& directions = first.at("directions");
    if (directions.size() == 1 && !directions[0].at("colour").get<bool>()) {
      folded.emplace(r.max_error, merged.plan.histogram_bins, directions[0].at("samples").at("total").get<std::size_t>());
    }
    for (const nlohmann::json& direction : directions) {
      DirectionReport& d = r.directions.emplace_back();
      d.label = direction.at("label").get<std::string>();
      d.reference_json = direction.at("reference");
      d.test_json = direction.at("test");
      const nlohmann::json& samples = direction.at("samples");
      d.samples.kind = samples.at("kind").get<std::string>();
      d.samples.skipped_degenerate_faces = samples.at("skipped_degenerate_faces").get<std::size_t>();
      d.samples.skipped_unreferenced_vertices = samples.at("skipped_unreferenced_vertices").get<std::size_t>();
      d.samples.skipped_zero_normal_vertices = samples.at("skipped_zero_normal_vertices").get<std::size_t>();
      d.result.colour_source = direction.at("colour_source").get<std::string>();
      if (direction.at("colour").get<bool>()) d.colour_pairs.emplace();
      if (folded) continue;
      const std::size_t total = samples.at("total").get<std::size_t>();
      d.result.signed_distance.reserve(total);
      d.result.hit.reserve(total);
      d.samples.weights.reserve(total);
    }
    std::vector<std::size_t> parts_with_areas(r.directions.size(), 0);
    for (const Part& part : parts) {
      std::vector<PartArrays> into;
      DistanceResult read;  // a folded part's arrays, held until folded in
      std::vector<double> read_weights;
      for (std::size_t i = 0; i < r.directions.size(); ++i) {
        DirectionReport& d = r.directions[i];
        ColourPairs* colours = d.colour_pairs ? &*d.colour_pairs : nullptr;
        if (folded) {
          into.push_back({&read.signed_distance, &read.hit, &read_weights, &agreement[i], nullptr, nullptr});
          continue;
        }
        into.push_back({&d.result.signed_distance, &d.result.hit, &d.samples.weights, &agreement[i],
                        colours ? &colours->reference : nullptr, colours ? &colours->test : nullptr});
      }
      append_part_arrays(part, into);
      if (folded) folded->add(read, read_weights);
      const nlohmann::json& seconds = part.description.at("seconds");
      r.load_seconds[0] += seconds.at("load_reference").get<double>();
      r.load_seconds[1] += seconds.at("load_test").get<double>();
      r.total_seconds += seconds.at("total").get<double>();
      for (std::size_t i = 0; i < r.directions.size(); ++i) {
        DirectionReport& d = r.directions[i];
        const nlohmann::json& direction = part.description.at("directions").at(i);
        d.result.build_seconds += direction.at("seconds").at("build").get<double>();
        d.result.query_seconds += direction.at("seconds").at("query").get<double>();
        if (!direction.at("gl").is_null()) {  // the GL report adds the part's up, as a streamed block's
          if (!d.result.gl) d.result.gl.emplace();
          try {
            d.result.gl->add_block(gl_report_of(direction["gl"]));
          } catch (const Error& e) {
            throw Error(fmt::format("{}: {}", part.path, e.what()));
          }
        }
        if (!direction.at("area_within").is_null()) {
          add_area_within(d.area_within, direction["area_within"], part.path);
          ++parts_with_areas[i];
        }
        if (direction.at("hausdorff").is_null()) continue;
        // The largest lower end (with the points that attain it) and the largest upper end.
        const HausdorffInterval h = hausdorff_of(direction["hausdorff"]);
        if (!d.hausdorff) {
          d.hausdorff = h;
          continue;
        }
        if (h.lower > d.hausdorff->lower) {
          d.hausdorff->lower = h.lower, d.hausdorff->lower_point = h.lower_point,
          d.hausdorff->lower_closest = h.lower_closest;
        }
        d.hausdorff->upper = std::max(d.hausdorff->upper, h.upper);
        d.hausdorff->distance_queries += h.distance_queries;
        d.hausdorff->triangles_split += h.triangles_split;
        d.hausdorff->seconds += h.seconds;
      }
    }
    for (std::size_t i = 0; i < r.directions.size(); ++i) {
      if (parts_with_areas[i] != 0 && parts_with_areas[i] != parts.size()) {
        throw Error(fmt::format("{}: {} of {} parts carry certified areas within the thresholds; expected all or none",
                                parts.front().path, parts_with_areas[i], parts.size()));
      }
    }
  } catch (const nlohmann::json::exception& e) {
    throw Error(fmt::format("{}: the part's description is incomplete: {}", parts.front().path, e.what()));
  }
  // From here, as measure_models computes them from the same arrays (or, folded, from the same
  // samples in the same order).
  const MeasurePlan& plan = merged.plan;
  for (std::size_t i = 0; i < r.directions.size(); ++i) {
    DirectionReport& d = r.directions[i];
    const bool area = d.samples.kind.rfind("area:", 0) == 0;
    if (folded) {
      d.statistics = folded->statistics.finish();
      d.signs = folded->signs;
      if (area && folded->intervals.count() >= 2) d.intervals = folded->intervals.finish();
      d.heatmap_range = plan.heatmap_range ? plan.heatmap_range->resolve(r.diagonal)
                                           : default_heatmap_range(folded->statistics, d.statistics.hit_count,
                                                                   r.max_error);
    } else {
      d.statistics = compute_statistics(d.result.signed_distance, d.result.hit, d.samples.weights, r.max_error,
                                        plan.histogram_bins);
      d.signs = sign_counts(d.result);
      if (area && d.result.hit.size() >= 2) {
        d.intervals = sampling_intervals(d.result.signed_distance, d.result.hit, r.max_error);
      }
      d.heatmap_range =
          plan.heatmap_range ? plan.heatmap_range->resolve(r.diagonal) : default_heatmap_range(d.result, r.max_error);
    }
    if (d.colour_pairs) {
      d.colour = compute_colour_statistics(*d.colour_pairs, d.result.hit);
    } else if (colour_compared && i == 0) {
      r.warnings.push_back(no_colour_warning(r.method));
    }
    for (const std::string& line : result_warnings(d.statistics, r.semantics))
      r.warnings.push_back((d.label.empty() ? "" : d.label + ": ") + line);
  }
  if (r.symmetric()) {
    const auto arrays = [&](std::size_t i) {
      const DirectionReport& d = r.directions[i];
      return SampleFigures{&d.result.signed_distance, &d.result.hit, &d.samples.weights, &agreement[i]};
    };
    merge_reconstruction(r, plan, arrays(0), arrays(1));
  }
  r.total_seconds += watch.seconds();
  return merged;
}

int run_merge(const MergeArguments& args, std::string& stage) {
  stage = "merging the shards' parts";
  const MergedReport merged = merge_parts(args.parts, args.command_line);
  const MeasureReport& report = merged.report;
  if (!args.quiet) {
    for (const std::string& line : report.warnings) std::fprintf(stderr, "roving: warning: %s\n", line.c_str());
  }
  const std::string json = to_json(report).dump(2) + "\n";
  if (!args.json_path.empty() && args.json_path != "-") {
    stage = "writing the report";
    AtomicFile file(args.json_path);
    std::fputs(json.c_str(), file.stream());
    file.commit();
  }
  write_stdout(args.json_path == "-" ? json : merged.header + format_body(report));
  return apply_gates(merged.plan.gates, gate_values(report), merged.plan.gate_on);
}

}  // namespace roving
