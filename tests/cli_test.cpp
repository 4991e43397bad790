// The `roving` executable end to end: a correct run, its outputs, and one-line errors with a
// non-zero exit for every bad option or file.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "test_support.h"

namespace {

namespace fs = std::filesystem;

struct CliRun {
  int exit_code;
  std::string out, err;
};

CliRun run_cli(const std::string& arguments) {
  const fs::path err_file = fs::temp_directory_path() / ("roving-cli-err-" + std::to_string(::getpid()));
  const std::string command = std::string(ROVING_CLI) + " " + arguments + " 2>" + err_file.string();
  CliRun run{};
  FILE* pipe = popen(command.c_str(), "r");
  std::array<char, 4096> buffer;
  while (std::size_t n = fread(buffer.data(), 1, buffer.size(), pipe)) run.out.append(buffer.data(), n);
  const int status = pclose(pipe);
  run.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream err(err_file);
  run.err.assign(std::istreambuf_iterator<char>(err), std::istreambuf_iterator<char>());
  fs::remove(err_file);
  return run;
}

std::string bunny() {
  return roving::testing::data_file("stanford-bunny.obj");
}

void expect_error(const std::string& arguments, std::initializer_list<const char*> fragments) {
  const CliRun run = run_cli(arguments);
  EXPECT_NE(run.exit_code, 0) << arguments;
  EXPECT_EQ(run.err.rfind("roving: error: ", 0), 0u) << run.err;
  EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << "one line expected: " << run.err;
  for (const char* fragment : fragments) EXPECT_NE(run.err.find(fragment), std::string::npos) << run.err;
}

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
  expect_error("measure " + pair + " --method roving --backend vulkan", {"--backend", "'vulkan'"});
  expect_error("measure " + pair + " --method viewpoint --resolution 0", {"--resolution"});
  expect_error("measure " + pair + " --method roving --semantics nearest", {"--semantics", "roving"});
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
      const auto& n = bunny.face_normals()[f * 300];
      file << c.x() << ' ' << c.y() << ' ' << c.z() << ' ' << n.x() << ' ' << n.y() << ' ' << n.z() << '\n';
    }
  }
  const CliRun run = run_cli("measure " + xyz.string() + " " + bunny() + " --json -");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const auto json = nlohmann::json::parse(run.out);
  EXPECT_EQ(json["reference"]["type"], "points");
  EXPECT_EQ(json["samples"]["count"], 200);
  EXPECT_LT(json["statistics"]["usiad"].get<double>(), 1e-6);  // the points lie on the bunny
  expect_error("measure " + bunny() + " " + xyz.string(), {xyz.string().c_str(), "cannot be the test model"});
  expect_error("measure " + bunny() + " " + bunny() + " --test-type points", {"cannot be the test model"});
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

}  // namespace
