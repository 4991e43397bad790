// .bpt files: Bezier patches as listed by the Utah teapot's distribution.
#include "roving/formats/points_voxels_patches/bpt.h"

#include <fmt/format.h>

#include <fstream>
#include <sstream>

#include "roving/core/error.h"
#include "roving/formats/files/file_bytes.h"

namespace roving {

BezierSurface read_bpt(const std::string& path) {
  require_regular_file(path, "a .bpt Bezier patch file");
  std::ifstream file(path);
  if (!file) throw Error(fmt::format("{}: cannot open for reading", path));
  std::string line;
  int line_number = 0;
  const auto next = [&](const char* expected) {
    while (std::getline(file, line)) {
      ++line_number;
      if (line.find_first_not_of(" \t\r") != std::string::npos) return;
    }
    throw Error(fmt::format("{}: truncated after line {}: expected {}", path, line_number, expected));
  };
  const auto fail = [&](const std::string& what) {
    return Error(fmt::format("{}:{}: {}, found '{}'", path, line_number, what, line.substr(0, 40)));
  };
  next("the patch count");
  long count = 0;
  {
    std::istringstream words(line);
    std::string rest;
    if (!(words >> count) || (words >> rest) || count < 1 || count > 1000000)
      throw fail("expected a patch count in 1..10^6");
  }
  BezierSurface surface;
  for (long patch = 0; patch < count; ++patch) {
    next("a patch's degrees 'm n'");
    BezierPatch p;
    std::istringstream words(line);
    std::string rest;
    if (!(words >> p.degree_u >> p.degree_v) || (words >> rest) || p.degree_u < 1 || p.degree_v < 1 ||
        p.degree_u > 16 || p.degree_v > 16) {
      throw fail(fmt::format("expected the degrees 'm n' (1..16) of patch {}", patch));
    }
    for (int k = 0; k < (p.degree_u + 1) * (p.degree_v + 1); ++k) {
      next("a control point 'x y z'");
      std::istringstream xyz(line);
      Vec3 c;
      if (!(xyz >> c.x() >> c.y() >> c.z()) || (xyz >> rest) || !c.allFinite()) {
        throw fail(fmt::format("expected control point {} of patch {} as 3 finite numbers", k, patch));
      }
      p.control.push_back(c);
    }
    surface.patches.push_back(std::move(p));
  }
  while (std::getline(file, line)) {
    ++line_number;
    if (line.find_first_not_of(" \t\r") != std::string::npos)
      throw fail(fmt::format("expected the end after {} patches", count));
  }
  return surface;
}

}  // namespace roving
