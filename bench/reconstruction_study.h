// roving-bench's reconstruction table (results/reconstruction.md): the real models as ground truth
// against reconstruction-like copies (noisy, holed, decimated, voxelised), with the figures DTU's
// protocol publishes (DTUeval-python's pipeline as roving reproduces it: points, thinning, nearest
// point, the distance cap; its spread over seeds) beside the exact ones (every point of one surface
// against the other surface, 95% intervals, certified F-score bounds), and the time of each.
#pragma once

#include <functional>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "report_table.h"
#include "roving/core/triangle_mesh.h"

namespace roving {

struct ReconstructionStudy {
  std::vector<ReportTable> tables;
  std::map<std::string, double> figures;  // for --check
  std::string notes;                      // Markdown: what the differences mean
};

// `models`: (name, mesh) pairs, any scale (each is scaled to longest side 200, millimetres as
// DTU's). Quick: two copies, 20,000 area samples a direction and DTU's density 1 mm; else four
// copies, 200,000 samples and DTU's own 0.2 mm.
ReconstructionStudy reconstruction_study(const std::vector<std::pair<std::string, TriangleMesh>>& models, bool quick,
                                         const std::function<void(const std::string&)>& step);

}  // namespace roving
