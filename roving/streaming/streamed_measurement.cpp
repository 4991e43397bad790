// A reference measured a block of faces at a time (streamed_measurement.h).
#include "streamed_measurement.h"

#include <fmt/format.h>

#include <cmath>

#include "roving/core/error.h"
#include "roving/core/stopwatch.h"
#include "roving/formats/heatmap.h"

namespace roving {
namespace {

// The block's triangles as a mesh of their own, three corners each, so that its centroids, normals
// and areas are computed from the same coordinates as the whole mesh's.
TriangleMesh block_mesh(const TriangleStream& stream, const std::vector<Triangle>& triangles) {
  std::vector<Vec3> corners;
  corners.reserve(3 * triangles.size());
  std::vector<Triangle> faces(triangles.size());
  for (std::size_t f = 0; f < triangles.size(); ++f) {
    for (int c = 0; c < 3; ++c) corners.push_back(stream.position(triangles[f][c]));
    const int first = static_cast<int>(3 * f);
    faces[f] = {first, first + 1, first + 2};
  }
  return TriangleMesh(std::move(corners), std::move(faces), stream.path());
}

}  // namespace

StreamedReference summarise(TriangleStream& stream, std::size_t chunk_faces) {
  TriangleMesh::Summary summary;
  summary.vertices = stream.vertex_count();
  std::vector<bool> referenced(stream.vertex_count(), false);
  std::vector<Triangle> triangles;
  double block_area = 0;  // TriangleMesh's current block of kAreaBlock faces
  stream.rewind();
  while (stream.next(chunk_faces, triangles)) {
    for (const Triangle& t : triangles) {
      for (const int corner : t) referenced[corner] = true;
    }
    const TriangleMesh block = block_mesh(stream, triangles);
    summary.degenerate_triangles += block.degenerate_triangle_count();
    for (std::size_t f = 0; f < block.triangle_count(); ++f) {
      block_area += block.face_area(f);
      if (++summary.triangles % TriangleMesh::kAreaBlock == 0) {
        summary.area += block_area;
        block_area = 0;
      }
    }
  }
  if (summary.triangles % TriangleMesh::kAreaBlock != 0) summary.area += block_area;
  for (std::size_t v = 0; v < referenced.size(); ++v) {
    if (referenced[v]) {
      summary.box.extend(stream.position(static_cast<int>(v)));
    } else {
      ++summary.unreferenced_vertices;
    }
  }
  return {TriangleMesh(summary), stream.dropped_repeated_vertex_faces()};
}

StreamedResult measure_streamed(TriangleStream& stream, DistanceMethod& method, const DistanceOptions& options,
                                std::size_t histogram_bins, std::size_t chunk_faces, std::size_t expected_samples,
                                const ProgressFn& progress) {
  StreamedResult result;
  result.samples.kind = SampleSpec().to_string();
  StatisticsAccumulator statistics(options.max_error, histogram_bins, expected_samples);
  std::vector<float> hit_magnitudes;  // 4 bytes a hit, for the heat-map range alone
  hit_magnitudes.reserve(expected_samples);
  std::size_t done = 0;
  method.set_progress([&](const char* stage, std::size_t block_done, std::size_t) {
    if (progress) progress(stage, done + block_done, expected_samples);
  });
  std::vector<Triangle> triangles;
  stream.rewind();
  while (stream.next(chunk_faces, triangles)) {
    ++result.chunks;
    if (triangles.empty()) continue;
    const TriangleMesh block = block_mesh(stream, triangles);
    if (block.degenerate_triangle_count() == block.triangle_count()) {
      result.samples.skipped_degenerate_faces += block.triangle_count();
      continue;
    }
    const SampleSet samples = make_samples(block, SampleSpec());
    result.samples.skipped_degenerate_faces += samples.skipped_degenerate_faces;
    const DistanceResult measured = method.measure(samples, options);
    result.query_seconds += measured.query_seconds;
    for (std::size_t k = 0; k < samples.size(); ++k) {
      const double d = measured.signed_distance[k];
      statistics.add(d, measured.hit[k], samples.weights[k]);
      if (!measured.hit[k]) continue;
      ++(d > 0 ? result.signs.positive : d < 0 ? result.signs.negative : result.signs.zero);
      hit_magnitudes.push_back(static_cast<float>(std::abs(d)));
    }
    done += samples.size();
  }
  method.set_progress({});
  if (statistics.count() == 0) {
    throw Error(fmt::format("reference model gives no 'faces' samples ({} triangles, all degenerate?)",
                            result.samples.skipped_degenerate_faces));
  }
  result.statistics = statistics.finish();
  result.heatmap_range = percentile_99(std::move(hit_magnitudes), options.max_error);
  return result;
}

}  // namespace roving
