// `gl-accuracy`: the full-size check of the GL methods against the exact references, on the
// bunny's 69,451 face samples (normalised, longest side 128, h = 5% of the diagonal) against its
// 10,459- and 800-triangle decimations and a smoothly perturbed copy (1.5% of the diagonal).
// Prints a Markdown report: agreement with Embree, the view-reading choices, observations and
// timings (with the naive vertex-to-plane baseline timed in the same run).
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "analytic.h"
#include "decimate.h"
#include "roving/core/normalise.h"
#include "roving/core/statistics.h"
#include "roving/formats/mesh_io.h"
#include "roving/gl_methods/agreement.h"
#include "roving/registry/method_registry.h"

using namespace roving;

namespace {

struct Run {
  DistanceResult result;
  Statistics stats;
};

Run run(const std::string& method, const GlMethodOptions& gl, const TriangleMesh& test,
        const SampleSet& samples, double h) {
  auto m = make_method(method, gl);
  Run r{measure_distances(*m, test, samples, {Semantics::FirstHit, h}), {}};
  r.stats = compute_statistics(r.result.signed_distance, r.result.hit, samples.weights, h);
  return r;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"gl-accuracy: GL methods against the exact references, full size"};
  std::string data =
      std::getenv("ROVING_DATA") ? std::getenv("ROVING_DATA") : ROVING_SOURCE_DIR "/../shared/data";
  std::string backend = "osmesa";
  bool time_naive = true;
  app.add_option("--data", data, "folder of the real models");
  app.add_option("--backend", backend, "osmesa or egl");
  app.add_flag("!--no-naive", time_naive, "skip timing the naive vertex-to-plane baseline");
  CLI11_PARSE(app, argc, argv);
  try {
    const TriangleMesh bunny = normalised(load_mesh(data + "/stanford-bunny.obj").mesh);
    const SampleSet samples = make_samples(bunny, {});
    const double diagonal = bunny.bounding_box().diagonal(), h = 0.05 * diagonal;
    // The gates apply to a test model 1-2% of the diagonal away (the issue's); the paper's two
    // decimations, far closer, are reported beside it.
    struct Pair {
      std::string label;
      TriangleMesh test;
      bool gated;
    };
    const TriangleMesh middle = decimate_quadric(bunny, 10459);
    const std::vector<Pair> pairs = {
        {"10,459-triangle decimation, smoothly perturbed by 1.5% of the diagonal (gated)",
         smoothly_perturbed(middle, 0.015 * diagonal, 0.5 * diagonal), true},
        {"10,459-triangle decimation (the paper's middle mesh)", middle, false},
        {"800-triangle decimation (the paper's low mesh)", decimate_quadric(bunny, 800), false}};
    GlMethodOptions gl;
    gl.backend = parse_gl_backend(backend);
    fmt::print("# GL methods against Embree, full size\n\n");
    fmt::print(
        "Bunny normalised to longest side 128 (diagonal {:.3f}), {} face samples, h = {:.4f}, first-hit.\n",
        diagonal, samples.size(), h);
    bool all_pass = true;
    for (const auto& [label, test, gated] : pairs) {
      const Run embree = run("embree", gl, test, samples, h);
      const Run roving = run("roving", gl, test, samples, h);
      const GlReport& rg = *roving.result.gl;
      fmt::print("\n## Bunny against its {}\n\nGL: {}\n\n", label, rg.renderer);
      const Agreement exact = agreement(embree.result, roving.result, roving_tolerance(rg));
      const double usiad_error = std::abs(roving.stats.usiad - embree.stats.usiad) / embree.stats.usiad;
      fmt::print(
          "Exact roving vs Embree: same hit flag on {:.4f}% (gate >= 99.9%); within the derived tolerance "
          "{:.3g} on {:.4f}% of {} common hits (gate >= 99.5%); USiAD {:.6f} vs {:.6f}, error {:.4f}% "
          "(gate <= 0.2%); {:.3f} s for {} cameras.\n\n",
          100 * exact.same_flag_fraction(), roving_tolerance(rg), 100 * exact.close_fraction(),
          exact.common_hits, roving.stats.usiad, embree.stats.usiad, 100 * usiad_error,
          roving.result.query_seconds, rg.sample_cameras);
      if (gated)
        all_pass &=
            exact.same_flag_fraction() >= 0.999 && exact.close_fraction() >= 0.995 && usiad_error <= 0.002;

      fmt::print(
          "| cooperative 24x12, 1024 px | SiAD | USiAD | STD | |dSiAD| / USiAD_roving | |dUSiAD| / "
          "USiAD_roving | view-resolved within view tol. of Embree | observations (views + cameras) | "
          "query s |\n|---|---|---|---|---|---|---|---|---|\n");
      fmt::print("| exact roving | {:.5f} | {:.5f} | {:.5f} | | | | {} | {:.3f} |\n", roving.stats.siad,
                 roving.stats.usiad, roving.stats.std_signed, rg.observations(), roving.result.query_seconds);
      for (const bool bilinear : {true, false}) {
        for (const bool cosine : {true, false}) {
          gl.bilinear = bilinear;
          gl.cosine_correction = cosine;
          const Run coop = run("cooperative", gl, test, samples, h);
          const GlReport& cg = *coop.result.gl;
          const double siad_error = std::abs(coop.stats.siad - roving.stats.siad) / roving.stats.usiad;
          const double usiad_err = std::abs(coop.stats.usiad - roving.stats.usiad) / roving.stats.usiad;
          const ViewAgreement views = view_agreement(embree.result, coop.result, samples, cg);
          fmt::print(
              "| {} pixel, {} | {:.5f} | {:.5f} | {:.5f} | {:.3f}% | {:.3f}% | {:.3f}% of {} | {} ({} + {}) "
              "| {:.3f} |\n",
              bilinear ? "bilinear" : "nearest", cosine ? "cos-corrected" : "along view", coop.stats.siad,
              coop.stats.usiad, coop.stats.std_signed, 100 * siad_error, 100 * usiad_err,
              100 * views.within_fraction(), views.resolved, cg.observations(), cg.views_rendered,
              cg.sample_cameras, coop.result.query_seconds);
          if (gated && bilinear && cosine)
            all_pass &= siad_error <= 0.01 && usiad_err <= 0.01 && views.within_fraction() >= 0.99;
        }
      }
      gl = GlMethodOptions{};
      gl.backend = parse_gl_backend(backend);
      fmt::print("\nEmbree: SiAD {:.5f}, USiAD {:.5f}, STD {:.5f}, {} no-hits.\n", embree.stats.siad,
                 embree.stats.usiad, embree.stats.std_signed, embree.stats.no_hit_count);
    }
    if (time_naive) {
      const TriangleMesh& test = pairs[1].test;
      const Run coop = run("cooperative", gl, test, samples, h);
      auto naive = make_method("v2p-naive");
      const DistanceResult n = measure_distances(*naive, test, samples, {Semantics::Closest, h});
      fmt::print(
          "\n## Speed, one run (bunny vs 10,459 triangles)\n\ncooperative 24x12: {:.3f} s (build {:.3f} + "
          "query "
          "{:.3f}); naive vertex-to-plane: {:.3f} s; ratio {:.1f}x (the paper: 38x).\n",
          coop.result.build_seconds + coop.result.query_seconds, coop.result.build_seconds,
          coop.result.query_seconds, n.build_seconds + n.query_seconds,
          (n.build_seconds + n.query_seconds) / (coop.result.build_seconds + coop.result.query_seconds));
    }
    fmt::print(
        "\nGates (exact roving vs Embree: same flag >= 99.9%, >= 99.5% within tolerance, USiAD within 0.2%; "
        "cooperative 24x12 bilinear + cos vs roving: SiAD and USiAD within 1% of USiAD, >= 99% of "
        "view-resolved "
        "samples within the view tolerance of Embree) on the gated pair: {}\n",
        all_pass ? "pass" : "FAIL");
    return all_pass ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "gl-accuracy: error: %s\n", e.what());
    return 2;
  }
}
