#pragma once
// Triangle geometry shared by every intersector. A Mesh is a soup of triangles, each tagged with the
// scene object (surface) it belongs to. Coordinates are metres in the world frame, stored in double;
// intersectors may use float internally but report ray distances that callers refine in double.
// Plain data: not synchronised, build it once and then share it read-only.
#include <array>
#include <vector>

#include "diffray/core/math.h"

namespace diffray::geometry {

using core::Vec3;

struct Mesh {
  std::vector<Vec3> vertices;
  std::vector<std::array<int, 3>> triangles;
  std::vector<int> object_of_triangle;  ///< scene object index of each triangle

  /// Adds the rectangle centre ± half_x ± half_y (two triangles) for object `object`.
  void addRect(const Vec3& centre, const Vec3& half_x, const Vec3& half_y, int object);
  std::size_t triangleCount() const { return triangles.size(); }
};

/// The parameter t at which the line o + t·d meets triangle abc, edges included (Möller–Trumbore in
/// double), or NaN if it misses it or lies in its plane (|det| < 1e-300). t may be negative.
double rayTriangleT(const Vec3& o, const Vec3& d, const Vec3& a, const Vec3& b, const Vec3& c);

/// A ray in double precision. Directions need not be normalised for intersection, but diffray's
/// transport always passes unit directions so that t is a distance in metres.
struct Ray {
  Vec3 origin;
  Vec3 dir;
  double tnear = 0.0;
  double tfar = 1e300;
};

/// The nearest hit along a ray: object < 0 means the ray escaped.
struct Hit {
  double t = 0.0;
  int triangle = -1;
  int object = -1;
  bool valid() const { return object >= 0; }
};

/// Up to kPacket rays in float, structure-of-arrays, as Embree's packet API takes them. Lanes with
/// active = 0 are ignored.
struct RayPacket {
  static constexpr int kSize = 16;
  alignas(64) float org_x[kSize], org_y[kSize], org_z[kSize];
  alignas(64) float dir_x[kSize], dir_y[kSize], dir_z[kSize];
  alignas(64) float tnear[kSize];
  alignas(64) int active[kSize];  ///< −1 active, 0 inactive (Embree's valid mask)
};

/// The nearest hit of each lane: object < 0 where the ray escaped; t is Embree's (float) distance.
struct HitPacket {
  float t[RayPacket::kSize];
  int object[RayPacket::kSize];
};

/// Anything that finds the nearest hit. Implementations are thread-safe for concurrent intersect().
class Intersector {
 public:
  virtual ~Intersector() = default;
  virtual Hit intersect(const Ray& ray) const = 0;
  /// Nearest hits of a packet's active lanes. The default loops over intersect(); Embree traces the
  /// packet at once.
  virtual void intersectPacket(const RayPacket& rays, HitPacket& hits) const;
};

}  // namespace diffray::geometry
