// Internal: the shared measuring loop of the closest-point baselines (nearest vertex / nearest
// point of the triangles); each baseline supplies only its nearest-point search.
#pragma once

#include <string>

#include "roving/core/colour.h"
#include "roving/core/distance_method.h"
#include "roving/core/error.h"
#include "roving/core/geometry.h"
#include "roving/core/stopwatch.h"

namespace roving {

class ClosestPointBaseline : public DistanceMethod {
 public:
  std::vector<Semantics> supported_semantics() const override { return {Semantics::Closest}; }

  // Colour: where the nearest element is a face, that face (the colour rule then takes TEST's
  // colour at its nearest point, which is the one found); where it is a vertex, that vertex's
  // colour by the rule (colour.h). Faces (hit_face) only where the nearest element is a face.
  DistanceResult measure(const SampleSet& samples, const DistanceOptions& options) override {
    if (!built_) throw Error(name() + ": measure() called before build()");
    validate_options(*this, options);
    // A nearest point always exists: every sample is a hit.
    std::vector<std::uint32_t> vertex;
    const bool by_vertex = options.colour && test_->has_colour() && nearest_is_a_vertex();
    if (by_vertex) {
      vertex.resize(samples.size());
      index_vertices();
    }
    DistanceResult result = measure_each(
        samples.size(),
        [&](std::size_t k) {
          const Vec3& x = samples.positions[k];
          const Nearest n = nearest(x);
          if (by_vertex) vertex[k] = n.element;
          return std::optional<FaceHit>(FaceHit{signed_offset(x, samples.normals[k], n.point), n.element});
        },
        progress_, (options.colour || options.faces) && !nearest_is_a_vertex());
    if (by_vertex) {
      const std::vector<Colour> colours = vertex_colours_by_rule(*test_);
      result.hit_colour.resize(samples.size());
      for (std::size_t k = 0; k < samples.size(); ++k) result.hit_colour[k] = colours[vertex[k]];
      result.colour_source = "at the nearest vertex";
    }
    return result;
  }

 protected:
  // The nearest point of TEST and the element it is: a vertex's or a face's index in TEST.
  struct Nearest {
    Vec3 point;
    std::uint32_t element;
  };
  virtual Nearest nearest(const Vec3& x) const = 0;
  virtual bool nearest_is_a_vertex() const = 0;
  // Makes what nearest() needs to name its vertex, where that costs memory a plain run should not
  // pay (the k-d tree's point-to-index map).
  virtual void index_vertices() {}
  bool built_ = false;
  const TriangleMesh* test_ = nullptr;  // set by build()
};

// The AABB-tree closest-point method under the baseline's name (cgal_reference.cpp).
std::unique_ptr<DistanceMethod> make_accelerated_vertex_to_plane();

}  // namespace roving
