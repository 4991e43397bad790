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

#include "data_folder.h"
#include "accuracy_pairs.h"
#include "analytic.h"
#include "decimate.h"
#include "roving/core/normalise.h"
#include "roving/core/statistics.h"
#include "roving/formats/meshes/mesh_io.h"
#include "roving/gl_methods/agreement.h"
#include "roving/registry/method_registry.h"
#include "roving/representations/bezier_surface.h"
#include "roving/representations/model.h"

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

// The cooperative method's error on every kind of pair (the exactness issue): 4 shapes (open
// boundaries, sharp creases, genus 1, thin parts) x 4 kinds of test model x h in {2%, 5%}, each
// against Embree, with the default reading and with the cosine correction it replaced. Gate:
// USiAD and SiAD within 1% of the exact USiAD, no-hits within 1% of the exact count.
bool cooperative_matrix(const std::string& data, GlMethodOptions gl) {
  struct Shape {
    const char* label;
    TriangleMesh mesh;
  };
  Model teapot = load_model(data + "/teapot.bpt");
  std::vector<Shape> shapes;
  shapes.push_back({"bunny (open boundaries)", normalised(load_mesh(data + "/stanford-bunny.obj").mesh)});
  shapes.push_back({"Fandisk (sharp creases)", normalised(load_mesh(data + "/fandisk.obj").mesh)});
  shapes.push_back({"Rocker Arm (genus 1)", normalised(load_mesh(data + "/rocker-arm.obj").mesh)});
  shapes.push_back({"teapot, 32x32 per patch (thin handle and spout)",
                    normalised(tessellate(*teapot.bezier, 2e-3 * teapot.bounding_box().diagonal()).mesh)});
  fmt::print(
      "\n## The cooperative method on every kind of pair\n\n"
      "Each shape normalised (longest side 128), 20,000 samples uniform by area, against Embree (first-hit). "
      "Errors are |cooperative - exact| / exact USiAD; no-hits as exact / cooperative. `cos` is the paper's "
      "reading (along the view line, times cos(normal, view)), which the default replaced. Gate: USiAD and "
      "SiAD within 1%, no-hits within 1% of the exact count.\n\n"
      "| shape | test | h | exact USiAD | USiAD err | SiAD err | no-hits | observations (views + cameras) | "
      "`cos`: USiAD err | `cos`: SiAD err | `cos`: no-hits "
      "|\n|---|---|---|---|---|---|---|---|---|---|---|\n");
  bool pass = true;
  std::size_t pairs = 0, passed = 0, cos_passed = 0;
  for (const Shape& shape : shapes) {
    const SampleSet samples = make_samples(shape.mesh, parse_sample_spec("area:20000"));
    for (const TestVariant& variant : accuracy_variants(shape.mesh)) {
      for (const double fraction : {0.02, 0.05}) {
        const double h = fraction * shape.mesh.bounding_box().diagonal();
        const Run exact = run("embree", gl, variant.mesh, samples, h);
        gl.normal_line = true;
        const Run coop = run("cooperative", gl, variant.mesh, samples, h);
        gl.normal_line = false;
        const Run cos = run("cooperative", gl, variant.mesh, samples, h);
        gl.normal_line = true;
        const auto errors = [&](const Run& r) {
          return std::pair{std::abs(r.stats.usiad - exact.stats.usiad) / exact.stats.usiad,
                           std::abs(r.stats.siad - exact.stats.siad) / exact.stats.usiad};
        };
        const auto hits_ok = [&](const Run& r) {
          const double gap = std::abs(double(r.stats.no_hit_count) - double(exact.stats.no_hit_count));
          return gap <= 0.01 * exact.stats.no_hit_count;
        };
        const auto [usiad_err, siad_err] = errors(coop);
        const auto [cos_usiad, cos_siad] = errors(cos);
        const bool ok = usiad_err <= 0.01 && siad_err <= 0.01 && hits_ok(coop);
        ++pairs;
        passed += ok;
        cos_passed += cos_usiad <= 0.01 && cos_siad <= 0.01 && hits_ok(cos);
        pass &= ok;
        const GlReport& g = *coop.result.gl;
        fmt::print(
            "| {} | {} | {:.0f}% | {:.4f} | {:.3f}% | {:.3f}% | {} / {} | {} ({} + {}) | {:.3f}% | {:.3f}% | "
            "{} |{}\n",
            shape.label, variant.name, 100 * fraction, exact.stats.usiad, 100 * usiad_err, 100 * siad_err,
            exact.stats.no_hit_count, coop.stats.no_hit_count, g.observations(), g.views_rendered,
            g.sample_cameras, 100 * cos_usiad, 100 * cos_siad, cos.stats.no_hit_count, ok ? "" : " **over**");
      }
    }
  }
  fmt::print("\nWithin the gate: {} of {} pairs with the default reading, {} of {} with `cos`.\n", passed,
             pairs, cos_passed, pairs);
  return pass;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"gl-accuracy: GL methods against the exact references, full size"};
  std::string data = default_data_folder();
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
          "| cooperative 24x12, 1024 px | SiAD | USiAD | STD | \\|dSiAD\\| / USiAD_roving | \\|dUSiAD\\| / "
          "USiAD_roving | view-resolved within view tol. of Embree | observations (views + cameras) | "
          "query s |\n|---|---|---|---|---|---|---|---|---|\n");
      fmt::print("| exact roving | {:.5f} | {:.5f} | {:.5f} | | | | {} | {:.3f} |\n", roving.stats.siad,
                 roving.stats.usiad, roving.stats.std_signed, rg.observations(), roving.result.query_seconds);
      // The default reading (the normal line marched across the view) first, then the paper's
      // cosine correction and plain readings it replaced.
      struct Reading {
        const char* label;
        bool normal_line, bilinear, cosine;
      };
      for (const Reading& reading : {Reading{"normal line across the view (default)", true, true, true},
                                     Reading{"bilinear pixel, cos-corrected", false, true, true},
                                     Reading{"bilinear pixel, along view", false, true, false},
                                     Reading{"nearest pixel, cos-corrected", false, false, true},
                                     Reading{"nearest pixel, along view", false, false, false}}) {
        gl.normal_line = reading.normal_line;
        gl.bilinear = reading.bilinear;
        gl.cosine_correction = reading.cosine;
        const Run coop = run("cooperative", gl, test, samples, h);
        const GlReport& cg = *coop.result.gl;
        const double siad_error = std::abs(coop.stats.siad - roving.stats.siad) / roving.stats.usiad;
        const double usiad_err = std::abs(coop.stats.usiad - roving.stats.usiad) / roving.stats.usiad;
        const ViewAgreement views = view_agreement(embree.result, coop.result, samples, cg);
        fmt::print(
            "| {} | {:.5f} | {:.5f} | {:.5f} | {:.3f}% | {:.3f}% | {:.3f}% of {} | {} ({} + {}) | {:.3f} |\n",
            reading.label, coop.stats.siad, coop.stats.usiad, coop.stats.std_signed, 100 * siad_error,
            100 * usiad_err, 100 * views.within_fraction(), views.resolved, cg.observations(),
            cg.views_rendered, cg.sample_cameras, coop.result.query_seconds);
        if (gated && reading.normal_line)
          all_pass &= siad_error <= 0.01 && usiad_err <= 0.01 && views.within_fraction() >= 0.99;
      }
      gl = GlMethodOptions{};
      gl.backend = parse_gl_backend(backend);
      fmt::print("\nEmbree: SiAD {:.5f}, USiAD {:.5f}, STD {:.5f}, {} no-hits.\n", embree.stats.siad,
                 embree.stats.usiad, embree.stats.std_signed, embree.stats.no_hit_count);
    }
    all_pass &= cooperative_matrix(data, gl);
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
        "cooperative 24x12 (default reading) vs roving: SiAD and USiAD within 1% of USiAD, >= 99% of "
        "view-resolved "
        "samples within the view tolerance of Embree) on the gated pair, and the cooperative matrix above: "
        "{}\n",
        all_pass ? "pass" : "FAIL");
    return all_pass ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "gl-accuracy: error: %s\n", e.what());
    return 2;
  }
}
