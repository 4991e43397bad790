// `roving batch`: reading the pairs, slicing them into shards, measuring each (models and samples
// reused while consecutive pairs share them), one report per pair, and the merged summary.
#include "batch.h"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <openssl/evp.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <memory>

#include "html_output.h"
#include "provenance.h"
#include "roving/core/error.h"
#include "roving/core/stopwatch.h"
#include "roving/formats/files/atomic_file.h"
#include "roving/formats/files/file_bytes.h"
#include "roving/formats/files/file_hash.h"
#include "roving/gl/depth_renderer.h"
#include "roving/html/html_index.h"
#include "roving/measurement/figure_families.h"
#include "roving/measurement/shard.h"

namespace roving {
namespace {

namespace fs = std::filesystem;

// The manifest columns a pair may set, and the option each stands for.
const std::vector<std::string> kPairColumns = {
    "method",     "semantics", "samples",  "seed",         "max_error",  "views",         "resolution",
    "backend",    "camera_geometry", "view_culling", "protocol",     "dtu_obs_mask", "dtu_plane",   "tnt_crop",
    "tnt_alignment", "tnt_scene", "tnt_tau", "tnt_trajectory", "tnt_reference_trajectory", "tnt_mapping",
    "pcc_normals"};
// The columns that name a file: relative to the manifest, as the models are.
const std::vector<std::string> kFileColumns = {"dtu_obs_mask", "dtu_plane", "tnt_crop", "tnt_alignment",
                                               "tnt_trajectory", "tnt_reference_trajectory", "tnt_mapping",
                                               "pcc_normals"};

struct Pair {
  std::size_t index = 0;  // in the list, 0-based
  std::string reference, test;
  std::map<std::string, std::string> options;  // column -> value, as given
};

// One CSV line into fields: commas separate, double quotes enclose fields holding commas.
std::vector<std::string> csv_fields(const std::string& line) {
  std::vector<std::string> fields(1);
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (c == '"' && quoted && i + 1 < line.size() && line[i + 1] == '"') {
      fields.back() += '"', ++i;
    } else if (c == '"') {
      quoted = !quoted;
    } else if (c == ',' && !quoted) {
      fields.emplace_back();
    } else if (c != '\r') {
      fields.back() += c;
    }
  }
  return fields;
}

std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string quoted = "\"";
  for (char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

// Relative paths in a manifest are relative to the manifest's folder.
std::string resolve(const fs::path& folder, const std::string& path) {
  return fs::path(path).is_absolute() ? path : (folder / path).lexically_normal().string();
}

void check_columns(const std::string& where, const std::map<std::string, std::string>& row) {
  for (const auto& [column, value] : row) {
    if (column == "reference" || column == "test") continue;
    if (std::find(kPairColumns.begin(), kPairColumns.end(), column) == kPairColumns.end()) {
      throw Error(fmt::format("{}: unknown column '{}'; expected reference, test and any of {}", where, column,
                              fmt::join(kPairColumns, ", ")));
    }
  }
  for (const char* needed : {"reference", "test"}) {
    const auto it = row.find(needed);
    if (it == row.end() || it->second.empty()) {
      throw Error(fmt::format("{}: expected a '{}' path, found none", where, needed));
    }
  }
}

std::vector<Pair> read_manifest(const std::string& path) {
  require_regular_file(path, "a batch manifest (.csv or .jsonl)");
  std::ifstream file(path);
  if (!file) throw Error(fmt::format("{}: cannot open the batch manifest", path));
  const fs::path folder = fs::path(path).parent_path();
  const bool json_lines = fs::path(path).extension() == ".jsonl" || fs::path(path).extension() == ".json";
  std::vector<Pair> pairs;
  std::vector<std::string> header;
  std::string line;
  for (std::size_t number = 1; std::getline(file, line); ++number) {
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    const std::string where = fmt::format("{}:{}", path, number);
    std::map<std::string, std::string> row;
    if (json_lines) {
      nlohmann::json object;
      try {
        object = nlohmann::json::parse(line);
      } catch (const nlohmann::json::exception& e) {
        throw Error(fmt::format("{}: expected a JSON object per line, found malformed JSON ({})", where, e.what()));
      }
      if (!object.is_object()) throw Error(fmt::format("{}: expected a JSON object per line", where));
      for (const auto& [key, value] : object.items()) {
        row[key] = value.is_string() ? value.get<std::string>() : value.dump();
      }
    } else if (header.empty()) {
      header = csv_fields(line);
      continue;
    } else {
      const std::vector<std::string> fields = csv_fields(line);
      if (fields.size() != header.size()) {
        throw Error(fmt::format("{}: expected {} fields as the header has, found {}", where, header.size(),
                                fields.size()));
      }
      for (std::size_t i = 0; i < fields.size(); ++i) row[header[i]] = fields[i];
    }
    check_columns(where, row);
    Pair pair{pairs.size(), resolve(folder, row["reference"]), resolve(folder, row["test"]), {}};
    for (const auto& [column, value] : row) {
      if (column == "reference" || column == "test" || value.empty()) continue;
      const bool file = std::find(kFileColumns.begin(), kFileColumns.end(), column) != kFileColumns.end();
      pair.options[column] = file ? resolve(folder, value) : value;
    }
    pairs.push_back(std::move(pair));
  }
  if (pairs.empty()) throw Error(fmt::format("{}: expected at least one pair, found none", path));
  return pairs;
}

// The names of the regular files in `folder`, sorted.
std::vector<std::string> file_names(const std::string& folder) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(folder)) {
    if (entry.is_regular_file()) names.push_back(entry.path().filename().string());
  }
  std::sort(names.begin(), names.end());
  return names;
}

// Files of `references` paired with the files of the same name in `tests`. A file without a
// partner is an error that lists every such file, unless `skip_unpaired`.
std::vector<Pair> pair_folders(const std::string& references, const std::string& tests, bool skip_unpaired) {
  const std::vector<std::string> in_references = file_names(references), in_tests = file_names(tests);
  std::vector<std::string> names, unpaired;
  std::set_intersection(in_references.begin(), in_references.end(), in_tests.begin(), in_tests.end(),
                        std::back_inserter(names));
  for (const auto& [folder, listed] : {std::pair{&references, &in_references}, {&tests, &in_tests}}) {
    for (const std::string& name : *listed) {
      if (!std::binary_search(names.begin(), names.end(), name)) {
        unpaired.push_back((fs::path(*folder) / name).string());
      }
    }
  }
  if (names.empty()) {
    throw Error(fmt::format("{} and {}: expected files of the same name in both folders, found none", references,
                            tests));
  }
  if (!unpaired.empty() && !skip_unpaired) {
    throw Error(fmt::format("{} and {}: {} file(s) without a partner of the same name in the other folder: {}; "
                            "pass --skip-unpaired to measure the {} pair(s) found",
                            references, tests, unpaired.size(), fmt::join(unpaired, ", "), names.size()));
  }
  if (!unpaired.empty()) {
    std::fprintf(stderr, "roving: skipping %zu file(s) without a partner (--skip-unpaired): %s\n", unpaired.size(),
                 fmt::format("{}", fmt::join(unpaired, ", ")).c_str());
  }
  std::vector<Pair> pairs;
  for (const std::string& name : names) {
    pairs.push_back({pairs.size(), (fs::path(references) / name).string(), (fs::path(tests) / name).string(), {}});
  }
  return pairs;
}

MeasureArguments arguments_for(const Pair& pair, const MeasureArguments& defaults) {
  MeasureArguments a = defaults;
  a.reference_path = pair.reference;
  a.test_path = pair.test;
  for (const auto& [column, value] : pair.options) {
    if (column == "method") a.method = value;
    if (column == "semantics") a.semantics = value;
    if (column == "samples") a.samples = value;
    if (column == "max_error") a.max_error = value;
    if (column == "views") a.views = value;
    if (column == "backend") a.backend = value;
    if (column == "camera_geometry") a.camera_geometry = value;
    if (column == "view_culling") a.view_culling = value;
    if (column == "protocol") {
      if (value != "dtu" && value != "tanks-and-temples") {
        throw Error(fmt::format("protocol: expected dtu or tanks-and-temples, found '{}'", value));
      }
      a.protocol = value;
    }
    if (column == "dtu_obs_mask") a.dtu_obs_mask = value;
    if (column == "dtu_plane") a.dtu_plane = value;
    if (column == "tnt_crop") a.tnt_crop = value;
    if (column == "tnt_alignment") a.tnt_alignment = value;
    if (column == "tnt_scene") a.tnt_scene = value;
    if (column == "tnt_trajectory") a.tnt_trajectory = value;
    if (column == "tnt_reference_trajectory") a.tnt_reference_trajectory = value;
    if (column == "tnt_mapping") a.tnt_mapping = value;
    if (column == "pcc_normals") a.pcc_normals = value;
    if (column == "tnt_tau") {
      double tau = 0;
      if (!parse_number(value, tau)) throw Error(fmt::format("tnt_tau: expected a number, found '{}'", value));
      a.tnt_tau = tau;
    }
    if (column == "resolution" || column == "seed") {
      long long number = 0;
      if (!parse_number(value, number) || number < 0) {
        throw Error(fmt::format("{}: expected a whole number >= 0, found '{}'", column, value));
      }
      if (column == "resolution") a.resolution = static_cast<int>(std::min<long long>(number, 1 << 30));
      if (column == "seed") a.seed = static_cast<std::uint64_t>(number);
    }
  }
  return a;
}

// What decides a pair's result: its inputs' bytes and every option. Two runs, or two shards,
// with the same key would write the same report.
// `other_files`: what identifies the other files read (a protocol's data set, --pcc-normals; their
// sha256), empty without any.
std::string pair_key(const MeasureArguments& a, const std::string& reference_sha, const std::string& test_sha,
                     const std::string& other_files) {
  std::string identity = fmt::format(
      "{}|{}|method={}|semantics={}|samples={}|seed={}|max_error={}|views={}|resolution={}|backend={}|"
      "camera_geometry={}|symmetric={}|ref_type={}|test_type={}|bins={}|hausdorff_bound={}",
      reference_sha, test_sha, a.method, a.semantics, a.samples, a.seed ? std::to_string(*a.seed) : "",
      a.max_error, a.views, a.resolution, to_string(parse_gl_backend(a.backend)), a.camera_geometry,
      a.symmetric, a.reference_type, a.test_type, a.histogram_bins, a.hausdorff_bound);
  // Added only when asked for, so that the keys of reports without it stay what they were.
  if (a.ibsm) identity += fmt::format("|ibsm={}x{}", a.ibsm_views, a.ibsm_resolution);
  if (a.view_culling != "footprint") identity += "|view_culling=" + a.view_culling;
  if (a.pcc) identity += "|pcc";
  if (a.pcc_resolution) identity += fmt::format("|pcc_resolution={}", *a.pcc_resolution);
  if (!a.pcc_normals.empty()) identity += "|pcc_normals=" + other_files;
  if (a.pcc_dropdups != 2 || a.pcc_neighbors_proc != 1 || a.pcc_average_normals != 1 || a.pcc_mse_space != 1) {
    identity += fmt::format("|pcc_options={},{},{},{}", a.pcc_dropdups, a.pcc_neighbors_proc, a.pcc_average_normals,
                            a.pcc_mse_space);
  }
  if (!a.pcc_normal_calc_modification) identity += "|pcc_normal_calc_modification=false";
  if (!a.protocol.empty()) {
    identity += fmt::format("|protocol={}|files={}|dtu={},{},{}|seed={}|runs={}|tnt_scene={}|tnt_tau={}", a.protocol,
                            other_files, a.dtu_density, a.dtu_patch, a.dtu_max_dist, a.protocol_seed,
                            a.protocol_runs, a.tnt_scene, a.tnt_tau ? fmt::format("{}", *a.tnt_tau) : "");
  }
  unsigned char digest[EVP_MAX_MD_SIZE];
  unsigned int length = 0;
  EVP_Digest(identity.data(), identity.size(), digest, &length, EVP_sha256(), nullptr);
  std::string hex;
  for (unsigned int i = 0; i < 8; ++i) hex += fmt::format("{:02x}", digest[i]);
  return hex;
}

void write_json(const fs::path& path, const nlohmann::json& json) {
  AtomicFile file(path.string());
  std::fputs((json.dump(2) + "\n").c_str(), file.stream());
  file.close_stream();
  file.commit();
}

// A pair's web page, written before its report: a pair with a report has its page.
void write_page(const fs::path& path, const MeasureReport& report, const MeasurePlan& plan, const Model& reference,
                const Model& test, const nlohmann::json& json, std::string& stage) {
  stage = "writing the web page";
  AtomicFile page(path.string());
  write_html_page(page.stream(), measurement_page(report, format_header(reference, test, report) + format_body(report), json,
                                                  plan.heatmap_of));
  page.close_stream();
  page.commit();
}

// The summary's columns: where the pair is, how it went, then the report's figures.
std::vector<std::string> summary_row(const nlohmann::json& report) {
  const nlohmann::json& batch = report["batch"];
  const bool ok = batch["status"] == "ok";
  // A --pcc report has MPEG's figures alone: the surface columns stay empty.
  const bool surface = ok && report.contains("semantics");
  const nlohmann::json& direction = !surface                      ? nlohmann::json()
                                    : report.contains("directions") ? report["directions"][0]
                                                                    : report;
  const auto number = [](const nlohmann::json& value) {
    return value.is_number() ? fmt::format("{}", value.get<double>()) : std::string();
  };
  std::vector<std::string> row = {std::to_string(batch["index"].get<std::size_t>()), batch["reference"],
                                  batch["test"], batch["status"], batch.value("error", "")};
  row.push_back(ok ? report["method"].get<std::string>() : "");
  row.push_back(surface ? report["semantics"].get<std::string>() : "");
  row.push_back(surface ? number(direction["samples"]["count"]) : "");
  row.push_back(surface ? number(direction["no_hits"]) : "");
  row.push_back(surface ? number(report["diagonal"]) : "");
  row.push_back(surface ? number(report["max_error"]["value"]) : "");
  const nlohmann::json statistics = statistics_json(Statistics());
  for (const auto& item : statistics.items())
    row.push_back(surface ? number(direction["statistics"][item.key()]) : "");
  for (const char* key : {"hausdorff", "mean_both", "rms_both"}) {
    row.push_back(surface && report.contains("two_sided") ? number(report["two_sided"][key]) : "");
  }
  // The families' figures (IBSM, MPEG's, reconstruction, a protocol's), empty where not measured.
  for (const FigureFamily* family : summary_families()) {
    for (const SummaryColumn& column : family->summary) row.push_back(ok ? summary_cell(report, column) : "");
  }
  row.push_back(ok ? number(report["seconds"]["total"]) : "");
  std::string warnings;
  if (ok) {
    for (const auto& w : report["warnings"]) warnings += (warnings.empty() ? "" : " | ") + w.get<std::string>();
  }
  row.push_back(warnings);
  return row;
}

// Removes the temporary files that writers killed mid-write left in `folder` (never those a live
// process, such as a concurrent shard, is writing); returns how many.
std::size_t sweep_abandoned(const std::string& folder) {
  std::size_t removed = 0;
  for (const auto& entry : fs::directory_iterator(folder)) {
    if (is_temporary_name(entry.path().filename().string())) removed += remove_if_abandoned(entry.path().string());
  }
  return removed;
}

// index.html: the summary's main columns, a row per pair linking to its page where there is one.
void write_index(const std::string& folder, const std::vector<std::string>& header,
                 const std::vector<nlohmann::json>& reports, const std::vector<fs::path>& paths) {
  std::vector<std::string> shown = {"index",     "reference", "test",    "status",   "method",
                                    "semantics", "samples",   "no_hits", "usiad",    "siad",
                                    "rms",       "max_abs",   "p95",     "hausdorff"};
  for (const FigureFamily* family : summary_families()) {  // those some pair has figures of
    if (std::none_of(reports.begin(), reports.end(),
                     [&](const nlohmann::json& r) { return r.contains(family->section); })) {
      continue;
    }
    for (const SummaryColumn& column : family->summary) shown.push_back(column.name);
  }
  shown.insert(shown.end(), {"seconds", "warnings"});
  HtmlIndex page;
  page.title = fmt::format("surface roving batch: {} pairs", reports.size());
  page.intro = fmt::format("<p>From the reports in {}; lengths in model units. Click a column's name to sort.</p>",
                           escape_html(folder));
  HtmlTable& index = page.tables.emplace_back();
  index.header = shown;
  for (std::size_t r = 0; r < reports.size(); ++r) {
    const std::vector<std::string> row = summary_row(reports[r]);
    std::vector<std::string> cells;
    for (const std::string& name : shown) {
      const std::size_t column = static_cast<std::size_t>(std::find(header.begin(), header.end(), name) - header.begin());
      cells.push_back(name == "warnings" && row[4].size() ? "error: " + row[4] : row[column]);
    }
    index.rows.push_back(cells);
    index.failed.push_back(row[3] != "ok");
    fs::path page = paths[r];
    page.replace_extension(".html");
    index.links.push_back(row[3] == "ok" && fs::exists(page) ? page.filename().string() : "");
  }
  AtomicFile file((fs::path(folder) / "index.html").string());
  write_html_index(file.stream(), page);
  file.close_stream();
  file.commit();
}

// summary.csv from the reports in `folder`, one row per pair index in index order (where a pair
// has two reports, a finished one over a failed one, then the newer); temporary files are never
// read as reports. Returns (ok, failed) counts.
std::pair<std::size_t, std::size_t> merge(const std::string& folder, bool html) {
  if (!fs::is_directory(folder)) throw Error(fmt::format("--merge: expected a batch folder, found '{}'", folder));
  sweep_abandoned(folder);
  struct Found {
    nlohmann::json report;
    fs::file_time_type written;
    fs::path path;
  };
  std::map<std::size_t, Found> by_index;
  for (const auto& entry : fs::directory_iterator(folder)) {
    const std::string name = entry.path().filename().string();
    if (entry.path().extension() != ".json" || name.front() == '.' || !entry.is_regular_file()) continue;
    std::ifstream file(entry.path());
    nlohmann::json report;
    try {
      report = nlohmann::json::parse(file);
    } catch (const nlohmann::json::exception&) {
      throw Error(fmt::format("{}: not a JSON report (a file of another kind in the batch folder?)",
                              entry.path().string()));
    }
    if (!report.contains("batch")) continue;
    const std::size_t index = report["batch"]["index"].get<std::size_t>();
    const fs::file_time_type written = entry.last_write_time();
    const auto rank = [](const nlohmann::json& r, fs::file_time_type t) { return std::pair(r["batch"]["status"] == "ok", t); };
    const auto found = by_index.find(index);
    if (found == by_index.end() || rank(found->second.report, found->second.written) < rank(report, written)) {
      by_index[index] = {std::move(report), written, entry.path()};
    }
  }
  std::vector<nlohmann::json> reports;
  std::vector<fs::path> paths;
  for (auto& [index, found] : by_index) reports.push_back(std::move(found.report)), paths.push_back(found.path);
  std::vector<std::string> header = {"index", "reference", "test", "status", "error", "method", "semantics",
                                     "samples", "no_hits", "diagonal", "max_error"};
  const nlohmann::json statistics = statistics_json(Statistics());
  for (const auto& item : statistics.items()) header.push_back(item.key());
  header.insert(header.end(), {"hausdorff", "mean_both", "rms_both"});
  for (const FigureFamily* family : summary_families()) {
    for (const SummaryColumn& column : family->summary) header.push_back(column.name);
  }
  header.insert(header.end(), {"seconds", "warnings"});
  AtomicFile summary((fs::path(folder) / "summary.csv").string());
  fmt::print(summary.stream(), "{}\n", fmt::join(header, ","));
  std::size_t ok = 0;
  for (const nlohmann::json& report : reports) {
    std::vector<std::string> row = summary_row(report);
    for (std::string& field : row) field = csv_field(field);
    fmt::print(summary.stream(), "{}\n", fmt::join(row, ","));
    ok += report["batch"]["status"] == "ok";
  }
  summary.close_stream();
  if (html) write_index(folder, header, reports, paths);
  summary.commit();
  return {ok, reports.size() - ok};
}

// A model and the reference samples made from it, kept while consecutive pairs share them.
struct LoadedModel {
  std::string path, type;
  std::unique_ptr<Model> model;
  std::string samples_spec;
  std::unique_ptr<SampleSet> samples;
};

const Model& cached_model(LoadedModel& cache, const std::string& path, const std::string& type_text,
                          const MeasurePlan& plan, std::optional<ModelType> type, bool reference) {
  const std::string how = type_text + (plan.pcc_only ? "|pcc" : "");  // --pcc reads point clouds as they are
  if (!cache.model || cache.path != path || cache.type != how) {
    cache.model.reset();
    cache.samples.reset();
    cache.samples_spec.clear();
    cache.model = std::make_unique<Model>(load_for(plan, path, type, reference));
    cache.path = path, cache.type = how;
  }
  return *cache.model;
}

}  // namespace

int run_batch(const BatchArguments& args, std::string& stage, const Progress::Listener& listener) {
  if (args.merge_only) {
    const auto [ok, failed] = merge(args.out, args.html);
    std::printf("batch: %s/summary.csv: %zu pairs measured, %zu failed\n", args.out.c_str(), ok, failed);
    return failed ? kSomePairsFailedExitCode : 0;
  }
  std::vector<Pair> pairs;
  if (args.inputs.size() == 1) {
    pairs = read_manifest(args.inputs[0]);
  } else if (args.inputs.size() == 2 && fs::is_directory(args.inputs[0]) && fs::is_directory(args.inputs[1])) {
    pairs = pair_folders(args.inputs[0], args.inputs[1], args.skip_unpaired);
  } else {
    throw UsageError(fmt::format("batch: expected a manifest (.csv or .jsonl) or two folders, found {} argument(s)",
                            args.inputs.size()));
  }
  if (!args.defaults.tnt_plys.empty()) {
    throw UsageError("--tnt-plys: one pair's files would overwrite the last's; not in batch (measure a pair with it)");
  }
  if (!args.defaults.tnt_curves.empty()) {
    throw UsageError("--tnt-curves: one picture per pair would overwrite the last; not in batch (the curves are "
                     "in each pair's report, tanks_and_temples_protocol)");
  }
  const auto [first, last] = [&] {
    try {
      return args.shard.empty() ? std::pair<std::size_t, std::size_t>{0, pairs.size()}
                                : parse_shard("--shard", args.shard).range(pairs.size());
    } catch (const Error& e) {
      throw UsageError(e.what());
    }
  }();
  plan_command_line(args.defaults);  // the command line's own options: a usage error (exit 2) if bad
  // Every pair's options are checked before any is measured: a typo fails the batch at once.
  std::vector<MeasureArguments> arguments;
  for (std::size_t i = first; i < last; ++i) {
    try {
      arguments.push_back(arguments_for(pairs[i], args.defaults));
      plan_measurement(arguments.back());
    } catch (const Error& e) {
      throw Error(fmt::format("pair {} ({} vs {}): {}", i, pairs[i].reference, pairs[i].test, e.what()));
    }
  }
  fs::create_directories(args.out);
  if (const std::size_t swept = sweep_abandoned(args.out)) {
    std::fprintf(stderr, "roving: removed %zu temporary file(s) an interrupted run left in %s\n", swept, args.out.c_str());
  }

  Progress progress(args.defaults.quiet, /*log_lines=*/!listener);  // Python hears it through its callback
  if (listener) progress.listen(listener);
  const Stopwatch watch;
  std::map<std::string, std::string> hashes;  // path -> sha256
  const auto sha256 = [&](const std::string& path) {
    auto it = hashes.find(path);
    if (it == hashes.end()) it = hashes.emplace(path, file_sha256(path)).first;
    return it->second;
  };
  LoadedModel reference_cache, test_cache;
  std::size_t measured = 0, skipped = 0, failed = 0;
  for (std::size_t i = first; i < last; ++i) {
    const Pair& pair = pairs[i];
    const MeasureArguments& a = arguments[i - first];
    const std::size_t done = i - first;
    const double eta = done ? watch.seconds() / done * (last - i) : 0;
    progress.stage(fmt::format("pair {}/{}: {} vs {}{}", done + 1, last - first, fs::path(pair.reference).filename().string(),
                               fs::path(pair.test).filename().string(),
                               done ? fmt::format(", about {:.0f} s left", eta) : ""));
    nlohmann::json batch = {{"index", pair.index}, {"reference", pair.reference}, {"test", pair.test}};
    std::string key;
    // The other files a measurement reads (a protocol's data set, A's normals for MPEG's figures).
    const std::vector<std::string> other_files = {a.dtu_obs_mask, a.dtu_plane, a.tnt_crop, a.tnt_alignment,
                                                  a.pcc_normals};
    const bool others = !a.protocol.empty() || !a.pcc_normals.empty();
    try {
      std::string files;  // by their bytes
      for (const std::string& file : other_files) files += (file.empty() ? std::string("-") : sha256(file)) + " ";
      // run.py's registration's files, only where given (the keys of pairs without them stay as they were).
      for (const std::string& file : {a.tnt_trajectory, a.tnt_reference_trajectory, a.tnt_mapping}) {
        if (!file.empty()) files += sha256(file) + " ";
      }
      key = pair_key(a, sha256(pair.reference), sha256(pair.test), others ? files : "");
    } catch (const Error&) {
      // Unreadable input: keyed by the paths, so that its failure is recorded all the same.
      key = pair_key(a, pair.reference, pair.test, others ? fmt::format("{}", fmt::join(other_files, " ")) : "");
    }
    // Named by its place in the list too: two pairs of identical files still get a row each.
    const std::string name = fmt::format("{:06}-{}", pair.index, key);
    const fs::path done_path = fs::path(args.out) / (name + ".json");
    const fs::path failed_path = fs::path(args.out) / (name + ".failed.json");
    if (fs::exists(done_path)) {  // finished by an earlier run or another shard
      ++skipped;
      continue;
    }
    try {
      if (!a.protocol.empty()) {
        // A benchmark's protocol, as `measure` runs it: the pair's data set files read, TEST aligned
        // (Tanks and Temples), nothing shared with the next pair.
        const MeasureRun run = measure_run(a, stage, progress);
        nlohmann::json json = to_json(run.report);
        batch["status"] = "ok";
        json["batch"] = batch;
        // The protocol alone has no page (as `measure --protocol --html` needs --symmetric): a row in the index.
        if (args.html && !run.report.protocol_only) {
          write_page(fs::path(args.out) / (name + ".html"), run.report, run.plan, *run.a, *run.b, json, stage);
        }
        write_json(done_path, json);
        fs::remove(failed_path);
        ++measured;
        continue;
      }
      MeasurePlan plan = plan_measurement(a);
      MeasureReport report;
      Stopwatch load;
      stage = fmt::format("loading {}", pair.reference);
      const Model& reference = cached_model(reference_cache, pair.reference, a.reference_type, plan, plan.reference_type, true);
      report.load_seconds[0] = load.seconds();
      load = Stopwatch();
      stage = fmt::format("loading {}", pair.test);
      const Model& test = cached_model(test_cache, pair.test, a.test_type, plan, plan.test_type, false);
      report.load_seconds[1] = load.seconds();
      report.provenance = {{"tool", tool_json()},
                           {"command_line", a.command_line},
                           {"inputs",
                            {input_json(a.symmetric || a.pcc ? "A" : "reference", pair.reference, sha256(pair.reference)),
                             input_json(a.symmetric || a.pcc ? "B" : "test", pair.test, sha256(pair.test))}}};
      const WarnFn keep = [&](const std::vector<std::string>& lines) {
        report.warnings.insert(report.warnings.end(), lines.begin(), lines.end());
      };
      if (plan.pcc_only && !(reference.type == ModelType::Mesh && test.type == ModelType::Mesh)) {
        measure_point_clouds(reference, test, plan, report, progress, stage, keep);
        report.total_seconds = report.load_seconds[0] + report.load_seconds[1] + report.mpeg->seconds;
        nlohmann::json json = to_json(report);
        batch["status"] = "ok";
        json["batch"] = batch;
        write_json(done_path, json);
        fs::remove(failed_path);
        ++measured;
        continue;
      }
      describe_pair(reference, test, plan, report);
      // The reference's samples, made once while consecutive pairs share it and the sampling.
      if (reference_cache.samples_spec != plan.sample_spec.to_string() + std::to_string(plan.sample_spec.seed)) {
        reference_cache.samples = std::make_unique<SampleSet>(reference_samples(reference, plan.sample_spec));
        reference_cache.samples_spec = plan.sample_spec.to_string() + std::to_string(plan.sample_spec.seed);
      }
      const Stopwatch pair_watch;
      measure_models(reference, test, plan, report, progress, stage, keep, reference_cache.samples.get());
      report.total_seconds = report.load_seconds[0] + report.load_seconds[1] + pair_watch.seconds();
      nlohmann::json json = to_json(report);
      batch["status"] = "ok";
      json["batch"] = batch;
      if (args.html) write_page(fs::path(args.out) / (name + ".html"), report, plan, reference, test, json, stage);
      write_json(done_path, json);
      fs::remove(failed_path);
      ++measured;
    } catch (const std::exception& e) {
      if (progress.stopped()) throw;  // the caller stopped the batch (Python: Ctrl-C, its callback)
      // Recorded, and tried again by the next run; the batch goes on.
      batch["status"] = "failed";
      batch["error"] = e.what();
      write_json(failed_path, {{"schema_version", kReportSchemaVersion}, {"tool", tool_json()}, {"batch", batch}});
      progress.clear();
      std::fprintf(stderr, "roving: pair %zu (%s vs %s) failed: %s\n", pair.index, pair.reference.c_str(),
                   pair.test.c_str(), e.what());
      ++failed;
    }
  }
  progress.clear();
  merge(args.out, args.html);
  std::printf("batch: pairs %zu..%zu of %zu: %zu measured, %zu already done, %zu failed in %.1f s; %s/summary.csv\n",
              first, last ? last - 1 : 0, pairs.size(), measured, skipped, failed, watch.seconds(), args.out.c_str());
  return failed ? kSomePairsFailedExitCode : 0;
}

}  // namespace roving
