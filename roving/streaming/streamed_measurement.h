// A reference measured a block of its faces at a time, read from its file as they are needed
// (triangle_stream.h), so that a measurement's memory is TEST's search structure, REF's
// vertices, one block and 8 bytes a sample (|d|, for the exact percentiles), not the whole
// reference and its samples (about 85 bytes a triangle). Every figure is the one the whole
// reference gives, bit for bit: the same samples, measured alike, folded into the statistics in
// the same order.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>

#include "roving/core/distance_method.h"
#include "roving/core/sample_set.h"
#include "roving/core/statistics.h"
#include "roving/core/triangle_mesh.h"
#include "roving/formats/meshes/triangle_stream.h"

namespace roving {

// Faces of REF read, sampled and measured at a time unless --chunk says otherwise: a block of 2^20
// faces holds about 100 MB (its triangles, samples and distances) while it is measured.
constexpr std::size_t kDefaultChunkFaces = std::size_t{1} << 20;

// Each vertex's sums over the faces that use it, in the file's order, and whether any does: what
// vertex samples are made of (33 bytes a vertex), on pages of their own from the kernel (not the
// heap's, which one_heap.cpp never hands back).
struct VertexSums {
  explicit VertexSums(std::size_t n);
  Vec3* normals;  // summed cross products, made unit as each sample is made
  double* third_areas;
  std::uint8_t* referenced;

  // Vertices [first, last) are no longer needed: their whole pages go back to the system, so
  // that the sums shrink as the vertices' distances (the statistics) grow.
  void release(std::size_t first, std::size_t last);

 private:
  struct Unmap {
    std::size_t bytes;
    void operator()(void* pages) const;
  };
  std::unique_ptr<void, Unmap> pages_;
};

// What TriangleMesh derives from the whole mesh, found in one pass over the stream: the same
// counts, box and area (summed in TriangleMesh's blocks and order), and the faces dropped for
// repeating a vertex; and, where asked, the vertex sums, from the same pass.
struct StreamedReference {
  TriangleMesh summary;
  std::size_t dropped_repeated_vertex_faces = 0, triangulated_polygons = 0;
  std::optional<VertexSums> vertex_sums;
};
// `progress` hears of the file's faces read.
StreamedReference summarise(TriangleStream& stream, std::size_t chunk_faces, const ProgressFn& progress = {},
                            bool with_vertex_sums = false);

// REF's file read a block of faces at a time, and the vertex sums of its first pass where its
// vertices are the samples.
struct ReferenceStream {
  TriangleStream& file;
  std::optional<VertexSums> vertex_sums;
};

struct StreamedResult {
  Statistics statistics;
  SampleSet samples;  // the kind, the skipped faces and, for a slice, its weights; no other per-sample arrays
  DistanceResult slice;  // for a slice, its samples' signed distances and hits; empty otherwise
  SignCounts signs;
  double heatmap_range = 0;  // default_heatmap_range's: the 99th percentile of the hits' |d|
  std::size_t chunks = 0;
  double query_seconds = 0;
  std::optional<GlReport> gl;  // a GL method's, its blocks' added up (GlReport::add_block)
};

// Samples [first, last) of REF's, in the whole's order: a shard's slice.
struct SampleRange {
  std::size_t first = 0, last = 0;
};

// Measures REF's face samples (make_samples' "faces", in its order) against the TEST `method`
// was built for, `chunk_faces` of the file's faces at a time; `progress` hears of the samples
// done of `expected_samples`. Samples go to the method in whole runs (independent_run()), so that
// chunking changes no answer. Where `slice` is given (its first a multiple of the run), only its
// samples are measured, the file read no further than its last, and their distances, hits and
// weights are kept (17 bytes a sample), as a shard's part needs them; the skipped faces are then
// those of the faces read. Throws roving::Error where REF gives no sample, or where the method
// answers each sample from them all.
StreamedResult measure_streamed(TriangleStream& stream, DistanceMethod& method, const DistanceOptions& options,
                                std::size_t histogram_bins, std::size_t chunk_faces, std::size_t expected_samples,
                                const ProgressFn& progress = {}, const std::optional<SampleRange>& slice = {});

// Measures REF's vertex samples (make_samples' "vertices": each vertex a kept face uses whose
// normal is not zero, at its position, with the unit sum of its faces' cross products and a third of
// their area, in vertex order) against the TEST `method` was built for, as measure_streamed does
// its faces: the file's first pass (summarise) summed each vertex's faces in the file's order, as
// TriangleMesh::vertex_normals sums them (the same bits); the vertices are measured `chunk_faces`
// at a time, their sums released as they go. Beside the stream's positions it holds 33 bytes a
// vertex, not REF's faces; the figures are the whole reference's, bit for bit. `progress` hears of
// the samples done of `expected_samples`. Throws roving::Error where REF gives no sample.
StreamedResult measure_streamed_vertices(TriangleStream& stream, VertexSums& sums, DistanceMethod& method,
                                         const DistanceOptions& options, std::size_t histogram_bins,
                                         std::size_t chunk_faces, std::size_t expected_samples,
                                         const ProgressFn& progress = {});

}  // namespace roving
