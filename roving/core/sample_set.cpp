// Sample sets on the reference model (DESIGN.md "Samples").
#include "roving/core/sample_set.h"

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <charconv>
#include <iterator>
#include <type_traits>

#include "roving/core/error.h"
#include "roving/core/memory_budget.h"
#include "roving/core/mersenne_twister.h"

namespace roving {

std::string SampleSpec::to_string() const {
  switch (kind) {
    case Kind::Faces: return "faces";
    case Kind::Vertices: return "vertices";
    case Kind::Area: return fmt::format("area:{}", count);
  }
  return "?";
}

SampleSpec parse_sample_spec(const std::string& text) {
  SampleSpec spec;
  if (text == "faces") return spec;
  if (text == "vertices") {
    spec.kind = SampleSpec::Kind::Vertices;
    return spec;
  }
  if (text == "area:auto") {
    spec.kind = SampleSpec::Kind::Area;
    spec.automatic = true;
    return spec;
  }
  if (text.rfind("area:", 0) == 0) {
    const std::string digits = text.substr(5);
    std::size_t count = 0;
    const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), count);
    // 2^31 samples would need > 100 GB of results: far beyond any sensible measurement.
    if (error == std::errc() && end == digits.data() + digits.size() && count > 0 &&
        count <= (std::size_t{1} << 31)) {
      spec.kind = SampleSpec::Kind::Area;
      spec.count = count;
      return spec;
    }
  }
  throw Error(
      fmt::format("--samples: expected 'faces', 'vertices', 'area:auto' or 'area:N' with N in [1, 2^31], "
                  "found '{}'",
                  text));
}

SampleSet SampleSet::head(std::size_t n) const { return slice(0, n); }

SampleSet SampleSet::slice(std::size_t first, std::size_t last) const {
  last = std::min(last, size());
  first = std::min(first, last);
  const auto part = [&](const auto& all) {  // an array not filled per sample stays empty
    using Array = std::decay_t<decltype(all)>;
    return all.size() < last ? Array() : Array(all.begin() + first, all.begin() + last);
  };
  SampleSet subset;
  subset.positions = part(positions);
  subset.normals = part(normals);
  subset.weights = part(weights);
  subset.elements = part(elements);
  subset.kind = kind;
  subset.skipped_degenerate_faces = skipped_degenerate_faces;
  subset.skipped_unreferenced_vertices = skipped_unreferenced_vertices;
  subset.skipped_zero_normal_vertices = skipped_zero_normal_vertices;
  return subset;
}

SampleSet SampleSet::split_off(std::size_t n) {
  SampleSet rest;
  const auto move_tail = [&](auto& all, auto& tail) {
    if (all.size() < n) return;  // an array not filled per sample
    tail.assign(std::make_move_iterator(all.begin() + n), std::make_move_iterator(all.end()));
    all.resize(n);
  };
  move_tail(positions, rest.positions);
  move_tail(normals, rest.normals);
  move_tail(weights, rest.weights);
  move_tail(elements, rest.elements);
  rest.kind = kind;
  return rest;
}

void SampleSet::append(SampleSet&& more) {
  const bool none = size() == 0;
  const auto add = [none](auto& all, auto& tail) {
    if (none) {
      all = std::move(tail);
    } else if (!all.empty()) {  // else not filled per sample
      all.insert(all.end(), tail.begin(), tail.end());
    }
  };
  add(positions, more.positions);
  add(normals, more.normals);
  add(weights, more.weights);
  add(elements, more.elements);
  if (kind.empty()) kind = more.kind;
  skipped_degenerate_faces += more.skipped_degenerate_faces;
  skipped_unreferenced_vertices += more.skipped_unreferenced_vertices;
  skipped_zero_normal_vertices += more.skipped_zero_normal_vertices;
}

namespace {

void reserve(SampleSet& samples, std::size_t n) {
  samples.positions.reserve(n);
  samples.normals.reserve(n);
  samples.weights.reserve(n);
  samples.elements.reserve(n);
}

void sample_faces(const TriangleMesh& mesh, SampleSet& samples) {
  reserve(samples, mesh.triangle_count());
  for (std::size_t f = 0; f < mesh.triangle_count(); ++f) {
    if (mesh.face_normal(f).isZero()) {
      ++samples.skipped_degenerate_faces;
      continue;
    }
    samples.positions.push_back(mesh.centroid(f));
    samples.normals.push_back(mesh.face_normal(f));
    samples.weights.push_back(mesh.face_area(f));
    samples.elements.push_back(static_cast<std::uint32_t>(f));
  }
}

// Vertex samples from `positions`, the mesh's own or a copy: compacted in place, as are the
// normals and areas, so that no second copy of any is ever made (170 MB at 10 M triangles).
void sample_vertices(const TriangleMesh& mesh, std::vector<Vec3> positions, std::vector<Vec3> normals,
                     std::vector<double> vertex_area, SampleSet& samples) {
  samples.elements.reserve(mesh.vertex_count());
  std::size_t kept = 0;
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
    if (!mesh.vertex_referenced()[v]) {
      ++samples.skipped_unreferenced_vertices;
    } else if (normals[v].isZero()) {
      ++samples.skipped_zero_normal_vertices;
    } else {
      positions[kept] = positions[v];
      normals[kept] = normals[v];
      vertex_area[kept] = vertex_area[v];
      samples.elements.push_back(static_cast<std::uint32_t>(v));
      ++kept;
    }
  }
  positions.resize(kept);
  normals.resize(kept);
  vertex_area.resize(kept);
  samples.positions = std::move(positions);
  samples.normals = std::move(normals);
  samples.weights = std::move(vertex_area);  // each vertex stands for a third of its faces' area
}

void sample_area(const TriangleMesh& mesh, const SampleSpec& spec, SampleSet& samples) {
  // Inverse-CDF over cumulative face areas, then uniform barycentrics (Turk 1990's square-root
  // map). std::mt19937_64's draws (which the standard fixes) and our own uniform mapping keep it
  // reproducible across libstdc++s; Mt19937_64 draws them, and jumps to a shard's first.
  std::vector<double> cumulative(mesh.triangle_count());
  double total = 0;
  for (std::size_t f = 0; f < mesh.triangle_count(); ++f) {
    total += mesh.face_normal(f).isZero() ? 0.0 : mesh.face_area(f);
    cumulative[f] = total;
  }
  if (!(total > 0)) return;  // no face with a normal: no samples, which make_samples refuses
  Mt19937_64 random(spec.seed);
  const auto uniform = [&random] { return (random() >> 11) * 0x1.0p-53; };
  const double weight = total / static_cast<double>(spec.count);
  const std::size_t last = std::min(spec.last, spec.count), first = std::min(spec.first, last);
  random.discard(3 * first);  // each sample takes three draws: those before the slice's, jumped
  // The draws in order a block at a time; the samples they make (a binary search in `cumulative`
  // each, mostly cache misses) on all cores.
  const std::size_t count = last - first;
  samples.positions.resize(count);
  samples.normals.resize(count);
  samples.weights.assign(count, weight);
  samples.elements.resize(count);
  constexpr std::size_t kBlock = std::size_t{1} << 16;
  std::vector<double> draws(3 * std::min(count, kBlock));
  for (std::size_t begin = 0; begin < count; begin += kBlock) {
    const std::size_t end = std::min(count, begin + kBlock);
    for (std::size_t k = 0; k < 3 * (end - begin); ++k) draws[k] = uniform();
    tbb::parallel_for(tbb::blocked_range<std::size_t>(begin, end, 4096), [&](const tbb::blocked_range<std::size_t>& range) {
      for (std::size_t i = range.begin(); i != range.end(); ++i) {
        const double* u = &draws[3 * (i - begin)];
        const double target = u[0] * total;
        std::size_t f = std::upper_bound(cumulative.begin(), cumulative.end(), target) - cumulative.begin();
        // A draw rounded up to the total: the last face with area, not a degenerate one after it.
        if (f == cumulative.size()) f = std::lower_bound(cumulative.begin(), cumulative.end(), total) - cumulative.begin();
        const double r1 = std::sqrt(u[1]), r2 = u[2];
        const Triangle& t = mesh.triangles()[f];
        const auto& p = mesh.positions();
        samples.positions[i] = (1 - r1) * p[t[0]] + r1 * (1 - r2) * p[t[1]] + r1 * r2 * p[t[2]];
        samples.normals[i] = mesh.face_normal(f);
        samples.elements[i] = static_cast<std::uint32_t>(f);
      }
    });
  }
}

void require_samples(const SampleSet& samples, const TriangleMesh& reference) {
  if (samples.size() == 0) {
    throw Error(fmt::format("reference model gives no '{}' samples ({} triangles, all degenerate?)",
                            samples.kind, reference.triangle_count()));
  }
}

}  // namespace

SampleSet make_samples(const TriangleMesh& reference, const SampleSpec& spec) {
  if (spec.kind == SampleSpec::Kind::Area && spec.count == 0) {
    throw Error("--samples area:auto: the sample count is chosen by `roving measure` for --precision; give area:N here");
  }
  SampleSet samples;
  samples.kind = spec.to_string();
  switch (spec.kind) {
    case SampleSpec::Kind::Faces: sample_faces(reference, samples); break;
    case SampleSpec::Kind::Vertices: {
      std::vector<double> vertex_area;
      std::vector<Vec3> normals = reference.vertex_normals(&vertex_area);
      sample_vertices(reference, {reference.positions().begin(), reference.positions().end()}, std::move(normals), std::move(vertex_area), samples);
      break;
    }
    case SampleSpec::Kind::Area:
      // Positions, normals, weights, elements, then a distance, a flag and a magnitude per sample.
      const std::size_t kept = std::min(spec.last, spec.count) - std::min(spec.first, std::min(spec.last, spec.count));
      require_memory("sampling", 85.0 * kept, fmt::format("{} samples", kept));
      sample_area(reference, spec, samples);
      break;
  }
  require_samples(samples, reference);
  return samples;
}

SampleSet make_samples_releasing(TriangleMesh& reference, const SampleSpec& spec) {
  if (spec.kind != SampleSpec::Kind::Vertices) {
    SampleSet samples = make_samples(reference, spec);
    reference.release_geometry();
    return samples;
  }
  SampleSet samples;
  samples.kind = spec.to_string();
  std::vector<double> vertex_area;
  std::vector<Vec3> normals = reference.vertex_normals(&vertex_area);
  sample_vertices(reference, reference.release_geometry(), std::move(normals), std::move(vertex_area),
                  samples);
  require_samples(samples, reference);
  return samples;
}

}  // namespace roving
