// Formatting of the `roving measure` report.
#include "report.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>

namespace roving {
namespace {

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
  }
  return json;
}

std::size_t count(const GlReport& gl, Resolution how) {
  return static_cast<std::size_t>(std::count(gl.resolved_by.begin(), gl.resolved_by.end(), how));
}

std::string model_line(const char* role, const Model& model) {
  const LoadedMesh& loaded = model.mesh;
  const TriangleMesh& m = loaded.mesh;
  if (model.type == ModelType::Points) {
    return fmt::format("{:<10} {}: point cloud, {} points, normals {}\n", role, loaded.path,
                       model.points.positions.size(),
                       model.normals_estimated ? "estimated (PCA, k = 12)" : "from the file");
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
  return line + "\n";
}

}  // namespace

std::string format_text(const MeasureReport& r) {
  const Statistics& s = r.statistics;
  const double diagonal = r.reference->bounding_box().diagonal();
  std::string out;
  out += model_line("reference", *r.reference);
  out += model_line("test", *r.test);
  out += fmt::format("{:<10} bounding-box diagonal {:.6g} (reference)\n", "", diagonal);
  out += fmt::format("{:<10} {}: {}", "samples", r.samples->kind, r.samples->size());
  if (r.samples->skipped_degenerate_faces)
    out += fmt::format(", {} zero-area faces skipped", r.samples->skipped_degenerate_faces);
  if (r.samples->skipped_unreferenced_vertices)
    out += fmt::format(", {} unreferenced vertices skipped", r.samples->skipped_unreferenced_vertices);
  if (r.samples->skipped_zero_normal_vertices)
    out += fmt::format(", {} vertices without a normal skipped", r.samples->skipped_zero_normal_vertices);
  out += "\n";
  out += fmt::format("{:<10} {}, semantics {}, max error h = {:.6g} ({})\n\n", "method", r.method,
                     to_string(r.semantics), r.max_error, r.max_error_text);

  out += fmt::format("  {:<28} {:>14} {:>14}\n", "statistic", "model units", "/ diagonal");
  const auto row = [&](const std::string& name, double value) {
    out += fmt::format("  {:<28} {:>14.6g} {:>14.6g}\n", name, value, value / diagonal);
  };
  row("SiAD (mean signed d)", s.siad);
  row("USiAD (mean |d|)", s.usiad);
  row("STD (of signed d)", s.std_signed);
  row("STD of |d|", s.std_unsigned);
  row("RMS", s.rms);
  row("max |d|", s.max_abs);
  row("|d| 50th percentile", s.p50);
  row("|d| 90th percentile", s.p90);
  row("|d| 95th percentile", s.p95);
  row("|d| 99th percentile", s.p99);
  row("SiAD, area-weighted", s.siad_area);
  row("USiAD, area-weighted", s.usiad_area);
  row("RMS, area-weighted", s.rms_area);
  row("SiAD, hits only", s.siad_hits);
  row("USiAD, hits only", s.usiad_hits);
  out += fmt::format("\n  no hit within h: {} of {} samples ({:.4g}%), counted as d = +h\n", s.no_hit_count,
                     s.sample_count, 100 * s.no_hit_fraction);
  if (r.gl) {
    const GlReport& g = *r.gl;
    out += fmt::format("  GL: {}\n", g.renderer);
    out += fmt::format(
        "  observations: {} ({} views of {} at {} px + {} per-sample cameras); resolved by views {}, by "
        "cameras {}, unresolved {}\n",
        g.observations(), g.views_rendered,
        g.axis_views ? "the 6 axes" : fmt::format("{}x{}", g.views_h, g.views_v), g.resolution,
        g.sample_cameras, count(g, Resolution::View), count(g, Resolution::Camera),
        count(g, Resolution::Unresolved));
    // Only what was rendered: views, cameras, or both.
    std::vector<std::string> precision;
    if (g.views_rendered) {
      precision.push_back(
          fmt::format("view pixel {:.4g}, view depth step {:.3g}", g.view_pixel_size, g.view_depth_step));
    }
    if (g.sample_cameras) {
      precision.push_back(fmt::format("camera half-width {:.3g}, camera depth step {:.3g}",
                                      g.camera_half_width, g.camera_depth_step));
    }
    if (!precision.empty()) out += fmt::format("  precision (model units): {}\n", fmt::join(precision, "; "));
  }
  out += fmt::format(
      "  time: load {:.3f} s (reference {:.3f}, test {:.3f}), build {:.3f} s, "
      "query {:.3f} s ({:.3g} samples/s), total {:.3f} s\n",
      r.load_reference_seconds + r.load_test_seconds, r.load_reference_seconds, r.load_test_seconds,
      r.build_seconds, r.query_seconds, r.query_seconds > 0 ? s.sample_count / r.query_seconds : 0.0,
      r.total_seconds);
  return out;
}

nlohmann::json to_json(const MeasureReport& r) {
  const Statistics& s = r.statistics;
  const double diagonal = r.reference->bounding_box().diagonal();
  nlohmann::json stats = {{"siad", s.siad},
                          {"usiad", s.usiad},
                          {"std_signed", s.std_signed},
                          {"std_unsigned", s.std_unsigned},
                          {"rms", s.rms},
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
  nlohmann::json relative;
  for (const auto& [key, value] : stats.items()) relative[key] = value.get<double>() / diagonal;
  nlohmann::json json = {
      {"reference", model_json(*r.reference)},
      {"test", model_json(*r.test)},
      {"samples",
       {{"kind", r.samples->kind},
        {"count", r.samples->size()},
        {"skipped_degenerate_faces", r.samples->skipped_degenerate_faces},
        {"skipped_unreferenced_vertices", r.samples->skipped_unreferenced_vertices},
        {"skipped_zero_normal_vertices", r.samples->skipped_zero_normal_vertices}}},
      {"method", r.method},
      {"semantics", to_string(r.semantics)},
      {"max_error",
       {{"value", r.max_error}, {"given_as", r.max_error_text}, {"relative", r.max_error / diagonal}}},
      {"diagonal", diagonal},
      {"statistics", stats},
      {"statistics_relative_to_diagonal", relative},
      {"hits", s.hit_count},
      {"no_hits", s.no_hit_count},
      {"no_hit_fraction", s.no_hit_fraction},
      {"no_hit_rule", "counted as d = +max_error"},
      {"histogram",
       {{"low", s.histogram.low},
        {"high", s.histogram.high},
        {"counts", s.histogram.counts},
        {"below", s.histogram.below},
        {"above", s.histogram.above}}},
      {"seconds",
       {{"load_reference", r.load_reference_seconds},
        {"load_test", r.load_test_seconds},
        {"build", r.build_seconds},
        {"query", r.query_seconds},
        {"total", r.total_seconds}}},
  };
  if (r.gl) {
    const GlReport& g = *r.gl;
    json["gl"] = {{"renderer", g.renderer},
                  {"observations", g.observations()},
                  {"views_rendered", g.views_rendered},
                  {"sample_cameras", g.sample_cameras},
                  {"views", g.axis_views ? "6 axes" : fmt::format("{}x{}", g.views_h, g.views_v)},
                  {"resolution", g.resolution},
                  {"resolved_by_view", count(g, Resolution::View)},
                  {"resolved_by_camera", count(g, Resolution::Camera)},
                  {"unresolved", count(g, Resolution::Unresolved)},
                  {"view_pixel_size", g.view_pixel_size},
                  {"view_depth_step", g.view_depth_step},
                  {"camera_half_width", g.camera_half_width},
                  {"camera_depth_step", g.camera_depth_step}};
  }
  return json;
}

}  // namespace roving
