// A program outside the project, built against the installed package (find_package or
// pkg-config) by scripts/test-install.sh: the README's example.
#include <cstdio>

#include "roving/core/statistics.h"
#include "roving/formats/meshes/mesh_io.h"
#include "roving/registry/method_registry.h"

int main(int argc, char** argv) {
  if (argc != 3) return std::fprintf(stderr, "usage: consumer REF TEST\n"), 2;
  const roving::TriangleMesh reference = roving::load_mesh(argv[1]).mesh, test = roving::load_mesh(argv[2]).mesh;
  const roving::SampleSet samples = roving::make_samples(reference, {});  // face centroids
  const double h = 0.05 * reference.bounding_box().diagonal();
  const auto embree = roving::make_method("embree");
  const roving::DistanceResult result = roving::measure_distances(*embree, test, samples, {roving::Semantics::FirstHit, h});
  const roving::Statistics s = roving::compute_statistics(result.signed_distance, result.hit, samples.weights, h);
  std::printf("USiAD %.9g over %zu samples\n", s.usiad, s.sample_count);
}
