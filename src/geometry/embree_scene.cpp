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
  native_packet16_ = rtcGetDeviceProperty(device_, RTC_DEVICE_PROPERTY_NATIVE_RAY16_SUPPORTED) != 0;
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

namespace {
// Lanes [first, first + W) of a packet as Embree's W-wide packet, traced with rtcIntersectW. The coherent
// hint picks Embree's traversal for rays of similar origin and direction, as a packet of one source's rays
// is (it changes the speed, not the hits): 0.69–0.72 → 0.83 on the transport bench (tools/README.md).
template <int W, typename RayHitW, typename IntersectW>
void tracePacketLanes(RTCScene scene, const RayPacket& rays, int first, const std::vector<int>& object_of_triangle,
                      HitPacket& hits, IntersectW intersect) {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
  alignas(64) RayHitW rh;
  for (int i = 0; i < W; ++i) {
    const int l = first + i;
    rh.ray.org_x[i] = rays.org_x[l];
    rh.ray.org_y[i] = rays.org_y[l];
    rh.ray.org_z[i] = rays.org_z[l];
    rh.ray.dir_x[i] = rays.dir_x[l];
    rh.ray.dir_y[i] = rays.dir_y[l];
    rh.ray.dir_z[i] = rays.dir_z[l];
    rh.ray.tnear[i] = rays.tnear[l];
    rh.ray.tfar[i] = std::numeric_limits<float>::infinity();
    rh.ray.time[i] = 0.0f;
    rh.ray.mask[i] = 0xFFFFFFFFu;
    rh.ray.id[i] = 0;
    rh.ray.flags[i] = 0;
    rh.hit.geomID[i] = RTC_INVALID_GEOMETRY_ID;
  }
  intersect(rays.active + first, scene, &context, &rh);
  for (int i = 0; i < W; ++i) {
    const bool hit = rh.hit.geomID[i] != RTC_INVALID_GEOMETRY_ID;
    hits.t[first + i] = rh.ray.tfar[i];
    hits.object[first + i] = hit ? object_of_triangle[rh.hit.primID[i]] : -1;
  }
}
}  // namespace

void EmbreeScene::intersectPacket(const RayPacket& rays, HitPacket& hits) const {
  if (native_packet16_)
    tracePacketLanes<16, RTCRayHit16>(scene_, rays, 0, object_of_triangle_, hits, rtcIntersect16);
  else
    intersectPacketBy8(rays, hits);
}

void EmbreeScene::intersectPacketBy8(const RayPacket& rays, HitPacket& hits) const {
  static_assert(RayPacket::kSize == 16, "a packet is two rtcIntersect8 halves or one rtcIntersect16");
  for (int first = 0; first < RayPacket::kSize; first += 8)
    tracePacketLanes<8, RTCRayHit8>(scene_, rays, first, object_of_triangle_, hits, rtcIntersect8);
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
