// Google Benchmark timings of the building blocks on the bunny's 69,451 face samples against its
// 10,459-triangle quadric decimation (the paper's middle mesh): BVH builds, Embree and CGAL
// queries, the baselines, one GL view and one batch of surface-roving cameras. Every benchmark
// first checks its answer (against the other reference, or against Embree) and refuses to time
// a wrong one.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>

#include "data_folder.h"
#include "decimate.h"
#include "roving/core/normalise.h"
#include "roving/formats/meshes/mesh_io.h"
#include "roving/gl/depth_renderer.h"
#include "roving/gl_methods/agreement.h"
#include "roving/reference_cgal/cgal_reference.h"
#include "roving/reference_embree/certified_hausdorff.h"
#include "roving/registry/method_registry.h"

namespace {

using namespace roving;

struct Pair {
  TriangleMesh reference, test;
  SampleSet samples;
  double max_error = 0;
};

const Pair& bunny_pair() {
  static const Pair pair = [] {
    const std::string folder = default_data_folder();
    Pair p;
    p.reference = normalised(load_mesh(folder + "/stanford-bunny.obj").mesh);
    p.test = decimate_quadric(p.reference, 10459);
    p.samples = make_samples(p.reference, {});
    p.max_error = 0.05 * p.reference.bounding_box().diagonal();
    return p;
  }();
  return pair;
}

// Both references must agree (same flag on >= 99.9%, within 1e-5 of the diagonal on >= 99.99%
// of common hits) before either is timed.
bool references_agree(Semantics semantics, std::string& why) {
  const Pair& p = bunny_pair();
  auto embree = make_method("embree");
  auto cgal = make_method("cgal");
  const auto a = measure_distances(*embree, p.test, p.samples, {semantics, p.max_error});
  const auto b = measure_distances(*cgal, p.test, p.samples, {semantics, p.max_error});
  std::size_t same = 0, common = 0, close = 0;
  const double tolerance = 1e-5 * p.reference.bounding_box().diagonal();
  for (std::size_t k = 0; k < a.hit.size(); ++k) {
    same += a.hit[k] == b.hit[k];
    if (a.hit[k] && b.hit[k])
      ++common, close += std::abs(a.signed_distance[k] - b.signed_distance[k]) <= tolerance;
  }
  why = std::to_string(a.hit.size() - same) + " flags and " + std::to_string(common - close) +
        " distances differ";
  return same >= 0.999 * a.hit.size() && close >= 0.9999 * common;
}

void BM_Build(benchmark::State& state, const std::string& method_name) {
  const Pair& p = bunny_pair();
  auto method = make_method(method_name);
  for (auto _ : state) benchmark::DoNotOptimize(method->build(p.test));
  state.counters["triangles"] = static_cast<double>(p.test.triangle_count());
}

void BM_Query(benchmark::State& state, const std::string& method_name, Semantics semantics) {
  const Pair& p = bunny_pair();
  if (method_name == "embree" || method_name == "cgal") {
    std::string why;
    if (!references_agree(semantics, why)) {
      state.SkipWithError(("references disagree: " + why).c_str());
      return;
    }
  }
  auto method = make_method(method_name);
  method->build(p.test);
  std::size_t hits = 0;
  for (auto _ : state) {
    const DistanceResult result = method->measure(p.samples, {semantics, p.max_error});
    hits = result.hit_count();
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * p.samples.size()));
  state.counters["samples"] = static_cast<double>(p.samples.size());
  state.counters["hits"] = static_cast<double>(hits);
}

// One whole-model view (1024 px) on the GL backend, checked first: the depth of 400 pixels
// against Embree's first hit along the same rays (cast from the view's near face), within 16
// steps of float depth.
void BM_GlView(benchmark::State& state) {
  const Pair& p = bunny_pair();
  auto renderer = make_depth_renderer(GlBackend::OSMesa);
  renderer->upload_model(p.test);
  const BoundingBox& box = p.test.bounding_box();
  const double radius = 0.5 * box.diagonal();
  const OrthoCamera camera =
      OrthoCamera::looking_along(Vec3(0.3, -1, 0.2), box.centre(), radius, radius, radius);
  const int resolution = 1024;
  std::vector<float> depth;
  renderer->render_view(camera, resolution, depth);
  SampleSet rays;  // a sample mid-depth whose "normal" points at the camera: its first-hit ray is the pixel's
  std::vector<std::size_t> pixels;
  for (int j = 12; j < resolution; j += 50)
    for (int i = 12; i < resolution; i += 50) {
      const double x = (i + 0.5) / resolution * 2 - 1, y = (j + 0.5) / resolution * 2 - 1;
      rays.positions.push_back(camera.centre + x * radius * camera.right + y * radius * camera.up);
      rays.normals.push_back(-camera.forward);
      rays.weights.push_back(1);
      pixels.push_back(static_cast<std::size_t>(j) * resolution + i);
    }
  auto embree = make_method("embree");
  const DistanceResult truth = measure_distances(*embree, p.test, rays, {Semantics::FirstHit, radius});
  const double step = 2 * radius * std::ldexp(1.0, -24);
  std::size_t wrong = 0;
  for (std::size_t k = 0; k < pixels.size(); ++k) {
    const bool drawn = depth[pixels[k]] < 1.0f;
    const double t = depth[pixels[k]] * 2 * radius;
    wrong += drawn != bool(truth.hit[k]) ||
             (drawn && std::abs(t - (radius - truth.signed_distance[k])) > 16 * step);
  }
  // A pixel centre within rounding of a silhouette edge may legitimately differ: 1 in 100.
  if (wrong > pixels.size() / 100) {
    state.SkipWithError(
        ("GL view depth disagrees with Embree on " + std::to_string(wrong) + " pixels").c_str());
    return;
  }
  for (auto _ : state) renderer->render_view(camera, resolution, depth);
  state.counters["pixels"] = double(resolution) * resolution;
  state.counters["triangles"] = double(p.test.triangle_count());
}

// One batch of surface-roving cameras (all 69,451 samples in one draw of one-pixel tiles),
// checked first against Embree with the derived roving tolerance.
void BM_RovingCameras(benchmark::State& state) {
  const Pair& p = bunny_pair();
  auto roving = make_method("roving");
  auto embree = make_method("embree");
  const DistanceOptions options{Semantics::FirstHit, p.max_error};
  const DistanceResult truth = measure_distances(*embree, p.test, p.samples, options);
  const DistanceResult first = measure_distances(*roving, p.test, p.samples, options);
  const Agreement a = agreement(truth, first, roving_tolerance(*first.gl));
  if (a.same_flag_fraction() < 0.999 || a.close_fraction() < 0.995) {
    state.SkipWithError("roving disagrees with Embree");
    return;
  }
  roving->build(p.test);  // measure_distances released it
  for (auto _ : state) benchmark::DoNotOptimize(roving->measure(p.samples, options));
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * p.samples.size()));
}

// The Hausdorff distance from the bunny to its 10,459-triangle mesh within 1e-4 of the diagonal:
// our certified interval and CGAL's bounded-error value, each checked against the other first
// (CGAL's value within its bound of our interval).
void BM_Hausdorff(benchmark::State& state, bool ours) {
  const Pair& p = bunny_pair();
  const double bound = 1e-4 * p.reference.bounding_box().diagonal();
  const HausdorffInterval h = certified_hausdorff(p.reference, p.test, bound);
  const double cgal = cgal_bounded_hausdorff(p.reference, p.test, bound);
  if (!(h.upper - h.lower <= bound && cgal >= h.lower - bound && cgal <= h.upper + bound)) {
    state.SkipWithError("the certified interval and CGAL's value disagree");
    return;
  }
  for (auto _ : state) {
    benchmark::DoNotOptimize(ours ? certified_hausdorff(p.reference, p.test, bound).upper
                                  : cgal_bounded_hausdorff(p.reference, p.test, bound));
  }
  state.counters["lower"] = h.lower;
  state.counters["upper"] = h.upper;
  state.counters["cgal"] = cgal;
}

void register_all() {
  benchmark::RegisterBenchmark("hausdorff/certified-1e-4", BM_Hausdorff, true)->Unit(benchmark::kMillisecond)->UseRealTime();
  benchmark::RegisterBenchmark("hausdorff/cgal-bounded-1e-4", BM_Hausdorff, false)
      ->Unit(benchmark::kMillisecond)
      ->UseRealTime();
  benchmark::RegisterBenchmark("gl/view-1024px", BM_GlView)->Unit(benchmark::kMillisecond)->UseRealTime();
  benchmark::RegisterBenchmark("gl/roving-cameras", BM_RovingCameras)
      ->Unit(benchmark::kMillisecond)
      ->UseRealTime();
  for (const char* name : {"embree", "cgal", "v2v-kdtree", "v2p-aabb"}) {
    benchmark::RegisterBenchmark((std::string("build/") + name).c_str(), BM_Build, std::string(name))
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime();
  }
  for (const char* name : {"embree", "cgal"}) {
    for (Semantics s : {Semantics::FirstHit, Semantics::Nearest, Semantics::Closest}) {
      benchmark::RegisterBenchmark((std::string("query/") + name + "/" + to_string(s)).c_str(), BM_Query,
                                   std::string(name), s)
          ->Unit(benchmark::kMillisecond)
          ->UseRealTime();
    }
  }
  for (const char* name : {"v2v-kdtree", "v2p-aabb", "v2v-naive", "v2p-naive"}) {
    auto* b = benchmark::RegisterBenchmark((std::string("query/") + name).c_str(), BM_Query,
                                           std::string(name), Semantics::Closest);
    b->Unit(benchmark::kMillisecond)->UseRealTime();
    if (std::string(name).find("naive") != std::string::npos) b->Iterations(1);  // seconds each
  }
}

}  // namespace

int main(int argc, char** argv) {
  register_all();
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
