#include "diffray/room/room.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "diffray/core/error.h"

namespace diffray::room {
namespace {

// Twice the signed area of the polygon's projection on the plane with normal `n` at corner (a, b, c).
double cornerSign(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& n) { return (b - a).cross(c - b).dot(n); }

bool insideTriangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& n) {
  return (b - a).cross(p - a).dot(n) >= 0.0 && (c - b).cross(p - b).dot(n) >= 0.0 &&
         (a - c).cross(p - c).dot(n) >= 0.0;
}

// Whether 2D segments pq and rs intersect (touching counts), by orientation signs.
bool segmentsMeet(const double p[2], const double q[2], const double r[2], const double s[2]) {
  const auto orient = [](const double a[2], const double b[2], const double c[2]) {
    const double v = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
    return (v > 0) - (v < 0);
  };
  const auto within = [](const double a[2], const double b[2], const double c[2]) {  // c on segment ab
    return std::min(a[0], b[0]) <= c[0] && c[0] <= std::max(a[0], b[0]) && std::min(a[1], b[1]) <= c[1] &&
           c[1] <= std::max(a[1], b[1]);
  };
  const int o1 = orient(p, q, r), o2 = orient(p, q, s), o3 = orient(r, s, p), o4 = orient(r, s, q);
  if (o1 != o2 && o3 != o4) return true;
  return (o1 == 0 && within(p, q, r)) || (o2 == 0 && within(p, q, s)) || (o3 == 0 && within(r, s, p)) ||
         (o4 == 0 && within(r, s, q));
}

// Checks that a polygon with unit normal n is planar and simple (no two non-adjacent edges meet),
// which ear clipping assumes but would not notice.
void requireSimplePlanar(const std::vector<Vec3>& v, const Vec3& n, const std::string& group) {
  double extent = 0.0;
  for (const auto& p : v) extent = std::max(extent, (p - v[0]).norm());
  for (const auto& p : v)
    if (std::abs((p - v[0]).dot(n)) > 1e-6 * extent)
      throw core::InputError(group, "the polygon is not planar");
  // Project on the coordinate plane most nearly parallel to the polygon.
  int drop = 0;
  for (int i = 1; i < 3; ++i)
    if (std::abs(n[i]) > std::abs(n[drop])) drop = i;
  const int a = (drop + 1) % 3, b = (drop + 2) % 3;
  std::vector<std::array<double, 2>> q(v.size());
  for (std::size_t i = 0; i < v.size(); ++i) q[i] = {v[i][a], v[i][b]};
  const std::size_t m = v.size();
  for (std::size_t i = 0; i < m; ++i)
    for (std::size_t j = i + 2; j < m; ++j) {
      if (i == 0 && j == m - 1) continue;  // adjacent through the closing edge
      if (segmentsMeet(q[i].data(), q[(i + 1) % m].data(), q[j].data(), q[(j + 1) % m].data()))
        throw core::InputError(group, "the polygon is self-intersecting (edges " + std::to_string(i + 1) + " and " +
                                          std::to_string(j + 1) + " meet)");
    }
}

}  // namespace

void Room::addBox(const Vec3& lo, const Vec3& hi, const int material_of_wall[6], const std::string& group) {
  for (int i = 0; i < 3; ++i)
    if (!(hi[i] > lo[i])) throw core::InputError(group, "box: every extent must be positive");
  const Vec3 c = 0.5 * (lo + hi), h = 0.5 * (hi - lo);
  const Vec3 ex(1, 0, 0), ey(0, 1, 0), ez(0, 0, 1);
  const std::string names[6] = {"x-", "x+", "y-", "y+", "floor", "ceiling"};
  // Walls as centre ± half_x ± half_y with half_x × half_y pointing into the room.
  const Vec3 centre[6] = {c - h.x() * ex, c + h.x() * ex, c - h.y() * ey, c + h.y() * ey, c - h.z() * ez, c + h.z() * ez};
  const Vec3 half_x[6] = {h.y() * ey, h.z() * ez, h.z() * ez, h.x() * ex, h.x() * ex, h.y() * ey};
  const Vec3 half_y[6] = {h.z() * ez, h.y() * ey, h.x() * ex, h.z() * ez, h.y() * ey, h.x() * ex};
  for (int w = 0; w < 6; ++w) {
    if (material_of_wall[w] < 0 || material_of_wall[w] >= static_cast<int>(materials.size()))
      throw core::InternalError("Room::addBox: material index out of range");
    mesh.addRect(centre[w], half_x[w], half_y[w], material_of_wall[w]);
    group_of_triangle.resize(mesh.triangles.size(), group + "/" + names[w]);
  }
}

void Room::addPolygon(const std::vector<Vec3>& vertices, int material, const std::string& group) {
  if (vertices.size() < 3) throw core::InputError(group, "a polygon needs at least 3 vertices");
  if (material < 0 || material >= static_cast<int>(materials.size()))
    throw core::InternalError("Room::addPolygon: material index out of range");
  // Newell's normal: robust for non-convex polygons, zero for degenerate ones.
  Vec3 n(0, 0, 0);
  for (std::size_t i = 0; i < vertices.size(); ++i) n += vertices[i].cross(vertices[(i + 1) % vertices.size()]);
  if (!(n.norm() > 1e-12)) {
    // A bow-tie's two halves cancel in Newell's normal: report it as self-intersecting, which it is, when the
    // vertices span a plane at all.
    Vec3 best(0, 0, 0);
    for (std::size_t i = 1; i < vertices.size(); ++i)
      for (std::size_t j = i + 1; j < vertices.size(); ++j) {
        const Vec3 c = (vertices[i] - vertices[0]).cross(vertices[j] - vertices[0]);
        if (c.norm() > best.norm()) best = c;
      }
    if (best.norm() > 1e-12) requireSimplePlanar(vertices, best.normalized(), group);
    throw core::InputError(group, "the polygon has no area (collinear or repeated vertices)");
  }
  n.normalize();
  requireSimplePlanar(vertices, n, group);
  // Ear clipping, O(n²) per ear: polygons in scene files are small.
  std::vector<int> idx(vertices.size());
  const int base = static_cast<int>(mesh.vertices.size());
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    idx[i] = static_cast<int>(i);
    mesh.vertices.push_back(vertices[i]);
  }
  while (idx.size() > 3) {
    bool clipped = false;
    for (std::size_t i = 0; i < idx.size() && !clipped; ++i) {
      const int ia = idx[(i + idx.size() - 1) % idx.size()], ib = idx[i], ic = idx[(i + 1) % idx.size()];
      const Vec3 &a = vertices[ia], &b = vertices[ib], &cc = vertices[ic];
      if (cornerSign(a, b, cc, n) <= 0.0) continue;  // reflex or degenerate corner
      bool empty = true;
      for (int j : idx)
        if (j != ia && j != ib && j != ic && insideTriangle(vertices[j], a, b, cc, n)) empty = false;
      if (!empty) continue;
      mesh.triangles.push_back({base + ia, base + ib, base + ic});
      mesh.object_of_triangle.push_back(material);
      group_of_triangle.push_back(group);
      idx.erase(idx.begin() + static_cast<std::ptrdiff_t>(i));
      clipped = true;
    }
    if (!clipped) throw core::InputError(group, "the polygon is self-intersecting or not planar");
  }
  mesh.triangles.push_back({base + idx[0], base + idx[1], base + idx[2]});
  mesh.object_of_triangle.push_back(material);
  group_of_triangle.push_back(group);
}

bool Room::isOpening(int m) const {
  for (int b = 0; b < bands.size(); ++b)
    if (materials[m].transmission[b] < 1.0) return false;
  return true;
}

std::vector<char> Room::enclosure() const {
  std::vector<char> all(mesh.triangles.size(), 1), walls(mesh.triangles.size(), 1);
  Vec3 area_all(0, 0, 0), area_walls(0, 0, 0);
  bool any_opening = false;
  for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
    const auto& t = mesh.triangles[i];
    const Vec3 a = 0.5 * (mesh.vertices[t[1]] - mesh.vertices[t[0]]).cross(mesh.vertices[t[2]] - mesh.vertices[t[0]]);
    area_all += a;
    if (isOpening(mesh.object_of_triangle[i])) {
      walls[i] = 0;
      any_opening = true;
    } else {
      area_walls += a;
    }
  }
  if (!any_opening) return all;
  return area_walls.norm() <= area_all.norm() ? walls : all;
}

double Room::volume() const {
  const std::vector<char> bounding = enclosure();
  double v6 = 0.0;
  for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
    if (!bounding[i]) continue;
    const auto& t = mesh.triangles[i];
    v6 += mesh.vertices[t[0]].dot(mesh.vertices[t[1]].cross(mesh.vertices[t[2]]));
  }
  return std::abs(v6) / 6.0;
}

double Room::surfaceArea() const {
  double a = 0.0;
  for (const auto& t : mesh.triangles)
    a += 0.5 * (mesh.vertices[t[1]] - mesh.vertices[t[0]]).cross(mesh.vertices[t[2]] - mesh.vertices[t[0]]).norm();
  return a;
}

}  // namespace diffray::room
