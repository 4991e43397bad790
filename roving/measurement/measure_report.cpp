// The `roving measure` report as JSON (measure_report.h; layout in docs/report-json.md).
#include "measure_report.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "figure_families.h"
#include "roving/core/error.h"

namespace roving {

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
namespace {

nlohmann::json relative_json(const nlohmann::json& absolute, double diagonal) {
  nlohmann::json relative;
  for (const auto& [key, value] : absolute.items()) relative[key] = value.get<double>() / diagonal;
  return relative;
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
          {"camera_geometry", to_string(g.camera_geometry)},
          {"view_culling", g.views_culled ? "footprint" : "none"},
          {"thin_cameras", g.thin_cameras},
          {"faces_chosen_in_pass", g.faces_chosen_in_pass},
          {"faces_left_to_cpu", g.faces_left_to_cpu},
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
  g.camera_geometry = parse_camera_geometry(json.at("camera_geometry").get<std::string>());
  g.thin_cameras = json.value("thin_cameras", std::size_t(0));  // absent before the compute path
  g.faces_chosen_in_pass = json.value("faces_chosen_in_pass", std::size_t(0));  // absent before the faces' choice
  g.faces_left_to_cpu = json.value("faces_left_to_cpu", std::size_t(0));
  g.views_culled = json.value("view_culling", std::string("footprint")) != "none";  // absent before the option
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
