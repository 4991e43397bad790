// The `roving` executable end to end: a correct run, its outputs, and one-line errors with a
// non-zero exit for every bad option or file.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "cli_support.h"

namespace {

using namespace roving::testing::cli;
namespace fs = std::filesystem;

TEST(Cli, MeasuresAndWritesEveryOutput) {
  const fs::path folder = fs::temp_directory_path() / ("roving-cli-" + std::to_string(::getpid()));
  fs::create_directories(folder);
  const std::string csv = (folder / "samples.csv").string(), ply = (folder / "heat.ply").string();
  const CliRun run = run_cli("measure " + bunny() + " " + bunny() +
                             " --samples area:500 --json - --samples-out " + csv + " --heatmap " + ply);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const auto json = nlohmann::json::parse(run.out);
  EXPECT_EQ(json["samples"]["count"], 500);
  EXPECT_EQ(json["method"], "embree");
  EXPECT_EQ(json["semantics"], "first-hit");
  EXPECT_NEAR(json["max_error"]["relative"].get<double>(), 0.05, 1e-12);
  EXPECT_EQ(json["reference"]["unreferenced_vertices"], 1113);
  for (const char* key : {"siad", "usiad", "std_signed", "rms", "max_abs", "p99", "usiad_area"}) {
    EXPECT_TRUE(json["statistics"].contains(key)) << key;
  }
  std::ifstream rows(csv);
  EXPECT_EQ(std::count(std::istreambuf_iterator<char>(rows), std::istreambuf_iterator<char>(), '\n'), 501);
  std::ifstream heat(ply);
  std::string header((std::istreambuf_iterator<char>(heat)), std::istreambuf_iterator<char>());
  EXPECT_NE(header.find("element vertex 500"), std::string::npos);
  fs::remove_all(folder);
}

// `--samples-out -` writes the rows to standard output, the same bytes as to a file, and nothing
// else (no text report) so that they pipe; with `--json -` as well, a clear error.
TEST(Cli, SamplesOutDashWritesTheRowsToStandardOutput) {
  const fs::path folder = fs::temp_directory_path() / ("roving-cli-dash-" + std::to_string(::getpid()));
  fs::create_directories(folder);
  const std::string csv = (folder / "samples.csv").string(), json = (folder / "report.json").string();
  const std::string pair = "measure " + bunny() + " " + bunny() + " --samples area:300 --quiet";
  const CliRun to_file = run_cli(pair + " --samples-out " + csv);
  ASSERT_EQ(to_file.exit_code, 0) << to_file.err;
  const CliRun piped = run_cli(pair + " --samples-out - --json " + json);
  ASSERT_EQ(piped.exit_code, 0) << piped.err;
  std::ifstream rows(csv);
  EXPECT_EQ(piped.out, std::string(std::istreambuf_iterator<char>(rows), std::istreambuf_iterator<char>()));
  EXPECT_FALSE(fs::exists(folder / "-"));
  EXPECT_EQ(nlohmann::json::parse(std::ifstream(json))["samples"]["count"], 300);
  expect_error(pair + " --samples-out - --json -", {"--json - and --samples-out -", "standard output"});
  fs::remove_all(folder);
}

// A plain run gives up REF's geometry once it is sampled (run_measure); one with a heat map keeps
// it. The report and every sample's figures must not tell them apart.
TEST(Cli, ReleasingTheReferenceChangesNothingReported) {
  const fs::path folder = fs::temp_directory_path() / ("roving-cli-release-" + std::to_string(::getpid()));
  fs::create_directories(folder);
  const std::string cube = (folder / "cube.obj").string();
  std::ofstream(cube) << cube_obj(0.05);
  for (const char* samples : {"vertices", "faces"}) {
    std::string csv[2];
    nlohmann::json report[2];
    for (int keep = 0; keep < 2; ++keep) {
      csv[keep] = (folder / fmt::format("{}-{}.csv", samples, keep)).string();
      const std::string heatmap = keep ? " --heatmap " + (folder / "heat.ply").string() : "";
      const CliRun run =
          run_cli(fmt::format("measure {} {} --semantics closest --hausdorff-bound none --samples {} "
                              "--json - --samples-out {}{}",
                              bunny(), cube, samples, csv[keep], heatmap));
      ASSERT_EQ(run.exit_code, 0) << run.err;
      report[keep] = nlohmann::json::parse(run.out);
      for (const char* volatile_key : {"seconds", "provenance", "outputs", "command_line"})
        report[keep].erase(volatile_key);
    }
    std::ifstream released(csv[0]), kept(csv[1]);
    EXPECT_EQ(std::string(std::istreambuf_iterator<char>(released), {}),
              std::string(std::istreambuf_iterator<char>(kept), {}))
        << samples;
    EXPECT_EQ(report[0].dump(), report[1].dump()) << samples;
  }
  fs::remove_all(folder);
}

TEST(Cli, TextReportShowsTheMetroFields) {
  const CliRun run = run_cli("measure " + bunny() + " " + bunny() + " --samples area:200 --method cgal");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  for (const char* field :
       {"bounding-box diagonal", "USiAD", "/ diagonal", "no hit", "build", "query", "load"}) {
    EXPECT_NE(run.out.find(field), std::string::npos) << field;
  }
}

TEST(Cli, BadOptionsGiveOneLineErrors) {
  const std::string pair = bunny() + " " + bunny();
  expect_error("measure " + pair + " --frobnicate", {"--frobnicate"});
  expect_error("measure " + bunny(), {"TEST"});
  expect_error("", {"subcommand"});
  expect_error("measure " + pair + " --max-error 0", {"--max-error", "'0'"});
  expect_error("measure " + pair + " --max-error -1", {"--max-error"});
  expect_error("measure " + pair + " --max-error abc", {"--max-error", "'abc'"});
  expect_error("measure " + pair + " --max-error 150%", {"--max-error", "'150%'"});
  expect_error("measure " + pair + " --max-error nan", {"--max-error", "'nan'"});
  expect_error("measure " + pair + " --samples area:0", {"--samples", "'area:0'"});
  expect_error("measure " + pair + " --method magic", {"--method", "'magic'", "embree"});
  expect_error("measure " + pair + " --semantics sideways", {"--semantics", "'sideways'"});
  expect_error("measure " + pair + " --method v2v-kdtree --semantics first-hit",
               {"--semantics", "v2v-kdtree"});
  expect_error("measure " + pair + " --histogram-bins 0", {"--histogram-bins"});
  expect_error("measure " + pair + " --method cooperative --views 24", {"--views", "'24'"});
  expect_error("measure " + pair + " --method cooperative --views auto:7", {"--views", "'auto:7'"});
  expect_error("measure " + pair + " --method viewpoint --views auto", {"--views auto", "cooperative"});
  expect_error("measure " + pair + " --method roving --backend vulkan", {"--backend", "'vulkan'"});
  expect_error("measure " + pair + " --method roving --camera-geometry shader",
               {"--camera-geometry", "'shader'"});
  expect_error("measure " + pair + " --method viewpoint --resolution 0", {"--resolution"});
  expect_error("measure " + pair + " --method viewpoint --view-culling some", {"--view-culling", "some"});
  expect_error("measure " + pair + " --method roving --semantics nearest", {"--semantics", "roving"});
}

// The default backend comes from ROVING_GL_BACKEND; any other value than osmesa or egl is an error
// naming the variable, as a bad --backend names the option.
TEST(Cli, BadGlBackendInTheEnvironmentIsAnError) {
  const char* before = std::getenv("ROVING_GL_BACKEND");
  const std::string saved = before ? before : "";
  setenv("ROVING_GL_BACKEND", "vulkan", 1);
  const std::string pair = bunny() + " " + bunny();
  expect_error("measure " + pair + " --method roving", {"ROVING_GL_BACKEND", "'vulkan'"});
  expect_error("measure " + pair + " --method cooperative --views 4x2", {"ROVING_GL_BACKEND", "'vulkan'"});
  if (before) {
    setenv("ROVING_GL_BACKEND", saved.c_str(), 1);
  } else {
    unsetenv("ROVING_GL_BACKEND");
  }
}

TEST(Cli, GlMethodsReportObservations) {
  const CliRun run = run_cli("measure " + bunny() + " " + bunny() +
                             " --samples area:300 --method cooperative --views 12x6 "
                             "--resolution 256 --json -");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const auto json = nlohmann::json::parse(run.out);
  EXPECT_EQ(json["gl"]["views"], "12x6");
  EXPECT_EQ(json["gl"]["observations"].get<int>(),
            json["gl"]["views_rendered"].get<int>() + json["gl"]["sample_cameras"].get<int>());
  EXPECT_EQ(json["gl"]["resolved_by_view"].get<int>() + json["gl"]["resolved_by_camera"].get<int>() +
                json["gl"]["unresolved"].get<int>(),
            300);
  EXPECT_EQ(json["gl"]["view_culling"], "footprint");
}

// Views drawn whole (--view-culling none) give the same answers as views culled to what their
// samples' pixels can show, without the CPU's footprint of each view: the bunny against a copy
// whose vertices are moved (a wave across it), so that the distances are not all zero.
TEST(Cli, ViewsDrawnWholeGiveTheCulledViewsAnswers) {
  const std::string moved = (fs::temp_directory_path() / "roving-cli-bunny-wave.obj").string();
  {
    std::ifstream in(bunny());
    std::ofstream out(moved);
    for (std::string line; std::getline(in, line);) {
      double x, y, z;
      if (line.rfind("v ", 0) == 0 && std::sscanf(line.c_str(), "v %lf %lf %lf", &x, &y, &z) == 3) {
        out << "v " << x << " " << y + 0.002 * std::sin(60 * x) << " " << z << "\n";
      } else {
        out << line << "\n";
      }
    }
  }
  const std::string pair = bunny() + " " + moved;
  const auto measured = [&](const std::string& culling) {
    const CliRun run = run_cli("measure " + pair + " --samples area:2000 --method cooperative --views 12x6 "
                               "--resolution 256 --view-culling " + culling + " --json -");
    EXPECT_EQ(run.exit_code, 0) << run.err;
    return nlohmann::json::parse(run.out);
  };
  const nlohmann::json culled = measured("footprint"), whole = measured("none");
  EXPECT_EQ(culled["gl"]["view_culling"], "footprint");
  EXPECT_EQ(whole["gl"]["view_culling"], "none");
  EXPECT_GT(culled["statistics"]["usiad"].get<double>(), 0);
  EXPECT_GT(culled["gl"]["resolved_by_view"].get<int>(), 100);  // the views answer some (202), the cameras the rest
  EXPECT_EQ(whole["statistics"], culled["statistics"]);
  EXPECT_EQ(whole["gl"]["resolved_by_view"], culled["gl"]["resolved_by_view"]);
  EXPECT_EQ(whole["gl"]["resolved_by_camera"], culled["gl"]["resolved_by_camera"]);
  fs::remove(moved);
}

TEST(Cli, PointCloudsAreReferencesNotTests) {
  const fs::path xyz =
      fs::temp_directory_path() / ("roving-cli-points-" + std::to_string(::getpid()) + ".xyz");
  {
    // 200 points of the bunny with their normals.
    const auto& bunny = roving::testing::bunny();
    std::ofstream file(xyz);
    for (std::size_t f = 0; f < 200; ++f) {
      const auto c = bunny.centroid(f * 300);
      const auto n = bunny.face_normal(f * 300);
      file << c.x() << ' ' << c.y() << ' ' << c.z() << ' ' << n.x() << ' ' << n.y() << ' ' << n.z() << '\n';
    }
  }
  const CliRun run = run_cli("measure " + xyz.string() + " " + bunny() + " --json -");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const auto json = nlohmann::json::parse(run.out);
  EXPECT_EQ(json["reference"]["type"], "points");
  EXPECT_EQ(json["samples"]["count"], 200);
  EXPECT_LT(json["statistics"]["usiad"].get<double>(), 1e-6);  // the points lie on the bunny
  // As the test model the points are drawn as surfels: 200 points over the whole bunny cover
  // little of it, and the rest is reported as no-hits, never as distances.
  const CliRun as_test = run_cli("measure " + bunny() + " " + xyz.string() + " --json -");
  ASSERT_EQ(as_test.exit_code, 0) << as_test.err;
  const auto test_json = nlohmann::json::parse(as_test.out);
  EXPECT_EQ(test_json["test"]["points"]["surfels"]["neighbours"], 8);
  EXPECT_EQ(test_json["test"]["points"]["surfels"]["triangles"], 200 * 8);
  EXPECT_GT(test_json["no_hits"].get<int>(), 0);
  EXPECT_GT(test_json["hits"].get<int>(), 0);
  // What cannot be drawn as surfels is refused with the file named, exit 1.
  const fs::path twins = fs::temp_directory_path() / "roving-cli-twins.xyz";
  {
    std::ofstream file(twins);
    for (int i = 0; i < 12; ++i) file << i % 4 << ' ' << i / 4 << " 0 0 0 1\n";
    file << "1 0 0 0 0 1\n";  // point 12 repeats point 1
  }
  expect_error("measure " + bunny() + " " + twins.string(), {twins.string().c_str(), "points 1 and 12", "distinct"});
  fs::remove(twins);
  expect_error("measure " + bunny() + " " + bunny() + " --ref-type surfels", {"--ref-type", "'surfels'"});
  expect_error("measure " + xyz.string() + " " + bunny() + " --samples area:10",
               {"--samples", "point-cloud"});
  fs::remove(xyz);
}

TEST(Cli, BadFilesNameTheFile) {
  expect_error("measure /nonexistent/ref.obj " + bunny(), {"/nonexistent/ref.obj", "cannot open"});
  expect_error("measure " + bunny() + " /nonexistent/test.ply", {"/nonexistent/test.ply"});
  const std::string unwritable = "/nonexistent/out.csv";
  expect_error("measure " + bunny() + " " + bunny() + " --samples area:10 --samples-out " + unwritable,
               {unwritable.c_str(), "cannot open for writing"});
}

TEST(Cli, FailedRunsLeaveOutputsUntouched) {
  const Folder folder;
  const std::string json = folder.file("report.json", "old report\n");
  // The CSV cannot be written: the JSON that existed stays as it was, and nothing else appears.
  expect_error("measure " + bunny() + " " + bunny() + " --samples area:100 --json " + json +
                   " --samples-out /nonexistent/samples.csv",
               {"/nonexistent/samples.csv"});
  std::ifstream kept(json);
  EXPECT_EQ(std::string(std::istreambuf_iterator<char>(kept), {}), "old report\n");
  EXPECT_EQ(folder.entries(), 1u);
  // An output that names a directory is refused before any work.
  expect_error("measure " + bunny() + " " + bunny() + " --json " + folder.path.string(),
               {"--json", "directory"});
  expect_error("measure " + bunny() + " " + bunny() + " --html " + folder.path.string(), {"--html", "directory"});
  // A successful run replaces the file whole and leaves no temporary file.
  const CliRun run = run_cli("measure " + bunny() + " " + bunny() + " --samples area:100 --json " + json);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  std::ifstream replaced(json);
  EXPECT_EQ(nlohmann::json::parse(replaced)["samples"]["count"], 100);
  EXPECT_EQ(folder.entries(), 1u);
}

TEST(Cli, FullStandardOutputIsAnError) {
  for (const char* json : {"", " --json -"}) {
    const CliRun run =
        run_cli("measure " + bunny() + " " + bunny() + " --samples area:100" + json + " >/dev/full");
    EXPECT_NE(run.exit_code, 0) << json;
    EXPECT_NE(run.err.find("standard output: write failed"), std::string::npos) << run.err;
  }
}

TEST(Cli, MaxErrorBeyondTheModelsIsRefused) {
  // Beyond the models' extent the float rays lose the distances (1e19 aborted inside Embree,
  // 1e10 gave SiAD 2.5e9 for a model against itself).
  for (const char* h : {"1e19", "1e10"}) {
    expect_error("measure " + bunny() + " " + bunny() + " --samples area:100 --max-error " + h,
                 {"--max-error", "diagonal of both models", h});
  }
}

TEST(Cli, AbsurdRequestsFailAtOnceWithTheirSizes) {
  ::setenv("ROVING_MEMORY_LIMIT", "1G", 1);
  expect_error("measure " + bunny() + " " + bunny() + " --samples area:2147483648",
               {"sampling", "2147483648 samples", "GiB"});
  ::unsetenv("ROVING_MEMORY_LIMIT");
  const Folder folder;
  // A 2048^3 binvox of 60-odd bytes: its runs cannot fill the grid.
  const std::string binvox = folder.file(
      "huge.binvox", std::string("#binvox 1\ndim 2048 2048 2048\ntranslate 0 0 0\nscale 1\ndata\n") +
                         std::string("\x01\xff\x00\xff", 4));
  expect_error("measure " + binvox + " " + bunny(), {"huge.binvox", "truncated", "8589934592"});
  // Identical points: no extent to measure in.
  const std::string xyz = folder.file("point.xyz", "1 2 3\n1 2 3\n1 2 3\n");
  expect_error("measure " + xyz + " " + bunny(), {"point.xyz", "no extent"});
}

TEST(Cli, DegenerateOrAbsurdBezierPatchesAreRefused) {
  const Folder folder;
  // Patches collapsed onto a line: no surface, so no samples and nothing to draw.
  std::string line_patch = "1\n3 3\n";
  for (int k = 0; k < 16; ++k) line_patch += std::to_string(k % 4) + " 0 0\n";
  const std::string flat = folder.file("line.bpt", line_patch);
  expect_error("measure " + bunny() + " " + flat, {"line.bpt", "no area"});
  expect_error("measure " + flat + " " + bunny() + " --samples area:10", {"line.bpt", "no area"});
  // A zigzag net of degree 16 needs the finest tessellation on all three patches.
  std::string wiggly = "3\n";
  for (int patch = 0; patch < 3; ++patch) {
    wiggly += "16 16\n";
    for (int i = 0; i <= 16; ++i)
      for (int j = 0; j <= 16; ++j)
        wiggly += fmt::format("{} {} {}\n", i + 20 * patch, j, (i + j) % 2 ? 30 : -30);
  }
  expect_error("measure " + folder.file("wiggly.bpt", wiggly) + " " + bunny(), {"wiggly.bpt", "at most"});
}

}  // namespace
