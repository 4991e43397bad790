// `roving batch`: many pairs from a manifest or two folders, one report per pair, a merged
// summary, failures recorded without stopping the others, shards that add up to one run, and a
// restarted run that recomputes nothing it had finished.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "cli_support.h"

namespace {

using namespace roving::testing::cli;

// Five cubes of half-sides 0.50 .. 0.54 and a manifest pairing the first with each of the
// others, plus one pair whose test does not exist.
struct Dataset {
  Folder folder;
  std::vector<std::string> cubes;
  std::string manifest;
  Dataset() {
    for (int k = 0; k < 5; ++k) cubes.push_back(folder.file(fmt::format("cube{}.obj", k), cube_obj(0.5 + 0.01 * k)));
    std::string csv = "reference,test,method\n";
    for (int k = 1; k < 5; ++k) csv += fmt::format("{},{},{}\n", cubes[0], cubes[k], k == 2 ? "cgal" : "");
    csv += fmt::format("{},{}/missing.obj,\n", cubes[0], folder.path.string());
    manifest = folder.file("pairs.csv", csv);
  }
  std::string out(const std::string& name) const { return (folder.path / name).string(); }
};

std::vector<std::vector<std::string>> read_csv(const std::string& path) {
  std::ifstream file(path);
  std::vector<std::vector<std::string>> rows;
  std::string line;
  while (std::getline(file, line)) {
    std::vector<std::string> fields;
    std::stringstream stream(line);
    std::string field;
    while (std::getline(stream, field, ',')) fields.push_back(field);
    rows.push_back(fields);
  }
  return rows;
}

// The index of the column `name` in a table's header row (a failure where there is none).
std::size_t column_of(const std::vector<std::vector<std::string>>& rows, const std::string& name) {
  const auto found = std::find(rows.at(0).begin(), rows[0].end(), name);
  EXPECT_NE(found, rows[0].end()) << name;
  return static_cast<std::size_t>(found - rows[0].begin());
}

// The summary without its timing column, which differs between runs.
std::vector<std::vector<std::string>> summary_without_seconds(const std::string& folder) {
  auto rows = read_csv(folder + "/summary.csv");
  const auto seconds = std::find(rows.at(0).begin(), rows.at(0).end(), "seconds") - rows[0].begin();
  for (auto& row : rows) {
    if (static_cast<std::size_t>(seconds) < row.size()) row.erase(row.begin() + seconds);
  }
  return rows;
}

TEST(CliBatch, EveryPairGetsAReportAndAFailureDoesNotStopTheOthers) {
  const Dataset data;
  const CliRun run = run_cli("batch " + data.manifest + " --out " + data.out("results"));
  EXPECT_EQ(run.exit_code, 4) << run.err;  // some pair failed
  EXPECT_NE(run.err.find("pair 4"), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("missing.obj"), std::string::npos) << run.err;
  EXPECT_NE(run.out.find("4 measured, 0 already done, 1 failed"), std::string::npos) << run.out;
  const auto rows = read_csv(data.out("results") + "/summary.csv");
  ASSERT_EQ(rows.size(), 6u);  // header + 5 pairs in manifest order
  const auto column = [&](const std::string& name) { return column_of(rows, name); };
  for (int k = 1; k <= 4; ++k) {
    EXPECT_EQ(rows[k][column("index")], std::to_string(k - 1));
    EXPECT_EQ(rows[k][column("status")], "ok");
    // First-hit from the small cube to one 0.01 k larger: every sample 0.01 k away.
    EXPECT_NEAR(std::stod(rows[k][column("usiad")]), 0.01 * k, 1e-6) << k;
  }
  EXPECT_EQ(rows[2][column("method")], "cgal");  // the manifest's column overrides the default
  EXPECT_EQ(rows[5][column("status")], "failed");
  EXPECT_NE(rows[5][column("error")].find("cannot open"), std::string::npos);
  // Each report is a full `measure --json` report plus where it came from.
  std::size_t reports = 0;
  for (const auto& entry : fs::directory_iterator(data.out("results"))) {
    if (entry.path().extension() != ".json" || entry.path().string().find(".failed.") != std::string::npos) continue;
    std::ifstream file(entry.path());
    const auto json = nlohmann::json::parse(file);
    EXPECT_EQ(json["schema_version"], 3);
    EXPECT_EQ(json["batch"]["status"], "ok");
    EXPECT_EQ(json["inputs"][0]["path"], data.cubes[0]);
    ++reports;
  }
  EXPECT_EQ(reports, 4u);
}

// --ibsm's figures in the summary (colour ones empty: the cubes have none), and a key of its own:
// reports made without it are not taken for reports with it.
TEST(CliBatch, ImageBasedFiguresInTheSummaryAndTheKey) {
  const Dataset data;
  EXPECT_EQ(run_cli("batch " + data.manifest + " --out " + data.out("results")).exit_code, 4);
  const CliRun run =
      run_cli("batch " + data.manifest + " --ibsm --ibsm-resolution 64 --html --out " + data.out("results"));
  EXPECT_EQ(run.exit_code, 4) << run.err;
  EXPECT_NE(run.out.find("4 measured, 0 already done"), std::string::npos) << run.out;
  const auto rows = read_csv(data.out("results") + "/summary.csv");
  const auto column = [&](const std::string& name) { return column_of(rows, name); };
  ASSERT_EQ(rows.size(), 6u);
  for (int k = 1; k <= 4; ++k) {
    // TEST a cube 0.01 k larger about the same centre: a depth difference, pixels only it covers.
    EXPECT_GT(std::stod(rows[k][column("ibsm_depth_psnr")]), 0) << k;
    EXPECT_GT(std::stod(rows[k][column("ibsm_unmatched_percent")]), 0) << k;
    EXPECT_EQ(rows[k][column("ibsm_psnr_rgb")], "") << k;
  }
  std::ifstream index(data.out("results") + "/index.html");
  std::stringstream page;
  page << index.rdbuf();
  EXPECT_NE(page.str().find("ibsm_depth_psnr"), std::string::npos);
}

TEST(CliBatch, ReconstructionFiguresInTheSummary) {
  const Dataset data;
  const CliRun run =
      run_cli("batch " + data.manifest + " --symmetric --threshold 0.015 --html --out " + data.out("results"));
  EXPECT_EQ(run.exit_code, 4) << run.err;
  const auto rows = read_csv(data.out("results") + "/summary.csv");
  const auto column = [&](const std::string& name) { return column_of(rows, name); };
  ASSERT_EQ(rows.size(), 6u);
  for (int k = 1; k <= 4; ++k) {
    // TEST a cube 0.01 k larger about the same centre: every point of REF is 0.01 k from TEST (its
    // face straight out), TEST's corners and edges are farther from REF; so recall is 1 at tau
    // 0.015 for k = 1 and 0 beyond, and the Chamfer mean at least 0.01 k.
    const double chamfer = std::stod(rows[k][column("chamfer_mean")]);
    EXPECT_GE(chamfer, 0.01 * k * (1 - 1e-12)) << k;
    EXPECT_LE(chamfer, 0.01 * k * 1.2) << k;
    EXPECT_EQ(std::stod(rows[k][column("tau")]), 0.015);
    EXPECT_EQ(std::stod(rows[k][column("recall")]), k == 1 ? 1.0 : 0.0) << k;
    EXPECT_GT(std::stod(rows[k][column("normal_consistency")]), 0.9) << k;
  }
  std::ifstream index(data.out("results") + "/index.html");
  std::stringstream page;
  page << index.rdbuf();
  EXPECT_NE(page.str().find("f_score"), std::string::npos);
}

// The benchmarks' protocols per pair: a manifest naming each pair's data set files (relative to
// it, as the models are), each report the one `measure --protocol` gives, the figures in the
// summary and the index; the command line's --protocol for pairs that share their files.
TEST(CliBatch, ProtocolsPerPairAreMeasuresOwn) {
  const Folder folder;
  const std::string source = std::string(ROVING_SOURCE_DIR) + "/tests/data/";
  const std::string manifest = folder.file(
      "protocols.csv",
      "reference,test,protocol,dtu_obs_mask,dtu_plane,tnt_crop,tnt_alignment,tnt_tau,tnt_trajectory,"
      "tnt_reference_trajectory,tnt_mapping\n"
      "dtu/Points/stl/stl001_total.ply,dtu/scan1_mesh.ply,dtu,dtu/ObsMask/ObsMask1_10.mat,dtu/ObsMask/Plane1.mat,,,,,,"
      "\n"
      "tnt/Bench.ply,tnt/Bench_points.ply,tanks-and-temples,,,tnt/Bench.json,tnt/Bench_trans.txt,0.01,,,\n"
      "tnt/Bench.ply,tnt/Bench_moved_points.ply,tanks-and-temples,,,tnt/Bench.json,tnt/Bench_trans.txt,0.01,"
      "tnt/Bench_moved.log,tnt/Bench_COLMAP_SfM.log,tnt/Bench_mapping_reference.txt\n");
  std::filesystem::create_symlink(source + "dtu", folder.path / "dtu");
  std::filesystem::create_symlink(source + "tnt", folder.path / "tnt");
  const std::string out = (folder.path / "results").string();
  const CliRun run = run_cli("batch " + manifest + " --html --quiet --out " + out);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const auto figures_of = [](const std::string& command, const char* protocol) {
    const CliRun one = run_cli(command + " --json - --quiet");
    EXPECT_EQ(one.exit_code, 0) << one.err;
    return nlohmann::json::parse(one.out)[protocol];
  };
  const nlohmann::json dtu = figures_of(
      "measure " + source + "dtu/Points/stl/stl001_total.ply " + source + "dtu/scan1_mesh.ply --protocol dtu " +
          "--dtu-obs-mask " + source + "dtu/ObsMask/ObsMask1_10.mat --dtu-plane " + source + "dtu/ObsMask/Plane1.mat",
      "dtu_protocol");
  const nlohmann::json tnt = figures_of("measure " + source + "tnt/Bench.ply " + source +
                                            "tnt/Bench_points.ply --protocol tanks-and-temples --tnt-crop " + source +
                                            "tnt/Bench.json --tnt-alignment " + source + "tnt/Bench_trans.txt --tnt-tau 0.01",
                                        "tanks_and_temples_protocol");
  // run.py's registration first (its files' columns), as measure runs it.
  const nlohmann::json registered = figures_of(
      "measure " + source + "tnt/Bench.ply " + source + "tnt/Bench_moved_points.ply --protocol tanks-and-temples " +
          "--tnt-crop " + source + "tnt/Bench.json --tnt-alignment " + source + "tnt/Bench_trans.txt --tnt-tau 0.01 " +
          "--tnt-trajectory " + source + "tnt/Bench_moved.log --tnt-reference-trajectory " + source +
          "tnt/Bench_COLMAP_SfM.log --tnt-mapping " + source + "tnt/Bench_mapping_reference.txt",
      "tanks_and_temples_protocol");
  const auto rows = read_csv(out + "/summary.csv");
  ASSERT_EQ(rows.size(), 4u);
  const auto cell = [&](int row, const std::string& name) { return std::stod(rows[row][column_of(rows, name)]); };
  EXPECT_EQ(cell(3, "tnt_f_score"), registered["fscore"].get<double>());
  EXPECT_NE(cell(3, "tnt_f_score"), cell(2, "tnt_f_score"));
  for (const char* figure : {"accuracy", "completeness", "overall"}) {
    EXPECT_EQ(cell(1, std::string("dtu_") + figure), dtu[figure].get<double>()) << figure;
  }
  EXPECT_EQ(cell(2, "tnt_tau"), 0.01);
  EXPECT_EQ(cell(2, "tnt_precision"), tnt["precision"].get<double>());
  EXPECT_EQ(cell(2, "tnt_recall"), tnt["recall"].get<double>());
  EXPECT_EQ(cell(2, "tnt_f_score"), tnt["fscore"].get<double>());
  EXPECT_EQ(rows[1][column_of(rows, "tnt_precision")], "");  // each pair its own protocol's columns
  EXPECT_EQ(rows[2][column_of(rows, "dtu_overall")], "");
  std::ifstream index(out + "/index.html");
  std::stringstream page;
  page << index.rdbuf();
  EXPECT_NE(page.str().find("dtu_overall"), std::string::npos);
  EXPECT_NE(page.str().find("tnt_f_score"), std::string::npos);

  // One scene's files on the command line, for every pair of the list.
  const std::string same = folder.file("same.csv", "reference,test\ntnt/Bench.ply,tnt/Bench_points.ply\n"
                                                    "tnt/Bench.ply,tnt/Bench_mesh.ply\n");
  const CliRun shared = run_cli("batch " + same + " --protocol tanks-and-temples --tnt-crop " + source +
                                "tnt/Bench.json --tnt-alignment " + source + "tnt/Bench_trans.txt --tnt-tau 0.01 --quiet"
                                " --out " + (folder.path / "shared").string());
  ASSERT_EQ(shared.exit_code, 0) << shared.err;
  const auto shared_rows = read_csv((folder.path / "shared").string() + "/summary.csv");
  ASSERT_EQ(shared_rows.size(), 3u);
  EXPECT_EQ(std::stod(shared_rows[1][column_of(shared_rows, "tnt_f_score")]), tnt["fscore"].get<double>());

  // A protocol no one knows, a file that is not there, one picture for many pairs: one line.
  expect_error("batch " + folder.file("unknown.csv", "reference,test,protocol\ntnt/Bench.ply,tnt/Bench_points.ply,eth3d\n") +
                   " --out " + out,
               {"pair 0", "protocol", "expected dtu or tanks-and-temples", "'eth3d'"});
  expect_error("batch " + folder.file("nomask.csv", "reference,test,protocol,dtu_obs_mask,dtu_plane\n"
                                                    "a.ply,b.ply,dtu,gone.mat,dtu/ObsMask/Plane1.mat\n") + " --out " + out,
               {"pair 0", "--dtu-obs-mask", "gone.mat"});
  expect_error("batch " + same + " --protocol tanks-and-temples --tnt-crop " + source + "tnt/Bench.json --tnt-tau 0.01 "
                   "--tnt-curves c.png --out " + out,
               {"--tnt-curves", "not in batch"});
}

TEST(CliBatch, TwoShardsTogetherEqualOneRun) {
  const Dataset data;
  EXPECT_EQ(run_cli("batch " + data.manifest + " --out " + data.out("whole")).exit_code, 4);
  const CliRun first = run_cli("batch " + data.manifest + " --shard 0/2 --out " + data.out("sharded"));
  const CliRun second = run_cli("batch " + data.manifest + " --shard 1/2 --out " + data.out("sharded"));
  EXPECT_NE(first.out.find("2 measured"), std::string::npos) << first.out;   // pairs 0, 1
  EXPECT_NE(second.out.find("2 measured"), std::string::npos) << second.out;  // pairs 2, 3 (and 4 failed)
  const CliRun merged = run_cli("batch --merge --out " + data.out("sharded"));
  EXPECT_EQ(merged.exit_code, 4) << merged.err;
  EXPECT_NE(merged.out.find("4 pairs measured, 1 failed"), std::string::npos) << merged.out;
  EXPECT_EQ(summary_without_seconds(data.out("sharded")), summary_without_seconds(data.out("whole")));
}

TEST(CliBatch, ARestartedRunRecomputesNothingItHadFinished) {
  const Dataset data;
  const std::string out = data.out("results");
  run_cli("batch " + data.manifest + " --out " + out);
  const auto before = summary_without_seconds(out);
  // As if killed after the others: one report and the summary never written.
  std::vector<fs::path> reports;
  for (const auto& entry : fs::directory_iterator(out)) {
    if (entry.path().extension() == ".json" && entry.path().string().find(".failed.") == std::string::npos)
      reports.push_back(entry.path());
  }
  ASSERT_EQ(reports.size(), 4u);
  fs::remove(reports[0]);
  fs::remove(out + "/summary.csv");
  const auto untouched = fs::last_write_time(reports[1]);
  const CliRun again = run_cli("batch " + data.manifest + " --out " + out);
  EXPECT_NE(again.out.find("1 measured, 3 already done, 1 failed"), std::string::npos) << again.out;
  EXPECT_EQ(fs::last_write_time(reports[1]), untouched);
  EXPECT_EQ(summary_without_seconds(out), before);
}

TEST(CliBatch, JsonLinesAndFoldersMatchedByName) {
  const Dataset data;
  const std::string jsonl = data.folder.file(
      "pairs.jsonl", fmt::format("{{\"reference\": \"{}\", \"test\": \"{}\", \"method\": \"cgal\"}}\n\n"
                                 "{{\"reference\": \"{}\", \"test\": \"{}\", \"resolution\": 256}}\n",
                                 data.cubes[0], data.cubes[3], data.cubes[0], data.cubes[4]));
  const CliRun lines = run_cli("batch " + jsonl + " --out " + data.out("lines"));
  EXPECT_EQ(lines.exit_code, 0) << lines.err;
  EXPECT_EQ(read_csv(data.out("lines") + "/summary.csv").size(), 3u);

  const Folder refs, tests;
  for (const char* name : {"a.obj", "b.obj", "only-here.obj"}) refs.file(name, cube_obj(0.5));
  for (const char* name : {"a.obj", "b.obj", "not-there.obj"}) tests.file(name, cube_obj(0.52));
  // A file without a partner is an error listing each such file (nothing measured), unless skipped.
  const std::string folder_pair = refs.path.string() + " " + tests.path.string();
  expect_error("batch " + folder_pair + " --out " + data.out("folders"),
               {"2 file(s) without a partner", "only-here.obj", "not-there.obj", "--skip-unpaired"});
  EXPECT_FALSE(fs::exists(data.out("folders")));
  const CliRun folders =
      run_cli("batch " + folder_pair + " --out " + data.out("folders") + " --semantics closest --skip-unpaired");
  EXPECT_EQ(folders.exit_code, 0) << folders.err;
  EXPECT_NE(folders.err.find("skipping 2 file(s) without a partner"), std::string::npos) << folders.err;
  const auto rows = read_csv(data.out("folders") + "/summary.csv");
  ASSERT_EQ(rows.size(), 3u);  // a.obj and b.obj
  EXPECT_NE(rows[1][1].find("a.obj"), std::string::npos);
  EXPECT_NE(rows[2][2].find("b.obj"), std::string::npos);
}

TEST(CliBatch, BadManifestsAndShardsAreOneLineErrors) {
  const Dataset data;
  const std::string out = " --out " + data.out("x");
  expect_error("batch " + data.folder.file("no-test.csv", "reference\na.obj\n") + out, {"no-test.csv:2", "'test'"});
  expect_error("batch " + data.folder.file("extra.csv", "reference,test,colour\na,b,red\n") + out,
               {"extra.csv:2", "unknown column 'colour'"});
  expect_error("batch " + data.folder.file("fields.csv", "reference,test\na,b,c\n") + out,
               {"fields.csv:2", "expected 2 fields", "found 3"});
  expect_error("batch " + data.folder.file("empty.csv", "reference,test\n") + out, {"empty.csv", "at least one pair"});
  expect_error("batch " + data.folder.file("bad.jsonl", "{\"reference\": \"a\",\n") + out, {"bad.jsonl:1", "JSON"});
  expect_error("batch " + data.folder.file("magic.csv", "reference,test,method\na,b,magic\n") + out,
               {"pair 0", "--method", "'magic'"});
  for (const char* shard : {"2/2", "x", "1/0", "-1/3"}) {
    expect_error("batch " + data.manifest + " --shard " + shard + out, {"--shard", shard});
  }
  expect_error("batch /nonexistent/pairs.csv" + out, {"/nonexistent/pairs.csv"});
  expect_error("batch --merge --out /nonexistent/folder", {"--merge", "/nonexistent/folder"});
}

}  // namespace
