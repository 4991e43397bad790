// One pair across processes: `measure --shard I/N --shard-out PART` and `roving merge` give the
// report one process gives: every figure but the times (and the certified Hausdorff interval,
// which each shard bounds over its own triangles: it must hold the truth within the same width).
// Bad shards, parts and merges get one line and no output.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "cli_support.h"

namespace {

using namespace roving::testing::cli;

// The report's fields that say how long or by which command it ran, or how a certified interval
// was searched for, not what was measured.
bool incidental(const std::string& key) {
  for (const char* name : {"seconds", "command_line", "tool", "merged_from", "distance_queries", "triangles_split"}) {
    if (key == name) return true;
  }
  const std::string timed = "_seconds";  // a GL method's stages: camera_build_seconds, ...
  return key.size() > timed.size() && key.compare(key.size() - timed.size(), timed.size(), timed) == 0;
}

// Every field of `one` equal in `merged` (numbers bit for bit), but the incidental ones; `path`
// names the field in the failure.
void expect_same_report(const nlohmann::json& one, const nlohmann::json& merged, const std::string& path = "") {
  ASSERT_EQ(one.type(), merged.type()) << path;
  if (one.is_object()) {
    for (const auto& [key, value] : one.items()) {
      if (incidental(key)) continue;
      ASSERT_TRUE(merged.contains(key)) << path << "/" << key;
      expect_same_report(value, merged[key], path + "/" + key);
    }
    for (const auto& [key, value] : merged.items()) {
      if (!incidental(key)) {
        EXPECT_TRUE(one.contains(key)) << "only merged: " << path << "/" << key;
      }
    }
  } else if (one.is_array()) {
    ASSERT_EQ(one.size(), merged.size()) << path;
    for (std::size_t i = 0; i < one.size(); ++i) expect_same_report(one[i], merged[i], fmt::format("{}[{}]", path, i));
  } else {
    EXPECT_EQ(one, merged) << path;
  }
}

// `shards` parts of `pair options` in `folder`, named NAME.I.part; returns their paths joined.
std::string measure_shards(const Folder& folder, const std::string& name, const std::string& command,
                           std::size_t shards) {
  std::string parts;
  for (std::size_t i = 0; i < shards; ++i) {
    const std::string part = folder.file(fmt::format("{}.{}.part", name, i));
    const CliRun run = run_cli(fmt::format("measure {} --shard {}/{} --shard-out {} --quiet", command, i, shards, part));
    EXPECT_EQ(run.exit_code, 0) << run.err;
    EXPECT_NE(run.out.find(fmt::format("shard {}/{}: ", i, shards)), std::string::npos) << run.out;
    parts += " " + part;
  }
  return parts;
}

nlohmann::json merged_json(const std::string& parts) {
  const CliRun run = run_cli("merge" + parts + " --json - --quiet");
  EXPECT_EQ(run.exit_code, 0) << run.err;
  return nlohmann::json::parse(run.out);
}

// Face, vertex and area samples, first-hit, nearest and closest, three methods, one direction and
// both, colour, 1 to 7 shards: the merged report is the one-process report.
TEST(CliShard, MergedShardsGiveTheOneProcessReport) {
  const Folder folder;
  const std::string bunny_path = bunny(), rocker = roving::testing::data_file("rocker-arm.obj");
  const std::string cases[] = {
      bunny_path + " " + rocker + " --samples faces",
      bunny_path + " " + rocker + " --samples area:20000 --seed 3 --method cgal --semantics closest",
      rocker + " " + bunny_path + " --samples vertices --method v2p-aabb --max-error 10%",
      rocker + " " + bunny_path + " --samples area:5000 --semantics nearest --histogram-bins 9",
      // Both directions: Metro's two-sided summary and the reconstruction figures, with their
      // certified bounds (areas summed in fixed point: bit for bit whatever the shards).
      bunny_path + " " + rocker + " --symmetric --samples area:8000 --threshold 1% --threshold 0.2 --certify-thresholds",
      rocker + " " + bunny_path + " --symmetric --method v2p-aabb",
  };
  // Colour: both models coloured, both directions.
  const std::string coloured = folder.file("red.ply", coloured_cube_ply(0.5, 200)) + " " +
                               folder.file("redder.ply", coloured_cube_ply(0.55, 210)) + " --symmetric";
  // Each case in one of 1, 3 and 7 shards, in turn: every count meets single and both directions,
  // and a process start costs seconds under the sanitizers.
  const std::size_t shard_counts[] = {7, 3, 1};
  int k = 0;
  for (const std::string& command : {cases[0], cases[1], cases[2], cases[3], cases[4], cases[5], coloured}) {
    const CliRun one = run_cli("measure " + command + " --json - --quiet");
    ASSERT_EQ(one.exit_code, 0) << one.err;
    const nlohmann::json expected = nlohmann::json::parse(one.out);
    const std::size_t shards = shard_counts[k % 3];
    SCOPED_TRACE(fmt::format("{} in {} shards", command, shards));
    const nlohmann::json merged = merged_json(measure_shards(folder, fmt::format("c{}", k), command, shards));
    expect_same_report(expected, merged);
    EXPECT_EQ(merged["merged_from"]["parts"].size(), shards);
    ++k;
  }
}

// Exact roving (GL) draws each sample's camera at its place in a batch of 4,096 cameras: its shards
// are cut at multiples of that, and the merged report, GL counts included, is the one process's.
TEST(CliShard, ExactRovingShardsAtItsCameraBatches) {
  const Folder folder;
  const std::string command = bunny() + " " + roving::testing::data_file("rocker-arm.obj") +
                              " --symmetric --samples area:10000 --seed 5 --method roving --max-error 0.2%";
  const CliRun one = run_cli("measure " + command + " --json - --quiet");
  ASSERT_EQ(one.exit_code, 0) << one.err;
  const nlohmann::json expected = nlohmann::json::parse(one.out);
  const nlohmann::json merged = merged_json(measure_shards(folder, "roving", command, 2));
  expect_same_report(expected, merged);
  for (const nlohmann::json& direction : merged["directions"]) EXPECT_EQ(direction["gl"]["sample_cameras"], 10000);
  // In 3 parts, 10,000 samples are cut at the nearest multiples, 4,096 and 8,192: each holds a batch.
  // In 4, the cuts at 2,500 and 5,000 both go to 4,096, and the second part is empty.
  const nlohmann::json three = merged_json(measure_shards(folder, "three", command, 3));
  expect_same_report(expected, three);
  expect_error(fmt::format("measure {} --shard 1/4 --shard-out {}", command, folder.file("x.part")),
               {"--shard 1/4", "at most 2 shards", "4096"});
  // 6,000 samples in 2 parts are cut at 4,096 (3,000 rounded up), not at 0.
  const std::string fewer = bunny() + " " + roving::testing::data_file("rocker-arm.obj") +
                            " --samples area:6000 --seed 5 --method roving --max-error 0.2%";
  const nlohmann::json whole = nlohmann::json::parse(run_cli("measure " + fewer + " --json - --quiet").out);
  expect_same_report(whole, merged_json(measure_shards(folder, "fewer", fewer, 2)));
  // In 3, the first cut (2,000) goes to 0.
  expect_error(fmt::format("measure {} --shard 0/3 --shard-out {}", fewer, folder.file("x.part")),
               {"--shard 0/3", "at most 1 shard (", "4096"});
}

// The text report too, but for its time lines.
TEST(CliShard, MergedTextIsTheOneProcessText) {
  const Folder folder;
  const std::string command = bunny() + " " + roving::testing::data_file("rocker-arm.obj") + " --samples area:3000";
  const CliRun one = run_cli("measure " + command + " --quiet");
  const CliRun merged = run_cli("merge" + measure_shards(folder, "t", command, 2) + " --quiet");
  ASSERT_EQ(merged.exit_code, 0) << merged.err;
  const auto without_times = [](const std::string& text) {
    std::string kept, line;
    std::istringstream in(text);
    while (std::getline(in, line)) {
      if (line.find("time:") == std::string::npos && line.find("build ") == std::string::npos) kept += line + "\n";
    }
    return kept;
  };
  EXPECT_EQ(without_times(one.out), without_times(merged.out));
}

// Cubes of half-sides 0.5 and 0.55: from the large one's corners the small one is 0.05 sqrt(3)
// away, the one-sided Hausdorff distance. Each shard bounds its share of the triangles; merged,
// the interval still holds it and is no wider than asked.
TEST(CliShard, MergedCertifiedIntervalHoldsTheClosedForm) {
  const Folder folder;
  const std::string command = folder.file("large.obj", cube_obj(0.55)) + " " + folder.file("small.obj", cube_obj(0.5)) +
                              " --semantics closest --hausdorff-bound 1e-6";
  const nlohmann::json merged = merged_json(measure_shards(folder, "h", command, 4));
  const auto& h = merged["hausdorff_certified"];
  const double truth = 0.05 * std::sqrt(3.0);
  EXPECT_LE(h["lower"].get<double>(), truth + 1e-12);
  EXPECT_GE(h["upper"].get<double>(), truth - 1e-12);
  EXPECT_LE(h["upper"].get<double>() - h["lower"].get<double>(), 1e-6);
}

// Gates given to the shards are the merge's: exit 3 when breached.
TEST(CliShard, MergeAppliesTheShardsGates) {
  const Folder folder;
  const std::string command = folder.file("a.obj", cube_obj(0.5)) + " " + folder.file("b.obj", cube_obj(0.55)) +
                              " --fail-above usiad=0.01";
  const CliRun run = run_cli("merge" + measure_shards(folder, "g", command, 2) + " --quiet");
  EXPECT_EQ(run.exit_code, 3) << run.err;
  EXPECT_NE(run.err.find("usiad"), std::string::npos) << run.err;
}

TEST(CliShard, BadShardsGetOneLineAndNoPart) {
  const Folder folder;
  const std::string pair = folder.file("a.obj", cube_obj(0.5)) + " " + folder.file("b.obj", cube_obj(0.55));
  const std::string part = folder.file("x.part");
  for (const char* shard : {"5/4", "0/0", "1", "a/4", "-1/4", "1/4/2", "4/4"}) {
    expect_error(fmt::format("measure {} --shard {} --shard-out {}", pair, shard, part), {"--shard", shard});
  }
  expect_error("measure " + pair + " --shard 0/2", {"--shard", "--shard-out"});
  expect_error("measure " + pair + " --shard-out " + part, {"--shard-out", "--shard"});
  expect_error("measure " + pair + " --shard 0/2 --shard-out " + part + " --ibsm", {"--ibsm", "--shard"});
  expect_error("measure " + pair + " --shard 0/2 --shard-out " + part + " --html x.html", {"--html", "--shard"});
  expect_error("measure " + pair + " --shard 0/2 --shard-out " + part + " --method viewpoint", {"--shard", "viewpoint"});
  // A cube has 12 face samples: in 13 shards, the first has none.
  expect_error("measure " + pair + " --shard 0/13 --shard-out " + part, {"--shard 0/13", "12 samples", "at most 12"});
  EXPECT_EQ(folder.entries(), 2u);  // the models alone: no part, no temporary file
}

TEST(CliShard, BadMergesGetOneLineAndNoReport) {
  const Folder folder;
  const std::string a = folder.file("a.obj", cube_obj(0.5)), b = folder.file("b.obj", cube_obj(0.55));
  const std::string pair = a + " " + b;
  const std::string p0 = folder.file("p0.part"), p1 = folder.file("p1.part"), p2 = folder.file("p2.part");
  for (const auto& [i, path] : {std::pair{0, p0}, {1, p1}, {2, p2}}) {
    ASSERT_EQ(run_cli(fmt::format("measure {} --shard {}/3 --shard-out {}", pair, i, path)).exit_code, 0);
  }
  const std::string other = folder.file("other.part");
  ASSERT_EQ(run_cli(fmt::format("measure {} --max-error 1% --shard 2/3 --shard-out {}", pair, other)).exit_code, 0);
  const std::string halves = folder.file("halves.part");
  ASSERT_EQ(run_cli(fmt::format("measure {} --shard 1/2 --shard-out {}", pair, halves)).exit_code, 0);
  const std::string report = folder.file("report.json");
  const std::string out = " --json " + report;

  expect_error("merge " + p0 + " " + p2 + out, {"shard 1/3 missing"});
  expect_error("merge " + p0 + " " + p1 + " " + p1 + " " + p2 + out, {"both are shard 1/3"});
  expect_error("merge " + p0 + " " + p1 + " " + other + out, {"different measurements", "arguments"});
  expect_error("merge " + p0 + " " + p1 + " " + halves + out, {"different shardings"});
  expect_error("merge " + a + out, {a.c_str(), "expected a shard's part"});
  expect_error("merge " + folder.file("none.part") + out, {"none.part", "cannot read"});
  expect_error("merge" + out, {"PARTS"});

  // A part cut short, or with a byte more: its size says so.
  std::string bytes;
  {
    std::ifstream in(p2, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  const std::string cut = folder.file("cut.part", bytes.substr(0, bytes.size() - 5));
  expect_error("merge " + p0 + " " + p1 + " " + cut + out, {"cut.part", "truncated"});
  const std::string longer = folder.file("longer.part", bytes + "x");
  expect_error("merge " + p0 + " " + p1 + " " + longer + out, {"longer.part", "bytes"});
  const std::string header_only = folder.file("header.part", bytes.substr(0, bytes.find('\n') + 10));
  expect_error("merge " + p0 + " " + p1 + " " + header_only + out, {"header.part"});
  // A hit flag that is neither 0 nor 1.
  std::string damaged = bytes;
  damaged[damaged.size() - 4 * 8 - 1] = 7;  // shard 2/3 holds 4 of the 12 face samples
  expect_error("merge " + p0 + " " + p1 + " " + folder.file("damaged.part", damaged) + out, {"hit flag", "damaged"});
  // A distance that is not a number, and a negative area: the arrays start after the second line.
  const std::size_t arrays = bytes.find('\n', bytes.find('\n') + 1) + 1;
  std::string not_a_number = bytes;
  const double nan = std::nan("");
  std::memcpy(&not_a_number[arrays], &nan, sizeof nan);
  expect_error("merge " + p0 + " " + p1 + " " + folder.file("nan.part", not_a_number) + out, {"distance nan", "damaged"});
  std::string negative = bytes;
  const double minus_one = -1;
  std::memcpy(&negative[bytes.size() - sizeof minus_one], &minus_one, sizeof minus_one);
  expect_error("merge " + p0 + " " + p1 + " " + folder.file("negative.part", negative) + out, {"sample area -1", "damaged"});
  EXPECT_FALSE(fs::exists(report));
}

// One process, a reference too large to hold: `measure --chunk N` reads, samples and measures a
// binary PLY REF N faces at a time. Its report is the one the whole reference gives, every figure
// bit for bit (the same samples, folded into the statistics in the same order).

std::string file_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Igea (134,345 vertices and 268,686 triangles of binary PLY) and where its body starts.
struct Igea {
  std::string path = roving::testing::data_file("igea.ply");
  std::string bytes = file_bytes(path);
  std::size_t body = bytes.find("end_header\n") + 11;
  std::size_t faces = body + 134345 * 12;

  // TEST: Igea's vertices moved by up to 0.3% of its size, smoothly, so that d varies.
  std::string moved(const Folder& folder) const {
    std::string moved = bytes;
    for (std::size_t v = 0; v < 134345; ++v) {
      float xyz[3];
      std::memcpy(xyz, &moved[body + 12 * v], sizeof xyz);
      xyz[0] += 3e-4f * std::sin(70.0f * xyz[1]);
      xyz[2] += 3e-4f * std::cos(70.0f * xyz[0]);
      std::memcpy(&moved[body + 12 * v], xyz, sizeof xyz);
    }
    return folder.file("moved.ply", moved);
  }

  // Igea with what a whole mesh counts: two faces that repeat a vertex (dropped), faces of zero
  // area (30 and 200,000, and any other on the edge 11-13: skipped) and two vertices no face uses,
  // far outside (left out of the box).
  std::string odd(const Folder& folder) const {
    std::string odd = bytes;
    const auto set_face = [&](std::size_t face, std::int32_t a, std::int32_t b, std::int32_t c) {
      const std::int32_t corners[3] = {a, b, c};
      std::memcpy(&odd[faces + 13 * face + 1], corners, sizeof corners);
    };
    set_face(100, 7, 7, 8);
    set_face(5000, 9, 10, 9);
    set_face(30, 13, 12, 11);  // zero-area once vertex 13 is on vertex 11, below
    set_face(200000, 11, 12, 13);
    std::memcpy(&odd[body + 12 * 13], &odd[body + 12 * 11], 12);
    const std::string header = "element vertex 134345";
    odd.replace(odd.find(header), header.size(), "element vertex 134347");
    const float far[6] = {100, 100, 100, -100, -100, -100};  // after the last vertex (the header kept its size)
    odd.insert(faces, reinterpret_cast<const char*>(far), sizeof far);
    return folder.file("odd.ply", odd);
  }
};

// `other` against `one` as expect_same_report, but for the certified Hausdorff interval, which a
// block or a shard bounds on its own: both hold the one-sided Hausdorff distance, so they meet, and
// each is as narrow as asked (`gap`).
void expect_same_bounded_report(const nlohmann::json& one, nlohmann::json other, double gap) {
  if (!one.contains("hausdorff_certified")) return expect_same_report(one, other);
  const auto ends = [](const nlohmann::json& h) { return std::pair{h["lower"].get<double>(), h["upper"].get<double>()}; };
  const auto [low, high] = ends(other["hausdorff_certified"]);
  const auto [whole_low, whole_high] = ends(one["hausdorff_certified"]);
  EXPECT_LE(low, whole_high);
  EXPECT_LE(whole_low, high);
  EXPECT_LE(high - low, gap);
  EXPECT_GE(high, other["statistics"]["max_abs"].get<double>()) << "every sample is a point of REF";
  other.erase("hausdorff_certified");
  nlohmann::json without = one;
  without.erase("hausdorff_certified");
  expect_same_report(without, other);
}

// Vertex samples with REF streamed: its faces read a block at a time for the vertex normals and
// areas (summed in the file's order, as the whole mesh sums them), then its vertices measured a
// block at a time: the whole report, the same bits.
TEST(CliStreamed, VertexSamplesGiveTheWholeReport) {
  const Folder folder;
  const Igea igea;
  const std::string test = igea.moved(folder);
  for (const char* options : {"--semantics closest --hausdorff-bound none", "--hausdorff-bound none",
                              "--method cgal --semantics closest --hausdorff-bound 1e-5"}) {
    SCOPED_TRACE(options);
    const std::string pair = fmt::format("measure {} {} --samples vertices {} --quiet --json -", igea.path, test, options);
    const CliRun whole = run_cli(pair + " --chunk 0");
    ASSERT_EQ(whole.exit_code, 0) << whole.err;
    const nlohmann::json one = nlohmann::json::parse(whole.out);
    const std::size_t chunk = 3 * 4096 + 1;
    const CliRun run = run_cli(fmt::format("{} --chunk {}", pair, chunk));
    ASSERT_EQ(run.exit_code, 0) << run.err;
    nlohmann::json streamed = nlohmann::json::parse(run.out);
    ASSERT_TRUE(streamed["samples"].contains("streamed"));
    const std::size_t vertices = one["samples"]["count"].get<std::size_t>() +
                                 one["samples"]["skipped_unreferenced_vertices"].get<std::size_t>() +
                                 one["samples"]["skipped_zero_normal_vertices"].get<std::size_t>();
    EXPECT_EQ(streamed["samples"]["streamed"]["chunks"], (vertices + chunk - 1) / chunk);
    streamed["samples"].erase("streamed");
    EXPECT_EQ(streamed["statistics"], one["statistics"]);
    expect_same_bounded_report(one, streamed, 1e-5);
  }
  const CliRun text = run_cli(fmt::format("measure {} {} --samples vertices --chunk 100000", igea.path, test));
  EXPECT_NE(text.out.find("REF read 100000 faces at a time for its vertex normals, then measured 100000 vertices"),
            std::string::npos)
      << text.out;
}

TEST(CliStreamed, ReferenceReadInChunksGivesTheWholeReport) {
  const Folder folder;
  const Igea igea;
  const std::string test = igea.moved(folder);
  const std::string report = folder.file("report.json");
  // "--max-error 0.04%": four samples in five miss, and the heat-map range is read past them.
  // Exact roving's cameras are drawn 4,096 tiles a batch: neither block size is a multiple of it.
  for (const char* options : {"", "--semantics nearest", "--method cgal --semantics closest --hausdorff-bound none",
                              "--method v2p-aabb --hausdorff-bound none --histogram-bins 7",
                              "--semantics closest --hausdorff-bound 1e-5", "--max-error 0.04%",
                              "--method roving --max-error 0.2%"}) {
    const std::string pair = fmt::format("measure {} {} {} --quiet --json -", igea.path, test, options);
    const CliRun whole = run_cli(pair + " --chunk 0");
    ASSERT_EQ(whole.exit_code, 0) << whole.err;
    const nlohmann::json one = nlohmann::json::parse(whole.out);
    EXPECT_FALSE(one["samples"].contains("streamed"));
    // 1,000 faces a time, and blocks that cut TriangleMesh's 4,096-face blocks of area sums (under
    // the sanitizers the latter alone, a third fewer runs).
    std::vector<std::size_t> chunks = {3 * 4096 + 1};
    if (!roving::testing::kUnderSanitizers) chunks.push_back(1000);
    for (const std::size_t chunk : chunks) {
      const CliRun run = run_cli(fmt::format("{} --chunk {}", pair, chunk));
      ASSERT_EQ(run.exit_code, 0) << run.err;
      nlohmann::json streamed = nlohmann::json::parse(run.out);
      ASSERT_TRUE(streamed["samples"].contains("streamed")) << options;
      EXPECT_EQ(streamed["samples"]["streamed"]["chunk_faces"], chunk);
      EXPECT_EQ(streamed["samples"]["streamed"]["chunks"], (268686 + chunk - 1) / chunk);
      streamed["samples"].erase("streamed");
      SCOPED_TRACE(fmt::format("{} --chunk {}", options, chunk));
      expect_same_bounded_report(one, streamed, 1e-5);
    }
  }
  // More faces per block than Igea has, or what needs REF whole: read whole.
  for (const std::string& options :
       {std::string("--chunk 300000"), std::string("--chunk 1000 --symmetric"),
        "--chunk 1000 --samples vertices --samples-out " + folder.file("samples.csv"),
        std::string("--chunk 1000 --method viewpoint"), std::string("--chunk 1000 --method cooperative")}) {
    const CliRun run = run_cli(fmt::format("measure {} {} {} --quiet --json -", igea.path, test, options));
    ASSERT_EQ(run.exit_code, 0) << options << run.err;
    EXPECT_EQ(run.out.find("\"streamed\""), std::string::npos) << options;
  }
}

// `pair` (a measure command line) with REF read whole and `chunk` faces at a time: both reports,
// the streamed one checked to say so and with that said left out.
struct WholeAndStreamed {
  nlohmann::json whole, streamed;
};
WholeAndStreamed whole_and_streamed(const std::string& pair, std::size_t chunk, std::size_t faces) {
  const CliRun whole = run_cli(pair + " --chunk 0");
  EXPECT_EQ(whole.exit_code, 0) << whole.err;
  const CliRun run = run_cli(fmt::format("{} --chunk {}", pair, chunk));
  EXPECT_EQ(run.exit_code, 0) << run.err;
  if (whole.exit_code != 0 || run.exit_code != 0) return {};
  WholeAndStreamed reports{nlohmann::json::parse(whole.out), nlohmann::json::parse(run.out)};
  EXPECT_EQ(reports.streamed["samples"]["streamed"]["chunks"], (faces + chunk - 1) / chunk) << pair;
  reports.streamed["samples"].erase("streamed");
  return reports;
}

// What the whole mesh says of itself, found by the streamed pass alike: faces repeating a vertex
// dropped and counted, zero-area faces skipped, unreferenced vertices left out of the box.
TEST(CliStreamed, SummaryCountsWhatTheWholeMeshCounts) {
  const Folder folder;
  const Igea igea;
  const std::string ref = igea.odd(folder);
  const auto [one, streamed] = whole_and_streamed(fmt::format("measure {} {} --quiet --json -", ref, igea.path), 4095,
                                                  268686);
  EXPECT_EQ(one["reference"]["dropped_repeated_vertex_faces"], 2);
  EXPECT_EQ(one["reference"]["unreferenced_vertices"], 2);
  EXPECT_GE(one["samples"]["skipped_degenerate_faces"], 2);  // and any other face on the edge 11-13
  EXPECT_LT(one["reference"]["diagonal"].get<double>(), 1);
  expect_same_report(one, streamed);
  // Its vertices as samples: the unreferenced ones skipped alike, by blocks of vertices made in
  // parts on every core (4095 is no multiple of the parts).
  const auto [by_vertex, streamed_by_vertex] = whole_and_streamed(
      fmt::format("measure {} {} --samples vertices --semantics closest --hausdorff-bound none --quiet --json -", ref,
                  igea.path),
      4095, 134347);
  EXPECT_EQ(by_vertex["samples"]["skipped_unreferenced_vertices"], 2);
  expect_same_report(by_vertex, streamed_by_vertex);
}

// A shard streams REF too: it reads the file only as far as its slice of the samples, measures
// that slice alone, and bounds its share of the triangles; merged, the parts are the report of
// one process holding REF whole. REF has faces of zero area before and within the slices.
TEST(CliStreamed, ShardsReadOnlyAsFarAsTheirSlices) {
  const Folder folder;
  const Igea igea;
  const std::string pair = igea.odd(folder) + " " + igea.moved(folder);
  const std::size_t chunk = 3 * 4096 + 1, chunks = (268686 + chunk - 1) / chunk;
  for (const char* options : {"", "--method roving --max-error 0.2%", "--semantics closest --hausdorff-bound 1e-5"}) {
    SCOPED_TRACE(options);
    const CliRun whole = run_cli(fmt::format("measure {} {} --chunk 0 --quiet --json -", pair, options));
    ASSERT_EQ(whole.exit_code, 0) << whole.err;
    std::string parts;
    std::vector<std::size_t> read;
    for (int i = 0; i < 3; ++i) {
      const std::string part = folder.file(fmt::format("p{}.part", i));
      const CliRun run = run_cli(fmt::format("measure {} {} --chunk {} --shard {}/3 --shard-out {} --quiet --json -",
                                             pair, options, chunk, i, part));
      ASSERT_EQ(run.exit_code, 0) << run.err;
      const nlohmann::json shard = nlohmann::json::parse(run.out);
      ASSERT_TRUE(shard["samples"].contains("streamed"));
      read.push_back(shard["samples"]["streamed"]["chunks"].get<std::size_t>());
      parts += " " + part;
    }
    EXPECT_LT(read[0], read[1]);
    EXPECT_LT(read[1], read[2]);
    EXPECT_EQ(read[2], chunks);
    expect_same_bounded_report(nlohmann::json::parse(whole.out), merged_json(parts), 1e-5);
  }
}

// A streamed REF is checked as read_ply checks a whole one: one line naming the file and the
// face or vertex, and no report written.
TEST(CliStreamed, BadStreamedReferenceGetsOneLine) {
  const Folder folder;
  const Igea igea;
  const std::string report = folder.file("report.json");
  const auto measure = [&](const std::string& name, const std::string& bytes) {
    return fmt::format("measure {} {} --chunk 1000 --json {}", folder.file(name, bytes), igea.path, report);
  };
  std::string quad = igea.bytes;
  quad[igea.faces + 13 * 5000] = 4;  // face 5000 declares 4 corners in a file sized for triangles
  expect_error(measure("quad.ply", quad), {"quad.ply", "face 5000 has 4 corners", "expected a triangle"});
  std::string far_index = igea.bytes;
  const std::int32_t beyond = 134345;
  std::memcpy(&far_index[igea.faces + 13 * 7 + 1 + 4], &beyond, sizeof beyond);
  expect_error(measure("index.ply", far_index), {"index.ply", "face 7 refers to vertex 134345", "[0, 134345)"});
  std::string not_finite = igea.bytes;
  const float nan = std::nanf("");
  std::memcpy(&not_finite[igea.body + 12 * 42 + 4], &nan, sizeof nan);
  expect_error(measure("nan.ply", not_finite), {"nan.ply", "vertex 42 has a non-finite coordinate"});
  EXPECT_FALSE(fs::exists(report));
}


// Igea as a binary STL: each facet's corners the PLY's vertices, which read_stl merges back by
// their bits into its 134,345 vertices.
std::string igea_as_stl(const Igea& igea) {
  constexpr std::uint32_t kFacets = 268686;
  std::string stl(80, '\0');
  stl.append(reinterpret_cast<const char*>(&kFacets), sizeof kFacets);
  for (std::size_t f = 0; f < kFacets; ++f) {
    char record[50] = {};
    for (int c = 0; c < 3; ++c) {
      std::int32_t v = 0;
      std::memcpy(&v, &igea.bytes[igea.faces + 13 * f + 1 + 4 * c], sizeof v);
      std::memcpy(record + 12 + 12 * c, &igea.bytes[igea.body + 12 * static_cast<std::size_t>(v)], 12);
    }
    stl.append(record, sizeof record);
  }
  return stl;
}

void set_corner(std::string& stl, std::size_t facet, int corner, float x, float y, float z) {
  const float xyz[3] = {x, y, z};
  std::memcpy(&stl[84 + 50 * facet + 12 + 12 * corner], xyz, sizeof xyz);
}

// A binary STL REF streams too, with the report its whole mesh gives: read_stl merges corners by
// their bits into vertices, so the streamed pass counts the distinct corners (0 and -0 apart),
// drops facets repeating a corner and leaves the corners only they have unreferenced.
TEST(CliStreamed, BinaryStlGivesTheWholeReport) {
  const Folder folder;
  const Igea igea;
  std::string stl = igea_as_stl(igea);
  std::memcpy(&stl[84 + 50 * 100 + 24], &stl[84 + 50 * 100 + 12], 12);  // corner 1 on corner 0: dropped
  set_corner(stl, 5000, 0, 100, 100, 100);  // and a facet of corners no other facet has: two
  set_corner(stl, 5000, 1, 100, 100, 100);  // unreferenced vertices, far outside the box
  set_corner(stl, 5000, 2, -100, -100, -100);
  set_corner(stl, 200000, 0, 0.0f, 0.01f, 0.0f);  // 0 and -0 are different corners: a kept facet
  set_corner(stl, 200000, 1, -0.0f, 0.01f, 0.0f);  // of zero area
  set_corner(stl, 200000, 2, 0.001f, 0.01f, 0.0f);
  const std::string ref = folder.file("igea.stl", stl);
  for (const char* options : {"", "--method cgal --semantics closest --hausdorff-bound none",
                              "--semantics closest --hausdorff-bound 1e-3"}) {  // the last: REF as small meshes
    SCOPED_TRACE(options);
    auto [one, streamed] =
        whole_and_streamed(fmt::format("measure {} {} {} --quiet --json -", ref, igea.path, options), 4095, 268686);
    EXPECT_EQ(one["reference"]["dropped_repeated_vertex_faces"], 2);
    EXPECT_EQ(one["reference"]["unreferenced_vertices"], 2);
    EXPECT_GE(one["samples"]["skipped_degenerate_faces"], 1);
    EXPECT_LT(one["reference"]["diagonal"].get<double>(), 1);
    if (one.contains("hausdorff_certified")) {  // bounded block by block: the intervals meet
      EXPECT_LE(streamed["hausdorff_certified"]["lower"], one["hausdorff_certified"]["upper"]);
      EXPECT_LE(one["hausdorff_certified"]["lower"], streamed["hausdorff_certified"]["upper"]);
      one.erase("hausdorff_certified");
      streamed.erase("hausdorff_certified");
    }
    expect_same_report(one, streamed);
  }
  // A triangle soup: no facet shares a corner, so there are six times the vertices the corner set
  // expects of a closed mesh, and it grows.
  std::string soup(80, '\0');
  constexpr std::uint32_t kSoup = 3000;
  soup.append(reinterpret_cast<const char*>(&kSoup), sizeof kSoup);
  for (std::uint32_t f = 0; f < kSoup; ++f) {
    soup.append(50, '\0');
    const float x = static_cast<float>(f);
    set_corner(soup, f, 0, x, 0, 0);
    set_corner(soup, f, 1, x, 1, 0);
    set_corner(soup, f, 2, x + 0.5f, 0, 1);
  }
  const std::string soup_path = folder.file("soup.stl", soup);
  const auto [whole_soup, streamed_soup] =
      whole_and_streamed(fmt::format("measure {} {} --quiet --json -", soup_path, ref), 1000, kSoup);
  EXPECT_EQ(streamed_soup["reference"]["vertices"], 3 * kSoup);
  expect_same_report(whole_soup, streamed_soup);

  // A corner that is not a number: one line naming the facet, no report. A file whose size is not
  // its count's is not streamed; read whole, it fails as ever.
  const std::string report = folder.file("report.json");
  std::string not_finite = stl;
  set_corner(not_finite, 42, 1, 0.0f, std::nanf(""), 0.0f);
  expect_error(fmt::format("measure {} {} --chunk 1000 --json {}", folder.file("nan.stl", not_finite), igea.path, report),
               {"nan.stl", "facet 42 corner 1 has a non-finite coordinate", "expected finite"});
  expect_error(fmt::format("measure {} {} --chunk 1000 --json {}", folder.file("long.stl", stl + "x"), igea.path, report),
               {"long.stl", "trailing data", "268686 triangles"});
  EXPECT_FALSE(fs::exists(report));
}


// Igea as an OBJ of the records people meet: comments, groups, normals, texture coordinates,
// relative indices, a polygon, a face repeating a vertex and a vertex defined after the faces that
// no face uses. Its lines, to be changed by the tests.
std::vector<std::string> igea_as_obj_lines(const Igea& igea) {
  std::vector<std::string> lines = {"# Igea", "o igea", "vt 0.25 0.75", "vn 0 0 1"};
  for (std::size_t v = 0; v < 134345; ++v) {
    float xyz[3];
    std::memcpy(xyz, &igea.bytes[igea.body + 12 * v], sizeof xyz);
    lines.push_back(fmt::format("v {:.9g} {:.9g} {:.9g}", xyz[0], xyz[1], xyz[2]));
  }
  lines.push_back("g face");
  for (std::size_t f = 0; f < 268686; ++f) {
    std::int32_t c[3];
    std::memcpy(c, &igea.bytes[igea.faces + 13 * f + 1], sizeof c);
    if (f % 3 == 0) {
      lines.push_back(fmt::format("f {}/1/1 {}//1 {}", c[0] + 1, c[1] + 1, c[2] + 1));
    } else {  // relative: counted back from the vertices defined so far
      lines.push_back(fmt::format("f {} {} {}", c[0] - 134345, c[1] - 134345, c[2] - 134345));
    }
  }
  lines.push_back("f 1 2 3 4");  // a quad: two triangles
  lines.push_back("f 5 6 5");    // dropped
  lines.push_back("v 9 9 9");    // no face uses it
  return lines;
}

std::string joined(const std::vector<std::string>& lines) {
  std::string text;
  for (const std::string& line : lines) text += line + "\n";
  return text;
}

// An OBJ REF streams too: the first pass reads its vertices, each block parses its faces from the
// text where the last stopped, with the whole read's checks and counts.
TEST(CliStreamed, ObjGivesTheWholeReport) {
  const Folder folder;
  const Igea igea;
  const std::vector<std::string> lines = igea_as_obj_lines(igea);
  const std::string ref = folder.file("igea.obj", joined(lines));
  for (const char* options : {"", "--method cgal --semantics closest --hausdorff-bound none"}) {
    SCOPED_TRACE(options);
    const auto [one, streamed] = whole_and_streamed(
        fmt::format("measure {} {} {} --quiet --json -", ref, igea.path, options), 4095, 268686 + 2);
    EXPECT_EQ(one["reference"]["dropped_repeated_vertex_faces"], 1);
    EXPECT_EQ(one["reference"]["triangulated_polygons"], 1);
    EXPECT_EQ(one["reference"]["unreferenced_vertices"], 1);
    EXPECT_EQ(one["reference"]["triangles"], 268686 + 2);
    expect_same_report(one, streamed);
  }
  // What carries colour is read whole: a vertex colour, a material library.
  std::vector<std::string> coloured = lines;
  for (std::string& line : coloured) {
    if (line.rfind("v ", 0) == 0) line += " 0.5 0.5 0.5";
  }
  std::vector<std::string> materials = lines;
  materials.insert(materials.begin(), "mtllib none.mtl");
  folder.file("none.mtl", "newmtl grey\nKd 0.5 0.5 0.5\n");
  materials.insert(materials.begin() + 1, "usemtl grey");
  for (const auto& [name, text] : {std::pair{"coloured.obj", joined(coloured)}, std::pair{"mtl.obj", joined(materials)}}) {
    const CliRun run = run_cli(fmt::format("measure {} {} --quiet --json - --chunk 4095", folder.file(name, text), igea.path));
    ASSERT_EQ(run.exit_code, 0) << name << run.err;
    EXPECT_EQ(run.out.find("\"streamed\""), std::string::npos) << name;
  }
  // Bad records: the line the whole read names, and no report.
  const std::string report = folder.file("report.json");
  const auto expect_bad = [&](std::size_t line, const std::string& record, const std::string& name,
                              const char* expected) {
    std::vector<std::string> bad = lines;
    bad[line - 1] = record;
    const std::string path = folder.file(name, joined(bad));
    const std::string where = fmt::format("{}:{}:", name, line);
    for (const char* chunk : {"0", "4095"}) {
      expect_error(fmt::format("measure {} {} --chunk {} --json {}", path, igea.path, chunk, report),
                   {where.c_str(), expected});
    }
  };
  expect_bad(4 + 134345 + 1 + 200000, "f 1 2 999999", "far.obj", "face refers to vertex 999999; expected 1..134345");
  expect_bad(4 + 134345 + 1 + 250000, "f 1 2", "short.obj", "expected at least 3 corners in 'f', found 2");
  expect_bad(4 + 134345 + 1 + 3, "f 1/7 2 3", "uv.obj", "texture coordinate '7'; expected 1..1");
  expect_bad(4 + 1000, "v 1 2 x", "vertex.obj", "expected 3 numbers after 'v', found 'x'");
  expect_bad(3, "vt 0.5 inf", "vt.obj", "expected 2 finite numbers after 'vt'");
  EXPECT_FALSE(fs::exists(report));
}

}  // namespace
