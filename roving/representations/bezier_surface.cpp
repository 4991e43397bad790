// Bezier patches: exact evaluation, tessellation with a chordal bound, and samples.
#include "roving/representations/bezier_surface.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>

#include "roving/core/error.h"
#include "roving/core/memory_budget.h"

namespace roving {
namespace {

// Bernstein basis values and derivatives of degree n at t.
void bernstein(int n, double t, double* b, double* db) {
  double binomial = 1;
  for (int i = 0; i <= n; ++i) {
    b[i] = binomial * std::pow(t, i) * std::pow(1 - t, n - i);
    binomial = binomial * (n - i) / (i + 1);
  }
  // d/dt B_i^n = n (B_{i-1}^{n-1} - B_i^{n-1})
  double lower[17] = {};
  binomial = 1;
  for (int i = 0; i < n; ++i) {
    lower[i] = binomial * std::pow(t, i) * std::pow(1 - t, n - 1 - i);
    binomial = binomial * (n - 1 - i) / (i + 1);
  }
  for (int i = 0; i <= n; ++i) db[i] = n * ((i > 0 ? lower[i - 1] : 0.0) - (i < n ? lower[i] : 0.0));
}

// Bounds on |S_uu|, |S_uv|, |S_vv| over the patch from the control net's differences.
void second_derivative_bounds(const BezierPatch& p, double& uu, double& uv, double& vv) {
  uu = uv = vv = 0;
  const int m = p.degree_u, n = p.degree_v;
  for (int i = 0; i <= m; ++i)
    for (int j = 0; j <= n; ++j) {
      if (i + 2 <= m) uu = std::max(uu, (p.at(i + 2, j) - 2 * p.at(i + 1, j) + p.at(i, j)).norm());
      if (j + 2 <= n) vv = std::max(vv, (p.at(i, j + 2) - 2 * p.at(i, j + 1) + p.at(i, j)).norm());
      if (i + 1 <= m && j + 1 <= n)
        uv = std::max(uv, (p.at(i + 1, j + 1) - p.at(i + 1, j) - p.at(i, j + 1) + p.at(i, j)).norm());
    }
  uu *= m * (m - 1);
  vv *= n * (n - 1);
  uv *= m * n;
}

double chordal_bound(const BezierSurface& surface, int cells) {
  double bound = 0;
  const double d = 1.0 / cells;
  for (const BezierPatch& p : surface.patches) {
    double uu, uv, vv;
    second_derivative_bounds(p, uu, uv, vv);
    bound = std::max(bound, (d * d * uu + 2 * d * d * uv + d * d * vv) / 8);
  }
  return bound;
}

}  // namespace

void evaluate(const BezierPatch& patch, double u, double v, Vec3& point, Vec3& du, Vec3& dv) {
  double bu[17], dbu[17], bv[17], dbv[17];
  bernstein(patch.degree_u, u, bu, dbu);
  bernstein(patch.degree_v, v, bv, dbv);
  point = du = dv = Vec3::Zero();
  for (int i = 0; i <= patch.degree_u; ++i)
    for (int j = 0; j <= patch.degree_v; ++j) {
      point += bu[i] * bv[j] * patch.at(i, j);
      du += dbu[i] * bv[j] * patch.at(i, j);
      dv += bu[i] * dbv[j] * patch.at(i, j);
    }
}

Vec3 normal_at(const BezierPatch& patch, double u, double v) {
  Vec3 p, du, dv;
  // Step towards the patch centre until the tangents span a plane: at a collapsed edge the
  // normal is the limit of the neighbouring normals.
  for (double step : {0.0, 1e-7, 1e-5, 1e-3}) {
    const double uu = u + step * (0.5 - u > 0 ? 1 : -1), vv = v + step * (0.5 - v > 0 ? 1 : -1);
    evaluate(patch, uu, vv, p, du, dv);
    const Vec3 n = du.cross(dv);
    const double scale = du.squaredNorm() + dv.squaredNorm();
    if (n.norm() > 1e-10 * scale && n.allFinite()) return n.normalized();
  }
  return Vec3::Zero();
}

namespace {

// The 4 boundary curves of a patch as control-point sequences, each traversed counter-clockwise
// in (u, v), i.e. anticlockwise about du x dv.
std::array<std::vector<Vec3>, 4> boundary(const BezierPatch& p) {
  std::array<std::vector<Vec3>, 4> edges;
  const int m = p.degree_u, n = p.degree_v;
  for (int i = 0; i <= m; ++i) edges[0].push_back(p.at(i, 0));
  for (int j = 0; j <= n; ++j) edges[1].push_back(p.at(m, j));
  for (int i = m; i >= 0; --i) edges[2].push_back(p.at(i, n));
  for (int j = n; j >= 0; --j) edges[3].push_back(p.at(0, j));
  return edges;
}

void transpose(BezierPatch& p) {
  BezierPatch t;
  t.degree_u = p.degree_v;
  t.degree_v = p.degree_u;
  for (int j = 0; j <= p.degree_v; ++j)
    for (int i = 0; i <= p.degree_u; ++i) t.control.push_back(p.at(i, j));
  p = std::move(t);
}

bool same(const std::vector<Vec3>& a, const std::vector<Vec3>& b, double tolerance) {
  if (a.size() != b.size()) return false;
  for (std::size_t k = 0; k < a.size(); ++k) {
    if ((a[k] - b[k]).norm() > tolerance) return false;
  }
  return true;
}

}  // namespace

std::size_t orient_consistently(BezierSurface& surface) {
  const std::size_t count = surface.patches.size();
  BoundingBox box;
  for (const BezierPatch& p : surface.patches) {
    for (const Vec3& c : p.control) box.extend(c);
  }
  const double tolerance = 1e-9 * box.diagonal();
  std::vector<int> flip(count, -1);  // -1 unvisited, 0 keep, 1 flip
  std::size_t flipped = 0;
  for (std::size_t seed = 0; seed < count; ++seed) {
    if (flip[seed] >= 0) continue;
    flip[seed] = 0;
    std::vector<std::size_t> queue = {seed};
    while (!queue.empty()) {
      const std::size_t a = queue.back();
      queue.pop_back();
      BezierPatch pa = surface.patches[a];
      if (flip[a]) transpose(pa);
      for (auto edge : boundary(pa)) {
        if (same(std::vector<Vec3>(edge.size(), edge.front()), edge, tolerance)) continue;  // collapsed edge
        for (std::size_t b = 0; b < count; ++b) {
          if (b == a || flip[b] >= 0) continue;
          for (auto other : boundary(surface.patches[b])) {
            const bool along = same(edge, other, tolerance);
            std::reverse(other.begin(), other.end());
            const bool against = same(edge, other, tolerance);
            // Neighbours agree when they run their shared edge in opposite directions.
            if (along || against) {
              flip[b] = along ? 1 : 0;
              queue.push_back(b);
              break;
            }
          }
        }
      }
    }
  }
  for (std::size_t k = 0; k < count; ++k) {
    if (flip[k] == 1) transpose(surface.patches[k]), ++flipped;
  }
  // Outward: the flux of (x - centre) through the surface is positive for a closed outward shape.
  double flux = 0;
  const Vec3 centre = box.centre();
  for (const BezierPatch& p : surface.patches) {
    for (int i = 0; i < 8; ++i)
      for (int j = 0; j < 8; ++j) {
        Vec3 point, du, dv;
        evaluate(p, (i + 0.5) / 8, (j + 0.5) / 8, point, du, dv);
        flux += (point - centre).dot(du.cross(dv));
      }
  }
  if (flux < 0) {
    for (BezierPatch& p : surface.patches) transpose(p);
    flipped = count - flipped;
  }
  return flipped;
}

Tessellation tessellate(const BezierSurface& surface, double max_error) {
  if (!(max_error > 0))
    throw Error(fmt::format("tessellate: expected a chordal error bound > 0, found {}", max_error));
  Tessellation t;
  t.cells_per_side = 1;
  while (chordal_bound(surface, t.cells_per_side) > max_error && t.cells_per_side < 1024)
    t.cells_per_side *= 2;
  t.chordal_error_bound = chordal_bound(surface, t.cells_per_side);
  const int n = t.cells_per_side;
  // Every patch gets the resolution of the wiggliest (shared edges must meet), so one patch far
  // larger or wigglier than the rest multiplies the whole count: refuse before the work.
  const double triangle_count = 2.0 * n * n * double(surface.patches.size());
  if (triangle_count > kMaxTessellationTriangles) {
    throw Error(fmt::format(
        "tessellating {} patches with a chordal error below {:.3g} needs {}x{} cells per patch ({:.3g} "
        "triangles); at most {:.3g} are allowed (is one patch's control net far larger or wigglier than the "
        "rest?)",
        surface.patches.size(), max_error, n, n, triangle_count, double(kMaxTessellationTriangles)));
  }
  require_memory("tessellating Bezier patches", triangle_count * 100,
                 fmt::format("{:.3g} triangles", triangle_count));
  std::vector<Vec3> positions;
  std::vector<Triangle> triangles;
  for (const BezierPatch& p : surface.patches) {
    const int base = static_cast<int>(positions.size());
    for (int i = 0; i <= n; ++i)
      for (int j = 0; j <= n; ++j) {
        Vec3 point, du, dv;
        evaluate(p, double(i) / n, double(j) / n, point, du, dv);
        positions.push_back(point);
      }
    const auto at = [&](int i, int j) { return base + i * (n + 1) + j; };
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) {
        // Same winding as du x dv; a triangle collapsed at a degenerate corner is left out.
        const Triangle a = {at(i, j), at(i + 1, j), at(i + 1, j + 1)},
                       b = {at(i, j), at(i + 1, j + 1), at(i, j + 1)};
        for (const Triangle& tri : {a, b}) {
          const Vec3 cross =
              (positions[tri[1]] - positions[tri[0]]).cross(positions[tri[2]] - positions[tri[0]]);
          if (cross.norm() > 0) triangles.push_back(tri);
        }
      }
  }
  t.mesh = TriangleMesh(std::move(positions), std::move(triangles), "Bezier tessellation");
  return t;
}

SampleSet bezier_samples(const BezierSurface& surface, const SampleSpec& spec, int cells) {
  SampleSet samples;
  samples.kind = spec.to_string();
  const auto add = [&](std::size_t patch, double u, double v, double weight) {
    const BezierPatch& p = surface.patches[patch];
    const Vec3 n = normal_at(p, u, v);
    if (n.isZero()) {
      ++samples.skipped_degenerate_faces;
      return;
    }
    Vec3 point, du, dv;
    evaluate(p, u, v, point, du, dv);
    samples.positions.push_back(point);
    samples.normals.push_back(n);
    samples.weights.push_back(weight);
    samples.elements.push_back(static_cast<std::uint32_t>(patch));
  };
  if (spec.kind == SampleSpec::Kind::Area && spec.count == 0) {
    throw Error("--samples area:auto: the sample count is chosen by `roving measure` for --precision; give area:N here");
  }
  if (spec.kind == SampleSpec::Kind::Area) {
    require_memory("sampling", 85.0 * spec.count, fmt::format("{} samples", spec.count));
    // Patch by its (tessellated) area, then (u, v) uniform, accepted with probability
    // |S_u x S_v| / max: uniform by area on the exact surface.
    std::vector<double> cumulative, largest;
    double total = 0;
    for (const BezierPatch& p : surface.patches) {
      double area = 0, peak = 0;
      for (int i = 0; i < 16; ++i)
        for (int j = 0; j < 16; ++j) {
          Vec3 point, du, dv;
          evaluate(p, (i + 0.5) / 16, (j + 0.5) / 16, point, du, dv);
          const double element = du.cross(dv).norm();
          area += element / 256;
          peak = std::max(peak, element);
        }
      total += area;
      cumulative.push_back(total);
      largest.push_back(1.5 * peak);  // margin over the sampled peak
    }
    if (!(total > 0) || !std::isfinite(total)) {
      throw Error(fmt::format("--samples {}: the Bezier patches have no area to sample (total {})",
                              spec.to_string(), total));
    }
    std::mt19937_64 random(spec.seed);
    const auto uniform = [&random] { return (random() >> 11) * 0x1.0p-53; };
    // Acceptance is at least 1 / (1.5 * 256) per try; far more tries than that means a surface
    // whose area sits in a few spikes, which the bound cannot sample fairly.
    const double max_tries = 400.0 * spec.count + 1e6;
    double tries = 0;
    while (samples.size() < spec.count) {
      if (++tries > max_tries) {
        throw Error(
            fmt::format("--samples {}: gave up after {:.3g} tries with {} samples accepted: the patches' "
                        "area is too unevenly spread to sample by rejection",
                        spec.to_string(), tries, samples.size()));
      }
      const std::size_t k = std::min<std::size_t>(
          std::upper_bound(cumulative.begin(), cumulative.end(), uniform() * total) - cumulative.begin(),
          cumulative.size() - 1);
      const double u = uniform(), v = uniform();
      Vec3 point, du, dv;
      evaluate(surface.patches[k], u, v, point, du, dv);
      if (uniform() * largest[k] <= du.cross(dv).norm()) add(k, u, v, total / spec.count);
    }
    return samples;
  }
  const bool nodes = spec.kind == SampleSpec::Kind::Vertices;
  const double d = 1.0 / cells;
  for (std::size_t patch = 0; patch < surface.patches.size(); ++patch) {
    const BezierPatch& p = surface.patches[patch];
    for (int i = 0; i < cells + (nodes ? 1 : 0); ++i)
      for (int j = 0; j < cells + (nodes ? 1 : 0); ++j) {
        const double u = nodes ? i * d : (i + 0.5) * d, v = nodes ? j * d : (j + 0.5) * d;
        Vec3 point, du, dv;
        evaluate(p, u, v, point, du, dv);
        add(patch, u, v, du.cross(dv).norm() * d * d);
      }
  }
  if (samples.size() == 0) throw Error("Bezier surface gives no samples (every patch degenerate?)");
  return samples;
}

}  // namespace roving
