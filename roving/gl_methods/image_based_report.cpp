// The image-based comparison's text and JSON sections (image_based_report.h).
#include "roving/gl_methods/image_based_report.h"

#include <fmt/format.h>

namespace roving {

std::string image_based_lines(const ImageBasedResult& ib) {
  std::string out = fmt::format(
      "\n  image-based (MPEG IBSM, as mmetric 1.1.7): {} views on a Fibonacci sphere, {} x {} px, back faces "
      "culled\n"
      "    {} pixels both models cover; unmatched (one only) {:.6g}% of them; box ratio {:.6g}%\n"
      "    depth PSNR {:.6g} dB (mmetric's GEO: depth as a fraction of 3 x the view sphere's radius)\n",
      ib.views, ib.resolution, ib.resolution, ib.matched_pixels, ib.unmatched_percent, ib.box_ratio,
      ib.depth_psnr);
  if (ib.colour) {
    out += fmt::format(
        "    colour PSNR (8-bit pixels, peak 255, 99.99 where they agree): R'G'B' {:.6g} dB (R {:.6g}, G "
        "{:.6g}, "
        "B {:.6g}),\n      Y'CbCr 6:1:1 {:.6g} dB (Y' {:.6g}, Cb {:.6g}, Cr {:.6g})\n",
        ib.psnr_rgb, ib.psnr_rgb_channels[0], ib.psnr_rgb_channels[1], ib.psnr_rgb_channels[2],
        ib.psnr_ycbcr_611, ib.psnr_ycbcr[0], ib.psnr_ycbcr[1], ib.psnr_ycbcr[2]);
  }
  return out + fmt::format("    {:.3f} s\n", ib.seconds);
}

nlohmann::json image_based_json(const ImageBasedResult& ib) {
  nlohmann::json json = {{"definition", "MPEG IBSM (mmetric 1.1.7 compare --mode ibsm)"},
                         {"views", ib.views},
                         {"resolution", ib.resolution},
                         {"back_faces_culled", true},
                         {"matched_pixels", ib.matched_pixels},
                         {"unmatched_pixels", ib.unmatched_pixels},
                         {"unmatched_percent", ib.unmatched_percent},
                         {"box_ratio", ib.box_ratio},
                         {"depth_psnr", ib.depth_psnr},
                         {"seconds", ib.seconds}};
  if (ib.colour) {
    json["colour"] = {{"psnr_rgb", ib.psnr_rgb},
                      {"psnr_r", ib.psnr_rgb_channels[0]},
                      {"psnr_g", ib.psnr_rgb_channels[1]},
                      {"psnr_b", ib.psnr_rgb_channels[2]},
                      {"psnr_ycbcr_611", ib.psnr_ycbcr_611},
                      {"psnr_y", ib.psnr_ycbcr[0]},
                      {"psnr_cb", ib.psnr_ycbcr[1]},
                      {"psnr_cr", ib.psnr_ycbcr[2]},
                      {"mse_rgb", ib.rgb_mse},
                      {"mse_ycbcr", ib.ycbcr_mse}};
  }
  return json;
}

}  // namespace roving
