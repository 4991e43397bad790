// MPEG's point-cloud figures as a measurement reports them: what was measured (points read and
// merged, D2's normals) with pc_error's or mmetric's figures, their JSON section (docs/report-json.md's
// `mpeg_pcc`) and their text table.
#pragma once

#include <array>
#include <cstddef>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "roving/mpeg/point_cloud_psnr.h"
#include "roving/mpeg/surface_psnr.h"

namespace roving {

// MPEG's point-cloud figures (pc_error's) of two point clouds, A the original and B the processed.
struct MpegReport {
  MpegFigures figures;
  std::size_t points_read[2] = {0, 0};  // A, B as read
  std::size_t points[2] = {0, 0};       // after pc_error's merging of points at one position
  bool coloured[2] = {false, false};    // A, B have colour
  bool normals[2] = {false, false};     // A, B have normals as measured (B's: mmetric's rules alone)
  double seconds = 0;                   // the figures, from the points as pc_error holds them
  double read_seconds[2] = {0, 0};      // A, B read here, straight into those (Model::points_in_file)
  std::string normals_from;             // D2's normals: from this file (--pcc-normals); empty: A's own
  bool a_sampled = false;               // A is a mesh, sampled as mmetric samples it (its normals its faces')
  // Two meshes under --pcc: D1 of the surfaces themselves, A -> B and B -> A (surface_psnr.h).
  std::optional<std::array<SurfaceFigures, 2>> surface;
  std::vector<std::string> warnings;  // about the clouds as pc_error reads them (the report's to give)
  PcErrorOptions options;             // pc_error's options the figures follow
  bool b_own_normals = true;          // mmetric's --normalCalcModificationEnable (meshes)
};

nlohmann::json mpeg_json(const MpegReport& report);

// The table: each figure A -> B, B -> A and the worse of the two, then the surfaces' own D1 and D2
// where they were measured.
std::string mpeg_lines(const MpegReport& report);

}  // namespace roving
