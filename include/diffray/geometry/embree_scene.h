#pragma once
// The Embree 3 back end: an RAII device and scene built once from a Mesh (one triangle geometry).
// intersect() calls rtcIntersect1 with an RTCIntersectContext and is thread-safe. Embree works in float:
// callers that need more than ~1e-7 relative precision (every WBSDF hit does, design.md §1) recompute the
// hit point in double from the object's plane. Errors reported by Embree's callback become InternalError.
#include <embree3/rtcore.h>

#include "diffray/geometry/mesh.h"

namespace diffray::geometry {

class EmbreeScene : public Intersector {
 public:
  explicit EmbreeScene(const Mesh& mesh);
  ~EmbreeScene() override;
  EmbreeScene(const EmbreeScene&) = delete;
  EmbreeScene& operator=(const EmbreeScene&) = delete;

  Hit intersect(const Ray& ray) const override;
  /// rtcIntersect8 (Embree's packet traversal, faster for the coherent rays of one source).
  void intersectPacket(const RayPacket& rays, HitPacket& hits) const override;

  RTCScene handle() const { return scene_; }  ///< for benchmarks that call rtcIntersect1 directly

 private:
  RTCDevice device_ = nullptr;
  RTCScene scene_ = nullptr;
  std::vector<int> object_of_triangle_;
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
