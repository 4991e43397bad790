// Exact reference distances by Embree ray casting and point queries (DESIGN.md "Definitions").
#include "reference_embree/embree_reference.h"

#include <cmath>
#include <limits>
#include <optional>

#include <embree3/rtcore.h>
#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "roving/error.h"
#include "roving/geometry.h"
#include "roving/stopwatch.h"

namespace roving {
namespace {

void embree_error(void* /*user*/, RTCError code, const char* message) {
  // Called from Embree's threads: remember nothing, the checks below turn codes into exceptions.
  (void)code;
  (void)message;
}

void check(RTCDevice device, const char* what) {
  const RTCError code = rtcGetDeviceError(device);
  if (code != RTC_ERROR_NONE) throw Error(fmt::format("embree: {} failed (error {})", what, int(code)));
}

struct PointQueryState {
  const TriangleMesh* mesh;
  Vec3 query;  // in mesh coordinates (double)
  Vec3 closest;
  double distance = std::numeric_limits<double>::infinity();
};

bool closest_point_callback(RTCPointQueryFunctionArguments* args) {
  auto* state = static_cast<PointQueryState*>(args->userPtr);
  const Triangle& t = state->mesh->triangles()[args->primID];
  const auto& p = state->mesh->positions();
  const Vec3 c = closest_point_on_triangle(state->query, p[t[0]], p[t[1]], p[t[2]]);
  const double distance = (c - state->query).norm();
  if (distance < state->distance) {
    state->distance = distance;
    state->closest = c;
    // Shrink the search sphere (in Embree's float, centred frame); pad so rounding never culls
    // the true closest triangle.
    args->query->radius = static_cast<float>(distance * (1 + 1e-6)) + 1e-30f;
    return true;
  }
  return false;
}

class EmbreeReference final : public DistanceMethod {
 public:
  EmbreeReference() {
    device_ = rtcNewDevice(nullptr);
    if (!device_) throw Error("embree: cannot create a device");
    rtcSetDeviceErrorFunction(device_, embree_error, nullptr);
  }
  ~EmbreeReference() override {
    if (scene_) rtcReleaseScene(scene_);
    rtcReleaseDevice(device_);
  }

  std::string name() const override { return "embree"; }
  std::vector<Semantics> supported_semantics() const override {
    return {Semantics::FirstHit, Semantics::Nearest, Semantics::Closest};
  }

  double build(const TriangleMesh& test) override {
    const Stopwatch watch;
    if (scene_) rtcReleaseScene(scene_);
    test_ = &test;
    // Embree stores float vertices: centre the model first so that float keeps ~1e-7 of the
    // diagonal wherever the model sits; queries are shifted by the same origin in double.
    origin_ = test.bounding_box().centre();
    diagonal_ = test.bounding_box().diagonal();

    scene_ = rtcNewScene(device_);
    rtcSetSceneFlags(scene_, RTC_SCENE_FLAG_ROBUST);
    rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_MEDIUM);
    RTCGeometry geometry = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(
        geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), test.vertex_count()));
    auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
        geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), test.triangle_count()));
    check(device_, "allocating geometry buffers");
    for (std::size_t v = 0; v < test.vertex_count(); ++v) {
      const Vec3 p = test.positions()[v] - origin_;
      vertices[3 * v + 0] = static_cast<float>(p.x());
      vertices[3 * v + 1] = static_cast<float>(p.y());
      vertices[3 * v + 2] = static_cast<float>(p.z());
    }
    for (std::size_t f = 0; f < test.triangle_count(); ++f) {
      for (int c = 0; c < 3; ++c) indices[3 * f + c] = static_cast<unsigned>(test.triangles()[f][c]);
    }
    rtcSetGeometryPointQueryFunction(geometry, closest_point_callback);
    rtcCommitGeometry(geometry);
    rtcAttachGeometry(scene_, geometry);
    rtcReleaseGeometry(geometry);
    rtcCommitScene(scene_);
    check(device_, "building the BVH");
    return watch.seconds();
  }

  DistanceResult measure(const SampleSet& samples, const DistanceOptions& options) override {
    if (!scene_) throw Error("embree: measure() called before build()");
    validate_options(*this, options);
    const Stopwatch watch;
    DistanceResult result;
    result.signed_distance.assign(samples.size(), 0.0);
    result.hit.assign(samples.size(), 0);
    const double h = options.max_error;
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, samples.size(), 256),
                      [&](const tbb::blocked_range<std::size_t>& range) {
      for (std::size_t k = range.begin(); k != range.end(); ++k) {
        const Vec3& x = samples.positions[k];
        const Vec3& n = samples.normals[k];
        std::optional<double> d;
        switch (options.semantics) {
          case Semantics::FirstHit: {
            // d = h - t for the first hit of the ray from x + h n along -n, t in [0, 2h].
            if (const auto t = first_hit(x + h * n, -n, 2 * h)) d = h - *t;
            break;
          }
          case Semantics::Nearest: d = nearest_on_line(x, n, h); break;
          case Semantics::Closest: d = closest_point(x, n); break;
        }
        if (d) {
          result.hit[k] = 1;
          result.signed_distance[k] = *d;
        }
      }
    });
    result.query_seconds = watch.seconds();
    return result;
  }

 private:
  // Distance t in [0, t_max] to the first triangle along origin + t * direction, if any.
  std::optional<double> first_hit(const Vec3& origin, const Vec3& direction, double t_max) const {
    if (auto t = cast(origin - origin_, direction, t_max)) return t;
    return cast_around(origin - origin_, direction, t_max);
  }

  std::optional<double> cast(const Vec3& origin, const Vec3& direction, double t_max) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRayHit rayhit;
    rayhit.ray.org_x = static_cast<float>(origin.x());
    rayhit.ray.org_y = static_cast<float>(origin.y());
    rayhit.ray.org_z = static_cast<float>(origin.z());
    rayhit.ray.dir_x = static_cast<float>(direction.x());
    rayhit.ray.dir_y = static_cast<float>(direction.y());
    rayhit.ray.dir_z = static_cast<float>(direction.z());
    rayhit.ray.tnear = 0.0f;
    rayhit.ray.tfar = static_cast<float>(t_max);
    rayhit.ray.time = 0.0f;
    rayhit.ray.mask = 0xFFFFFFFFu;  // Debian's Embree has ray masks on: mask 0 hits nothing
    rayhit.ray.id = 0;
    rayhit.ray.flags = 0;
    rayhit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rayhit.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(scene_, &context, &rayhit);
    if (rayhit.hit.geomID == RTC_INVALID_GEOMETRY_ID) return std::nullopt;
    // Recompute t in double against the hit triangle's plane: Embree's float t carries the
    // rounding of the float origin; the plane is exact for the triangle we know was hit.
    return plane_distance(rayhit.hit.primID, origin, direction, t_max);
  }

  // The re-cast of a missed ray: four parallel rays offset across it; the triangles they hit
  // are intersected with the original line. Finds what an edge or vertex crossing lost.
  std::optional<double> cast_around(const Vec3& origin, const Vec3& direction, double t_max) const {
    const Vec3 helper = std::abs(direction.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
    const Vec3 e1 = direction.cross(helper).normalized();
    const Vec3 e2 = direction.cross(e1);
    const double offset = 1e-6 * diagonal_;
    std::optional<double> best;
    for (const Vec3& shift : {Vec3(offset * e1), Vec3(-offset * e1), Vec3(offset * e2), Vec3(-offset * e2)}) {
      RTCIntersectContext context;
      rtcInitIntersectContext(&context);
      RTCRayHit rayhit{};
      const Vec3 o = origin + shift;
      rayhit.ray.org_x = float(o.x()), rayhit.ray.org_y = float(o.y()), rayhit.ray.org_z = float(o.z());
      rayhit.ray.dir_x = float(direction.x()), rayhit.ray.dir_y = float(direction.y());
      rayhit.ray.dir_z = float(direction.z());
      rayhit.ray.tnear = 0.0f;
      rayhit.ray.tfar = static_cast<float>(t_max * (1 + 1e-6));
      rayhit.ray.mask = 0xFFFFFFFFu;
      rayhit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
      rtcIntersect1(scene_, &context, &rayhit);
      if (rayhit.hit.geomID == RTC_INVALID_GEOMETRY_ID) continue;
      if (const auto t = plane_distance(rayhit.hit.primID, origin, direction, t_max)) {
        if (!best || *t < *best) best = t;
      }
    }
    return best;
  }

  // t where origin + t * direction meets the plane of triangle `face` (centred frame), clamped
  // into [0, t_max] when rounding put it just outside; nullopt for a parallel ray.
  std::optional<double> plane_distance(unsigned face, const Vec3& origin, const Vec3& direction,
                                       double t_max) const {
    const Triangle& t = test_->triangles()[face];
    const auto& p = test_->positions();
    const Vec3 a = p[t[0]] - origin_;
    const Vec3 normal = (p[t[1]] - p[t[0]]).cross(p[t[2]] - p[t[0]]);
    const double denominator = normal.dot(direction);
    if (denominator == 0) return std::nullopt;
    const double hit_t = normal.dot(a - origin) / denominator;
    // Float traversal may accept a hit a few ulps beyond [0, t_max]; the double plane may then
    // fall a hair outside. Beyond 1e-6 of t_max it is a genuine out-of-range hit.
    if (hit_t < -1e-6 * t_max || hit_t > t_max * (1 + 1e-6)) return std::nullopt;
    return std::clamp(hit_t, 0.0, t_max);
  }

  // Signed distance to the intersection of the line x + s n nearest to x, |s| <= h: one ray each
  // way, both starting a hair behind x so that a crossing at x itself is seen by both.
  std::optional<double> nearest_on_line(const Vec3& x, const Vec3& n, double h) const {
    const double behind = 1e-6 * h;
    std::optional<double> outward, inward;
    if (const auto t = first_hit(x - behind * n, n, h + behind)) outward = *t - behind;
    if (const auto t = first_hit(x + behind * n, -n, h + behind)) inward = behind - *t;
    if (outward && inward) return std::abs(*inward) < std::abs(*outward) ? inward : outward;
    return outward ? outward : inward;
  }

  double closest_point(const Vec3& x, const Vec3& n) const {
    PointQueryState state{test_, x, x};
    RTCPointQuery query;
    const Vec3 centred = x - origin_;
    query.x = static_cast<float>(centred.x());
    query.y = static_cast<float>(centred.y());
    query.z = static_cast<float>(centred.z());
    query.time = 0.0f;
    query.radius = std::numeric_limits<float>::infinity();
    RTCPointQueryContext context;
    rtcInitPointQueryContext(&context);
    rtcPointQuery(scene_, &query, &context, nullptr, &state);
    return signed_offset(x, n, state.closest);
  }

  RTCDevice device_ = nullptr;
  RTCScene scene_ = nullptr;
  const TriangleMesh* test_ = nullptr;
  Vec3 origin_ = Vec3::Zero();
  double diagonal_ = 1;
};

}  // namespace

std::unique_ptr<DistanceMethod> make_embree_reference() { return std::make_unique<EmbreeReference>(); }

}  // namespace roving
