// Colour at a point of a triangle, and each sample's pair of colours.
#include "roving/core/colour.h"

#include <tbb/parallel_for.h>

#include <limits>

#include "roving/core/error.h"
#include "roving/core/geometry.h"

namespace roving {

Colour colour_on_face(const TriangleMesh& mesh, std::size_t face, const Vec3& point) {
  const Triangle& t = mesh.triangles()[face];
  const auto& p = mesh.positions();
  const Vec3 w = closest_on_triangle(point, p[t[0]], p[t[1]], p[t[2]]).weights;
  // In double, then rounded once: interpolating float colours in float drifted by 3e-5 of a step.
  Eigen::Vector3d colour = Eigen::Vector3d::Constant(255);
  if (const auto& c = mesh.vertex_colours(); !c.empty()) {
    colour = w[0] * c[t[0]].cast<double>() + w[1] * c[t[1]].cast<double>() + w[2] * c[t[2]].cast<double>();
  }
  if (const TextureMapping* mapping = mesh.texture_mapping()) {
    const Material& material = mapping->materials[mapping->face_material[face]];
    Eigen::Vector3d surface = material.factor.cast<double>();
    if (material.texture) {
      const TexCoord* uv = &mapping->corner_uv[3 * face];
      const TexCoord at = w[0] * uv[0] + w[1] * uv[1] + w[2] * uv[2];
      surface =
          surface.cwiseProduct(sample_texture(*material.texture, material.sampler, at).cast<double>()) / 255;
    }
    colour = colour.cwiseProduct(surface) / 255;
  }
  return colour.cast<float>();
}

namespace {

// A face each vertex belongs to (the lowest; -1 for none): where a vertex sample of a textured mesh
// takes its colour, a vertex on a texture seam having one coordinate per face.
std::vector<int> first_face_of_vertices(const TriangleMesh& mesh) {
  std::vector<int> face(mesh.vertex_count(), -1);
  for (std::size_t f = mesh.triangle_count(); f-- > 0;) {
    for (const int v : mesh.triangles()[f]) face[v] = static_cast<int>(f);
  }
  return face;
}

}  // namespace

std::vector<Colour> vertex_colours_by_rule(const TriangleMesh& mesh) {
  if (!mesh.texture_mapping()) return mesh.vertex_colours();
  const std::vector<int> face = first_face_of_vertices(mesh);
  std::vector<Colour> colours(mesh.vertex_count(), Colour::Constant(std::numeric_limits<float>::quiet_NaN()));
  tbb::parallel_for(std::size_t(0), mesh.vertex_count(), [&](std::size_t v) {
    if (face[v] >= 0) colours[v] = colour_on_face(mesh, face[v], mesh.positions()[v]);
  });
  return colours;
}

std::vector<Colour> sample_colours(const TriangleMesh& reference, const SampleSet& samples) {
  const bool vertex_samples = samples.kind == "vertices";
  const std::vector<int> vertex_face =
      vertex_samples && reference.texture_mapping() ? first_face_of_vertices(reference) : std::vector<int>();
  std::vector<Colour> colours(samples.size());
  tbb::parallel_for(std::size_t(0), samples.size(), [&](std::size_t k) {
    const Vec3& x = samples.positions[k];
    if (!vertex_samples) {
      colours[k] = colour_on_face(reference, samples.elements[k], x);
    } else if (vertex_face.empty()) {
      colours[k] = reference.vertex_colours()[samples.elements[k]];
    } else {
      colours[k] = colour_on_face(reference, vertex_face[samples.elements[k]], x);
    }
  });
  return colours;
}

ColourPairs colour_pairs(std::vector<Colour> reference, const SampleSet& samples, const TriangleMesh& test,
                         const DistanceResult& result, Semantics semantics) {
  ColourPairs pairs;
  pairs.reference = std::move(reference);
  if (result.hit_colour.size() == samples.size()) {
    pairs.test = result.hit_colour;
    for (std::size_t k = 0; k < samples.size(); ++k) {
      if (!result.hit[k]) pairs.test[k] = Colour::Constant(std::numeric_limits<float>::quiet_NaN());
    }
    return pairs;
  }
  if (result.hit_face.size() != samples.size()) {
    throw Error(
        "colour: the method gave no hit colours or faces; colour needs where each sample's line meets TEST");
  }
  pairs.test.assign(samples.size(), Colour::Constant(std::numeric_limits<float>::quiet_NaN()));
  tbb::parallel_for(std::size_t(0), samples.size(), [&](std::size_t k) {
    if (!result.hit[k]) return;
    const Vec3 at =
        correspondence_point(samples.positions[k], samples.normals[k], result.signed_distance[k], semantics);
    pairs.test[k] = colour_on_face(test, result.hit_face[k], at);
  });
  return pairs;
}

}  // namespace roving
