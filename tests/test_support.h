// Shared helpers of the test suites: where the real models are, and small closed-form meshes.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "data_folder.h"
#include "roving/core/error.h"
#include "roving/core/sample_set.h"
#include "roving/core/triangle_mesh.h"
#include "roving/formats/meshes/mesh_io.h"
#include "roving/gl/depth_renderer.h"

namespace roving::testing {

// Under AddressSanitizer (scripts/test-sanitizers.sh: every allocation checked, 10-20x slower where
// the exact fallbacks and the GL methods allocate) the slowest tests run a lighter variant of the
// same checks, on fewer models, cases or samples, each saying what it leaves to the Release suite,
// which runs them whole.
#ifdef __SANITIZE_ADDRESS__
constexpr bool kUnderSanitizers = true;
#else
constexpr bool kUnderSanitizers = false;
#endif

// Under the sanitizers at most `at_most` of the samples, evenly spread over the set (their weights
// scaled to keep the total area); all of them otherwise. The code paths are the same; the
// per-sample checks over the whole set are the Release suite's.
inline SampleSet lighter_under_sanitizers(SampleSet samples, std::size_t at_most) {
  if (!kUnderSanitizers || samples.size() <= at_most) return samples;
  SampleSet kept;
  kept.kind = samples.kind;
  const double scale = static_cast<double>(samples.size()) / static_cast<double>(at_most);
  for (std::size_t k = 0; k < at_most; ++k) {
    const std::size_t from = k * samples.size() / at_most;
    kept.positions.push_back(samples.positions[from]);
    kept.normals.push_back(samples.normals[from]);
    if (!samples.weights.empty()) kept.weights.push_back(samples.weights[from] * scale);
    if (!samples.elements.empty()) kept.elements.push_back(samples.elements[from]);
  }
  return kept;
}

// Path of a real model in $ROVING_DATA or the checkout's data/. A test that needs one fails
// (never skips) when the folder lacks it: CI must not pass without the data.
inline std::string data_file(const std::string& name) {
  const std::filesystem::path folder = default_data_folder();
  const auto path = folder / name;
  if (!std::filesystem::exists(path)) {
    throw std::runtime_error("test data '" + name + "' not found in " + folder.string() +
                             ": set ROVING_DATA to the folder holding the real models");
  }
  return path.string();
}

// The bunny, loaded once per test binary.
inline const TriangleMesh& bunny() {
  static const TriangleMesh mesh = load_mesh(data_file("stanford-bunny.obj")).mesh;
  return mesh;
}

// Axis-aligned box [-s, s]^3 centred at the origin, 12 outward-facing triangles.
inline TriangleMesh box(double s) {
  std::vector<Vec3> p;
  for (int i = 0; i < 8; ++i) p.emplace_back(i & 1 ? s : -s, i & 2 ? s : -s, i & 4 ? s : -s);
  const std::vector<Triangle> t = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                                   {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  return TriangleMesh(std::move(p), t);
}

}  // namespace roving::testing

namespace roving::testing {
// True under CI (CI=true), where a missing GL context is a failure, never a skip.
inline bool under_ci() {
  const char* ci = std::getenv("CI");
  return ci && std::string(ci) == "true";
}
}  // namespace roving::testing

// GL tests skip, with the reason, only where no context can be made at all; under CI a missing
// context is a failure.
#define REQUIRE_GL_CONTEXT(backend)                                                                       \
  do {                                                                                                    \
    try {                                                                                                 \
      ::roving::make_depth_renderer(backend);                                                             \
    } catch (const ::roving::Error& e) {                                                                  \
      if (::roving::testing::under_ci()) FAIL() << "no GL context under CI: " << e.what();                \
      GTEST_SKIP() << "no " << ::roving::to_string(backend) << " context can be made here: " << e.what(); \
    }                                                                                                     \
  } while (0)
