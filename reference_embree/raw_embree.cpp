// Embree's own triangle BVH and queries, without the shared rule (roving/core/raw_queries.h).
#include <embree3/rtcore.h>

#include <cmath>
#include <limits>

#include "embree_queries.h"
#include "roving/core/error.h"
#include "roving/core/raw_queries.h"
#include "roving/reference_embree/embree_reference.h"

namespace roving {
namespace {

// Triangle geometry, robust traversal, vertices centred as the reference centres them.
struct EmbreeScene {
  RTCDevice device = rtcNewDevice(nullptr);
  RTCScene scene = nullptr;
  Vec3 origin = Vec3::Zero();
  const TriangleMesh* mesh = nullptr;
  ~EmbreeScene() {
    if (scene) rtcReleaseScene(scene);
    rtcReleaseDevice(device);
  }
};

struct ClosestState {
  const TriangleMesh* mesh;
  Vec3 query;
  double distance = std::numeric_limits<double>::infinity();
};

bool closest_callback(RTCPointQueryFunctionArguments* args) {
  auto* state = static_cast<ClosestState*>(args->userPtr);
  const Triangle& t = state->mesh->triangles()[args->primID];
  const auto& p = state->mesh->positions();
  const double distance =
      (closest_point_on_triangle(state->query, p[t[0]], p[t[1]], p[t[2]]) - state->query).norm();
  if (!(distance < state->distance)) return false;
  state->distance = distance;
  args->query->radius = static_cast<float>(distance);
  return true;
}

void build_embree(EmbreeScene& s, const TriangleMesh& test) {
  if (!s.device) throw Error("embree: cannot create a device");
  s.mesh = &test;
  s.origin = test.bounding_box().centre();
  s.scene = rtcNewScene(s.device);
  rtcSetSceneFlags(s.scene, RTC_SCENE_FLAG_ROBUST);
  rtcSetSceneBuildQuality(s.scene, RTC_BUILD_QUALITY_MEDIUM);
  RTCGeometry geometry = rtcNewGeometry(s.device, RTC_GEOMETRY_TYPE_TRIANGLE);
  auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(
      geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), test.vertex_count()));
  auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
      geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), test.triangle_count()));
  if (!vertices || !indices) throw Error("embree: cannot allocate the triangle buffers");
  for (std::size_t v = 0; v < test.vertex_count(); ++v) {
    const Vec3 p = test.positions()[v] - s.origin;
    for (int c = 0; c < 3; ++c) vertices[3 * v + c] = static_cast<float>(p[c]);
  }
  for (std::size_t f = 0; f < test.triangle_count(); ++f)
    for (int c = 0; c < 3; ++c) indices[3 * f + c] = test.triangles()[f][c];
  rtcSetGeometryPointQueryFunction(geometry, closest_callback);
  rtcCommitGeometry(geometry);
  rtcAttachGeometry(s.scene, geometry);
  rtcReleaseGeometry(geometry);
  rtcCommitScene(s.scene);
  if (rtcGetDeviceError(s.device) != RTC_ERROR_NONE) throw Error("embree: building the triangle BVH failed");
}

// The distance along `direction` from `from` (model coordinates) to the first triangle, within
// `length`; infinity for none.
double cast(const EmbreeScene& s, const Vec3& from, const Vec3& direction, double length) {
  const Vec3 o = from - s.origin;
  RTCRayHit rayhit;
  rayhit.ray.org_x = static_cast<float>(o.x());
  rayhit.ray.org_y = static_cast<float>(o.y());
  rayhit.ray.org_z = static_cast<float>(o.z());
  rayhit.ray.dir_x = static_cast<float>(direction.x());
  rayhit.ray.dir_y = static_cast<float>(direction.y());
  rayhit.ray.dir_z = static_cast<float>(direction.z());
  rayhit.ray.tnear = 0.0f;
  rayhit.ray.tfar = static_cast<float>(length);
  rayhit.ray.time = 0.0f;
  rayhit.ray.mask = 0xFFFFFFFFu;  // Debian's Embree has ray masks on
  rayhit.ray.id = 0;
  rayhit.ray.flags = 0;
  rayhit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rayhit.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  rtcIntersect1(s.scene, &context, &rayhit);
  return rayhit.hit.geomID == RTC_INVALID_GEOMETRY_ID ? std::numeric_limits<double>::infinity()
                                                      : rayhit.ray.tfar;
}

}  // namespace

RawRun raw_embree_queries(const TriangleMesh& test, const SampleSet& samples, Semantics semantics, double h) {
  RawRun run;
  EmbreeScene scene;
  const Stopwatch build;
  build_embree(scene, test);
  run.build_seconds = build.seconds();
  time_raw_queries(
      run, samples, semantics, h,
      [&](const Vec3& from, const Vec3& direction, double length) {
        return cast(scene, from, direction, length);
      },
      [&](const Vec3& x) {
        ClosestState state{&test, x};
        RTCPointQuery query = point_query(x - scene.origin, std::numeric_limits<float>::infinity());
        RTCPointQueryContext context;
        rtcInitPointQueryContext(&context);
        rtcPointQuery(scene.scene, &query, &context, nullptr, &state);
        return state.distance;
      });
  return run;
}

}  // namespace roving
