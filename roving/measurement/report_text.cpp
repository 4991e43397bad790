// The `roving measure` report as Metro-style plain text (measure_report.h): the header known
// before the long work, then each direction's statistics, the two-sided summary, colour, GL
// observations, the families' sections and times.
#include "measure_report.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>

#include "figure_families.h"

namespace roving {
namespace {

// Where a mesh's colour comes from, for the report's model line.
std::string colour_source(const TriangleMesh& m) {
  if (!m.has_colour()) return "";
  std::vector<std::string> parts;
  if (!m.vertex_colours().empty()) parts.push_back("vertex colours");
  if (const TextureMapping* mapping = m.texture_mapping()) {
    const std::size_t n = mapping->materials.size();
    parts.push_back(fmt::format("{} material{}", n, n == 1 ? "" : "s"));
    for (const Texture* t : textures_of(m)) {
      parts.push_back(fmt::format("texture {} ({} x {})", t->source, t->width, t->height));
    }
  }
  return fmt::format("; colour: {}", fmt::join(parts, ", "));
}

std::string model_line(const std::string& role, const Model& model) {
  const LoadedMesh& loaded = model.mesh;
  const TriangleMesh& m = loaded.mesh;
  if (model.mesh_vertices_only) {
    return fmt::format("{:<10} {}: mesh, read as its {} vertices (the protocol's points; faces not read)\n", role,
                       loaded.path, model.points.positions.size());
  }
  if (model.type == ModelType::Points) {
    std::string line = fmt::format("{:<10} {}: point cloud, {} points, normals {}{}\n", role, loaded.path,
                                   model.points.positions.size(),
                                   model.normals_estimated        ? "estimated (PCA, k = 12)"
                                   : model.points.normals.empty() ? "none"
                                                                  : "from the file",
                                   model.points.colours.empty() ? "" : "; colour: point colours");
    if (model.surfels) {
      const SurfelSurface& s = *model.surfels;
      line += fmt::format(
          "{:<10} drawn as surfels: disks reaching each point's {}th nearest neighbour, radius {:.4g} median "
          "({:.4g} to {:.4g}), {} triangles\n",
          "", s.rule.neighbours, s.median_radius, s.min_radius, s.max_radius, s.mesh.triangle_count());
    }
    return line;
  }
  std::string line = fmt::format("{:<10} {}: {} vertices, {} triangles", role, loaded.path, m.vertex_count(),
                                 m.triangle_count());
  if (model.bezier) {
    line = fmt::format(
        "{:<10} {}: {} Bezier patches ({} flipped to face out), tessellated {}x{} per patch ({} "
        "triangles), chordal error <= {:.3g}",
        role, loaded.path, model.bezier->patches.size(), model.patches_flipped, model.bezier_cells,
        model.bezier_cells, m.triangle_count(), model.chordal_error_bound);
  }
  if (model.voxels) {
    line = fmt::format(
        "{:<10} {}: {}^3 voxels of side {:.6g}, {} occupied; exposed faces: {} vertices, {} triangles", role,
        loaded.path, model.voxels->dimension, model.voxels->voxel_size, model.voxels->occupied_count(),
        m.vertex_count(), m.triangle_count());
  }
  if (m.unreferenced_vertex_count())
    line += fmt::format(", {} unreferenced vertices", m.unreferenced_vertex_count());
  if (m.degenerate_triangle_count())
    line += fmt::format(", {} zero-area triangles", m.degenerate_triangle_count());
  if (loaded.dropped_repeated_vertex_faces) {
    line += fmt::format(", {} faces with a repeated vertex dropped", loaded.dropped_repeated_vertex_faces);
  }
  return line + colour_source(m) + "\n";
}
// The statistics every table shows, by JSON key and row label.
const std::vector<std::pair<const char*, const char*>>& statistic_rows() {
  static const std::vector<std::pair<const char*, const char*>> rows = {
      {"siad", "SiAD (mean signed d)"},
      {"usiad", "USiAD (mean |d|)"},
      {"std_signed", "STD (of signed d)"},
      {"std_unsigned", "STD of |d|"},
      {"rms", "RMS"},
      {"min_signed", "min signed d (hits)"},
      {"max_signed", "max signed d (hits)"},
      {"max_abs", "max |d| (hits)"},
      {"p50", "|d| 50th percentile"},
      {"p90", "|d| 90th percentile"},
      {"p95", "|d| 95th percentile"},
      {"p99", "|d| 99th percentile"},
      {"siad_area", "SiAD, area-weighted"},
      {"usiad_area", "USiAD, area-weighted"},
      {"rms_area", "RMS, area-weighted"},
      {"siad_hits", "SiAD, hits only"},
      {"usiad_hits", "USiAD, hits only"}};
  return rows;
}
// `text` wrapped greedily at `width` columns, each line indented by two spaces.
std::string wrapped(const std::string& text, std::size_t width = 100) {
  std::string out, line = " ";
  std::size_t start = 0;
  while (start < text.size()) {
    const std::size_t end = std::min(text.find(' ', start), text.size());
    const std::string word = text.substr(start, end - start);
    if (line.size() + 1 + word.size() > width && line.size() > 1) {
      out += line + "\n";
      line = " ";
    }
    line += " " + word;
    start = end + 1;
  }
  return out + line + "\n";
}

std::string camera_geometry_text(const GlReport& g) {
  switch (g.camera_geometry) {
    case CameraGeometry::Cpu: return "cameras built on the CPU";
    case CameraGeometry::Gpu: return "cameras built on the GPU";
    case CameraGeometry::Compute: {
      std::string text = fmt::format("cameras in a compute pass; {} with a thin face decided on the CPU", g.thin_cameras);
      if (g.faces_chosen_in_pass + g.faces_left_to_cpu > 0) {
        text += fmt::format("; hits' faces: {} chosen in the pass, {} on the CPU", g.faces_chosen_in_pass,
                            g.faces_left_to_cpu);
      }
      return text;
    }
  }
  return "?";
}

std::string gl_lines(const GlReport& g) {
  std::string out = fmt::format("  GL: {}\n", g.renderer);
  if (g.views_h == 0 && !g.axis_views) {  // exact roving: cameras only
    out += fmt::format("  observations: {} per-sample cameras (exact roving draws no views); unresolved {}\n",
                       g.sample_cameras, g.resolved(Resolution::Unresolved));
  } else {
    out += fmt::format(
        "  observations: {} ({} views of {} at {} px + {} per-sample cameras); resolved by views {}, by "
        "cameras {}, unresolved {}\n",
        g.observations(), g.views_rendered,
        g.axis_views ? "the 6 axes" : fmt::format("{}x{}", g.views_h, g.views_v), g.resolution,
        g.sample_cameras, g.resolved(Resolution::View), g.resolved(Resolution::Camera),
        g.resolved(Resolution::Unresolved));
  }
  // Only what was rendered: views, cameras, or both.
  std::vector<std::string> precision;
  if (g.views_rendered) {
    precision.push_back(fmt::format("view pixel {:.4g}, view depth step {:.3g}{}", g.view_pixel_size,
                                    g.view_depth_step, g.views_culled ? "" : " (views drawn whole)"));
  }
  if (g.sample_cameras) {
    precision.push_back(
        fmt::format("camera half-width {:.3g}, camera depth step {:.3g} ({})", g.camera_half_width,
                    g.camera_depth_step, camera_geometry_text(g)));
  }
  if (!precision.empty()) out += fmt::format("  precision (model units): {}\n", fmt::join(precision, "; "));
  return out;
}

std::string samples_line(const SampleSet& samples, std::size_t count, std::uint64_t seed) {
  std::string out = fmt::format("{}{}", samples.kind,
                                samples.kind.rfind("area:", 0) == 0 ? fmt::format(" (seed {})", seed) : "");
  out += fmt::format(": {}", count);
  if (samples.skipped_degenerate_faces)
    out += fmt::format(", {} zero-area faces skipped", samples.skipped_degenerate_faces);
  if (samples.skipped_unreferenced_vertices)
    out += fmt::format(", {} unreferenced vertices skipped", samples.skipped_unreferenced_vertices);
  if (samples.skipped_zero_normal_vertices)
    out += fmt::format(", {} vertices without a normal skipped", samples.skipped_zero_normal_vertices);
  return out;
}
// One direction's colour figures as a small table: a column per channel, then the summaries.
std::string colour_lines(const DirectionReport& d) {
  const ColourStatistics& c = *d.colour;
  std::string out = fmt::format(
      "  {}colour: REF's at the sample against TEST's where d was measured ({}):\n"
      "    {} hits compared, {} no-hits without a colour\n",
      d.label.empty() ? "" : d.label + ": ", d.result.colour_source, c.compared, c.no_hit);
  if (c.compared == 0) return out + "    no colour figures: no hit to compare\n";
  out += fmt::format("    {:<34}", "sRGB code values (0-255)");
  for (const char* name : {"R'", "G'", "B'", "Y'", "Cb", "Cr"}) out += fmt::format(" {:>9}", name);
  out += "\n";
  const auto row = [&](const char* name, double ChannelErrors::*field) {
    std::string line = fmt::format("    {:<34}", name);
    for (const auto* channels : {&c.rgb, &c.ycbcr}) {
      for (const ChannelErrors& e : *channels) line += fmt::format(" {:>9.4g}", e.*field);
    }
    return line + "\n";
  };
  out += row("mean |delta|", &ChannelErrors::mean_abs);
  out += row("RMS", &ChannelErrors::rms);
  out += row("PSNR (dB, peak 255)", &ChannelErrors::psnr);
  out += fmt::format(
      "    PSNR R'G'B' {:.4g} dB, Y'CbCr 6:1:1 (MPEG) {:.4g} dB\n"
      "    CIEDE2000 delta E mean {:.4g}, p95 {:.4g}, max {:.4g}\n",
      c.psnr_rgb, c.psnr_ycbcr_611, c.delta_e_mean, c.delta_e_p95, c.delta_e_max);
  return out;
}

// "[lower, upper]" of a certified interval, with its width.
std::string interval_text(double lower, double upper, double diagonal) {
  return fmt::format("[{:.6g}, {:.6g}] (/ diagonal [{:.6g}, {:.6g}]; width {:.3g})", lower, upper,
                     lower / diagonal, upper / diagonal, upper - lower);
}

// The models load at once (measure_run), so loading takes the longer of the two times.
double loading_seconds(const MeasureReport& r) { return std::max(r.load_seconds[0], r.load_seconds[1]); }

}  // namespace

std::string format_header(const Model& a, const Model& b, const MeasureReport& r) {
  if (r.protocol_only) {
    return model_line("reference", a) + model_line("test", b) +
           fmt::format("{:<10} {}, REF its ground truth\n", "figures",
                       r.dtu || r.protocol == "dtu" ? "the DTU benchmark's own evaluation (DTUeval-python's eval.py)"
                             : "the Tanks and Temples benchmark's own evaluation (its toolbox's EvaluateHisto)");
  }
  if (r.pcc_only) {
    // A cloud read straight into MPEG's points (points_in_file) is described from what was read.
    const auto line = [&](const char* role, const Model& model, int side) {
      if (!model.points_in_file || !r.mpeg) return model_line(role, model);
      const MpegReport& m = *r.mpeg;
      const std::string normals = m.normals[side] ? (side == 0 && !m.normals_from.empty() ? "from " + m.normals_from
                                                                                           : "from the file")
                                  : side == 1 && !m.figures.mmetric ? "not read (D2 uses A's)"
                                                                    : "none";
      return fmt::format("{:<10} {}: point cloud, {} points, normals {}{}\n", role, model.path(), m.points_read[side],
                         normals, m.coloured[side] ? "; colour: point colours" : "");
    };
    return line("A", a, 0) + line("B", b, 1) +
           fmt::format("{:<10} MPEG's point-cloud figures, as pc_error (mpeg-pcc-dmetric 0.14) computes them (as "
                       "mmetric's compare --mode pcc where a model is a mesh)\n",
                       "figures");
  }
  const bool symmetric = r.diagonal_of_both;
  std::string out = model_line(symmetric ? "A" : "reference", a) + model_line(symmetric ? "B" : "test", b);
  out += fmt::format("{:<10} bounding-box diagonal {:.6g} ({})\n", "", r.diagonal,
                     symmetric ? "of both models" : "reference");
  out += fmt::format("{:<10} {}, semantics {}, max error h = {:.6g} ({})\n", "method", r.method,
                     to_string(r.semantics), r.max_error, r.max_error_text);
  return out;
}
std::string format_body(const MeasureReport& r) {
  if (r.protocol_only) {
    std::string out = family_sections(r);
    out += fmt::format("  time: load {:.3f} s, protocol {:.3f} s, total {:.3f} s\n", loading_seconds(r),
                       r.dtu ? r.dtu->seconds : r.tnt->seconds, r.total_seconds);
    for (const std::string& line : r.warnings) out += fmt::format("  warning: {}\n", line);
    return out;
  }
  if (r.pcc_only) {
    std::string out = family_sections(r);
    out += fmt::format("  time: load {:.3f} s, figures {:.3f} s, total {:.3f} s\n",
                       loading_seconds(r), r.mpeg->seconds, r.total_seconds);
    for (const std::string& line : r.warnings) out += fmt::format("  warning: {}\n", line);
    return out;
  }
  std::string out;
  for (const DirectionReport& d : r.directions) {
    out += fmt::format("{:<10} {}{}{}\n", "samples", d.label.empty() ? "" : d.label + ": ",
                       samples_line(d.samples, d.statistics.sample_count, r.seed),
                       !d.chunks ? ""
                       : d.samples.kind == "vertices"
                           ? fmt::format(" (REF read {} faces at a time for its vertex normals, then measured {} "
                                         "vertices at a time, {} blocks)",
                                         d.chunk_faces, d.chunk_faces, d.chunks)
                           : fmt::format(" (REF read and measured {} faces at a time, {} blocks)", d.chunk_faces,
                                         d.chunks));
  }
  out += "\n";
  // A column pair per direction: model units and / diagonal.
  std::string head = fmt::format("  {:<28}", "statistic");
  for (const DirectionReport& d : r.directions) {
    head += fmt::format(" {:>14} {:>12}", d.label.empty() ? "model units" : d.label, "/ diagonal");
  }
  out += head + "\n";
  std::vector<nlohmann::json> stats;
  for (const DirectionReport& d : r.directions) stats.push_back(statistics_json(d.statistics));
  for (const auto& [key, label] : statistic_rows()) {
    out += fmt::format("  {:<28}", label);
    for (const auto& s : stats) {
      const double value = s[key].get<double>();
      out += fmt::format(" {:>14.6g} {:>12.6g}", value, value / r.diagonal);
    }
    out += "\n";
  }
  out += "\n";
  for (const DirectionReport& d : r.directions) {
    const Statistics& s = d.statistics;
    out += fmt::format("  {}no hit within h: {} of {} samples ({:.4g}%)\n",
                       d.label.empty() ? "" : d.label + ": ", s.no_hit_count, s.sample_count,
                       100 * s.no_hit_fraction);
  }
  out += wrapped(semantics_note(r.semantics));
  for (const DirectionReport& d : r.directions) {
    if (d.colour) out += colour_lines(d);
  }
  if (r.symmetric()) {
    const TwoSided t = r.two_sided();
    const char* max_name = r.semantics == Semantics::Closest ? "Hausdorff distance, sampled"
                                                             : "max |d|, both directions (not Hausdorff)";
    out += fmt::format("\n  {:<40} {:>14} {:>12}\n", "two-sided (Metro)", "model units", "/ diagonal");
    for (const auto& [name, value] : {std::pair<std::string, double>{max_name, t.max_abs},
                                      {"mean |d|, both (area-weighted)", t.mean_abs},
                                      {"RMS, both (area-weighted)", t.rms}}) {
      out += fmt::format("  {:<40} {:>14.6g} {:>12.6g}\n", name, value, value / r.diagonal);
    }
    if (t.certified) {
      out += fmt::format("  {:<40} {}\n", "Hausdorff distance, certified",
                         interval_text(t.hausdorff_lower, t.hausdorff_upper, r.diagonal));
    }
  }
  out += family_sections(r);
  for (const DirectionReport& d : r.directions) {
    if (!d.result.gl) continue;
    if (!d.label.empty()) out += fmt::format("  {}:\n", d.label);
    out += gl_lines(*d.result.gl);
  }
  out += fmt::format("  time: load {:.3f} s ({} {:.3f}, {} {:.3f}), total {:.3f} s\n",
                     loading_seconds(r), r.symmetric() ? "A" : "reference",
                     r.load_seconds[0], r.symmetric() ? "B" : "test", r.load_seconds[1], r.total_seconds);
  for (const DirectionReport& d : r.directions) {
    out += fmt::format("        {}build {:.3f} s, query {:.3f} s ({:.3g} samples/s)\n",
                       d.label.empty() ? "" : d.label + ": ", d.result.build_seconds, d.result.query_seconds,
                       d.result.query_seconds > 0 ? d.statistics.sample_count / d.result.query_seconds : 0.0);
  }
  for (const DirectionReport& d : r.directions) {
    const std::string label = d.label.empty() ? "" : d.label + ": ";
    if (d.intervals) {
      const auto text = [&](const char* name, const MeanInterval& m) {
        return fmt::format("{} [{:.6g}, {:.6g}]", name, m.lower, m.upper);
      };
      out += fmt::format(
          "  {}95% intervals of the surface means (eq. 1) from {} random samples (normal approximation): {}, "
          "{}, {}\n",
          label, d.statistics.sample_count, text("SiAD", d.intervals->siad), text("USiAD", d.intervals->usiad),
          text("RMS", d.intervals->rms));
      if (d.auto_sampling) {
        out += fmt::format(
            "  {}area:auto: {} samples in {} round(s) {} a half-width of {:.3g} for USiAD (asked {:.3g}){}\n",
            label, d.statistics.sample_count, d.auto_sampling->rounds,
            d.auto_sampling->met ? "reached" : "did not reach, stopping at", d.auto_sampling->reached,
            d.auto_sampling->target,
            d.auto_sampling->met ? "" : ": the sample cap or round limit came first");
      }
    } else {
      const double difference = d.statistics.usiad - d.statistics.usiad_area;
      out += fmt::format(
          "  {}{} samples: SiAD, USiAD, RMS are the exact means over these samples (eq. 2), not estimates; "
          "as an "
          "estimate of the surface mean (eq. 1) USiAD differs from its area-weighted form by {:.3g} "
          "({:.3g}%)\n",
          label, d.samples.kind, difference,
          d.statistics.usiad_area > 0 ? 100 * difference / d.statistics.usiad_area : 0.0);
    }
  }
  for (const DirectionReport& d : r.directions) {
    if (!d.hausdorff) continue;
    const HausdorffInterval& h = *d.hausdorff;
    out += fmt::format(
        "  {}Hausdorff distance from {} to {}, certified (every point of the surface, not only the samples): "
        "{}; "
        "farthest point found ({:.6g}, {:.6g}, {:.6g}); {:.3f} s, {} closest-point queries\n",
        d.label.empty() ? "" : d.label + ": ", r.symmetric() ? d.label.substr(0, 1) : "REF",
        r.symmetric() ? d.label.substr(d.label.size() - 1) : "TEST",
        interval_text(h.lower, h.upper, r.diagonal), h.lower_point.x(), h.lower_point.y(), h.lower_point.z(),
        h.seconds, h.distance_queries);
  }
  // Also printed to stderr as found (unless --quiet); here so that the report keeps them.
  for (const std::string& line : r.warnings) out += fmt::format("  warning: {}\n", line);
  return out;
}

}  // namespace roving
