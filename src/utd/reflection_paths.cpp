// The geometric part of the UTD paths (utd/paths.h): first-order specular reflections, and the reflections
// a listener on a shadow or reflection boundary sees at half strength.
#include <algorithm>
#include <cmath>
#include <vector>

#include "path_util.h"

namespace diffray::utd {

using core::Vec3;
using detail::insideTriangle;
using detail::reflectionPath;

int UtdModel::triangleAt(int plane, const Vec3& p) const {
  for (int t : geometry_.planes()[plane].triangles) {
    if (opening_[room_.mesh.object_of_triangle[t]]) continue;
    const auto& v = room_.mesh.triangles[t];
    if (insideTriangle(p, room_.mesh.vertices[v[0]], room_.mesh.vertices[v[1]], room_.mesh.vertices[v[2]])) return t;
  }
  return -1;
}

bool UtdModel::crossesSurfaceAt(const transport::MirrorPlane& reflecting, const Vec3& p, const Vec3& s,
                                const Vec3& r) const {
  const double tol = offsetAt(p);
  const auto& planes = geometry_.planes();
  for (std::size_t k = 0; k < planes.size(); ++k) {
    const auto& other = planes[k];
    if (&other == &reflecting) continue;
    const double dp = other.normal.dot(p) - other.offset;
    const double ds = other.normal.dot(s) - other.offset, dr = other.normal.dot(r) - other.offset;
    if (std::abs(dp) > tol || !(ds * dr < 0.0) || std::abs(ds) <= tol || std::abs(dr) <= tol) continue;
    if (triangleAt(static_cast<int>(k), p) >= 0) return true;
  }
  return false;
}

bool UtdModel::onEdge(const Vec3& p) const {
  const double tol = offsetAt(p);
  for (const Edge& e : edges_) {
    const Vec3 d = e.end - e.start;
    const double t = std::clamp((p - e.start).dot(d) / d.squaredNorm(), 0.0, 1.0);
    if ((e.start + t * d - p).norm() <= tol) return true;
  }
  return false;
}

void UtdModel::addReflections(const Vec3& s, const Vec3& r, std::vector<Path>& out) const {
  const auto& planes = geometry_.planes();
  for (std::size_t k = 0; k < planes.size(); ++k) {
    const auto& pl = planes[k];
    double ds = pl.normal.dot(s) - pl.offset, dr = pl.normal.dot(r) - pl.offset;
    // A point within the offset of the plane is on it: its image coincides with it (on a rigid plane the
    // field doubles there, the limit of the two paths as the height goes to 0). Only points farther than
    // the offset on opposite sides have no reflection.
    const bool s_on = std::abs(ds) < offsetAt(s), r_on = std::abs(dr) < offsetAt(r);
    if (!s_on && !r_on && !(ds * dr > 0.0)) continue;
    const double side = std::abs(ds) >= std::abs(dr) ? (ds >= 0.0 ? 1.0 : -1.0) : (dr >= 0.0 ? 1.0 : -1.0);
    if (!s_on && side * ds < 0.0) continue;
    if (!r_on && side * dr < 0.0) continue;
    ds = side * std::max(side * ds, 0.0);  // a point a little behind the plane is taken as on it
    dr = side * std::max(side * dr, 0.0);
    const Vec3 s_c = s - (pl.normal.dot(s) - pl.offset - ds) * pl.normal;
    const Vec3 r_c = r - (pl.normal.dot(r) - pl.offset - dr) * pl.normal;
    const Vec3 image = s_c - 2.0 * ds * pl.normal;
    const Vec3 p = ds + dr != 0.0 ? Vec3(image + (r_c - image) * (ds / (ds + dr))) : Vec3(0.5 * (s_c + r_c));
    const int tri = triangleAt(static_cast<int>(k), p);
    if (tri < 0) continue;
    if (crossesSurfaceAt(pl, p, s, r)) continue;
    // Visibility only: the reflection point and any point on the plane are lifted by the offset into the air.
    const Vec3 lift = side * offsetAt(p) * pl.normal;
    const Vec3 lifted = p + lift;
    if (!visible(s_on ? Vec3(s_c - ds * pl.normal + lift) : s, lifted) ||
        !visible(lifted, r_on ? Vec3(r_c - dr * pl.normal + lift) : r))
      continue;
    out.push_back(reflectionPath(tri, s, p, r, (r_c - image).norm(), 1.0));
  }
}

void UtdModel::halveReflection(int e, int face, const Vec3& s, const Vec3& r, std::vector<Path>& out) const {
  const Edge& edge = edges_[e];
  const int face_tri = face == 0 ? edge.triangle0 : edge.trianglen;
  const Vec3& normal = face == 0 ? edge.normal0 : edge.normaln;
  if (face_tri < 0) return;
  const int plane = geometry_.triangle(face_tri).plane;
  for (Path& p : out) {
    if (p.kind == PathKind::Reflection && geometry_.triangle(p.triangle).plane == plane) {
      p.gain = 0.5;
      return;
    }
  }
  // The triangle test missed the reflection point, which lies on the edge: add the path, with the face's
  // triangle for its material. The listener sees the image of s in the face plane through the edge.
  const double ds = normal.dot(s - edge.start), dr = normal.dot(r - edge.start);
  if (!(ds + dr > 0.0)) return;  // both on the face's plane: no distinct reflection
  const Vec3 image = s - 2.0 * ds * normal;
  const Vec3 q = image + (r - image) * (ds / (ds + dr));
  out.push_back(reflectionPath(face_tri, s, q, r, (r - image).norm(), 0.5));
}

void UtdModel::halvePlaneReflection(int plane, int triangle, const Vec3& s, const Vec3& r, std::vector<Path>& out) const {
  for (Path& p : out) {
    if (p.kind == PathKind::Reflection && geometry_.triangle(p.triangle).plane == plane) {
      p.gain = 0.5;
      return;
    }
  }
  // The visibility test of the reflection grazing the edge went the other way: add it at half strength.
  const auto& pl = geometry_.planes()[plane];
  const double ds = std::abs(detail::signedDistance(pl, s)), dr = std::abs(detail::signedDistance(pl, r));
  if (!(ds + dr > 0.0)) return;
  const Vec3 image = detail::mirror(pl, s);
  const Vec3 q = image + (r - image) * (ds / (ds + dr));
  out.push_back(reflectionPath(triangle, s, q, r, (r - image).norm(), 0.5));
}

}  // namespace diffray::utd
