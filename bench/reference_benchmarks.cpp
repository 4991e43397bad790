// Google Benchmark timings of the exact references and the baselines, on the bunny's 69,451
// face samples against its 10,459-triangle quadric decimation (the paper's middle mesh).
// Every benchmark first checks its answer against the other reference and refuses to time a
// wrong one.
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <filesystem>

#include "decimate.h"
#include "method_registry.h"
#include "roving/mesh_io.h"
#include "roving/normalise.h"

namespace {

using namespace roving;

struct Pair {
  TriangleMesh reference, test;
  SampleSet samples;
  double max_error = 0;
};

const Pair& bunny_pair() {
  static const Pair pair = [] {
    const char* env = std::getenv("ROVING_DATA");
    const std::string folder = env && *env ? env : ROVING_SOURCE_DIR "/../shared/data";
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

void register_all() {
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
