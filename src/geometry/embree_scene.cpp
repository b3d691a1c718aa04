#include "diffray/geometry/embree_scene.h"

#include <limits>
#include <string>

#include "diffray/core/error.h"

namespace diffray::geometry {

namespace {
void embreeError(void*, RTCError code, const char* message) {
  // Embree calls this from inside its API; turning it into an exception here would unwind through C
  // frames, so remember the message and let the caller check rtcGetDeviceError.
  (void)code;
  (void)message;
}

void throwIfError(RTCDevice device, const char* what) {
  const RTCError err = rtcGetDeviceError(device);
  if (err != RTC_ERROR_NONE)
    throw core::InternalError(std::string("Embree error ") + std::to_string(static_cast<int>(err)) + " in " +
                              what);
}
}  // namespace

EmbreeScene::EmbreeScene(const Mesh& mesh) : object_of_triangle_(mesh.object_of_triangle) {
  device_ = rtcNewDevice(nullptr);
  if (!device_) throw core::InternalError("cannot create an Embree device");
  rtcSetDeviceErrorFunction(device_, embreeError, nullptr);
  scene_ = rtcNewScene(device_);
  rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_HIGH);

  RTCGeometry geom = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
  auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0,
                                                                RTC_FORMAT_FLOAT3, 3 * sizeof(float),
                                                                mesh.vertices.size()));
  auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0,
                                                                 RTC_FORMAT_UINT3, 3 * sizeof(unsigned),
                                                                 mesh.triangles.size()));
  throwIfError(device_, "buffer allocation");
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i)
    for (int c = 0; c < 3; ++c) vertices[3 * i + c] = static_cast<float>(mesh.vertices[i][c]);
  for (std::size_t i = 0; i < mesh.triangles.size(); ++i)
    for (int c = 0; c < 3; ++c) indices[3 * i + c] = static_cast<unsigned>(mesh.triangles[i][c]);
  rtcCommitGeometry(geom);
  rtcAttachGeometry(scene_, geom);
  rtcReleaseGeometry(geom);
  rtcCommitScene(scene_);
  throwIfError(device_, "scene build");
}

EmbreeScene::~EmbreeScene() {
  if (scene_) rtcReleaseScene(scene_);
  if (device_) rtcReleaseDevice(device_);
}

Hit EmbreeScene::intersect(const Ray& ray) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit rh = makeRayHit(ray.origin, ray.dir, ray.tnear, ray.tfar);
  rtcIntersect1(scene_, &context, &rh);
  Hit hit;
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return hit;
  hit.t = rh.ray.tfar;
  hit.triangle = static_cast<int>(rh.hit.primID);
  hit.object = object_of_triangle_[rh.hit.primID];
  return hit;
}

void EmbreeScene::intersectPacket(const RayPacket& rays, HitPacket& hits) const {
  static_assert(RayPacket::kSize == 8, "EmbreeScene::intersectPacket uses rtcIntersect8");
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  alignas(32) RTCRayHit8 rh;
  for (int i = 0; i < 8; ++i) {
    rh.ray.org_x[i] = rays.org_x[i];
    rh.ray.org_y[i] = rays.org_y[i];
    rh.ray.org_z[i] = rays.org_z[i];
    rh.ray.dir_x[i] = rays.dir_x[i];
    rh.ray.dir_y[i] = rays.dir_y[i];
    rh.ray.dir_z[i] = rays.dir_z[i];
    rh.ray.tnear[i] = rays.tnear[i];
    rh.ray.tfar[i] = std::numeric_limits<float>::infinity();
    rh.ray.time[i] = 0.0f;
    rh.ray.mask[i] = 0xFFFFFFFFu;
    rh.ray.id[i] = 0;
    rh.ray.flags[i] = 0;
    rh.hit.geomID[i] = RTC_INVALID_GEOMETRY_ID;
  }
  rtcIntersect8(rays.active, scene_, &context, &rh);
  for (int i = 0; i < 8; ++i) {
    const bool hit = rh.hit.geomID[i] != RTC_INVALID_GEOMETRY_ID;
    hits.t[i] = rh.ray.tfar[i];
    hits.object[i] = hit ? object_of_triangle_[rh.hit.primID[i]] : -1;
  }
}

Hit BruteForceScene::intersect(const Ray& ray) const {
  Hit best;
  double best_t = ray.tfar;
  for (std::size_t i = 0; i < mesh_.triangles.size(); ++i) {
    const auto& tri = mesh_.triangles[i];
    const double t = rayTriangleT(ray.origin, ray.dir, mesh_.vertices[tri[0]], mesh_.vertices[tri[1]],
                                  mesh_.vertices[tri[2]]);
    if (!(t >= ray.tnear && t < best_t)) continue;  // a miss (NaN) too
    best_t = t;
    best.t = t;
    best.triangle = static_cast<int>(i);
    best.object = mesh_.object_of_triangle[i];
  }
  return best;
}

}  // namespace diffray::geometry
