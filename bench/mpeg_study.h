// roving-bench's MPEG table (results/mpeg.md): the real models quantised to a 10-bit grid against
// copies a mesh codec would make (coarser quantisation, decimation), with mmetric's sampled D1 / D2
// PSNR (`compare --mode pcc`, as roving reproduces it) beside D1 of the surfaces themselves with its
// 95% interval and the certified Hausdorff PSNR, and the time of each.
#pragma once

#include <functional>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "report_table.h"
#include "roving/core/triangle_mesh.h"

namespace roving {

struct MpegStudy {
  std::vector<ReportTable> tables;
  std::map<std::string, double> figures;  // for --check
  std::string notes;                      // Markdown: what the differences mean
};

// `models`: (name, mesh) pairs, any scale. Quick: 20,000 area samples a direction, else 200,000.
MpegStudy mpeg_study(const std::vector<std::pair<std::string, TriangleMesh>>& models, bool quick,
                     const std::function<void(const std::string&)>& step);

}  // namespace roving
