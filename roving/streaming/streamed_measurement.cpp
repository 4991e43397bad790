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
#include <new>

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

// Adds the block's faces to each vertex's sums. As vertex_normals: each thread owns a range of
// vertices and scans the block's faces for its corners, so that each vertex adds its faces in the
// file's order on any number of threads.
void add_to_vertex_sums(const TriangleStream& stream, const std::vector<Triangle>& triangles, VertexSums& sums) {
  const std::size_t n = stream.position_count();
  const std::size_t parts = std::size_t(std::max(1, tbb::this_task_arena::max_concurrency()));
  const std::size_t per_part = (n + parts - 1) / parts;
  tbb::parallel_for(std::size_t{0}, parts, [&](std::size_t part) {
    const auto low = static_cast<int>(std::min(n, part * per_part));
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

// Zeroed sums for the stream's vertices. The kernel's pages are zero already; each thread writes
// zeroes to its own range all the same, so that they are faulted in (at 10^8 faces 1.6 GiB of
// them) by both cores at once, in order, not one by one in the face pass's scattered writes.
VertexSums zeroed_vertex_sums(std::size_t n) {
  VertexSums sums(n);
  const std::size_t parts = std::size_t(std::max(1, tbb::this_task_arena::max_concurrency()));
  const std::size_t per_part = (n + parts - 1) / parts;
  tbb::parallel_for(std::size_t{0}, parts, [&](std::size_t part) {
    const std::size_t low = std::min(n, part * per_part), high = std::min(n, (part + 1) * per_part);
    std::fill(sums.normals + low, sums.normals + high, Vec3::Zero());
    std::fill(sums.third_areas + low, sums.third_areas + high, 0.0);
    std::fill(sums.referenced + low, sums.referenced + high, std::uint8_t{0});
  });
  return sums;
}

// Vertices [first, last)'s samples as sample_vertices makes them (sample_set.cpp), in order:
// each vertex a kept face uses whose normal is not zero. On every core: a part of the range at a
// time counts its samples, then writes them where the counts before it put them.
SampleSet vertex_samples(const TriangleStream& stream, const VertexSums& sums, std::size_t first, std::size_t last) {
  // The normal made unit as TriangleMesh::vertex_normals makes it (zero where its length is not
  // > 0), here rather than in a pass of its own over the sums; a zero one skipped as
  // sample_vertices skips it.
  const auto unit_normal = [&](std::size_t v) {
    const double length = sums.normals[v].norm();
    return length > 0 ? Vec3(sums.normals[v] / length) : Vec3::Zero();
  };
  const std::size_t parts = 4 * std::size_t(std::max(1, tbb::this_task_arena::max_concurrency()));
  const auto range = [&](std::size_t part) {
    return std::pair{first + (last - first) * part / parts, first + (last - first) * (part + 1) / parts};
  };
  std::vector<std::size_t> unreferenced(parts), zero_normal(parts), kept(parts + 1);
  tbb::parallel_for(std::size_t{0}, parts, [&](std::size_t part) {
    const auto [low, high] = range(part);
    for (std::size_t v = low; v < high; ++v) {
      if (!sums.referenced[v]) {
        ++unreferenced[part];
      } else if (unit_normal(v).isZero()) {
        ++zero_normal[part];
      }
    }
    kept[part + 1] = high - low - unreferenced[part] - zero_normal[part];
  });
  SampleSet samples;
  for (std::size_t part = 0; part < parts; ++part) {
    kept[part + 1] += kept[part];
    samples.skipped_unreferenced_vertices += unreferenced[part];
    samples.skipped_zero_normal_vertices += zero_normal[part];
  }
  samples.positions.resize(kept[parts]);
  samples.normals.resize(kept[parts]);
  samples.weights.resize(kept[parts]);
  tbb::parallel_for(std::size_t{0}, parts, [&](std::size_t part) {
    const auto [low, high] = range(part);
    std::size_t k = kept[part];
    for (std::size_t v = low; v < high; ++v) {
      if (!sums.referenced[v]) continue;
      const Vec3 normal = unit_normal(v);
      if (normal.isZero()) continue;
      samples.positions[k] = stream.position(static_cast<int>(v));
      samples.normals[k] = normal;
      samples.weights[k] = sums.third_areas[v];
      ++k;
    }
  });
  return samples;
}

void release_pages(const void* from, const void* to) {
  const auto page = static_cast<std::uintptr_t>(sysconf(_SC_PAGESIZE));
  const std::uintptr_t low = (reinterpret_cast<std::uintptr_t>(from) + page - 1) / page * page;
  const std::uintptr_t high = reinterpret_cast<std::uintptr_t>(to) / page * page;
  if (low < high) madvise(reinterpret_cast<void*>(low), high - low, MADV_DONTNEED);
}

}  // namespace

VertexSums::VertexSums(std::size_t n) {
  const std::size_t bytes = std::max<std::size_t>(1, n * (sizeof(Vec3) + sizeof(double) + sizeof(std::uint8_t)));
  void* pages = mmap(nullptr, bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS | MAP_NORESERVE, -1, 0);
  if (pages == MAP_FAILED) throw std::bad_alloc();
  pages_ = std::unique_ptr<void, Unmap>(pages, Unmap{bytes});
  normals = static_cast<Vec3*>(pages);
  third_areas = reinterpret_cast<double*>(normals + n);
  referenced = reinterpret_cast<std::uint8_t*>(third_areas + n);
}

void VertexSums::Unmap::operator()(void* pages) const {
  munmap(pages, bytes);
}

void VertexSums::release(std::size_t first, std::size_t last) {
  release_pages(normals + first, normals + last);
  release_pages(third_areas + first, third_areas + last);
  release_pages(referenced + first, referenced + last);
}

StreamedReference summarise(TriangleStream& stream, std::size_t chunk_faces, const ProgressFn& progress,
                            bool with_vertex_sums) {
  StreamedReference result;
  // The vertex samples' sums from this same pass: reading and parsing the faces once, not twice
  // (at 10^8 faces that pass is seconds).
  if (with_vertex_sums) result.vertex_sums = zeroed_vertex_sums(stream.position_count());
  TriangleMesh::Summary summary;
  std::vector<Triangle> triangles;
  double block_area = 0;  // TriangleMesh's current block of kAreaBlock faces
  stream.rewind();
  for (std::size_t read = 0; stream.next(chunk_faces, triangles);) {
    read = std::min(read + chunk_faces, stream.face_count());
    if (progress) progress("faces", read, stream.face_count());
    if (with_vertex_sums) add_to_vertex_sums(stream, triangles, *result.vertex_sums);
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
  result.summary = TriangleMesh(summary);
  result.dropped_repeated_vertex_faces = stream.dropped_repeated_vertex_faces();
  result.triangulated_polygons = stream.triangulated_polygons();
  return result;
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

StreamedResult measure_streamed_vertices(TriangleStream& stream, VertexSums& sums, DistanceMethod& method,
                                         const DistanceOptions& options, std::size_t histogram_bins,
                                         std::size_t chunk_faces, std::size_t expected_samples,
                                         const ProgressFn& progress) {
  const std::size_t run = method.independent_run();
  if (run == 0) throw Error(method.name() + ": answers every sample from them all; REF cannot be streamed");
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
    SampleSet samples = vertex_samples(stream, sums, first, last);
    result.samples.skipped_unreferenced_vertices += samples.skipped_unreferenced_vertices;
    result.samples.skipped_zero_normal_vertices += samples.skipped_zero_normal_vertices;
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
