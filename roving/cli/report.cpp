// Formatting of the `roving measure` report.
#include "report.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>

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

// The image-based comparison (IBSM), as mmetric names its figures.
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

void certify_reconstruction(MeasureReport& report) {
  if (!report.reconstruction || !report.symmetric() || !report.directions[0].area_within ||
      !report.directions[1].area_within) {
    return;
  }
  const auto bounds = [](const AreaWithin& w) {
    std::vector<ReconstructionFigures::Bounds> out;
    for (std::size_t k = 0; k < w.thresholds.size(); ++k) out.push_back({w.lower(k), w.upper(k)});
    return out;
  };
  set_certified_shares(*report.reconstruction, bounds(*report.directions[1].area_within),
                       bounds(*report.directions[0].area_within));
}

namespace {

// An estimate with its 95% interval where it has one.
nlohmann::json estimate_json(const Estimate& e) {
  if (std::isnan(e.lower)) return e.value;
  return {{"estimate", e.value}, {"lower", e.lower}, {"upper", e.upper}};
}

nlohmann::json reconstruction_json(const ReconstructionFigures& f) {
  const auto direction = [](const DirectionFigures& d) {
    return nlohmann::json{{"mean", estimate_json(d.mean)},
                          {"median", d.median},
                          {"rms", estimate_json(d.rms)},
                          {"normal_consistency", estimate_json(d.normal_consistency)},
                          {"hits", d.hits},
                          {"no_hits", d.no_hits}};
  };
  nlohmann::json json = {
      {"definition",
       "REF is the ground truth, TEST the reconstruction. accuracy: |d| of TEST's samples to REF (B -> A); "
       "completeness: REF's to TEST (A -> B); means, medians and RMS over the hits weighted by the area each "
       "sample stands for. chamfer_mean = (accuracy.mean + completeness.mean) / 2 (DTU's overall, Tanks and "
       "Temples); chamfer_sum = accuracy.mean + completeness.mean; chamfer_squared_mean = (accuracy.rms^2 + "
       "completeness.rms^2) / 2; chamfer_squared_sum = their sum. precision at tau: the share of TEST's area "
       "within tau of REF; recall: REF's within tau of TEST (a no-hit is beyond); f_score = 2 P R / (P + R). "
       "normal_consistency: mean |n . n'| of a sample's normal and the other surface's at the "
       "correspondence, "
       "each direction and their mean. Intervals (estimate, lower, upper): 95%, for area-uniform samples; "
       "chamfer_*_interval and f_score_interval combine the two directions' (independent samples: the delta "
       "method). "
       "*_certified (closest semantics between surfaces): the shares of area surely and possibly within tau, "
       "every point of the surfaces bounded, not sampled (docs/reconstruction.md); f_score_certified from them."},
      {"accuracy", direction(f.accuracy)},
      {"completeness", direction(f.completeness)},
      {"chamfer_mean", f.chamfer_mean},
      {"chamfer_sum", f.chamfer_sum},
      {"chamfer_squared_mean", f.chamfer_squared_mean},
      {"chamfer_squared_sum", f.chamfer_squared_sum},
      {"normal_consistency", f.normal_consistency},
      {"thresholds", nlohmann::json::array()}};
  const auto interval = [](const Estimate& e) { return nlohmann::json{{"lower", e.lower}, {"upper", e.upper}}; };
  if (!std::isnan(f.chamfer_mean_estimate.lower)) {
    json["chamfer_mean_interval"] = interval(f.chamfer_mean_estimate);
    json["chamfer_sum_interval"] = interval(f.chamfer_sum_estimate);
  }
  const auto bounds = [](const ReconstructionFigures::Bounds& b) {
    return nlohmann::json{{"lower", b.lower}, {"upper", b.upper}};
  };
  for (std::size_t i = 0; i < f.thresholds.size(); ++i) {
    nlohmann::json row = {{"tau", f.thresholds[i]},
                          {"precision", estimate_json(f.accuracy.within[i])},
                          {"recall", estimate_json(f.completeness.within[i])},
                          {"f_score", f.f_score[i]}};
    if (!std::isnan(f.f_score_estimate[i].lower)) row["f_score_interval"] = interval(f.f_score_estimate[i]);
    if (!f.precision_certified.empty()) {
      row["precision_certified"] = bounds(f.precision_certified[i]);
      row["recall_certified"] = bounds(f.recall_certified[i]);
      row["f_score_certified"] = bounds(f.f_score_certified[i]);
    }
    json["thresholds"].push_back(row);
  }
  return json;
}

std::string reconstruction_lines(const ReconstructionFigures& f, double diagonal) {
  std::string out = fmt::format("\n  {:<40} {:>14} {:>12}\n", "reconstruction (REF the ground truth)",
                                "model units", "/ diagonal");
  const auto length = [&](const std::string& name, double value) {
    out += fmt::format("  {:<40} {:>14.6g} {:>12.6g}\n", name, value, value / diagonal);
  };
  length("accuracy, mean (TEST to REF)", f.accuracy.mean.value);
  length("accuracy, median", f.accuracy.median);
  length("completeness, mean (REF to TEST)", f.completeness.mean.value);
  length("completeness, median", f.completeness.median);
  length("Chamfer, mean of the two", f.chamfer_mean);
  if (!std::isnan(f.chamfer_mean_estimate.lower)) {
    out += fmt::format("  {:<40} {:>14}\n", "  95% interval",
                       fmt::format("[{:.6g}, {:.6g}]", f.chamfer_mean_estimate.lower, f.chamfer_mean_estimate.upper));
  }
  length("Chamfer, sum of the two", f.chamfer_sum);
  out += fmt::format("  {:<40} {:>14.6g}\n", "Chamfer, squared, mean of the two", f.chamfer_squared_mean);
  out += fmt::format("  {:<40} {:>14.6g}\n", "normal consistency", f.normal_consistency);
  for (std::size_t i = 0; i < f.thresholds.size(); ++i) {
    out += fmt::format(
        "  {:<40} {:>14}\n",
        fmt::format("at tau = {:.6g} ({:.3g}%)", f.thresholds[i], 100 * f.thresholds[i] / diagonal),
        fmt::format("P {:.4f} R {:.4f} F {:.4f}", f.precision[i], f.recall[i], f.f_score[i]));
    if (!std::isnan(f.f_score_estimate[i].lower)) {
      const Estimate &p = f.accuracy.within[i], &r = f.completeness.within[i], &q = f.f_score_estimate[i];
      out += fmt::format("  {:<40} {:>14}\n", "  95% intervals",
                         fmt::format("P [{:.4f}, {:.4f}] R [{:.4f}, {:.4f}] F [{:.4f}, {:.4f}]", p.lower, p.upper,
                                     r.lower, r.upper, q.lower, q.upper));
    }
    if (!f.precision_certified.empty()) {
      const auto& p = f.precision_certified[i];
      const auto& r = f.recall_certified[i];
      out += fmt::format("  {:<40} {:>14}\n", "  certified (every point, not sampled)",
                         fmt::format("P [{:.4f}, {:.4f}] R [{:.4f}, {:.4f}]", p.lower, p.upper, r.lower, r.upper));
    }
  }
  return out;
}

// A PSNR as JSON: null where the MSE is 0 (+infinity).
nlohmann::json psnr_json(double psnr) { return std::isfinite(psnr) ? nlohmann::json(psnr) : nlohmann::json(nullptr); }

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
  return json;
}

// The surfaces' own D1 and D2 in one direction (or the worse), their PSNRs at `peak`; an interval
// is [lower, upper], null where there is none.
nlohmann::json surface_json(const SurfaceFigures& d, double peak) {
  const auto interval = [](const std::optional<Interval>& i) {
    return i ? nlohmann::json::array({i->lower, i->upper}) : nlohmann::json(nullptr);
  };
  const auto psnr_interval = [&](const std::optional<Interval>& i) {
    return i ? nlohmann::json::array({psnr_json(geometry_psnr(i->upper, peak)), psnr_json(geometry_psnr(i->lower, peak))})
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

nlohmann::json mpeg_json(const MpegReport& m) {
  const MpegFigures& f = m.figures;
  nlohmann::json json = {
      {"definition",
       "MPEG pc_error (mpeg-pcc-dmetric 0.14, default options): each point paired with the other cloud's "
       "nearest; D1 = squared distance, D2 = squared distance along the normal (A's normals, carried onto B "
       "for A -> B); MSE = mean over the points, hausdorff = largest; PSNR = 10 log10(3 peak^2 / MSE); colour "
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
      {"normals_from", !f.d2                   ? nlohmann::json()
                       : !m.normals_from.empty() ? nlohmann::json(m.normals_from)
                       : m.a_sampled             ? nlohmann::json("A's samples (their faces' normals)")
                                                 : nlohmann::json("A's file")},
      {"colour", f.colour},
      {"a_to_b", mpeg_direction_json(f.a_to_b, f)},
      {"b_to_a", mpeg_direction_json(f.b_to_a, f)},
      {"symmetric", mpeg_direction_json(f.symmetric(), f)},
      {"seconds", m.seconds}};
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
  out += fmt::format("  {:<28} {:>16} {:>16} {:>16}\n", "figure", "A -> B", "B -> A", "symmetric");
  const MpegDirection both = f.symmetric();
  const auto row = [&](const char* name, auto value) {
    const auto text = [](double v) { return std::isfinite(v) ? fmt::format("{:.9g}", v) : std::string("inf"); };
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
    row("D2 Hausdorff PSNR, dB", [&](const MpegDirection& d) { return geometry_psnr(d.d2_hausdorff, f.peak); });
  }
  if (f.colour) {
    const char* names[3] = {"Y PSNR, dB", "Cb PSNR, dB", "Cr PSNR, dB"};
    for (int c = 0; c < 3; ++c)
      row(names[c], [&](const MpegDirection& d) { return colour_psnr(d.ycbcr_mse[c], 1); });
    const char* rgb[3] = {"R PSNR, dB", "G PSNR, dB", "B PSNR, dB"};
    for (int c = 0; c < 3; ++c)
      row(rgb[c], [&](const MpegDirection& d) { return colour_psnr(d.rgb_mse[c], 255); });
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
    out += fmt::format("  {:<28} {:>28} {:>28} {:>28}\n", "the surfaces themselves", "A -> B", "B -> A", "symmetric");
    out += fmt::format("  {:<28} {:>28} {:>28} {:>28}\n", "D1 PSNR, dB (95% interval)",
                       cell(ab.d1_mse, ab.d1_mse_interval), cell(ba.d1_mse, ba.d1_mse_interval),
                       cell(both.d1_mse, both.d1_mse_interval));
    out += fmt::format("  {:<28} {:>28} {:>28} {:>28}\n", "D2 PSNR, dB (95% interval)",
                       cell(ab.d2_mse, ab.d2_mse_interval), cell(ba.d2_mse, ba.d2_mse_interval),
                       cell(both.d2_mse, both.d2_mse_interval));
    out += fmt::format("  {:<28} {:>28} {:>28} {:>28}\n", "D1 Hausdorff PSNR, certified", certified(ab),
                       certified(ba), certified(both));
    out += "  (every point of each surface against the other, closest point, area-weighted; the sampled figures "
           "above\n   measure samples against samples)\n";
  }
  return out;
}

// The mean, sample standard deviation, least and largest of one figure over the protocol's runs.
struct Spread {
  double mean = 0, sd = 0, min = 0, max = 0;
};

template <class Run>
Spread spread_of(const std::vector<Run>& runs, double Run::*figure) {
  Spread s{0, 0, runs.front().*figure, runs.front().*figure};
  for (const Run& run : runs) {
    s.mean += run.*figure / runs.size();
    s.min = std::min(s.min, run.*figure);
    s.max = std::max(s.max, run.*figure);
  }
  for (const Run& run : runs) s.sd += (run.*figure - s.mean) * (run.*figure - s.mean);
  s.sd = runs.size() > 1 ? std::sqrt(s.sd / (runs.size() - 1)) : 0;
  return s;
}

// Each figure's spread over the runs as JSON (null for one run).
template <class Run, std::size_t N>
nlohmann::json spread_json(const std::vector<Run>& runs,
                           const std::array<std::pair<const char*, double Run::*>, N>& figures) {
  if (runs.size() < 2) return nullptr;
  nlohmann::json spread = nlohmann::json::object();
  for (const auto& [name, figure] : figures) {
    const Spread s = spread_of(runs, figure);
    spread[name] = {{"mean", s.mean}, {"sd", s.sd}, {"min", s.min}, {"max", s.max}};
  }
  return spread;
}

constexpr std::array<std::pair<const char*, double DtuRun::*>, 3> kDtuFigures = {
    {{"accuracy", &DtuRun::accuracy}, {"completeness", &DtuRun::completeness}, {"overall", &DtuRun::overall}}};

std::string dtu_order(const DtuFigures& f) {
  if (!f.options.first_seed) return "the points' own order (eval.py with its shuffle left out)";
  const std::uint64_t first = *f.options.first_seed;
  return f.runs.size() == 1 ? fmt::format("shuffled with seed {}", first)
                            : fmt::format("shuffled with seeds {} to {}", first, first + f.runs.size() - 1);
}

// The exact figures where the protocol measures (null without --symmetric).
nlohmann::json dtu_exact_json(const DtuReport& d) {
  if (!d.exact) return nullptr;
  return {{"definition",
           "The exact figures (as under 'reconstruction') over the part of each surface the protocol measures: "
           "accuracy over TEST's samples inside BB - patch .. BB + 2 patch whose ObsMask voxel is observed, "
           "completeness over REF's samples above the plane P, measured against the whole other surface. figures: "
           "every distance counted; figures_below_max_dist: only the distances below max_dist, as the protocol "
           "counts them (what the cap hides is the difference)"},
          {"test_samples_counted", d.exact_test_counted},
          {"test_samples", d.exact_test_samples},
          {"reference_samples_counted", d.exact_reference_counted},
          {"reference_samples", d.exact_reference_samples},
          {"figures", reconstruction_json(*d.exact)},
          {"figures_below_max_dist", reconstruction_json(*d.exact_below_cap)}};
}

nlohmann::json dtu_json(const DtuReport& d) {
  const DtuFigures& f = d.figures;
  const DtuRun& first = f.runs.front();
  nlohmann::json runs = nlohmann::json::array();
  for (const DtuRun& r : f.runs) {
    runs.push_back({{"seed", r.seed ? nlohmann::json(*r.seed) : nlohmann::json(nullptr)},
                    {"accuracy", r.accuracy},
                    {"completeness", r.completeness},
                    {"overall", r.overall},
                    {"thinned", r.thinned},
                    {"in_box", r.in_box},
                    {"observed", r.observed},
                    {"accuracy_counted", r.accuracy_counted},
                    {"completeness_counted", r.completeness_counted}});
  }
  return {{"definition",
           "DTU MVS evaluation as DTUeval-python's eval.py computes it: TEST sampled (a mesh: its vertices, then "
           "per face a grid of step density scaled to its shape) or read (points), shuffled, thinned to no two "
           "points within density, kept inside BB - patch .. BB + 2 patch; accuracy = mean distance from the "
           "kept points inside ObsMask to REF's nearest point, completeness = mean distance from REF's points "
           "above the plane P to the kept points' nearest, each over the distances below max_dist; overall = "
           "(accuracy + completeness) / 2. See docs/reconstruction.md"},
          {"computed_as", "DTUeval-python eval.py (github.com/jzhangbs/DTUeval-python, 45b4fec), step by step"},
          {"obs_mask", d.obs_mask},
          {"plane", d.plane},
          {"density", f.options.density},
          {"patch", f.options.patch},
          {"max_dist", f.options.max_dist},
          {"order", dtu_order(f)},
          {"reconstruction_points", f.reconstruction_points},
          {"samples", f.samples},
          {"ground_truth_points", f.ground_truth_points},
          {"ground_truth_above", f.ground_truth_above},
          {"seed", first.seed ? nlohmann::json(*first.seed) : nlohmann::json(nullptr)},
          {"accuracy", first.accuracy},
          {"completeness", first.completeness},
          {"overall", first.overall},
          {"runs", runs},
          {"spread", spread_json(f.runs, kDtuFigures)},
          {"exact_within_region", dtu_exact_json(d)},
          {"seconds", d.seconds}};
}

std::string dtu_lines(const DtuReport& d) {
  const DtuFigures& f = d.figures;
  const DtuRun& first = f.runs.front();
  std::string out = fmt::format(
      "\n  DTU protocol (DTUeval-python's eval.py): density {:.6g}, patch {:.6g}, max_dist {:.6g}; {}\n", f.options.density,
      f.options.patch, f.options.max_dist, dtu_order(f));
  out += fmt::format("  reconstruction {} points ({} sampled from faces); ground truth {} points, {} above the plane\n",
                     f.reconstruction_points, f.samples, f.ground_truth_points, f.ground_truth_above);
  const std::string first_label = first.seed ? fmt::format("seed {}", *first.seed) : std::string("own order");
  out += fmt::format("  {:<14} {:>14}", "figure", first_label);
  if (f.runs.size() > 1) out += fmt::format(" {:>30} {:>28}", fmt::format("mean +- sd over {} runs", f.runs.size()), "[min, max]");
  out += "\n";
  for (const auto& [name, figure] : kDtuFigures) {
    out += fmt::format("  {:<14} {:>14.8g}", name, first.*figure);
    if (f.runs.size() > 1) {
      const Spread s = spread_of(f.runs, figure);
      out += fmt::format(" {:>30} {:>28}", fmt::format("{:.8g} +- {:.2g}", s.mean, s.sd),
                         fmt::format("[{:.8g}, {:.8g}]", s.min, s.max));
    }
    out += "\n";
  }
  out += fmt::format(
      "  ({}: {} points after thinning, {} in the box, {} observed; below max_dist: {} of the observed, {} of the "
      "ground truth above the plane)\n",
      first_label, first.thinned, first.in_box, first.observed, first.accuracy_counted, first.completeness_counted);
  if (d.exact) {
    const ReconstructionFigures &e = *d.exact, &capped = *d.exact_below_cap;
    out += fmt::format(
        "  exact, where the protocol measures (TEST's samples observed: {} of {}; REF's above the plane: {} of {}):\n",
        d.exact_test_counted, d.exact_test_samples, d.exact_reference_counted, d.exact_reference_samples);
    out += fmt::format("  {:<14} {:>40} {:>40}\n", "figure", "every distance [95%]", "below max_dist [95%]");
    const auto cell = [](const Estimate& value) {
      return std::isnan(value.lower) ? fmt::format("{:.8g}", value.value)
                                     : fmt::format("{:.8g} [{:.6g}, {:.6g}]", value.value, value.lower, value.upper);
    };
    out += fmt::format("  {:<14} {:>40} {:>40}\n", "accuracy", cell(e.accuracy.mean), cell(capped.accuracy.mean));
    out += fmt::format("  {:<14} {:>40} {:>40}\n", "completeness", cell(e.completeness.mean),
                       cell(capped.completeness.mean));
    out += fmt::format("  {:<14} {:>40} {:>40}\n", "overall", cell(e.chamfer_mean_estimate),
                       cell(capped.chamfer_mean_estimate));
    out += fmt::format("  (below max_dist: {} of TEST's observed samples, {} of REF's above the plane)\n",
                       capped.accuracy.hits, capped.completeness.hits);
  }
  return out;
}

std::string tnt_tau_source(const TanksAndTemplesReport& t) {
  return t.scene.empty() ? std::string("as given by --tnt-tau") : fmt::format("{}'s, as the toolbox's config.py sets it", t.scene);
}

nlohmann::json matrix_json(const Eigen::Matrix4d& m) {
  nlohmann::json rows = nlohmann::json::array();
  for (int r = 0; r < 4; ++r) rows.push_back({m(r, 0), m(r, 1), m(r, 2), m(r, 3)});
  return rows;
}

constexpr std::array<std::pair<const char*, double TanksAndTemplesRegistrationRun::*>, 3> kTntFigures = {
    {{"precision", &TanksAndTemplesRegistrationRun::precision},
     {"recall", &TanksAndTemplesRegistrationRun::recall},
     {"fscore", &TanksAndTemplesRegistrationRun::fscore}}};

// run.py's registration, per run (null where the alignment was given).
nlohmann::json tnt_registration_json(const TanksAndTemplesReport& t) {
  if (t.registrations.empty()) return nullptr;
  nlohmann::json runs = nlohmann::json::array();
  for (const TanksAndTemplesRegistrationRun& run : t.registrations) {
    const TanksAndTemplesRegistration& r = run.registration;
    nlohmann::json rounds = nlohmann::json::array();
    for (const TanksAndTemplesRegistration::Round& round : r.rounds) {
      rounds.push_back({{"voxel_size", round.voxel_size > 0 ? nlohmann::json(round.voxel_size) : nlohmann::json(nullptr)},
                        {"max_distance", round.max_distance},
                        {"source_points", round.source_points},
                        {"target_points", round.target_points},
                        {"fitness", round.icp.fitness},
                        {"inlier_rmse", round.icp.inlier_rmse},
                        {"iterations", round.icp.iterations},
                        {"transformation", matrix_json(round.transformation)}});
    }
    runs.push_back({{"seed", r.seed},
                    {"cameras", {{"fitness", r.trajectory.fitness},
                                 {"inlier_rmse", r.trajectory.inlier_rmse},
                                 {"transformation", matrix_json(r.trajectory.transformation)}}},
                    {"rounds", rounds},
                    {"transformation", matrix_json(r.transformation)},
                    {"precision", run.precision},
                    {"recall", run.recall},
                    {"fscore", run.fscore}});
  }
  return {{"definition",
           "run.py's registration before EvaluateHisto: the reconstruction's camera centres (those the mapping "
           "names where there are more than 1,600) aligned to the scene's (COLMAP's, moved by alignment_file) by "
           "RANSAC (6 pairs a draw, pairs closer than 0.2, confidence 0.999, draws from the seed), then ICP "
           "point to point with scale in three rounds on both clouds cropped: voxels of tau and pairs within 80 "
           "tau, voxels of tau / 2 and 20 tau, uniform (every k-th point above 4 M) and 2 tau, each round stopping "
           "once its fitness changes by less than 1e-6 (ICPConvergenceCriteria(1e-6, 20): the RMSE's criterion "
           "is 20) or after 30 updates. Each run's transformation is the product of the rounds' and RANSAC's; "
           "the first run's is 'alignment' and gives the figures above; spread: over the runs' seeds"},
          {"trajectory", t.trajectory},
          {"reference_trajectory", t.reference_trajectory},
          {"mapping", t.mapping.empty() ? nlohmann::json(nullptr) : nlohmann::json(t.mapping)},
          {"cameras", t.registrations.front().registration.cameras},
          {"runs", runs},
          {"spread", spread_json(t.registrations, kTntFigures)},
          {"seconds", t.registration_seconds}};
}

nlohmann::json tnt_json(const TanksAndTemplesReport& t) {
  const TanksAndTemplesFigures& f = t.figures;
  nlohmann::json exact = nullptr;
  if (t.exact) {
    exact = {{"definition",
              "The exact figures (as under 'reconstruction', the first threshold tau) over the part of each surface "
              "inside the crop volume: precision's side (accuracy) over TEST's aligned samples inside it, recall's "
              "(completeness) over REF's, each measured against the whole other surface, neither thinned"},
             {"test_samples_counted", t.exact_test_counted},
             {"test_samples", t.exact_test_samples},
             {"reference_samples_counted", t.exact_reference_counted},
             {"reference_samples", t.exact_reference_samples},
             {"figures", reconstruction_json(*t.exact)}};
  }
  return {{"definition",
           "Tanks and Temples evaluation as its toolbox's EvaluateHisto computes it: TEST (its points, or a mesh's "
           "vertices) moved by the alignment, both clouds cropped to the crop volume and voxel down-sampled at "
           "voxel_size (each occupied cube's mean point); precision = share of TEST's points whose nearest REF "
           "point is closer than tau, recall = share of REF's points closer than tau to TEST's nearest, fscore = "
           "2 precision recall / (precision + recall); cumulative_precision[i] and cumulative_recall[i] = share of "
           "the distances below edges[i + 1] (at or below, for the last), edges = np.arange(0, tau * plot_stretch, "
           "tau / 100). See docs/reconstruction.md"},
          {"computed_as",
           t.registrations.empty()
               ? "TanksAndTemples python_toolbox/evaluation (github.com/isl-org/TanksAndTemples, 3c2c212), "
                 "EvaluateHisto step by step on Open3D 0.16's operations; run.py's registration (RANSAC and ICP) not "
                 "run: the alignment is the one given"
               : "TanksAndTemples python_toolbox/evaluation (github.com/isl-org/TanksAndTemples, 3c2c212), run.py "
                 "step by step on Open3D 0.16's operations: its registration (RANSAC from the seed, as Open3D on "
                 "one thread after utility.random.seed) and EvaluateHisto"},
          {"scene", t.scene.empty() ? nlohmann::json(nullptr) : nlohmann::json(t.scene)},
          {"tau", f.options.tau},
          {"tau_source", tnt_tau_source(t)},
          {"voxel_size", f.options.voxel_size},
          {"plot_stretch", f.options.plot_stretch},
          {"crop", t.crop},
          {"alignment_file", t.alignment.empty() ? nlohmann::json(nullptr) : nlohmann::json(t.alignment)},
          {"alignment", matrix_json(t.alignment_matrix)},
          {"registration", tnt_registration_json(t)},
          {"reconstruction_points", f.reconstruction_points},
          {"reconstruction_cropped", f.reconstruction_cropped},
          {"reconstruction_thinned", f.reconstruction_thinned},
          {"ground_truth_points", f.ground_truth_points},
          {"ground_truth_cropped", f.ground_truth_cropped},
          {"ground_truth_thinned", f.ground_truth_thinned},
          {"precision_counted", f.precision_counted},
          {"recall_counted", f.recall_counted},
          {"precision", f.precision},
          {"recall", f.recall},
          {"fscore", f.fscore},
          {"edges", f.edges},
          {"cumulative_precision", f.cumulative_precision},
          {"cumulative_recall", f.cumulative_recall},
          {"curves_png", t.curves_png.empty() ? nlohmann::json(nullptr) : nlohmann::json(t.curves_png)},
          {"plys", t.plys.empty() ? nlohmann::json(nullptr)
                                  : nlohmann::json({t.plys + ".precision.ply", t.plys + ".recall.ply"})},
          {"exact_within_crop", exact},
          {"seconds", t.seconds}};
}

std::string tnt_lines(const TanksAndTemplesReport& t) {
  const TanksAndTemplesFigures& f = t.figures;
  std::string out = fmt::format(
      "\n  Tanks and Temples protocol (the toolbox's EvaluateHisto): tau {:.6g} ({}), voxel size {:.6g}, crop {}, "
      "alignment {}\n",
      f.options.tau, tnt_tau_source(t), f.options.voxel_size, t.crop,
      t.registrations.empty() ? (t.alignment.empty() ? "none" : t.alignment)
                              : fmt::format("run.py's registration from {}", t.alignment));
  if (!t.registrations.empty()) {
    const TanksAndTemplesRegistration& r = t.registrations.front().registration;
    out += fmt::format("  registration ({:.3g} s): RANSAC on {} cameras of {} (seed {}): fitness {:.6g}, RMSE {:.6g}\n",
                       t.registration_seconds, r.cameras, t.trajectory, r.seed, r.trajectory.fitness,
                       r.trajectory.inlier_rmse);
    for (std::size_t k = 0; k < r.rounds.size(); ++k) {
      const TanksAndTemplesRegistration::Round& round = r.rounds[k];
      out += fmt::format("    ICP round {} ({}, pairs within {:.6g}): {} TEST and {} REF points, fitness {:.6g}, "
                         "RMSE {:.6g} after {} update{}\n",
                         k + 1, round.voxel_size > 0 ? fmt::format("voxels of {:.6g}", round.voxel_size) : "uniform",
                         round.max_distance, round.source_points, round.target_points, round.icp.fitness,
                         round.icp.inlier_rmse, round.icp.iterations, round.icp.iterations == 1 ? "" : "s");
    }
  }
  out += fmt::format("  reconstruction {} points, {} in the crop, {} after down-sampling; ground truth {}, {}, {}\n",
                     f.reconstruction_points, f.reconstruction_cropped, f.reconstruction_thinned, f.ground_truth_points,
                     f.ground_truth_cropped, f.ground_truth_thinned);
  out += fmt::format("  {:<14} {:>14} {:>28}\n", "figure", "protocol", "points below tau");
  out += fmt::format("  {:<14} {:>14.8g} {:>28}\n", "precision", f.precision,
                     fmt::format("{} of {}", f.precision_counted, f.reconstruction_thinned));
  out += fmt::format("  {:<14} {:>14.8g} {:>28}\n", "recall", f.recall,
                     fmt::format("{} of {}", f.recall_counted, f.ground_truth_thinned));
  out += fmt::format("  {:<14} {:>14.8g}\n", "F-score", f.fscore);
  if (t.registrations.size() > 1) {
    out += fmt::format("  {:<14} {:>47} {:>28}\n",
                       fmt::format("seeds {} to {}", t.registrations.front().registration.seed,
                                   t.registrations.back().registration.seed),
                       fmt::format("mean +- sd over {} registrations", t.registrations.size()), "[min, max]");
    for (const auto& [name, figure] : kTntFigures) {
      const Spread s = spread_of(t.registrations, figure);
      out += fmt::format("  {:<14} {:>47} {:>28}\n", std::string(name) == "fscore" ? "F-score" : name,
                         fmt::format("{:.8g} +- {:.2g}", s.mean, s.sd), fmt::format("[{:.8g}, {:.8g}]", s.min, s.max));
    }
  }
  if (!t.curves_png.empty()) out += fmt::format("  curves: {}\n", t.curves_png);
  if (!t.plys.empty()) {
    out += fmt::format("  coloured by distance (hot_r up to 3 tau): {0}.precision.ply, {0}.recall.ply\n", t.plys);
  }
  if (t.exact) {
    const ReconstructionFigures& e = *t.exact;
    out += fmt::format("  exact, within the crop (TEST's samples: {} of {}; REF's: {} of {}), at tau [95%]:\n",
                       t.exact_test_counted, t.exact_test_samples, t.exact_reference_counted, t.exact_reference_samples);
    const auto cell = [](const Estimate& value) {
      return std::isnan(value.lower) ? fmt::format("{:.8g}", value.value)
                                     : fmt::format("{:.8g} [{:.6g}, {:.6g}]", value.value, value.lower, value.upper);
    };
    out += fmt::format("  {:<14} {:>40}\n", "precision", cell(e.accuracy.within.front()));
    out += fmt::format("  {:<14} {:>40}\n", "recall", cell(e.completeness.within.front()));
    out += fmt::format("  {:<14} {:>40}\n", "F-score", cell(e.f_score_estimate.front()));
  }
  return out;
}

// The models load at once (measure_run), so loading takes the longer of the two times.
double loading_seconds(const MeasureReport& r) { return std::max(r.load_seconds[0], r.load_seconds[1]); }

}  // namespace

std::string format_body(const MeasureReport& r) {
  if (r.protocol_only) {
    std::string out = r.dtu ? dtu_lines(*r.dtu) : tnt_lines(*r.tnt);
    out += fmt::format("  time: load {:.3f} s, protocol {:.3f} s, total {:.3f} s\n", loading_seconds(r),
                       r.dtu ? r.dtu->seconds : r.tnt->seconds, r.total_seconds);
    for (const std::string& line : r.warnings) out += fmt::format("  warning: {}\n", line);
    return out;
  }
  if (r.pcc_only) {
    std::string out = mpeg_lines(*r.mpeg);
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
  if (r.reconstruction) out += reconstruction_lines(*r.reconstruction, r.diagonal);
  if (r.mpeg) out += mpeg_lines(*r.mpeg);
  if (r.dtu) out += dtu_lines(*r.dtu);
  if (r.tnt) out += tnt_lines(*r.tnt);
  if (r.image_based) out += image_based_lines(*r.image_based);
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
    if (r.dtu) json["dtu_protocol"] = dtu_json(*r.dtu);
    if (r.tnt) json["tanks_and_temples_protocol"] = tnt_json(*r.tnt);
    json["seconds"] = {
        {"load_reference", r.load_seconds[0]}, {"load_test", r.load_seconds[1]}, {"total", r.total_seconds}};
    return json;
  }
  if (r.pcc_only) {
    json["method"] = "pcc";
    json["warnings"] = r.warnings;
    json["mpeg_pcc"] = mpeg_json(*r.mpeg);
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
    if (r.reconstruction) json["reconstruction"] = reconstruction_json(*r.reconstruction);
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
  if (r.mpeg) json["mpeg_pcc"] = mpeg_json(*r.mpeg);
  if (r.dtu) json["dtu_protocol"] = dtu_json(*r.dtu);
  if (r.tnt) json["tanks_and_temples_protocol"] = tnt_json(*r.tnt);
  if (r.image_based) {
    const ImageBasedResult& ib = *r.image_based;
    json["image_based"] = {{"definition", "MPEG IBSM (mmetric 1.1.7 compare --mode ibsm)"},
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
      json["image_based"]["colour"] = {{"psnr_rgb", ib.psnr_rgb},
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
  }
  json["seconds"]["load_reference"] = r.load_seconds[0];
  json["seconds"]["load_test"] = r.load_seconds[1];
  json["seconds"]["total"] = r.total_seconds;
  return json;
}

}  // namespace roving
