// libFuzzer harness for the closest-point kernel: the bytes choose adversarial triangles (equal and
// collinear corners, needles, caps, slivers; tests/adversarial_pairs.h), their scale and offset, and
// points near them; roving::closest_on_triangle's distance must be within its stated bound of the
// exact rational oracle's (tests/exact_oracle.h). A discrepancy aborts: a finding.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "../adversarial_pairs.h"
#include "../exact_oracle.h"
#include "roving/core/geometry.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  roving::adversarial::Choices choose(data, size);
  std::string kind;
  auto t = roving::adversarial::triangle(choose, kind);
  const double scale = std::pow(10.0, 6 * (choose.below(3) - 1));
  const roving::Vec3 offset = choose.below(2) ? roving::Vec3(1e6, -1e6, 3e5) : roving::Vec3::Zero();
  for (roving::Vec3& v : t) v = v * scale + offset;
  while (!choose.exhausted()) {
    const roving::Vec3 p = t[choose.below(3)] + scale * std::pow(10.0, -choose.below(15)) * choose.vector();
    const roving::TrianglePoint found = roving::closest_on_triangle(p, t[0], t[1], t[2]);
    double m = p.cwiseAbs().maxCoeff();
    for (const roving::Vec3& v : t) m = std::max(m, v.cwiseAbs().maxCoeff());
    const double exact = roving::oracle::distance(roving::oracle::squared_distance(p, t[0], t[1], t[2]));
    const double error = std::abs((found.point - p).norm() - exact);
    if (!(error <= roving::closest_point_error_bound(m)) || !(found.weights.minCoeff() >= 0)) {
      std::fprintf(stderr, "%s: distance %.17g, exact %.17g, weights %g %g %g\n", kind.c_str(), (found.point - p).norm(),
                   exact, found.weights.x(), found.weights.y(), found.weights.z());
      std::abort();
    }
  }
  return 0;
}
