// One direction of a pair measured (measure_direction.h).
#include "measure_direction.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <tuple>

#include "checks.h"
#include "roving/core/error.h"
#include "roving/reference_embree/certified_hausdorff.h"
#include "roving/streaming/mesh_blocks.h"

namespace roving {
namespace {

// REF's colour at each sample: a point cloud's at its points, a mesh's by the colour rule.
std::vector<Colour> reference_colours(const Model& reference, const SampleSet& samples) {
  if (reference.type != ModelType::Points) return sample_colours(reference.mesh.mesh, samples);
  std::vector<Colour> colours;
  colours.reserve(samples.size());
  for (const std::size_t point : samples.elements) colours.push_back(reference.points.colours[point]);
  return colours;
}

// One direction with REF read a block of faces at a time (streamed_measurement.h), `a` its summary.
// A shard measures its slice of the samples (`slice`) and bounds its share of the triangles, as it
// would with REF whole, keeping what its part holds.
void measure_streamed_direction(const Model& a, const TriangleMesh& test_mesh, ReferenceStream& source,
                                MeasurePlan& plan, double hausdorff_bound, const std::optional<SampleRange>& slice,
                                Progress& progress, std::string& stage, DirectionReport& d) {
  stage = fmt::format("measuring {} {} {} at a time against {} triangles with {}", a.path(), plan.chunk_faces,
                      plan.sample_spec.kind == SampleSpec::Kind::Vertices ? "vertices" : "faces",
                      test_mesh.triangle_count(), plan.method->name());
  progress.stage("measuring");
  validate_options(*plan.method, plan.options);
  d.result.build_seconds = plan.method_built_seconds ? *plan.method_built_seconds : plan.method->build(test_mesh);
  const TriangleMesh& m = a.mesh.mesh;
  TriangleStream& stream = source.file;
  StreamedResult streamed =
      plan.sample_spec.kind == SampleSpec::Kind::Vertices
          ? measure_streamed_vertices(stream, source.vertex_sums.value(), *plan.method, plan.options, plan.histogram_bins, plan.chunk_faces,
                                      m.vertex_count() - m.unreferenced_vertex_count(), progress.callback())
          : measure_streamed(stream, *plan.method, plan.options, plan.histogram_bins, plan.chunk_faces,
                             slice ? slice->last - slice->first : m.triangle_count() - m.degenerate_triangle_count(),
                             progress.callback(), slice);
  plan.method->release();
  plan.method_built_seconds.reset();
  d.samples = std::move(streamed.samples);
  if (slice) {  // what the part holds: the slice's figures, and the count of the whole's skipped faces
    d.result.signed_distance = std::move(streamed.slice.signed_distance);
    d.result.hit = std::move(streamed.slice.hit);
    d.samples.skipped_degenerate_faces = m.degenerate_triangle_count();
  }
  d.result.query_seconds = streamed.query_seconds;
  d.result.gl = std::move(streamed.gl);
  d.statistics = streamed.statistics;
  d.signs = streamed.signs;
  d.heatmap_range = streamed.heatmap_range;
  d.chunk_faces = plan.chunk_faces;
  d.chunks = streamed.chunks;
  if (plan.hausdorff_bound) {  // a pass of its own: TEST's closest-point structure, REF's blocks as meshes
    stage = fmt::format("bounding the Hausdorff distance from {} to {}, {} faces at a time", a.path(),
                        d.test->path(), plan.chunk_faces);
    progress.stage("certified Hausdorff");
    CertifiedHausdorff bound(test_mesh, hausdorff_bound);
    MeshBlocks blocks(stream, plan.chunk_faces);
    const ProgressFn tell = progress.callback();
    const auto [first, last] =  // of REF's triangles
        plan.shard ? plan.shard->range(m.triangle_count()) : std::pair{std::size_t{0}, m.triangle_count()};
    TriangleMesh block;
    for (std::size_t before = 0; before < last && blocks.next(block); before += block.triangle_count()) {
      const std::size_t from = std::max(first, before), to = std::min(last, before + block.triangle_count());
      if (from < to) bound.add(block, from - before, to - before);
      if (tell) tell("faces", blocks.faces_read(), stream.face_count());
    }
    d.hausdorff = bound.interval();
  }
}

}  // namespace

void measure_direction(const Model& reference_model, const Model& test_model, const DirectionSource& source,
                       MeasurePlan& plan, const MeasureReport& report, const std::vector<double>& thresholds,
                       Progress& progress, std::string& stage, const WarnFn& warn, DirectionReport& d) {
  const Model* reference = &reference_model;
  const Model* test = &test_model;
  stage = fmt::format("sampling {} ({})", reference->path(), plan.sample_spec.to_string());
  progress.stage(fmt::format("{}sampling", d.label.empty() ? "" : d.label + ": "));
  const TriangleMesh& test_mesh = test_surface(*test);
  SampleSpec spec = plan.sample_spec;
  if (spec.automatic) {
    spec.count = kAutoFirstSamples;
    d.auto_sampling.emplace();
  }
  // A shard's slice of `total` samples, beginning at a whole run of the method's (exact
  // roving's camera batches); never empty.
  const auto slice = [&](std::size_t total) {
    const std::size_t run = plan.method->independent_run();
    const auto [first, last] = plan.shard->range(total, run);
    if (first == last) {
      const std::size_t most = std::max<std::size_t>(1, total / run);
      throw Error(fmt::format("--shard {}/{}: this slice of {}'s {} samples is empty; use at most {} shard{}{}",
                              plan.shard->index, plan.shard->count, reference->path(), total, most,
                              most == 1 ? "" : "s",
                              run > 1 ? fmt::format(" ({} cuts at multiples of {} samples)", plan.method->name(), run)
                                      : ""));
    }
    return std::pair{first, last};
  };
  if (plan.shard && spec.kind == SampleSpec::Kind::Area) {  // a mesh draws only its slice
    std::tie(spec.first, spec.last) = slice(spec.count);
  }
  const bool streamed = source.stream != nullptr;
  if (streamed) {  // REF a block of faces at a time, its certified bound too
    std::optional<SampleRange> samples;
    if (plan.shard) {
      const TriangleMesh& m = reference->mesh.mesh;
      d.slice_total = m.triangle_count() - m.degenerate_triangle_count();
      const auto [first, last] = slice(d.slice_total);
      d.slice_first = first;
      samples = SampleRange{first, last};
    }
    measure_streamed_direction(*reference, test_mesh, *source.stream, plan, report.hausdorff_bound, samples,
                               progress, stage, d);
  } else {
    // area:auto measures again with more samples until USiAD's interval is as narrow as asked.
    for (int round = 1;; ++round) {
      if (source.samples && !spec.automatic) {
        d.samples = *source.samples;
      } else if (source.releasable && !spec.automatic) {
        d.samples = reference_samples_releasing(*source.releasable, spec);
      } else {
        d.samples = reference_samples(*reference, spec);
      }
      if (plan.shard) {  // this shard's slice of the pair's samples: the same samples whatever N
        const std::size_t total = spec.kind == SampleSpec::Kind::Area ? spec.count : d.samples.size();
        const auto [first, last] = slice(total);
        d.slice_first = first;
        d.slice_total = total;
        // A mesh's area samples come drawn as the slice already; all others are sliced here.
        if (d.samples.size() != last - first) d.samples = d.samples.slice(first, last);
      }
      stage = fmt::format("measuring {} samples against {} triangles with {}", d.samples.size(),
                          test_mesh.triangle_count(), plan.method->name());
      progress.stage(fmt::format("{}measuring", d.label.empty() ? "" : d.label + ": "));
      d.result = measure_distances(*plan.method, test_mesh, d.samples, plan.options);
      d.statistics = compute_statistics(d.result.signed_distance, d.result.hit, d.samples.weights,
                                        plan.options.max_error, plan.histogram_bins);
      if (d.samples.kind.rfind("area:", 0) == 0 && d.samples.size() >= 2) {
        d.intervals = sampling_intervals(d.result.signed_distance, d.result.hit, plan.options.max_error);
      }
      if (!spec.automatic) break;
      auto& aim = *d.auto_sampling;
      aim.rounds = round;
      aim.target = plan.precision->percent_of_diagonal
                       ? plan.precision->value / 100 * d.intervals->usiad.estimate
                       : plan.precision->value;
      aim.reached = (d.intervals->usiad.upper - d.intervals->usiad.lower) / 2;
      aim.met = aim.reached <= aim.target;
      if (aim.met || spec.count >= kAutoMaxSamples || round == 5) break;
      // The half-width shrinks as 1 / sqrt(N): the N that reaches the target, with 10% to spare.
      const double ratio = aim.target > 0 ? aim.reached / aim.target : 10.0;
      spec.count = static_cast<std::size_t>(
          std::min<double>(kAutoMaxSamples, std::ceil(spec.count * ratio * ratio * 1.1)));
    }
    d.signs = sign_counts(d.result);
    d.heatmap_range = plan.heatmap_range ? plan.heatmap_range->resolve(report.diagonal)
                                         : default_heatmap_range(d.result, report.max_error);
  }
  if (plan.hausdorff_bound && reference->type != ModelType::Points && !streamed) {
    stage = fmt::format("bounding the Hausdorff distance from {} to {}", reference->path(), test->path());
    progress.stage(fmt::format("{}certified Hausdorff", d.label.empty() ? "" : d.label + ": "));
    const TriangleMesh& surface = test_surface(*reference);
    if (plan.shard) {  // this shard's slice of the reference's triangles
      const auto [first, last] = plan.shard->range(surface.triangle_count());
      d.hausdorff = certified_hausdorff(surface, test_mesh, report.hausdorff_bound, first, last, progress.callback());
    } else {
      d.hausdorff = certified_hausdorff(surface, test_mesh, report.hausdorff_bound, progress.callback());
    }
    if (plan.certify_thresholds && test->type != ModelType::Points) {
      stage = fmt::format("bounding the share of {} within each threshold of {}", reference->path(), test->path());
      progress.stage(fmt::format("{}certified precision and recall", d.label + ": "));
      const auto [first, last] =
          plan.shard ? plan.shard->range(surface.triangle_count()) : std::pair{std::size_t{0}, surface.triangle_count()};
      d.area_within = certified_area_within(surface, test_mesh, thresholds, report.hausdorff_bound, first, last,
                                            progress.callback());
    }
  }
  if (plan.correspondences)
    d.correspondences = correspondences(d.samples, test_mesh, d.result, plan.options.semantics);
  if (plan.options.colour && d.result.hit_face.empty() && d.result.hit_colour.empty()) {
    if (&d == &report.directions.front()) warn({no_colour_warning(plan.method->name())});
  } else if (plan.options.colour) {
    stage = "comparing colours";
    d.colour_pairs = colour_pairs(reference_colours(*reference, d.samples), d.samples, test_mesh, d.result,
                                  plan.options.semantics);
    d.colour = compute_colour_statistics(*d.colour_pairs, d.result.hit);
  }
  std::vector<std::string> found = result_warnings(d.statistics, plan.options.semantics);
  for (std::string& line : found) line = (d.label.empty() ? "" : d.label + ": ") + line;
  warn(found);
}

}  // namespace roving
