// Internal: closest points on a triangle mesh by Embree's BVH, distances in double; shared by the
// certified bounds (certified_hausdorff.cpp, certified_area_within.cpp).
#pragma once

#include <embree3/rtcore.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>

#include "roving/core/error.h"
#include "roving/core/geometry.h"
#include "roving/core/triangle_mesh.h"
#include "embree_queries.h"

namespace roving {

// Closest points on a triangle mesh by Embree's BVH over its triangles' boxes.
class ClosestPoints {
 public:
  explicit ClosestPoints(const TriangleMesh& mesh) : mesh_(mesh) {
    origin_ = mesh.bounding_box().centre();
    pad_ = 1e-6 * mesh.bounding_box().diagonal() + 1e-30;
    device_ = rtcNewDevice(nullptr);
    if (!device_) throw Error("embree: cannot create a device");
    scene_ = rtcNewScene(device_);
    RTCGeometry geometry = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_USER);
    rtcSetGeometryUserPrimitiveCount(geometry, static_cast<unsigned>(mesh.triangle_count()));
    rtcSetGeometryUserData(geometry, this);
    rtcSetGeometryBoundsFunction(geometry, bounds, this);
    rtcSetGeometryPointQueryFunction(geometry, visit);
    rtcCommitGeometry(geometry);
    rtcAttachGeometry(scene_, geometry);
    rtcReleaseGeometry(geometry);
    rtcCommitScene(scene_);
    if (rtcGetDeviceError(device_) != RTC_ERROR_NONE) throw Error("embree: building the BVH for closest points failed");
  }
  ~ClosestPoints() {
    rtcReleaseScene(scene_);
    rtcReleaseDevice(device_);
  }
  ClosestPoints(const ClosestPoints&) = delete;
  ClosestPoints& operator=(const ClosestPoints&) = delete;

  struct Found {
    double distance = std::numeric_limits<double>::infinity();
    Vec3 point = Vec3::Zero();
    std::uint32_t triangle = 0;
  };

  Found query(const Vec3& x) const {
    State state{this, x, {}};
    RTCPointQuery query = point_query(x - origin_, std::numeric_limits<float>::infinity());
    RTCPointQueryContext context;
    rtcInitPointQueryContext(&context);
    rtcPointQuery(scene_, &query, &context, nullptr, &state);
    return state.found;
  }

  // The distance from x to triangle `t` of the mesh, in double.
  double distance_to(const Vec3& x, std::uint32_t t) const {
    const Triangle& tri = mesh_.triangles()[t];
    const auto& p = mesh_.positions();
    return (closest_point_on_triangle(x, p[tri[0]], p[tri[1]], p[tri[2]]) - x).norm();
  }

 private:
  struct State {
    const ClosestPoints* self;
    Vec3 query;
    Found found;
  };

  static void bounds(const RTCBoundsFunctionArguments* args) {
    const auto* self = static_cast<const ClosestPoints*>(args->geometryUserPtr);
    const Triangle& t = self->mesh_.triangles()[args->primID];
    const auto& p = self->mesh_.positions();
    const Vec3 low = p[t[0]].cwiseMin(p[t[1]]).cwiseMin(p[t[2]]) - self->origin_ - Vec3::Constant(self->pad_);
    const Vec3 high = p[t[0]].cwiseMax(p[t[1]]).cwiseMax(p[t[2]]) - self->origin_ + Vec3::Constant(self->pad_);
    write_bounds(low, high, args->bounds_o);
  }

  static bool visit(RTCPointQueryFunctionArguments* args) {
    auto* state = static_cast<State*>(args->userPtr);
    const Triangle& t = state->self->mesh_.triangles()[args->primID];
    const auto& p = state->self->mesh_.positions();
    const double distance = state->self->distance_to(state->query, args->primID);
    if (distance >= state->found.distance) return false;
    state->found = {distance, closest_point_on_triangle(state->query, p[t[0]], p[t[1]], p[t[2]]), args->primID};
    // Shrink the search sphere, padded so that float rounding never culls the true closest.
    args->query->radius = static_cast<float>(distance * (1 + 1e-6) + state->self->pad_);
    return true;
  }

  const TriangleMesh& mesh_;
  Vec3 origin_;
  double pad_;
  RTCDevice device_ = nullptr;
  RTCScene scene_ = nullptr;
};

}  // namespace roving
