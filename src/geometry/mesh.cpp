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

}  // namespace diffray::geometry
