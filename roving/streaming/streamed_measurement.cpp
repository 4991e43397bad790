// A reference measured a block of faces at a time (streamed_measurement.h).
#include "streamed_measurement.h"

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <sys/mman.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>

#include "roving/core/error.h"
#include "roving/formats/outputs/heatmap.h"

namespace roving {
namespace {

// Each triangle's shape, on all cores, by TriangleMesh's own arithmetic.
std::vector<TriangleMesh::FaceShape> shapes_of(const TriangleStream& stream, const std::vector<Triangle>& triangles) {
  std::vector<TriangleMesh::FaceShape> shapes(triangles.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, triangles.size(), 4096),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t f = range.begin(); f != range.end(); ++f) {
                        const Triangle& t = triangles[f];
                        shapes[f] = TriangleMesh::shape_of(stream.position(t[0]), stream.position(t[1]),
                                                           stream.position(t[2]));
                      }
                    });
  return shapes;
}

// The block's face samples as make_samples makes them of the whole mesh (sample_set.cpp): a
// sample per face that is not degenerate, at its centroid, with its normal and area, in order.
SampleSet face_samples(const TriangleStream& stream, const std::vector<Triangle>& triangles) {
  const std::vector<TriangleMesh::FaceShape> shapes = shapes_of(stream, triangles);
  std::vector<std::size_t> kept;
  kept.reserve(triangles.size());
  for (std::size_t f = 0; f < triangles.size(); ++f) {
    if (!shapes[f].degenerate) kept.push_back(f);
  }
  SampleSet samples;
  samples.skipped_degenerate_faces = triangles.size() - kept.size();
  samples.positions.resize(kept.size());
  samples.normals.resize(kept.size());
  samples.weights.resize(kept.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, kept.size(), 4096),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t k = range.begin(); k != range.end(); ++k) {
                        const Triangle& t = triangles[kept[k]];
                        samples.positions[k] = TriangleMesh::centroid_of(
                            stream.position(t[0]), stream.position(t[1]), stream.position(t[2]));
                        samples.normals[k] = shapes[kept[k]].normal();
                        samples.weights[k] = shapes[kept[k]].area();
                      }
                    });
  return samples;
}

// The block's degenerate faces (which give no face sample), by TriangleMesh's own arithmetic.
std::size_t degenerate_count(const TriangleStream& stream, const std::vector<Triangle>& triangles) {
  const std::vector<TriangleMesh::FaceShape> shapes = shapes_of(stream, triangles);
  return std::size_t(std::count_if(shapes.begin(), shapes.end(), [](const auto& s) { return s.degenerate; }));
}

// A measured block's samples folded into the figures, in order, as one call for them all would.
void fold(const SampleSet& samples, const DistanceResult& measured, StatisticsAccumulator& statistics,
          StreamedResult& result) {
  result.query_seconds += measured.query_seconds;
  if (measured.gl) {
    if (!result.gl) result.gl.emplace();
    result.gl->add_block(*measured.gl);
  }
  for (std::size_t k = 0; k < samples.size(); ++k) {
    const double d = measured.signed_distance[k];
    statistics.add(d, measured.hit[k], samples.weights[k]);
    if (!measured.hit[k]) continue;
    ++(d > 0 ? result.signs.positive : d < 0 ? result.signs.negative : result.signs.zero);
  }
}

// Each vertex's sums over the faces that use it, in the file's order, and whether any does.
// Arrays left uninitialised by their allocation: each part of vertex_sums zeroes its own range,
// so that the pages are first written (and faulted in, at 10^8 faces 1.6 GiB of them: seconds on
// one core) by both cores at once.
struct VertexSums {
  explicit VertexSums(std::size_t n) : normals(new Vec3[n]), third_areas(new double[n]), referenced(new std::uint8_t[n]) {}
  std::unique_ptr<Vec3[]> normals;  // summed cross products, made unit as each sample is made
  std::unique_ptr<double[]> third_areas;
  std::unique_ptr<std::uint8_t[]> referenced;

  // Vertices [first, last) are no longer needed: their whole pages go back to the system, so
  // that the sums shrink as the vertices' distances (the statistics) grow.
  void release(std::size_t first, std::size_t last) {
    release_pages(normals.get() + first, normals.get() + last);
    release_pages(third_areas.get() + first, third_areas.get() + last);
    release_pages(referenced.get() + first, referenced.get() + last);
  }

 private:
  static void release_pages(const void* from, const void* to) {
    const auto page = static_cast<std::uintptr_t>(sysconf(_SC_PAGESIZE));
    const std::uintptr_t low = (reinterpret_cast<std::uintptr_t>(from) + page - 1) / page * page;
    const std::uintptr_t high = reinterpret_cast<std::uintptr_t>(to) / page * page;
    if (low < high) madvise(reinterpret_cast<void*>(low), high - low, MADV_DONTNEED);
  }
};

VertexSums vertex_sums(TriangleStream& stream, std::size_t chunk_faces, const ProgressFn& progress) {
  const std::size_t n = stream.position_count();
  VertexSums sums(n);
  // As vertex_normals: each thread owns a range of vertices and scans the block's faces for its
  // corners, so that each vertex adds its faces in the file's order on any number of threads.
  const std::size_t parts = std::size_t(std::max(1, tbb::this_task_arena::max_concurrency()));
  const std::size_t per_part = (n + parts - 1) / parts;
  tbb::parallel_for(std::size_t{0}, parts, [&](std::size_t part) {
    const std::size_t low = std::min(n, part * per_part), high = std::min(n, (part + 1) * per_part);
    std::fill(sums.normals.get() + low, sums.normals.get() + high, Vec3::Zero());
    std::fill(sums.third_areas.get() + low, sums.third_areas.get() + high, 0.0);
    std::fill(sums.referenced.get() + low, sums.referenced.get() + high, std::uint8_t{0});
  });
  std::vector<Triangle> triangles;
  stream.rewind();
  for (std::size_t read = 0; stream.next(chunk_faces, triangles);) {
    read = std::min(read + chunk_faces, stream.face_count());
    if (progress) progress("faces", read, stream.face_count());
    tbb::parallel_for(std::size_t{0}, parts, [&](std::size_t part) {
      const auto low = static_cast<int>(part * per_part);
      const auto high = static_cast<int>(std::min(n, (part + 1) * per_part));
      for (const Triangle& t : triangles) {
        const auto mine = [&](int corner) { return corner >= low && corner < high; };
        if (!mine(t[0]) && !mine(t[1]) && !mine(t[2])) continue;
        const Vec3 p0 = stream.position(t[0]);
        const Vec3 cross = (stream.position(t[1]) - p0).cross(stream.position(t[2]) - p0);
        const double third_area = 0.5 * cross.norm() / 3.0;
        for (int corner : t) {
          if (!mine(corner)) continue;
          sums.normals[corner] += cross;
          sums.third_areas[corner] += third_area;
          sums.referenced[corner] = 1;
        }
      }
    });
  }
  return sums;
}

}  // namespace

StreamedReference summarise(TriangleStream& stream, std::size_t chunk_faces, const ProgressFn& progress) {
  TriangleMesh::Summary summary;
  std::vector<Triangle> triangles;
  double block_area = 0;  // TriangleMesh's current block of kAreaBlock faces
  stream.rewind();
  for (std::size_t read = 0; stream.next(chunk_faces, triangles);) {
    read = std::min(read + chunk_faces, stream.face_count());
    if (progress) progress("faces", read, stream.face_count());
    for (const TriangleMesh::FaceShape& shape : shapes_of(stream, triangles)) {
      summary.degenerate_triangles += shape.degenerate;
      block_area += shape.area();
      if (++summary.triangles % TriangleMesh::kAreaBlock == 0) {
        summary.area += block_area;
        block_area = 0;
      }
    }
  }
  if (summary.triangles % TriangleMesh::kAreaBlock != 0) summary.area += block_area;
  const VertexCensus vertices = stream.census();
  summary.vertices = vertices.vertices;
  summary.unreferenced_vertices = vertices.unreferenced;
  summary.box = vertices.box;
  return {TriangleMesh(summary), stream.dropped_repeated_vertex_faces(), stream.triangulated_polygons()};
}

StreamedResult measure_streamed(TriangleStream& stream, DistanceMethod& method, const DistanceOptions& options,
                                std::size_t histogram_bins, std::size_t chunk_faces, std::size_t expected_samples,
                                const ProgressFn& progress, const std::optional<SampleRange>& slice) {
  const std::size_t run = method.independent_run();
  if (run == 0) throw Error(method.name() + ": answers every sample from them all; REF cannot be streamed");
  StreamedResult result;
  result.samples.kind = SampleSpec().to_string();
  StatisticsAccumulator statistics(options.max_error, histogram_bins, expected_samples);
  std::size_t done = 0;
  method.set_progress([&](const char* stage, std::size_t block_done, std::size_t) {
    if (progress) progress(stage, done + block_done, expected_samples);
  });
  // The method is given whole runs of samples (independent_run), the rest carried into the next
  // block's: each sample is answered where one call for them all puts it.
  SampleSet pending;
  const auto measure = [&](SampleSet& samples) {
    samples.kind = result.samples.kind;
    const DistanceResult measured = method.measure(samples, options);
    fold(samples, measured, statistics, result);
    done += samples.size();
    if (slice) {
      std::vector<double>& weights = result.samples.weights;
      weights.insert(weights.end(), samples.weights.begin(), samples.weights.end());
      result.slice.signed_distance.insert(result.slice.signed_distance.end(), measured.signed_distance.begin(),
                                          measured.signed_distance.end());
      result.slice.hit.insert(result.slice.hit.end(), measured.hit.begin(), measured.hit.end());
    }
  };
  const std::size_t first = slice ? slice->first : 0, last = slice ? slice->last : SIZE_MAX;
  if (slice) {
    result.samples.weights.reserve(last - first);
    result.slice.signed_distance.reserve(last - first);
    result.slice.hit.reserve(last - first);
  }
  std::vector<Triangle> triangles;
  stream.rewind();
  for (std::size_t made = 0; made < last && stream.next(chunk_faces, triangles);) {  // REF's samples made so far
    ++result.chunks;
    if (made + triangles.size() <= first) {  // wholly before the slice: its samples counted, not made
      const std::size_t degenerate = degenerate_count(stream, triangles);
      result.samples.skipped_degenerate_faces += degenerate;
      made += triangles.size() - degenerate;
      continue;
    }
    const std::size_t before = made;
    SampleSet samples = face_samples(stream, triangles);
    result.samples.skipped_degenerate_faces += samples.skipped_degenerate_faces;
    made += samples.size();
    if (before < first || made > last) {
      samples = samples.slice(std::max(before, first) - before, std::min(made, last) - before);
    }
    pending.append(std::move(samples));
    const std::size_t ready = pending.size() / run * run;
    if (ready == 0) continue;
    SampleSet rest = pending.split_off(ready);
    measure(pending);
    pending = std::move(rest);
  }
  if (pending.size() > 0) measure(pending);
  method.set_progress({});
  if (statistics.count() == 0) {
    throw Error(fmt::format("reference model gives no 'faces' samples ({} triangles, all degenerate?)",
                            result.samples.skipped_degenerate_faces));
  }
  result.statistics = statistics.finish();
  result.heatmap_range = default_heatmap_range(statistics, result.statistics.hit_count, options.max_error);
  return result;
}

StreamedResult measure_streamed_vertices(TriangleStream& stream, DistanceMethod& method,
                                         const DistanceOptions& options, std::size_t histogram_bins,
                                         std::size_t chunk_faces, std::size_t expected_samples,
                                         const ProgressFn& progress) {
  const std::size_t run = method.independent_run();
  if (run == 0) throw Error(method.name() + ": answers every sample from them all; REF cannot be streamed");
  VertexSums sums = vertex_sums(stream, chunk_faces, progress);
  StreamedResult result;
  result.samples.kind = SampleSpec{SampleSpec::Kind::Vertices}.to_string();
  StatisticsAccumulator statistics(options.max_error, histogram_bins, expected_samples);
  std::size_t done = 0;
  method.set_progress([&](const char* stage, std::size_t block_done, std::size_t) {
    if (progress) progress(stage, done + block_done, expected_samples);
  });
  SampleSet pending;
  const auto measure = [&](SampleSet& samples) {
    samples.kind = result.samples.kind;
    fold(samples, method.measure(samples, options), statistics, result);
    done += samples.size();
  };
  // sample_vertices' choice (sample_set.cpp), a block of vertices at a time.
  const std::size_t n = stream.position_count();
  for (std::size_t first = 0; first < n; first += chunk_faces) {
    ++result.chunks;
    const std::size_t last = std::min(n, first + chunk_faces);
    SampleSet samples;  // room for the block at once: growing by doubling wrote each array twice over
    samples.positions.reserve(last - first);
    samples.normals.reserve(last - first);
    samples.weights.reserve(last - first);
    for (std::size_t v = first; v < last; ++v) {
      // The normal made unit as TriangleMesh::vertex_normals makes it (zero where its length is
      // not > 0), here rather than in a pass of its own over the sums; a zero one skipped as
      // sample_vertices skips it.
      const double length = sums.normals[v].norm();
      const Vec3 normal = length > 0 ? Vec3(sums.normals[v] / length) : Vec3::Zero();
      if (!sums.referenced[v]) {
        ++result.samples.skipped_unreferenced_vertices;
      } else if (normal.isZero()) {
        ++result.samples.skipped_zero_normal_vertices;
      } else {
        samples.positions.push_back(stream.position(static_cast<int>(v)));
        samples.normals.push_back(normal);
        samples.weights.push_back(sums.third_areas[v]);
      }
    }
    sums.release(first, last);
    pending.append(std::move(samples));
    const std::size_t ready = pending.size() / run * run;
    if (ready == 0) continue;
    SampleSet rest = pending.split_off(ready);
    measure(pending);
    pending = std::move(rest);
  }
  if (pending.size() > 0) measure(pending);
  method.set_progress({});
  if (statistics.count() == 0) {
    throw Error(fmt::format("reference model gives no 'vertices' samples ({} triangles, all degenerate?)",
                            stream.face_count()));
  }
  result.statistics = statistics.finish();
  result.heatmap_range = default_heatmap_range(statistics, result.statistics.hit_count, options.max_error);
  return result;
}

}  // namespace roving
