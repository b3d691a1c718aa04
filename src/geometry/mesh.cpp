#include "diffray/geometry/mesh.h"

#include <cmath>
#include <limits>

namespace diffray::geometry {

double rayTriangleT(const Vec3& o, const Vec3& d, const Vec3& a, const Vec3& b, const Vec3& c) {
  constexpr double kMiss = std::numeric_limits<double>::quiet_NaN();
  const Vec3 e1 = b - a, e2 = c - a, p = d.cross(e2);
  const double det = e1.dot(p);
  if (std::abs(det) < 1e-300) return kMiss;
  const double inv = 1.0 / det;
  const Vec3 s = o - a;
  const double u = s.dot(p) * inv;
  if (u < 0.0 || u > 1.0) return kMiss;
  const Vec3 q = s.cross(e1);
  const double v = d.dot(q) * inv;
  if (v < 0.0 || u + v > 1.0) return kMiss;
  return e2.dot(q) * inv;
}

void Mesh::addRect(const Vec3& centre, const Vec3& half_x, const Vec3& half_y, int object) {
  const int base = static_cast<int>(vertices.size());
  vertices.push_back(centre - half_x - half_y);
  vertices.push_back(centre + half_x - half_y);
  vertices.push_back(centre + half_x + half_y);
  vertices.push_back(centre - half_x + half_y);
  triangles.push_back({base, base + 1, base + 2});
  triangles.push_back({base, base + 2, base + 3});
  object_of_triangle.push_back(object);
  object_of_triangle.push_back(object);
}

void Intersector::intersectPacket(const RayPacket& rays, HitPacket& hits) const {
  for (int i = 0; i < RayPacket::kSize; ++i) {
    if (!rays.active[i]) continue;
    Ray r{Vec3(rays.org_x[i], rays.org_y[i], rays.org_z[i]), Vec3(rays.dir_x[i], rays.dir_y[i], rays.dir_z[i]),
          rays.tnear[i], 1e300};
    const Hit h = intersect(r);
    hits.t[i] = static_cast<float>(h.t);
    hits.object[i] = h.object;
  }
}

}  // namespace diffray::geometry
