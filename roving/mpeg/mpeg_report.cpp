// MPEG's figures' JSON section and text table (mpeg_report.h).
#include "roving/mpeg/mpeg_report.h"

#include <fmt/format.h>

#include <cmath>

namespace roving {
namespace {

// A PSNR as JSON: null where the MSE is 0 (+infinity).
nlohmann::json psnr_json(double psnr) {
  return std::isfinite(psnr) ? nlohmann::json(psnr) : nlohmann::json(nullptr);
}

// YCoCg-R's PSNR peaks, as pc_error's: 255 for Y, 511 for Co and Cg.
double ycocg_peak(int channel) { return channel == 0 ? 255 : 511; }

nlohmann::json mpeg_direction_json(const MpegDirection& d, const MpegFigures& f) {
  nlohmann::json json = {{"points", d.points},
                         {"d1_mse", d.d1_mse},
                         {"d1_psnr", psnr_json(geometry_psnr(d.d1_mse, f.peak))},
                         {"d1_hausdorff", d.d1_hausdorff},
                         {"d1_hausdorff_psnr", psnr_json(geometry_psnr(d.d1_hausdorff, f.peak))}};
  if (f.d2) {
    json["d2_mse"] = d.d2_mse;
    json["d2_psnr"] = psnr_json(geometry_psnr(d.d2_mse, f.peak));
    json["d2_hausdorff"] = d.d2_hausdorff;
    json["d2_hausdorff_psnr"] = psnr_json(geometry_psnr(d.d2_hausdorff, f.peak));
  }
  if (f.colour) {
    const char* ycbcr[3] = {"y", "cb", "cr"};
    const char* rgb[3] = {"r", "g", "b"};
    for (int c = 0; c < 3; ++c) {
      json[fmt::format("{}_mse", ycbcr[c])] = d.ycbcr_mse[c];
      json[fmt::format("{}_psnr", ycbcr[c])] = psnr_json(colour_psnr(d.ycbcr_mse[c], 1));
    }
    for (int c = 0; c < 3; ++c) {
      json[fmt::format("{}_mse", rgb[c])] = d.rgb_mse[c];
      json[fmt::format("{}_psnr", rgb[c])] = psnr_json(colour_psnr(d.rgb_mse[c], 255));
      json[fmt::format("{}_hausdorff", rgb[c])] = d.rgb_hausdorff[c];
      json[fmt::format("{}_hausdorff_psnr", rgb[c])] = psnr_json(colour_psnr(d.rgb_hausdorff[c], 255));
    }
  }
  if (f.ycocg) {  // pc_error's --mseSpace=8: Y on [0, 255], Co and Cg on [1, 511]
    const char* ycocg[3] = {"ycocg_y", "co", "cg"};
    for (int c = 0; c < 3; ++c) {
      json[fmt::format("{}_mse", ycocg[c])] = d.ycocg_mse[c];
      json[fmt::format("{}_psnr", ycocg[c])] = psnr_json(colour_psnr(d.ycocg_mse[c], ycocg_peak(c)));
    }
  }
  return json;
}

// The surfaces' own D1 and D2 in one direction (or the worse), their PSNRs at `peak`; an interval
// is [lower, upper], null where there is none.
nlohmann::json surface_json(const SurfaceFigures& d, double peak) {
  const auto interval = [](const std::optional<Interval>& i) {
    return i ? nlohmann::json::array({i->lower, i->upper}) : nlohmann::json(nullptr);
  };
  const auto psnr_interval = [&](const std::optional<Interval>& i) {
    return i ? nlohmann::json::array(
                   {psnr_json(geometry_psnr(i->upper, peak)), psnr_json(geometry_psnr(i->lower, peak))})
             : nlohmann::json(nullptr);
  };
  return {{"samples", d.samples},
          {"no_hits", d.no_hits},
          {"d1_mse", d.d1_mse},
          {"d1_mse_interval", interval(d.d1_mse_interval)},
          {"d1_psnr", psnr_json(geometry_psnr(d.d1_mse, peak))},
          {"d1_psnr_interval", psnr_interval(d.d1_mse_interval)},
          {"d2_mse", std::isnan(d.d2_mse) ? nlohmann::json(nullptr) : nlohmann::json(d.d2_mse)},
          {"d2_mse_interval", interval(d.d2_mse_interval)},
          {"d2_psnr", psnr_json(geometry_psnr(d.d2_mse, peak))},
          {"d2_psnr_interval", psnr_interval(d.d2_mse_interval)},
          {"d1_hausdorff_certified", interval(d.hausdorff)},
          {"d1_hausdorff_psnr_interval", psnr_interval(d.hausdorff)}};
}

}  // namespace

nlohmann::json mpeg_json(const MpegReport& m) {
  const MpegFigures& f = m.figures;
  nlohmann::json json = {
      {"definition",
       "MPEG pc_error (mpeg-pcc-dmetric 0.14, default options): each point paired with the other cloud's "
       "nearest; D1 = squared distance, D2 = squared distance along the normal (A's normals, carried onto B "
       "for A -> B); MSE = mean over the points, hausdorff = largest; PSNR = 10 log10(3 peak^2 / MSE); "
       "colour "
       "over BT.709 Y'CbCr on [0, 1] (peak 1) and RGB (peak 255); symmetric = the worse direction; points at "
       "one position merged first. See docs/mpeg.md"},
      {"computed_as", f.mmetric ? "mmetric 1.1.7 compare --mode pcc: meshes sampled as mmetric samples them"
                                : "pc_error (mpeg-pcc-dmetric 0.14)"},
      {"peak", f.peak},
      {"peak_from", f.peak_given ? "--pcc-resolution"
                    : f.mmetric  ? "the diagonal of A's box (mmetric's default)"
                                 : "the largest nearest-neighbour spacing within A"},
      {"points_read", {m.points_read[0], m.points_read[1]}},
      {"points", {m.points[0], m.points[1]}},
      {"d2", f.d2 ? nlohmann::json(true) : nlohmann::json("none: A has no normals in its file")},
      {"normals_from", !f.d2                     ? nlohmann::json()
                       : !m.normals_from.empty() ? nlohmann::json(m.normals_from)
                       : m.a_sampled             ? nlohmann::json("A's samples (their faces' normals)")
                                                 : nlohmann::json("A's file")},
      {"colour", f.colour},
      {"a_to_b", mpeg_direction_json(f.a_to_b, f)},
      {"b_to_a", mpeg_direction_json(f.b_to_a, f)},
      {"symmetric", mpeg_direction_json(f.symmetric(), f)},
      {"seconds", m.seconds}};
  // Options other than the tools' defaults, named as the tools name them.
  const PcErrorOptions& o = m.options;
  if (!o.defaults() || o.ycocg) {
    json["pc_error_options"] = {{"dropdups", o.dropdups},
                                {"neighborsProc", o.neighbors_proc},
                                {"averageNormals", o.average_normals ? 1 : 0},
                                {"mseSpace", o.ycocg ? 8 : 1}};
  }
  if (!m.b_own_normals) json["mmetric_options"] = {{"normalCalcModificationEnable", false}};
  if (m.surface) {
    const auto& [ab, ba] = *m.surface;
    json["exact_surface"] = {
        {"definition",
         "D1 and D2 of the surfaces themselves: every point of one surface against the other surface; D1 the "
         "area-weighted mean squared closest distance (the directions' closest-point measurement; a no-hit "
         "counts at h), D2 the same of its component along the other surface's normal at the closest point "
         "(null where the method names no face), each with its 95% interval for area:N samples, and the "
         "certified Hausdorff interval squared (bounding D2's largest value too); PSNRs at the same peak"},
        {"a_to_b", surface_json(ab, f.peak)},
        {"b_to_a", surface_json(ba, f.peak)},
        {"symmetric", surface_json(worse(ab, ba), f.peak)}};
  }
  return json;
}

std::string mpeg_lines(const MpegReport& m) {
  const MpegFigures& f = m.figures;
  std::string out = fmt::format(
      "\n  MPEG point-cloud figures ({}): peak {:.9g} ({}); {} and {} points ({} and {} {})\n",
      f.mmetric ? "mmetric's compare --mode pcc" : "pc_error's", f.peak,
      f.peak_given ? "--pcc-resolution"
      : f.mmetric  ? "diagonal of A's box"
                   : "largest nearest-neighbour spacing within A",
      m.points[0], m.points[1], m.points_read[0], m.points_read[1], f.mmetric ? "sampled or read" : "read");
  if (!m.normals_from.empty()) out += fmt::format("  D2 along A's normals from {}\n", m.normals_from);
  if (!m.options.defaults() || m.options.ycocg) {
    out += fmt::format("  pc_error's --dropdups={} --neighborsProc={} --averageNormals={} --mseSpace={}\n",
                       m.options.dropdups, m.options.neighbors_proc, m.options.average_normals ? 1 : 0,
                       m.options.ycocg ? 8 : 1);
  }
  if (!m.b_own_normals) out += "  mmetric's --normalCalcModificationEnable=false: A's normals carried onto B\n";
  out += fmt::format("  {:<28} {:>16} {:>16} {:>16}\n", "figure", "A -> B", "B -> A", "symmetric");
  const MpegDirection both = f.symmetric();
  const auto row = [&](const char* name, auto value) {
    const auto text = [](double v) {
      return std::isfinite(v) ? fmt::format("{:.9g}", v) : std::string("inf");
    };
    out += fmt::format("  {:<28} {:>16} {:>16} {:>16}\n", name, text(value(f.a_to_b)), text(value(f.b_to_a)),
                       text(value(both)));
  };
  row("D1 MSE (p2point)", [](const MpegDirection& d) { return d.d1_mse; });
  row("D1 PSNR, dB", [&](const MpegDirection& d) { return geometry_psnr(d.d1_mse, f.peak); });
  if (f.d2) {
    row("D2 MSE (p2plane)", [](const MpegDirection& d) { return d.d2_mse; });
    row("D2 PSNR, dB", [&](const MpegDirection& d) { return geometry_psnr(d.d2_mse, f.peak); });
  }
  row("D1 Hausdorff (squared)", [](const MpegDirection& d) { return d.d1_hausdorff; });
  row("D1 Hausdorff PSNR, dB", [&](const MpegDirection& d) { return geometry_psnr(d.d1_hausdorff, f.peak); });
  if (f.d2) {
    row("D2 Hausdorff (squared)", [](const MpegDirection& d) { return d.d2_hausdorff; });
    row("D2 Hausdorff PSNR, dB",
        [&](const MpegDirection& d) { return geometry_psnr(d.d2_hausdorff, f.peak); });
  }
  if (f.colour) {
    const char* names[3] = {"Y PSNR, dB", "Cb PSNR, dB", "Cr PSNR, dB"};
    for (int c = 0; c < 3; ++c)
      row(names[c], [&](const MpegDirection& d) { return colour_psnr(d.ycbcr_mse[c], 1); });
    const char* rgb[3] = {"R PSNR, dB", "G PSNR, dB", "B PSNR, dB"};
    for (int c = 0; c < 3; ++c)
      row(rgb[c], [&](const MpegDirection& d) { return colour_psnr(d.rgb_mse[c], 255); });
  }
  if (f.ycocg) {
    const char* names[3] = {"Y PSNR (YCoCg-R), dB", "Co PSNR, dB", "Cg PSNR, dB"};
    for (int c = 0; c < 3; ++c)
      row(names[c], [&](const MpegDirection& d) { return colour_psnr(d.ycocg_mse[c], ycocg_peak(c)); });
  }
  if (!f.d2) out += "  no D2: A has no normals in its file (pc_error takes D2's normals from A alone)\n";
  if (m.surface) {
    const auto& [ab, ba] = *m.surface;
    const SurfaceFigures both = worse(ab, ba);
    const auto psnr = [&](double mse) {
      const double v = geometry_psnr(mse, f.peak);
      return std::isfinite(v) ? fmt::format("{:.4f}", v) : std::string("inf");
    };
    const auto cell = [&](double mse, const std::optional<Interval>& interval) {
      if (std::isnan(mse)) return std::string("-");
      return psnr(mse) + (interval ? fmt::format(" [{}, {}]", psnr(interval->upper), psnr(interval->lower))
                                   : std::string());
    };
    const auto certified = [&](const SurfaceFigures& d) {
      return d.hausdorff ? fmt::format("[{}, {}]", psnr(d.hausdorff->upper), psnr(d.hausdorff->lower))
                         : std::string("-");
    };
    out += fmt::format("  {:<28} {:>28} {:>28} {:>28}\n", "the surfaces themselves", "A -> B", "B -> A",
                       "symmetric");
    out += fmt::format("  {:<28} {:>28} {:>28} {:>28}\n", "D1 PSNR, dB (95% interval)",
                       cell(ab.d1_mse, ab.d1_mse_interval), cell(ba.d1_mse, ba.d1_mse_interval),
                       cell(both.d1_mse, both.d1_mse_interval));
    out += fmt::format("  {:<28} {:>28} {:>28} {:>28}\n", "D2 PSNR, dB (95% interval)",
                       cell(ab.d2_mse, ab.d2_mse_interval), cell(ba.d2_mse, ba.d2_mse_interval),
                       cell(both.d2_mse, both.d2_mse_interval));
    out += fmt::format("  {:<28} {:>28} {:>28} {:>28}\n", "D1 Hausdorff PSNR, certified", certified(ab),
                       certified(ba), certified(both));
    out +=
        "  (every point of each surface against the other, closest point, area-weighted; the sampled figures "
        "above\n   measure samples against samples)\n";
  }
  return out;
}

}  // namespace roving
