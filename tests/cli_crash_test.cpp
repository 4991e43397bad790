// Batch outputs that survive a crash at any moment, inputs that can never block, and file
// references that stay in the model's folder (issue: nothing lost, nothing counted twice).
#include <fcntl.h>
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>

#include <chrono>
#include <nlohmann/json.hpp>
#include <random>
#include <sstream>
#include <thread>

#include "cli_support.h"

namespace {

using namespace roving::testing::cli;

// Starts `roving ARGUMENTS` (stdout and stderr to /dev/null) and returns its pid.
pid_t start_cli(const std::vector<std::string>& arguments) {
  const pid_t pid = ::fork();
  if (pid == 0) {
    const int null = ::open("/dev/null", O_WRONLY);
    ::dup2(null, STDOUT_FILENO);
    ::dup2(null, STDERR_FILENO);
    std::vector<char*> argv = {const_cast<char*>(ROVING_CLI)};
    for (const std::string& a : arguments) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    ::execv(ROVING_CLI, argv.data());
    ::_exit(127);
  }
  return pid;
}

int wait_for(pid_t pid) {
  int status = 0;
  ::waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

// Every report's statistics by pair index, and the files of the folder.
std::map<std::size_t, std::string> statistics_by_index(const fs::path& folder) {
  std::map<std::size_t, std::string> out;
  for (const auto& entry : fs::directory_iterator(folder)) {
    const std::string name = entry.path().filename().string();
    if (entry.path().extension() != ".json" || name[0] == '.') continue;
    const auto report = nlohmann::json::parse(std::ifstream(entry.path()));
    const std::size_t index = report["batch"]["index"];
    EXPECT_EQ(out.count(index), 0u) << "pair " << index << " has two reports in " << folder;
    out[index] = report["statistics"].dump();
  }
  return out;
}

std::size_t summary_rows(const fs::path& folder) {
  std::ifstream file(folder / "summary.csv");
  std::size_t rows = 0;
  for (std::string line; std::getline(file, line);) ++rows;
  return rows - 1;
}

// 12 pairs of cubes; the manifest.
struct Pairs {
  Folder folder;
  std::string manifest;
  static constexpr std::size_t kCount = 12;
  Pairs() {
    std::string csv = "reference,test,method\n";
    for (std::size_t k = 0; k < kCount; ++k) {
      const std::string a = folder.file(fmt::format("a{}.obj", k), cube_obj(0.5));
      const std::string b = folder.file(fmt::format("b{}.obj", k), cube_obj(0.5 + 0.01 * (k + 1)));
      csv += fmt::format("{},{},{}\n", a, b, k % 3 == 0 ? "cgal" : "embree");
    }
    manifest = folder.file("pairs.csv", csv);
  }
};

TEST(CrashConsistency, BatchKilledAtRandomMomentsResumesToTheUninterruptedResult) {
  const Pairs pairs;
  const std::string whole = (pairs.folder.path / "whole").string();
  ASSERT_EQ(run_cli("batch " + pairs.manifest + " --out " + whole + " --semantics closest").exit_code, 0);
  const auto expected = statistics_by_index(whole);
  ASSERT_EQ(expected.size(), Pairs::kCount);
  const auto started = std::chrono::steady_clock::now();
  ASSERT_EQ(run_cli("batch " + pairs.manifest + " --out " + (pairs.folder.path / "timing").string() +
                    " --semantics closest").exit_code, 0);
  const auto run_time = std::chrono::steady_clock::now() - started;

  std::mt19937 random(20261124);
  for (int trial = 0; trial < 50; ++trial) {
    const fs::path out = pairs.folder.path / fmt::format("killed{}", trial);
    // Killed once or twice at a random moment of a run (and, every fifth trial, during --merge).
    for (int kill = 0; kill < 1 + trial % 2; ++kill) {
      const bool merge = trial % 5 == 4 && kill == 1;
      const pid_t pid = merge ? start_cli({"batch", "--merge", "--out", out.string()})
                              : start_cli({"batch", pairs.manifest, "--out", out.string(), "--semantics", "closest"});
      std::this_thread::sleep_for(std::uniform_real_distribution<double>(0, 1)(random) * run_time);
      ::kill(pid, SIGKILL);
      wait_for(pid);
    }
    ASSERT_EQ(run_cli("batch " + pairs.manifest + " --out " + out.string() + " --semantics closest").exit_code, 0);
    EXPECT_EQ(statistics_by_index(out), expected) << out;
    EXPECT_EQ(summary_rows(out), Pairs::kCount) << out;
    for (const auto& entry : fs::directory_iterator(out)) {
      EXPECT_NE(entry.path().filename().string()[0], '.') << "stray temporary file " << entry.path();
    }
  }
}

TEST(CrashConsistency, MergeSkipsAndSweepsTemporaryFilesAndKeepsOneRowPerPair) {
  const Pairs pairs;
  const fs::path out = pairs.folder.path / "out";
  ASSERT_EQ(run_cli("batch " + pairs.manifest + " --out " + out.string()).exit_code, 0);
  // What a kill between writing a report's temporary file and its rename leaves: a whole copy of a
  // report under a temporary name, and one cut short.
  fs::path report;
  for (const auto& entry : fs::directory_iterator(out)) {
    if (entry.path().filename().string().rfind("000003-", 0) == 0) report = entry.path();
  }
  ASSERT_FALSE(report.empty());
  const fs::path whole = out / ("." + report.filename().string() + ".nZ5oKx.json");
  const fs::path cut = out / ("." + report.filename().string() + ".Ab12Cd.json");
  fs::copy_file(report, whole);
  std::ofstream(cut) << "{\"batch\": {\"ind";
  const CliRun merged = run_cli("batch --merge --out " + out.string());
  EXPECT_EQ(merged.exit_code, 0) << merged.err;
  EXPECT_EQ(summary_rows(out), Pairs::kCount);
  EXPECT_FALSE(fs::exists(whole));
  EXPECT_FALSE(fs::exists(cut));
}

TEST(CrashConsistency, SigtermAndSigintLeaveNoTemporaryFileAndExit143And130) {
  const Pairs pairs;
  for (const int signal : {SIGTERM, SIGINT}) {
    const fs::path out = pairs.folder.path / fmt::format("signal{}", signal);
    // Area samples make each pair long enough to be caught mid-write often.
    const pid_t pid =
        start_cli({"batch", pairs.manifest, "--out", out.string(), "--samples", "area:400000", "--semantics", "closest"});
    std::this_thread::sleep_for(std::chrono::milliseconds(700));
    ::kill(pid, signal);
    EXPECT_EQ(wait_for(pid), 128 + signal);
    for (const auto& entry : fs::directory_iterator(out)) {
      EXPECT_NE(entry.path().filename().string()[0], '.') << "temporary file left: " << entry.path();
    }
  }
}

TEST(NoInputBlocks, NamedPipesSocketsDevicesAndFoldersAreOneLineErrors) {
  const Folder folder;
  const std::string cube = folder.file("cube.obj", cube_obj(0.5));
  const std::string fifo = folder.file("fifo.obj");
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const std::string socket_path = folder.file("socket.ply");
  const int s = ::socket(AF_UNIX, SOCK_STREAM, 0);
  sockaddr_un address{};
  address.sun_family = AF_UNIX;
  std::snprintf(address.sun_path, sizeof address.sun_path, "%s", socket_path.c_str());
  ASSERT_EQ(::bind(s, reinterpret_cast<sockaddr*>(&address), sizeof address), 0);
  const std::string dir = folder.file("dir.obj");
  fs::create_directories(dir);
  for (const auto& [model, kind] : std::vector<std::pair<std::string, const char*>>{
           {fifo, "a named pipe"}, {socket_path, "a socket"}, {dir, "a directory"}}) {
    expect_error("measure " + model + " " + cube, {model.c_str(), kind});
    expect_error("measure " + cube + " " + model, {model.c_str(), kind});
  }
  expect_error("measure /dev/zero " + cube + " --ref-type mesh", {"/dev/zero"});
  for (const char* extension : {"xyz", "bpt", "binvox", "3mf", "gltf"}) {
    const std::string pipe = folder.file(fmt::format("pipe.{}", extension));
    ASSERT_EQ(::mkfifo(pipe.c_str(), 0600), 0);
    expect_error("measure " + pipe + " " + cube, {pipe.c_str(), "a named pipe"});
  }
  // A manifest that is a pipe, and a glTF whose buffer is one.
  const std::string manifest = folder.file("pairs.csv");
  ASSERT_EQ(::mkfifo(manifest.c_str(), 0600), 0);
  expect_error("batch " + manifest + " --out " + folder.file("out"), {"pairs.csv", "a named pipe"});
  ASSERT_EQ(::mkfifo(folder.file("buffer.bin").c_str(), 0600), 0);
  const std::string gltf = folder.file(
      "pipe-buffer.gltf",
      R"({"asset": {"version": "2.0"}, "buffers": [{"uri": "buffer.bin", "byteLength": 36}],
          "bufferViews": [{"buffer": 0, "byteLength": 36}],
          "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                         "min": [0, 0, 0], "max": [1, 1, 0]}],
          "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}], "nodes": [{"mesh": 0}],
          "scenes": [{"nodes": [0]}], "scene": 0})");
  expect_error("measure " + gltf + " " + cube, {"buffer.bin", "a named pipe"});
  ::close(s);
}

// A glTF whose only buffer is `uri`, 36 bytes: one triangle.
std::string triangle_gltf(const std::string& uri) {
  return fmt::format(
      R"({{"asset": {{"version": "2.0"}}, "buffers": [{{"uri": "{}", "byteLength": 36}}],
          "bufferViews": [{{"buffer": 0, "byteLength": 36}}],
          "accessors": [{{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                         "min": [0, 0, 0], "max": [1, 1, 0]}}],
          "meshes": [{{"primitives": [{{"attributes": {{"POSITION": 0}}}}]}}], "nodes": [{{"mesh": 0}}],
          "scenes": [{{"nodes": [0]}}], "scene": 0}})",
      uri);
}

TEST(References, StayInTheModelsFolderUnlessTrusted) {
  const Folder folder;
  const std::string cube = folder.file("cube.obj", cube_obj(0.5));
  std::string triangle(36, '\0');
  const float xyz[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  std::memcpy(triangle.data(), xyz, 36);
  fs::create_directories(folder.path / "models");
  folder.file("outside.bin", triangle);
  folder.file("models/inside.bin", triangle);
  fs::create_symlink(folder.path / "outside.bin", folder.path / "models" / "link.bin");
  const std::string inside = folder.file("models/inside.gltf", triangle_gltf("inside.bin"));
  EXPECT_EQ(run_cli("measure " + inside + " " + cube + " --semantics closest").exit_code, 0);
  for (const auto& [uri, why] : std::vector<std::pair<std::string, const char*>>{
           {"../outside.bin", "leads out of the folder"},
           {(folder.path / "outside.bin").string(), "is an absolute path"},
           {"link.bin", "symbolic link"},
           {"sub/../../outside.bin", "leads out of the folder"}}) {
    const std::string gltf = folder.file("models/escape.gltf", triangle_gltf(uri));
    expect_error("measure " + gltf + " " + cube, {"escape.gltf", uri.c_str(), why, "--trust-references"});
    const CliRun trusted = run_cli("measure " + gltf + " " + cube + " --semantics closest --trust-references");
    EXPECT_EQ(trusted.exit_code, 0) << uri << ": " << trusted.err;
  }
}

}  // namespace
