#include "diffray/geometry/mesh.h"

namespace diffray::geometry {

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
