#include "diffray/transport/image_sources.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

#include "diffray/core/error.h"
#include "diffray/transport/room_tracer.h"

namespace diffray::transport {

using core::Vec3;

namespace {

struct Validator {
  const room::Room& room;
  const RoomGeometry& geometry;
  std::vector<char> opening;  ///< per material: transmits everything
  const std::vector<char>* blocking = nullptr;  ///< per triangle: blocks even if an opening

  // First hit along from → from + dist·dir that is not an opening: its triangle and distance, or −1.
  int firstSurface(const Vec3& from, const Vec3& dir, double max_t, double& t_out) const {
    const double eps = 1e-7 * geometry.extent();
    double t0 = eps;
    for (int guard = 0; guard < 64; ++guard) {
      const geometry::Hit hit = geometry.intersector().intersect(geometry::Ray{from, dir, t0, max_t});
      if (!hit.valid()) return -1;
      double t = geometry.planeDistance(hit.triangle, from, dir);
      if (!(t > 0.0 && t < 1e300)) t = hit.t;
      if (!opening[geometry.triangle(hit.triangle).material] || (blocking && (*blocking)[hit.triangle])) {
        t_out = t;
        return hit.triangle;
      }
      t0 = t + eps;
    }
    return -1;
  }

  // A reflecting triangle of mirror plane `plane` holding point p (within `tol` of it), or −1.
  int triangleOn(int plane, const Vec3& p, double tol) const {
    for (int tri : geometry.planes()[plane].triangles) {
      if (opening[geometry.triangle(tri).material] && !(blocking && (*blocking)[tri])) continue;  // no mirror
      const auto& t = room.mesh.triangles[tri];
      if (insideTriangle(p, room.mesh.vertices[t[0]], room.mesh.vertices[t[1]], room.mesh.vertices[t[2]], tol)) return tri;
    }
    return -1;
  }

  // Traces the candidate back from the listener; on success fills the reflection points' triangles.
  // A reflection point on an edge between two mirror planes (the path meets both at once: in a box, at a
  // listener whose line to the image passes through a room edge) is accepted for each plane: the path is
  // the limit of the valid paths on either side of the edge, which the rays leave to the image sources
  // too. Its two plane orders give the same image; imageSources() keeps one.
  bool validate(const Vec3& source, const Vec3& listener, const std::vector<int>& planes,
                const std::vector<Vec3>& images, std::vector<int>& triangles, Vec3& first_leg_dir) const {
    const double tol = 1e-6 * geometry.extent();
    Vec3 x = listener;
    triangles.assign(planes.size(), -1);
    std::vector<Vec3> path(planes.size() + 2);  // source, the reflection points in order, listener
    path.front() = source;
    path.back() = listener;
    std::vector<int> here;  // the planes reflected at x so far: each once (A, B, A at one edge point is A∘B∘A = B)
    for (int k = static_cast<int>(planes.size()) - 1; k >= 0; --k) {
      const MirrorPlane& pl = geometry.planes()[planes[k]];
      const Vec3 to_image = images[k] - x;
      const double denom = pl.normal.dot(to_image);
      if (std::abs(denom) < 1e-300) return false;
      const double s = (pl.offset - pl.normal.dot(x)) / denom;  // crossing at x + s·to_image
      const double len = to_image.norm();
      if (!(s * len > -tol && s < 1.0)) return false;
      if (s * len <= tol) {  // x, the previous reflection point, is on this plane too: an edge
        if (std::find(here.begin(), here.end(), planes[k]) != here.end()) return false;
        const int tri = triangleOn(planes[k], x, tol);
        if (tri < 0) return false;
        triangles[k] = tri;
        path[k + 1] = x;
        here.push_back(planes[k]);
        continue;
      }
      const Vec3 dir = to_image / len;
      double t;
      const int hit = firstSurface(x, dir, s * len + tol, t);
      if (hit >= 0 && t < s * len - tol) return false;  // blocked before the plane
      // Usually the surface hit is this plane's. At an edge it may be a neighbour's at the same point, or
      // the float ray may slip between the two: then the crossing point decides.
      const int tri = hit >= 0 && geometry.triangle(hit).plane == planes[k] ? hit
                                                                            : triangleOn(planes[k], x + s * to_image, tol);
      if (tri < 0) return false;
      triangles[k] = tri;
      x += s * to_image;
      path[k + 1] = x;
      here.assign(1, planes[k]);
    }
    const Vec3 to_source = source - x;
    const double dist = to_source.norm();
    if (!(dist > tol)) return false;
    double t;
    const int blocker = firstSurface(x, to_source / dist, dist - tol, t);
    if (blocker >= 0) return false;
    first_leg_dir = -to_source / dist;  // leaving the source
    return !blockedUnseen(path, planes, tol);
  }

  // Whether a surface blocks the path where the intersector cannot see it. The intersector misses a
  // crossing at a leg's end, so a reflection point on the edge of a surface whose plane the path crosses
  // right there passes unseen: a side wall's reflection where a partition meets that wall, a floor
  // reflection at a door's sill, a jamb reflection in a door's plane (the source and the listener
  // mirror-symmetric about the partition). Such a point blocks when it lies in the surface (edges included,
  // within tol) and the surface stands on the reflection's air side: it then blocks the paths on either
  // side of this one, which is their limit. A surface behind the mirror (a convex corner's other face)
  // leaves the path the limit of valid ones on one side, and it stays. A blocking opening (the WBSDF's
  // occluders, whose triangles are no mirrors for the rays' sake) blocks wherever a leg crosses it, edges
  // included. `path` holds the source, the reflection points (path[k + 1] on plane k) and the listener.
  bool blockedUnseen(const std::vector<Vec3>& path, const std::vector<int>& planes, double tol) const {
    for (std::size_t tri = 0; tri < room.mesh.triangles.size(); ++tri) {
      const bool masked = blocking && (*blocking)[tri];
      const TrianglePlane& tp = geometry.triangle(static_cast<int>(tri));
      if (opening[tp.material] && !masked) continue;
      const auto& tv = room.mesh.triangles[tri];
      const Vec3 &a = room.mesh.vertices[tv[0]], &b = room.mesh.vertices[tv[1]], &c = room.mesh.vertices[tv[2]];
      const Vec3& n = tp.normal;
      int side = 0;  // the side of the last point off the plane
      for (std::size_t i = 0; i < path.size(); ++i) {
        const double d = n.dot(path[i] - a);
        if (std::abs(d) <= tol) {  // on the plane: a crossing there if the path goes on to the other side
          if (side == 0 || i == 0 || i + 1 == path.size() || !onOtherSide(path, i, n, a, side, tol) ||
              !insideTriangle(path[i], a, b, c, tol))
            continue;
          const Vec3& mirror = geometry.planes()[planes[i - 1]].normal;  // path[i] is reflection i − 1
          const double front = mirror.dot(path[i - 1] - path[i]), centre = mirror.dot((a + b + c) / 3.0 - path[i]);
          if (masked || front * centre > 0.0) return true;
          continue;
        }
        const int s = d > 0.0 ? 1 : -1;
        if (masked && side == -s && i > 0 && std::abs(n.dot(path[i - 1] - a)) > tol) {
          const double d0 = n.dot(path[i - 1] - a);
          if (insideTriangle(path[i - 1] + d0 / (d0 - d) * (path[i] - path[i - 1]), a, b, c, tol)) return true;
        }
        side = s;
      }
    }
    return false;
  }

  // Whether the first point after path[i] that lies off the plane (n, a) is on the side opposite `side`.
  static bool onOtherSide(const std::vector<Vec3>& path, std::size_t i, const Vec3& n, const Vec3& a, int side,
                          double tol) {
    for (std::size_t j = i + 1; j < path.size(); ++j) {
      const double d = n.dot(path[j] - a);
      if (std::abs(d) > tol) return (d > 0.0 ? 1 : -1) == -side;
    }
    return false;
  }

  // p (on the triangle's plane) inside triangle abc by its barycentric coordinates, up to tol over the
  // triangle's size.
  static bool insideTriangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c, double tol) {
    const Vec3 e1 = b - a, e2 = c - a, q = p - a;
    const double d11 = e1.dot(e1), d12 = e1.dot(e2), d22 = e2.dot(e2), q1 = q.dot(e1), q2 = q.dot(e2);
    const double det = d11 * d22 - d12 * d12;
    if (!(det > 0.0)) return false;
    const double u = (d22 * q1 - d12 * q2) / det, v = (d11 * q2 - d12 * q1) / det;
    const double slack = tol / std::sqrt(std::max(d11, d22));
    return u >= -slack && v >= -slack && u + v <= 1.0 + slack;
  }
};

Vec3 mirror(const Vec3& p, const MirrorPlane& pl) { return p - 2.0 * (pl.normal.dot(p) - pl.offset) * pl.normal; }

}  // namespace

std::vector<ir::Arrival> imageSources(const room::Room& room, const RoomGeometry& geometry, int source,
                                      int listener, const ImageSourceOptions& options) {
  if (options.max_order < 0) throw core::InputError("ism_order", "must be >= 0");
  const int n_planes = static_cast<int>(geometry.planes().size());
  double candidates = 1.0, level = n_planes;
  for (int k = 1; k <= options.max_order; ++k) {
    candidates += level;
    level *= std::max(n_planes - 1, 1);
  }
  if (candidates > options.max_candidates) {
    // Printed as a double: the count overflows any integer type long before the order limit (6 planes at
    // order 50 make ~1e34).
    std::ostringstream why;
    why.precision(3);
    why << "order " << options.max_order << " with " << n_planes << " planes makes " << candidates
        << " image-source candidates, more than the limit of " << options.max_candidates << "; lower it";
    throw core::InputError("output.ism_order", why.str());
  }
  Validator v{room, geometry, {}, options.blocking_triangles};
  for (int m = 0; m < static_cast<int>(room.materials.size()); ++m) v.opening.push_back(room.isOpening(m) ? 1 : 0);
  const room::Source& src = room.sources[source];
  const Vec3 s = src.position_m, l = room.listeners[listener].position_m;
  const Vec3 axis = src.directivity.axis.normalized();
  const double max_d = options.length_s * options.speed_of_sound_m_s;
  const int nb = room.bands.size();
  std::vector<ir::Arrival> out;
  std::vector<Vec3> out_images;              // each arrival's image
  std::vector<std::vector<int>> out_planes;  // and its planes, sorted
  std::vector<int> planes, triangles;
  std::vector<Vec3> images;

  auto emit = [&] {
    const Vec3& img = images.empty() ? s : images.back();
    const double d = (img - l).norm();
    if (!(d > 0.0) || d > max_d) return;
    Vec3 leg;
    if (!v.validate(s, l, planes, images, triangles, leg)) return;
    ir::Arrival a;
    a.delay_s = d / options.speed_of_sound_m_s;
    a.order = static_cast<int>(planes.size());
    a.direction = (img - l) / d;
    const double gain = src.power_w * directivityGain(src.directivity, leg.dot(axis)) / (d * d);
    for (int b = 0; b < nb; ++b) {
      double e = gain * std::exp(-options.air_m_per_m[b] * d);
      for (int tri : triangles) {
        const room::Material& m = room.materials[geometry.triangle(tri).material];
        e *= (1.0 - m.absorption[b]) * (1.0 - m.scattering[b]);
      }
      a.energy[b] = e;
    }
    out.push_back(a);
    out_images.push_back(img);
    out_planes.push_back(planes);
    std::sort(out_planes.back().begin(), out_planes.back().end());
  };
  // Depth-first over plane sequences up to max_order. A child's valid path is at least as long as its
  // parent image's distance to the listener (unfold the last leg: |I − R| + |R − L| ≥ |I − L|, triangle
  // inequality), so an image beyond c·length prunes its whole subtree exactly.
  auto recurse = [&](auto&& self, int depth) -> void {
    if (((images.empty() ? s : images.back()) - l).norm() > max_d) return;
    emit();
    if (depth == options.max_order) return;
    const Vec3 from = images.empty() ? s : images.back();
    for (int p = 0; p < n_planes; ++p) {
      if (!planes.empty() && planes.back() == p) continue;
      const MirrorPlane& pl = geometry.planes()[p];
      if (std::abs(pl.normal.dot(from) - pl.offset) < 1e-9 * geometry.extent()) continue;  // on the plane
      planes.push_back(p);
      images.push_back(mirror(from, pl));
      self(self, depth + 1);
      planes.pop_back();
      images.pop_back();
    }
  };
  recurse(recurse, 0);
  // By delay; and the same image by the same planes in another order (two planes at right angles, the path
  // through their edge: Validator::validate) is one path, counted once. Such twins have equal delays.
  std::vector<std::size_t> order(out.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return out[a].delay_s < out[b].delay_s; });
  const double same_m = 1e-9 * geometry.extent();
  std::vector<ir::Arrival> kept;
  std::vector<std::size_t> kept_index;
  for (std::size_t i : order) {
    bool twin = false;
    for (std::size_t j = kept.size(); j-- > 0;) {
      if ((out[i].delay_s - kept[j].delay_s) * options.speed_of_sound_m_s > same_m) break;
      const std::size_t o = kept_index[j];
      twin = twin || (out_planes[o] == out_planes[i] && (out_images[o] - out_images[i]).norm() <= same_m);
    }
    if (twin) continue;
    kept.push_back(out[i]);
    kept_index.push_back(i);
  }
  return kept;
}

}  // namespace diffray::transport
