#pragma once
// The Embree 3 back end: an RAII device and scene built once from a Mesh (one triangle geometry).
// intersect() calls rtcIntersect1 with an RTCIntersectContext, intersectPacket() Embree's 16- or 8-wide
// packets; both are thread-safe. Embree works in float: callers that need more than ~1e-7 relative precision
// (every WBSDF hit does) recompute the hit point in double from the object's plane. Errors
// reported by Embree's callback become InternalError.
#include <embree3/rtcore.h>

#include <limits>

#include "diffray/geometry/mesh.h"

namespace diffray::geometry {

/// Points an RTCRayHit anew: origin and direction in float, tfar = ∞, no hit. rtcIntersect1 writes only
/// tfar and the hit, so a ray from makeRayHit can be re-aimed so along a path (its tnear, time, mask, id and
/// flags stay as made).
inline void aimRayHit(RTCRayHit& rh, const core::Vec3& origin, const core::Vec3& dir) {
  rh.ray.org_x = static_cast<float>(origin.x());
  rh.ray.org_y = static_cast<float>(origin.y());
  rh.ray.org_z = static_cast<float>(origin.z());
  rh.ray.dir_x = static_cast<float>(dir.x());
  rh.ray.dir_y = static_cast<float>(dir.y());
  rh.ray.dir_z = static_cast<float>(dir.z());
  rh.ray.tfar = std::numeric_limits<float>::infinity();
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
}

/// An RTCRayHit ready for rtcIntersect1: the ray in float, no hit yet. Inline: hot loops call Embree
/// directly (transport/room_tracer.cpp) as well as through EmbreeScene::intersect.
inline RTCRayHit makeRayHit(const core::Vec3& origin, const core::Vec3& dir, double tnear, double tfar) {
  RTCRayHit rh;
  aimRayHit(rh, origin, dir);
  rh.ray.tnear = static_cast<float>(tnear);
  if (!(tfar > 3e38)) rh.ray.tfar = static_cast<float>(tfar);
  rh.ray.time = 0.0f;
  rh.ray.mask = 0xFFFFFFFFu;
  rh.ray.id = 0;
  rh.ray.flags = 0;
  return rh;
}

class EmbreeScene : public Intersector {
 public:
  explicit EmbreeScene(const Mesh& mesh);
  ~EmbreeScene() override;
  EmbreeScene(const EmbreeScene&) = delete;
  EmbreeScene& operator=(const EmbreeScene&) = delete;

  Hit intersect(const Ray& ray) const override;
  /// Embree's packet traversal, faster than single rays for the coherent rays of one source: one
  /// rtcIntersect16 where Embree traces 16-wide packets natively (AVX-512), else intersectPacketBy8.
  void intersectPacket(const RayPacket& rays, HitPacket& hits) const override;
  /// The packet as two rtcIntersect8 halves (public so tests cover it on any CPU).
  void intersectPacketBy8(const RayPacket& rays, HitPacket& hits) const;
  bool nativePacket16() const { return native_packet16_; }

  RTCScene handle() const { return scene_; }  ///< for benchmarks that call rtcIntersect1 directly

 private:
  RTCDevice device_ = nullptr;
  RTCScene scene_ = nullptr;
  std::vector<int> object_of_triangle_;
  bool native_packet16_ = false;
};

/// Reference back end for tests: loops over every triangle (Möller–Trumbore, double precision).
class BruteForceScene : public Intersector {
 public:
  explicit BruteForceScene(Mesh mesh) : mesh_(std::move(mesh)) {}
  Hit intersect(const Ray& ray) const override;

 private:
  Mesh mesh_;
};

}  // namespace diffray::geometry
