// Sample points on the reference model M_R (DESIGN.md "Samples"): positions, unit normals, weights.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "roving/core/triangle_mesh.h"

namespace roving {

// Which points of M_R are measured: `faces` (triangle centroids with face normals, the paper's
// default), `vertices` (referenced vertices with area-weighted normals) or `area:N` (N points
// uniform by area with the face normal, from `seed`: reported, and fixed unless chosen).
struct SampleSpec {
  enum class Kind { Faces, Vertices, Area };
  Kind kind = Kind::Faces;
  std::size_t count = 0;       // Area only
  std::uint64_t seed = 12345;  // Area only
  bool automatic = false;      // area:auto: the caller chooses count for a precision, then samples
  // Area only: keep samples [first, last) of the `count` drawn (a shard's slice), drawn exactly as
  // the whole set draws them; the rest are never made.
  std::size_t first = 0, last = static_cast<std::size_t>(-1);

  std::string to_string() const;
};

// Parses "faces", "vertices", "area:N" (N a positive integer) or "area:auto" (automatic, count 0
// until the caller sets it); throws roving::Error naming the option `--samples` and what was found
// otherwise.
SampleSpec parse_sample_spec(const std::string& text);

struct SampleSet {
  std::vector<Vec3> positions;
  std::vector<Vec3> normals;    // unit length
  std::vector<double> weights;  // area each sample stands for (eq. 1); sums to M_R's area
  // The element of M_R each sample comes from: its face (faces, area:N) or its vertex (vertices).
  std::vector<std::uint32_t> elements;
  std::string kind;
  // Elements of M_R that gave no sample: zero-area faces, unreferenced vertices, or vertices
  // whose incident normals cancel.
  std::size_t skipped_degenerate_faces = 0;
  std::size_t skipped_unreferenced_vertices = 0;
  std::size_t skipped_zero_normal_vertices = 0;

  std::size_t size() const { return positions.size(); }
  // The first `n` samples (or all, if fewer), for fast subsets in tests.
  SampleSet head(std::size_t n) const;
  // Samples [first, last) (clamped to the set), with the set's kind and skipped counts: a shard's.
  SampleSet slice(std::size_t first, std::size_t last) const;
  // Samples [n, size()) moved into a set of their own (with the kind), these kept: n must be <= size().
  SampleSet split_off(std::size_t n);
  // `more`'s samples after these, in every array both fill per sample (an empty set takes all).
  void append(SampleSet&& more);
};

// Builds samples on `reference`; throws roving::Error if none can be made.
SampleSet make_samples(const TriangleMesh& reference, const SampleSpec& spec);

// The same samples, made while `reference` gives up its geometry (release_geometry): vertex
// samples take its positions rather than copy them. For a reference nothing reads once sampled.
SampleSet make_samples_releasing(TriangleMesh& reference, const SampleSpec& spec);

}  // namespace roving
