// The rows of a --samples-out file, for tests that recompute a figure from the samples it names.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "roving/core/triangle_mesh.h"

namespace roving {

// One direction's rows of a --samples-out file: position, |d|, hit, weight.
struct SampleRow {
  Vec3 position;
  double distance = 0, weight = 0;
  bool hit = false;
};
inline std::vector<SampleRow> sample_rows(const std::string& csv, const std::string& direction) {
  std::ifstream in(csv);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line.rfind("x,y,z,nx,ny,nz,d,hit,element,weight,", 0), 0u) << line;
  std::vector<SampleRow> rows;
  while (std::getline(in, line)) {
    std::vector<std::string> fields;
    std::stringstream cells(line);
    for (std::string cell; std::getline(cells, cell, ',');) fields.push_back(cell);
    if (fields.back() != direction) continue;
    rows.push_back({Vec3(std::stod(fields[0]), std::stod(fields[1]), std::stod(fields[2])), std::abs(std::stod(fields[6])),
                    std::stod(fields[9]), fields[7] == "1"});
  }
  return rows;
}

// The area-weighted mean |d| of the hits `inside` takes, and how many it took.
template <typename Inside>
std::pair<double, std::size_t> region_mean(const std::vector<SampleRow>& rows, Inside&& inside) {
  double sum = 0, weight = 0;
  std::size_t count = 0;
  for (const SampleRow& r : rows) {
    if (!r.hit || !inside(r)) continue;
    sum += r.weight * r.distance, weight += r.weight, ++count;
  }
  return {sum / weight, count};
}

}  // namespace roving
