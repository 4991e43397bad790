#include "roving/reconstruction/trajectory_log.h"

#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <fstream>

#include "roving/core/error.h"

namespace roving {
namespace {

// The whitespace-separated numbers of a line; nullopt-like: `ok` false at the first that is not one.
template <class Number>
std::vector<Number> numbers_of(const std::string& line, bool& ok) {
  std::vector<Number> values;
  ok = true;
  std::size_t at = 0;
  while ((at = line.find_first_not_of(" \t\r", at)) != std::string::npos) {
    const std::size_t end = std::min(line.find_first_of(" \t\r", at), line.size());
    Number value{};
    const auto [last, error] = std::from_chars(line.data() + at, line.data() + end, value);
    if (error != std::errc() || last != line.data() + end) {
      ok = false;
      return values;
    }
    values.push_back(value);
    at = end;
  }
  return values;
}

bool blank(const std::string& line) { return line.find_first_not_of(" \t\r") == std::string::npos; }

}  // namespace

std::vector<Eigen::Matrix4d> read_trajectory_log(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw Error(fmt::format("{}: cannot read the camera trajectory", path));
  std::vector<Eigen::Matrix4d> poses;
  std::string line;
  std::size_t number = 0;
  while (std::getline(in, line)) {
    ++number;
    if (blank(line)) continue;  // between cameras and at the end
    Eigen::Matrix4d pose;
    for (int row = 0; row < 4; ++row) {
      if (!std::getline(in, line)) {
        throw Error(fmt::format("{}: camera {} ends after {} of its pose's 4 rows; expected a line of metadata, then 4 "
                                "rows of 4 numbers per camera",
                                path, poses.size() + 1, row));
      }
      ++number;
      bool ok = false;
      const std::vector<double> values = numbers_of<double>(line, ok);
      bool finite = true;
      for (const double v : values) finite = finite && std::isfinite(v);
      if (!ok || values.size() != 4 || !finite) {
        throw Error(fmt::format("{}: line {} is '{}'; expected a row of camera {}'s pose: 4 finite numbers", path,
                                number, line, poses.size() + 1));
      }
      for (int c = 0; c < 4; ++c) pose(row, c) = values[static_cast<std::size_t>(c)];
    }
    poses.push_back(pose);
  }
  if (poses.empty()) throw Error(fmt::format("{}: no camera; expected a trajectory (.log) of camera poses", path));
  return poses;
}

std::vector<std::size_t> read_frame_mapping(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw Error(fmt::format("{}: cannot read the frame mapping", path));
  std::size_t counts[2] = {0, 0};
  std::string line;
  for (int k = 0; k < 2; ++k) {
    bool ok = false;
    const std::vector<std::size_t> values = std::getline(in, line) ? numbers_of<std::size_t>(line, ok) : std::vector<std::size_t>{};
    if (!ok || values.size() != 1) {
      throw Error(fmt::format("{}: line {} is '{}'; expected the count of {} frames, a whole number", path, k + 1, line,
                              k == 0 ? "reference" : "all"));
    }
    counts[k] = values[0];
  }
  std::vector<std::size_t> frames;
  for (std::size_t i = 0; i < counts[0]; ++i) {
    bool ok = false;
    const std::vector<std::size_t> values = std::getline(in, line) ? numbers_of<std::size_t>(line, ok) : std::vector<std::size_t>{};
    if (!ok || values.size() != 2) {
      throw Error(fmt::format("{}: line {} is '{}'; expected reference frame {} of {} as 'index frame', two whole "
                              "numbers",
                              path, i + 3, line, i + 1, counts[0]));
    }
    if (values[1] < 1 || values[1] > counts[1]) {
      throw Error(fmt::format("{}: line {} names frame {}; expected a frame from 1 to {} (line 2)", path, i + 3,
                              values[1], counts[1]));
    }
    frames.push_back(values[1]);
  }
  if (frames.empty()) throw Error(fmt::format("{}: no reference frame; expected at least one", path));
  return frames;
}

}  // namespace roving
