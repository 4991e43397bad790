// roving-bench's colour table (results/colour.md): coloured and textured bunnies against copies
// degraded as codecs and pipelines degrade them, by every method that gives colour and by the
// image-based comparison (MPEG's IBSM), each GL method checked against Embree on the same samples
// before its figures and time are shown.
#pragma once

#include <functional>
#include <map>
#include <string>
#include <vector>

#include "report_table.h"
#include "roving/gl/depth_renderer.h"
#include "roving/pictures/heatmap_picture.h"

namespace roving {

struct ColourStudy {
  std::vector<ReportTable> tables;
  std::map<std::string, double> figures;  // for --check
  std::vector<std::string> failures;      // checks that did not hold
  struct PictureJob {
    std::string file, caption;
    ColouredSurface surface;
    Picture picture;
  };
  std::vector<PictureJob> pictures;
  std::string notes;  // Markdown: how the models were made, and what the two correspondences show
};

// `bunny` and `rocker_arm` (the 20k one; used unless quick): normalised to longest side 128.
// Quick: 8,000 samples, three pairs, IBSM at 512 pixels. `step` hears of each pair.
ColourStudy colour_study(const TriangleMesh& bunny, const TriangleMesh* rocker_arm, bool quick, GlBackend backend,
                         const std::function<void(const std::string&)>& step);

}  // namespace roving
