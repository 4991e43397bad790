// Formatting of the `roving measure` report.
#include "report.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>

#include "figure_families.h"
#include "roving/core/error.h"

namespace roving {
namespace {

// The textures a mesh's materials use, each once.
std::vector<const Texture*> textures_of(const TriangleMesh& m) {
  std::vector<const Texture*> textures;
  if (const TextureMapping* mapping = m.texture_mapping()) {
    for (const Material& material : mapping->materials) {
      const Texture* t = material.texture.get();
      if (t && std::find(textures.begin(), textures.end(), t) == textures.end()) textures.push_back(t);
    }
  }
  return textures;
}

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

}  // namespace

nlohmann::json model_json(const Model& model) {
  const LoadedMesh& loaded = model.mesh;
  const TriangleMesh& m = loaded.mesh;
  const BoundingBox box = model.bounding_box();
  nlohmann::json json = {
      {"path", loaded.path},
      {"type", to_string(model.type)},
      {"vertices", m.vertex_count()},
      {"triangles", m.triangle_count()},
      {"unreferenced_vertices", m.unreferenced_vertex_count()},
      {"degenerate_triangles", m.degenerate_triangle_count()},
      {"dropped_repeated_vertex_faces", loaded.dropped_repeated_vertex_faces},
      {"triangulated_polygons", loaded.triangulated_polygons},
      {"area", m.total_area()},
      {"bounding_box",
       {{"min", {box.min.x(), box.min.y(), box.min.z()}}, {"max", {box.max.x(), box.max.y(), box.max.z()}}}},
      {"diagonal", box.diagonal()}};
  if (model.type == ModelType::Points && !model.points.colours.empty()) {
    json["colour"] = {{"point_colours", true}};
  } else if (m.has_colour()) {
    nlohmann::json textures = nlohmann::json::array();
    for (const Texture* t : textures_of(m)) {
      textures.push_back({{"path", t->source}, {"width", t->width}, {"height", t->height}});
    }
    const TextureMapping* mapping = m.texture_mapping();
    json["colour"] = {{"vertex_colours", !m.vertex_colours().empty()},
                      {"materials", mapping ? mapping->materials.size() : 0},
                      {"textures", textures}};
  }
  if (model.voxels) {
    json["voxels"] = {{"dimension", model.voxels->dimension},
                      {"voxel_size", model.voxels->voxel_size},
                      {"occupied", model.voxels->occupied_count()}};
  }
  if (model.bezier) {
    json["bezier"] = {{"patches", model.bezier->patches.size()},
                      {"cells_per_patch_side", model.bezier_cells},
                      {"patches_flipped", model.patches_flipped},
                      {"chordal_error_bound", model.chordal_error_bound}};
  }
  if (model.type == ModelType::Points) {
    json["points"] = {{"count", model.points.positions.size()},
                      {"normals_estimated", model.normals_estimated}};
    if (model.surfels) {
      const SurfelSurface& surfels = *model.surfels;
      json["points"]["surfels"] = {
          {"neighbours", surfels.rule.neighbours},      {"fan_sides", surfels.rule.fan_sides},
          {"triangles", surfels.mesh.triangle_count()}, {"radius_min", surfels.min_radius},
          {"radius_median", surfels.median_radius},     {"radius_max", surfels.max_radius}};
    }
  }
  return json;
}

namespace {

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

const char* semantics_note(Semantics semantics) {
  switch (semantics) {
    case Semantics::FirstHit:
      return "first-hit: d is where the ray from x + h n back along the normal first meets TEST; a no-hit "
             "means no surface within h along the normal (counted as d = +h in the means, left out of max "
             "|d|); "
             "a false alarm (the paper's Figure 4c) is another part of TEST met first. For a Hausdorff-style "
             "figure use --semantics closest.";
    case Semantics::Nearest:
      return "nearest: d is TEST's crossing of the normal line nearest to x, within h; a no-hit means none "
             "(counted as d = +h in the means, left out of max |d|). For a Hausdorff-style figure use "
             "--semantics closest.";
    case Semantics::Closest:
      return "closest: |d| is the distance to TEST's nearest point (Metro, MeshLab, CloudCompare), signed + "
             "where that point lies along REF's normal; every sample has a hit.";
  }
  return "";
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

nlohmann::json relative_json(const nlohmann::json& absolute, double diagonal) {
  nlohmann::json relative;
  for (const auto& [key, value] : absolute.items()) relative[key] = value.get<double>() / diagonal;
  return relative;
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
    precision.push_back(
        fmt::format("view pixel {:.4g}, view depth step {:.3g}", g.view_pixel_size, g.view_depth_step));
  }
  if (g.sample_cameras) {
    precision.push_back(
        fmt::format("camera half-width {:.3g}, camera depth step {:.3g} (cameras built on the {})",
                    g.camera_half_width, g.camera_depth_step, g.gpu_cameras ? "GPU" : "CPU"));
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

nlohmann::json sign_counts_json(const SignCounts& c) {
  return {{"positive", c.positive}, {"negative", c.negative}, {"zero", c.zero}};
}

// One direction's fields, in the layout a one-sided report has always had at its top level.
nlohmann::json direction_json(const DirectionReport& d, const MeasureReport& r) {
  const Statistics& s = d.statistics;
  const nlohmann::json stats = statistics_json(s);
  nlohmann::json json = {
      {"reference", d.reference_json},
      {"test", d.test_json},
      {"samples",
       {{"kind", d.samples.kind},
        {"count", d.statistics.sample_count},
        {"skipped_degenerate_faces", d.samples.skipped_degenerate_faces},
        {"skipped_unreferenced_vertices", d.samples.skipped_unreferenced_vertices},
        {"skipped_zero_normal_vertices", d.samples.skipped_zero_normal_vertices}}},
      {"statistics", stats},
      {"statistics_relative_to_diagonal", relative_json(stats, r.diagonal)},
      {"hits", s.hit_count},
      {"no_hits", s.no_hit_count},
      {"no_hit_fraction", s.no_hit_fraction},
      {"no_hit_rule",
       "counted as d = +max_error in the means and percentiles; left out of min, max and max_abs"},
      {"histogram",
       {{"low", s.histogram.low},
        {"high", s.histogram.high},
        {"counts", s.histogram.counts},
        {"below", s.histogram.below},
        {"above", s.histogram.above}}},
      {"seconds", {{"build", d.result.build_seconds}, {"query", d.result.query_seconds}}},
      {"signs", sign_counts_json(d.signs)},
      {"heatmap_range", d.heatmap_range},
  };
  if (d.result.gl) json["gl"] = gl_json(*d.result.gl);
  if (d.chunks) json["samples"]["streamed"] = {{"chunk_faces", d.chunk_faces}, {"chunks", d.chunks}};
  if (d.colour) {
    json["colour"] = colour_json(*d.colour);
    json["colour"]["test_colour"] = d.result.colour_source;
  }
  if (d.auto_sampling) {
    json["samples"]["auto"] = {{"usiad_half_width_asked", d.auto_sampling->target},
                               {"usiad_half_width_reached", d.auto_sampling->reached},
                               {"rounds", d.auto_sampling->rounds},
                               {"met", d.auto_sampling->met}};
  }
  if (d.intervals) {
    const auto interval = [](const MeanInterval& m) {
      return nlohmann::json{{"estimate", m.estimate},
                            {"standard_error", m.standard_error},
                            {"lower", m.lower},
                            {"upper", m.upper}};
    };
    json["sampling_error"] = {
        {"level", d.intervals->level},
        {"method", "normal approximation: independent samples uniform by area; mean +- 1.96 standard errors"},
        {"siad", interval(d.intervals->siad)},
        {"usiad", interval(d.intervals->usiad)},
        {"rms", interval(d.intervals->rms)}};
  } else {
    json["sampling_error"] = {
        {"method", "none: the statistics are the exact means (eq. 2) over these samples, not estimates"},
        {"usiad_minus_usiad_area", s.usiad - s.usiad_area}};
  }
  if (d.hausdorff) {
    const HausdorffInterval& h = *d.hausdorff;
    const auto point = [](const Vec3& p) { return nlohmann::json::array({p.x(), p.y(), p.z()}); };
    json["hausdorff_certified"] = {{"lower", h.lower},
                                   {"upper", h.upper},
                                   {"bound", r.hausdorff_bound},
                                   {"farthest_point", point(h.lower_point)},
                                   {"its_closest_point", point(h.lower_closest)},
                                   {"distance_queries", h.distance_queries},
                                   {"triangles_split", h.triangles_split},
                                   {"seconds", h.seconds}};
  }
  return json;
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

}  // namespace

nlohmann::json gl_json(const GlReport& g) {
  return {{"renderer", g.renderer},
          {"observations", g.observations()},
          {"views_rendered", g.views_rendered},
          {"sample_cameras", g.sample_cameras},
          {"views", g.axis_views     ? "6 axes"
                    : g.views_h == 0 ? "none"
                                     : fmt::format("{}x{}", g.views_h, g.views_v)},
          {"resolution", g.resolution},
          {"resolved_by_view", g.resolved(Resolution::View)},
          {"resolved_by_camera", g.resolved(Resolution::Camera)},
          {"unresolved", g.resolved(Resolution::Unresolved)},
          {"view_pixel_size", g.view_pixel_size},
          {"view_depth_step", g.view_depth_step},
          {"camera_half_width", g.camera_half_width},
          {"camera_depth_step", g.camera_depth_step},
          {"camera_geometry", g.gpu_cameras ? "gpu" : "cpu"},
          {"camera_build_seconds", g.camera_build_seconds},
          {"camera_render_seconds", g.camera_render_seconds},
          {"view_cpu_seconds", g.view_cpu_seconds},
          {"view_draw_seconds", g.view_draw_seconds}};
}

GlReport gl_report_of(const nlohmann::json& json) {
  GlReport g;
  g.renderer = json.at("renderer").get<std::string>();
  g.views_rendered = json.at("views_rendered").get<std::size_t>();
  g.sample_cameras = json.at("sample_cameras").get<std::size_t>();
  const std::string views = json.at("views").get<std::string>();
  g.axis_views = views == "6 axes";
  if (!g.axis_views && views != "none" && std::sscanf(views.c_str(), "%dx%d", &g.views_h, &g.views_v) != 2) {
    throw Error(fmt::format("GL views: expected HxV, '6 axes' or 'none', found '{}'", views));
  }
  g.resolution = json.at("resolution").get<int>();
  // The counts stand for the per-sample record, as a streamed block's do.
  g.earlier_resolved[static_cast<std::size_t>(Resolution::View)] = json.at("resolved_by_view").get<std::size_t>();
  g.earlier_resolved[static_cast<std::size_t>(Resolution::Camera)] =
      json.at("resolved_by_camera").get<std::size_t>();
  g.earlier_resolved[static_cast<std::size_t>(Resolution::Unresolved)] = json.at("unresolved").get<std::size_t>();
  g.view_pixel_size = json.at("view_pixel_size").get<double>();
  g.view_depth_step = json.at("view_depth_step").get<double>();
  g.camera_half_width = json.at("camera_half_width").get<double>();
  g.camera_depth_step = json.at("camera_depth_step").get<double>();
  g.gpu_cameras = json.at("camera_geometry").get<std::string>() == "gpu";
  g.camera_build_seconds = json.at("camera_build_seconds").get<double>();
  g.camera_render_seconds = json.at("camera_render_seconds").get<double>();
  g.view_cpu_seconds = json.at("view_cpu_seconds").get<double>();
  g.view_draw_seconds = json.at("view_draw_seconds").get<double>();
  return g;
}

nlohmann::json colour_json(const ColourStatistics& c) {
  const auto channels = [](const std::array<ChannelErrors, 3>& e, std::array<const char*, 3> names) {
    nlohmann::json json;
    for (int i = 0; i < 3; ++i)
      json[names[i]] = {{"mean_abs", e[i].mean_abs}, {"rms", e[i].rms}, {"psnr", e[i].psnr}};
    return json;
  };
  return {{"encoding", "sRGB code values on [0, 255], compared as stored"},
          {"peak", kColourPeak},
          {"compared", c.compared},
          {"no_hits", c.no_hit},
          {"rgb", channels(c.rgb, {"r", "g", "b"})},
          {"ycbcr_bt709", channels(c.ycbcr, {"y", "cb", "cr"})},
          {"psnr_rgb", c.psnr_rgb},
          {"psnr_ycbcr_611", c.psnr_ycbcr_611},
          {"delta_e_mean", c.delta_e_mean},
          {"delta_e_p95", c.delta_e_p95},
          {"delta_e_max", c.delta_e_max},
          {"colour_rms_y", c.ycbcr[0].rms}};
}

nlohmann::json statistics_json(const Statistics& s) {
  return {{"siad", s.siad},
          {"usiad", s.usiad},
          {"std_signed", s.std_signed},
          {"std_unsigned", s.std_unsigned},
          {"rms", s.rms},
          {"min_signed", s.min_signed},
          {"max_signed", s.max_signed},
          {"max_abs", s.max_abs},
          {"p50", s.p50},
          {"p90", s.p90},
          {"p95", s.p95},
          {"p99", s.p99},
          {"siad_area", s.siad_area},
          {"usiad_area", s.usiad_area},
          {"rms_area", s.rms_area},
          {"siad_hits", s.siad_hits},
          {"usiad_hits", s.usiad_hits}};
}

TwoSided MeasureReport::two_sided() const {
  TwoSided t;
  double weight = 0, sum_abs = 0, sum_squares = 0;
  t.certified =
      std::all_of(directions.begin(), directions.end(), [](const DirectionReport& d) { return d.hausdorff; });
  for (const DirectionReport& d : directions) {
    t.max_abs = std::max(t.max_abs, d.statistics.max_abs);
    if (t.certified) {
      t.hausdorff_lower = std::max(t.hausdorff_lower, d.hausdorff->lower);
      t.hausdorff_upper = std::max(t.hausdorff_upper, d.hausdorff->upper);
    }
    const double w = std::accumulate(d.samples.weights.begin(), d.samples.weights.end(), 0.0);
    weight += w;
    sum_abs += w * d.statistics.usiad_area;
    sum_squares += w * d.statistics.rms_area * d.statistics.rms_area;
  }
  if (weight > 0) {
    t.mean_abs = sum_abs / weight;
    t.rms = std::sqrt(sum_squares / weight);
  }
  return t;
}

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

namespace {

// The models load at once (measure_run), so loading takes the longer of the two times.
double loading_seconds(const MeasureReport& r) { return std::max(r.load_seconds[0], r.load_seconds[1]); }

}  // namespace

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
                       d.chunks ? fmt::format(" (REF read and measured {} faces at a time, {} blocks)", d.chunk_faces,
                                              d.chunks)
                                : "");
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

nlohmann::json to_json(const MeasureReport& r) {
  nlohmann::json json = {{"schema_version", kReportSchemaVersion}};
  json.update(r.provenance);
  if (r.protocol_only) {
    json["method"] = "protocol";
    json["warnings"] = r.warnings;
    add_family_json(r, json);
    json["seconds"] = {
        {"load_reference", r.load_seconds[0]}, {"load_test", r.load_seconds[1]}, {"total", r.total_seconds}};
    return json;
  }
  if (r.pcc_only) {
    json["method"] = "pcc";
    json["warnings"] = r.warnings;
    add_family_json(r, json);
    json["seconds"] = {
        {"load_reference", r.load_seconds[0]}, {"load_test", r.load_seconds[1]}, {"total", r.total_seconds}};
    return json;
  }
  json["method"] = r.method;
  json["semantics"] = to_string(r.semantics);
  json["semantics_note"] = semantics_note(r.semantics);
  json["max_error"] = {
      {"value", r.max_error}, {"given_as", r.max_error_text}, {"relative", r.max_error / r.diagonal}};
  json["diagonal"] = r.diagonal;
  json["diagonal_of"] = r.diagonal_of_both ? "both models" : "reference";
  json["seed"] = r.seed;
  json["warnings"] = r.warnings;
  if (r.symmetric()) {
    json["directions"] = nlohmann::json::array();
    for (const DirectionReport& d : r.directions) {
      nlohmann::json direction = direction_json(d, r);
      direction["label"] = d.label;
      json["directions"].push_back(direction);
    }
    const TwoSided t = r.two_sided();
    const nlohmann::json two_sided = {
        {"hausdorff",
         r.semantics == Semantics::Closest ? nlohmann::json(t.max_abs) : nlohmann::json(nullptr)},
        {"max_abs", t.max_abs},
        {"mean_both", t.mean_abs},
        {"rms_both", t.rms}};
    json["two_sided"] = two_sided;
    if (t.certified) {
      json["two_sided"]["hausdorff_certified"] = {{"lower", t.hausdorff_lower}, {"upper", t.hausdorff_upper}};
    }
    if (r.directions[0].colour && r.directions[1].colour) {
      const ColourStatistics &ab = *r.directions[0].colour, &ba = *r.directions[1].colour;
      json["two_sided"]["colour_worse"] = {{"psnr_rgb", std::min(ab.psnr_rgb, ba.psnr_rgb)},
                                           {"psnr_ycbcr_611", std::min(ab.psnr_ycbcr_611, ba.psnr_ycbcr_611)},
                                           {"delta_e_mean", std::max(ab.delta_e_mean, ba.delta_e_mean)}};
    }
    json["two_sided_relative_to_diagonal"] =
        relative_json({{"max_abs", t.max_abs}, {"mean_both", t.mean_abs}, {"rms_both", t.rms}}, r.diagonal);
  } else {
    json.update(direction_json(r.directions.front(), r));
  }
  if (r.shard) {
    const ShardSlice& s = *r.shard;
    nlohmann::json slices = nlohmann::json::array();
    for (const DirectionReport& d : r.directions) {
      slices.push_back({{"first", d.slice_first}, {"count", d.statistics.sample_count}, {"total", d.slice_total}});
    }
    json["shard"] = {{"index", s.shard.index},
                     {"count", s.shard.count},
                     {"samples", slices},
                     {"note", "this run's slice of the samples alone; roving merge gives the pair's figures"}};
  }
  add_family_json(r, json);
  json["seconds"]["load_reference"] = r.load_seconds[0];
  json["seconds"]["load_test"] = r.load_seconds[1];
  json["seconds"]["total"] = r.total_seconds;
  return json;
}

}  // namespace roving
