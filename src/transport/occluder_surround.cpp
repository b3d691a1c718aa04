// The wall around an opening occluder (RoomOccluders::surroundReflectance): which surface the part of the
// incident energy that the opening does not carry returns from.
#include <vector>

#include "diffray/geometry/mesh.h"
#include "diffray/transport/room_occluders.h"

namespace diffray::transport {

using core::Vec3;
using Kind = room::OccluderAxis::Kind;

namespace {

constexpr double kProbeInsetM = 0.01;  // probes start this far inside the opening, or outside it
constexpr double kReachM = 0.25;       // a surface farther than this from an edge does not surround it

// The nearest triangle along o + t·d, t in (0, kReachM], that is neither one of the occluders' nor an
// opening; −1 if none.
int nearestSurface(const room::Room& room, const std::vector<int>& of_triangle, const Vec3& o, const Vec3& d) {
  double best = kReachM;
  int found = -1;
  const geometry::Mesh& mesh = room.mesh;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    if (of_triangle[t] >= 0 || room.isOpening(mesh.object_of_triangle[t])) continue;
    const auto& tri = mesh.triangles[t];
    const double s = geometry::rayTriangleT(o, d, mesh.vertices[tri[0]], mesh.vertices[tri[1]], mesh.vertices[tri[2]]);
    if (s > 0.0 && s <= best) best = s, found = static_cast<int>(t);
  }
  return found;
}

}  // namespace

core::BandArray RoomOccluders::surroundReflectance(const room::Room& room, const room::Occluder& o,
                                                   const std::vector<int>& of_triangle) {
  core::BandArray r = core::bandFill(0.0);
  const bool openings = (o.x.kind == Kind::Opening || o.x.kind == Kind::Uniform) &&
                        (o.y.kind == Kind::Opening || o.y.kind == Kind::Uniform) &&
                        (o.x.kind == Kind::Opening || o.y.kind == Kind::Opening) && !o.reflect;
  const bool kirchhoff = o.x.faces == room::OccluderAxis::Faces::Kirchhoff &&
                         o.y.faces == room::OccluderAxis::Faces::Kirchhoff;
  if (!openings || !kirchhoff) return r;
  // One probe at the middle of each diffracting edge (a door's sill stands on the floor and does not
  // diffract): first along the occluder's plane from just inside the opening outward (the reveal of a
  // thick wall), then toward the plane from just beyond the edge on either side (a thin wall, whose plane
  // the first cast lies in).
  int probes = 0;
  auto probe = [&](const Vec3& edge_mid, const Vec3& outward) {
    int t = nearestSurface(room, of_triangle, edge_mid - kProbeInsetM * outward, outward);
    if (t < 0) {
      const Vec3 beyond = edge_mid + kProbeInsetM * outward;
      t = nearestSurface(room, of_triangle, beyond + kProbeInsetM * o.normal, -o.normal);
      if (t < 0) t = nearestSurface(room, of_triangle, beyond - kProbeInsetM * o.normal, o.normal);
    }
    if (t < 0) return;
    const room::Material& m = room.materials[room.mesh.object_of_triangle[t]];
    for (int b = 0; b < room.bands.size(); ++b) r[b] += 1.0 - m.absorption[b];
    ++probes;
  };
  if (o.x.kind == Kind::Opening) {
    const Vec3 mid_y = o.origin_m + (o.y.kind == Kind::Opening ? 0.5 * (o.y.lo_m + o.y.hi_m) : 0.0) * o.ey;
    probe(mid_y + o.x.hi_m * o.ex, o.ex);
    if (!o.x.mirror_lo) probe(mid_y + o.x.lo_m * o.ex, -o.ex);
  }
  if (o.y.kind == Kind::Opening) {
    const Vec3 mid_x = o.origin_m + (o.x.kind == Kind::Opening ? 0.5 * (o.x.lo_m + o.x.hi_m) : 0.0) * o.ex;
    probe(mid_x + o.y.hi_m * o.ey, o.ey);
    if (!o.y.mirror_lo) probe(mid_x + o.y.lo_m * o.ey, -o.ey);
  }
  if (probes > 0)
    for (int b = 0; b < room.bands.size(); ++b) r[b] /= probes;
  return r;
}

}  // namespace diffray::transport
