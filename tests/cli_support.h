// Running the `roving` executable from tests: its exit code, stdout and stderr; one-line error
// checks; scratch folders.
#pragma once

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>

#include "test_support.h"

namespace roving::testing::cli {

namespace fs = std::filesystem;

struct CliRun {
  int exit_code;
  std::string out, err;
};

// ROVING_CLI_RECORD=DIR: each run's command line, exit code, stdout and stderr kept in DIR, a file
// per run named by its test, so that a refactoring's reports can be compared byte for byte with
// the ones before it (tests/compare_reports.py).
inline void record_run(const std::string& arguments, const CliRun& run) {
  const char* folder = std::getenv("ROVING_CLI_RECORD");
  const ::testing::TestInfo* test = ::testing::UnitTest::GetInstance()->current_test_info();
  if (folder == nullptr || test == nullptr) return;
  std::string name = fmt::format("{}.{}", test->test_suite_name(), test->name());
  std::replace(name.begin(), name.end(), '/', '_');
  static std::map<std::string, int> runs;
  std::ofstream(fs::path(folder) / fmt::format("{}.{}", name, ++runs[name]), std::ios::binary)
      << "$ roving " << arguments << "\n--- exit " << run.exit_code << "\n" << run.out << "\n--- stderr\n" << run.err;
}

inline CliRun run_cli(const std::string& arguments) {
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
  record_run(arguments, run);
  return run;
}

inline std::string bunny() {
  return roving::testing::data_file("stanford-bunny.obj");
}

inline void expect_error(const std::string& arguments, std::initializer_list<const char*> fragments) {
  const CliRun run = run_cli(arguments);
  EXPECT_NE(run.exit_code, 0) << arguments;
  EXPECT_EQ(run.err.rfind("roving: error: ", 0), 0u) << run.err;
  EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << "one line expected: " << run.err;
  for (const char* fragment : fragments) EXPECT_NE(run.err.find(fragment), std::string::npos) << run.err;
}

inline int& serial() {
  static int count = 0;
  return count;
}

// An OBJ cube [-s, s]^3 moved by `shift` along x, outward-facing unless `inside_out`.
inline std::string cube_obj(double s, double shift = 0, bool inside_out = false) {
  std::string obj;
  for (int i = 0; i < 8; ++i) {
    obj += fmt::format("v {} {} {}\n", (i & 1 ? s : -s) + shift, i & 2 ? s : -s, i & 4 ? s : -s);
  }
  const int faces[12][3] = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                            {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  for (const auto& f : faces) {
    obj += inside_out ? fmt::format("f {} {} {}\n", f[0] + 1, f[2] + 1, f[1] + 1)
                      : fmt::format("f {} {} {}\n", f[0] + 1, f[1] + 1, f[2] + 1);
  }
  return obj;
}

// The same cube as an ASCII PLY with a colour per vertex: (red, 40 * corner index mod 256, 200).
inline std::string coloured_cube_ply(double s, int red) {
  std::string ply =
      "ply\nformat ascii 1.0\nelement vertex 8\nproperty float x\nproperty float y\nproperty float z\n"
      "property uchar red\nproperty uchar green\nproperty uchar blue\nelement face 12\n"
      "property list uchar int vertex_indices\nend_header\n";
  for (int i = 0; i < 8; ++i) {
    ply += fmt::format("{} {} {} {} {} 200\n", i & 1 ? s : -s, i & 2 ? s : -s, i & 4 ? s : -s, red,
                       40 * i % 256);
  }
  const int faces[12][3] = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                            {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  for (const auto& f : faces) ply += fmt::format("3 {} {} {}\n", f[0], f[1], f[2]);
  return ply;
}

// A scratch folder removed at the end of a test.
struct Folder {
  fs::path path = fs::temp_directory_path() / ("roving-cli-out-" + std::to_string(::getpid()) + "-" + std::to_string(++serial()));
  Folder() { fs::create_directories(path); }
  ~Folder() { fs::remove_all(path); }
  std::string file(const std::string& name, const std::string& content = "") const {
    const std::string p = (path / name).string();
    if (!content.empty()) std::ofstream(p, std::ios::binary) << content;
    return p;
  }
  std::size_t entries() const {
    return std::distance(fs::directory_iterator(path), fs::directory_iterator());
  }
};

}  // namespace roving::testing::cli
