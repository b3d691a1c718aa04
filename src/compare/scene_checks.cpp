#include "diffray/compare/scene_checks.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numeric>
#include <set>
#include <vector>

#include "diffray/core/error.h"
#include "diffray/room/checks.h"
#include "diffray/room/json_fields.h"
#include "diffray/room/occluder_file.h"

namespace diffray::compare {

using core::Vec3;

namespace {

std::string where(const room::Listener& l) {
  const Vec3& p = l.position_m;
  return "listener " + l.name + " at (" + room::formatNumber(p.x()) + ", " + room::formatNumber(p.y()) + ", " +
         room::formatNumber(p.z()) + ")";
}

// Length scale of the scene for tolerances (m).
double sceneScale(const room::Room& room) {
  double s = 1.0;
  for (const Vec3& v : room.mesh.vertices) s = std::max(s, v.cwiseAbs().maxCoeff());
  for (const auto& src : room.sources) s = std::max(s, src.position_m.cwiseAbs().maxCoeff());
  for (const auto& l : room.listeners) s = std::max(s, l.position_m.cwiseAbs().maxCoeff());
  return s;
}

struct Tri {
  Vec3 a, b, c;
  std::string group;
};

// The triangles that stop sound: every mesh triangle except the occluders' own rectangles (where the
// occluder model takes over) and fully transmitting openings.
std::vector<Tri> solidTriangles(const room::Room& room) {
  std::set<std::string> occluder_groups;
  for (const auto& o : room.occluders) occluder_groups.insert(o.group);
  std::vector<Tri> out;
  const auto& m = room.mesh;
  for (std::size_t t = 0; t < m.triangles.size(); ++t) {
    const std::string& g = t < room.group_of_triangle.size() ? room.group_of_triangle[t] : std::string();
    if (occluder_groups.count(g) || room.isOpening(m.object_of_triangle[t])) continue;
    out.push_back({m.vertices[m.triangles[t][0]], m.vertices[m.triangles[t][1]], m.vertices[m.triangles[t][2]], g});
  }
  return out;
}

// Whether the triangle lies in an occluder's plane (within tol).
bool inOccluderPlane(const room::Room& room, const Tri& t, double tol) {
  for (const auto& o : room.occluders) {
    const auto off = [&](const Vec3& p) { return std::abs((p - o.origin_m).dot(o.normal)); };
    if (off(t.a) < tol && off(t.b) < tol && off(t.c) < tol) return true;
  }
  return false;
}

// The closed objects among `solid`: per triangle its part (triangles joined across shared edges, vertices
// matched on a grid of `tol`) and whether that part is closed (every edge of the part shared by an even
// number of its triangles). It does not depend on the listener: built once per scene.
struct ClosedParts {
  std::vector<int> part;     ///< per triangle: its part's representative triangle
  std::vector<char> closed;  ///< per triangle: whether its part is closed
};

ClosedParts closedParts(const std::vector<Tri>& solid, double tol) {
  using Key = std::array<long long, 3>;
  const auto key = [&](const Vec3& v) { return Key{std::llround(v.x() / tol), std::llround(v.y() / tol), std::llround(v.z() / tol)}; };
  std::vector<int> parent(solid.size());
  std::iota(parent.begin(), parent.end(), 0);
  const auto find = [&](int i) {
    while (parent[static_cast<std::size_t>(i)] != i) i = parent[static_cast<std::size_t>(i)] = parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(i)])];
    return i;
  };
  std::map<std::pair<Key, Key>, std::vector<int>> edges;
  for (std::size_t t = 0; t < solid.size(); ++t) {
    const Key k[3] = {key(solid[t].a), key(solid[t].b), key(solid[t].c)};
    for (int i = 0; i < 3; ++i) edges[std::minmax(k[i], k[(i + 1) % 3])].push_back(static_cast<int>(t));
  }
  for (const auto& [edge, tris] : edges)
    for (int t : tris) parent[static_cast<std::size_t>(find(t))] = find(tris[0]);
  std::vector<char> part_closed(solid.size(), 1);
  for (const auto& [edge, tris] : edges) {
    std::map<int, int> count;
    for (int t : tris) ++count[find(t)];
    for (const auto& [part, n] : count)
      if (n % 2 != 0) part_closed[static_cast<std::size_t>(part)] = 0;
  }
  ClosedParts out;
  for (std::size_t t = 0; t < solid.size(); ++t) {
    out.part.push_back(find(static_cast<int>(t)));
    out.closed.push_back(part_closed[static_cast<std::size_t>(out.part.back())]);
  }
  return out;
}

// Per triangle of `solid`: whether it bounds a closed object (`parts`) that p lies outside of: rays from p
// along three fixed directions cross that part an even number of times (majority). Behind a face of such an
// object (a cupboard) a listener is reached round it by diffraction, unlike one below the ground.
std::vector<char> outsideClosedObject(const std::vector<Tri>& solid, const ClosedParts& parts, const Vec3& p) {
  static const Vec3 dirs[3] = {Vec3(0.5773, 0.5781, 0.5765).normalized(), Vec3(-0.3111, 0.8123, -0.4932).normalized(),
                               Vec3(0.7071, -0.2017, 0.6777).normalized()};
  std::map<int, int> odd;  // per closed part: how many of the three rays cross it an odd number of times
  for (const Vec3& d : dirs) {
    std::map<int, int> crossings;
    for (std::size_t t = 0; t < solid.size(); ++t)
      if (parts.closed[t] && room::crossesTriangle(p, d, solid[t].a, solid[t].b, solid[t].c)) ++crossings[parts.part[t]];
    for (const auto& [part, n] : crossings) odd[part] += n % 2;
  }
  std::vector<char> out(solid.size(), 0);
  for (std::size_t t = 0; t < solid.size(); ++t) out[t] = parts.closed[t] && odd[parts.part[t]] < 2;
  return out;
}

}  // namespace

double wrapDegrees(double deg) {
  double a = std::fmod(deg, 360.0);  // (−360, 360)
  if (a <= -180.0) a += 360.0;
  if (a > 180.0) a -= 360.0;
  return a;
}

void checkListeners(const room::Room& room) {
  if (room.sources.empty()) return;
  const room::Source& s = room.sources[0];
  const double scale = sceneScale(room), tol = 1e-9 * scale;
  const std::vector<Tri> solid = solidTriangles(room);
  for (const room::Listener& l : room.listeners) {
    if ((l.position_m - s.position_m).norm() <= tol)
      throw core::InputError(room.file, where(l) + " coincides with source " + s.name +
                                            ": no level re free field exists there; move them apart");
    for (const Tri& t : solid) {
      if (!inOccluderPlane(room, t, tol)) continue;
      const double d = (l.position_m - room::closestOnTriangle(l.position_m, t.a, t.b, t.c)).norm();
      if (d < l.radius_m)
        throw core::InputError(room.file, where(l) + ": its sphere (radius " + room::formatNumber(l.radius_m) +
                                              " m) meets " + t.group + " in the occluder's plane, " +
                                              room::formatNumber(std::round(d * 1e4) / 1e4) +
                                              " m from its centre: move it off the screen");
    }
  }
}

std::vector<std::string> hiddenListenerWarnings(const room::Room& room) {
  std::vector<std::string> out;
  if (room.sources.empty()) return out;
  const room::Source& s = room.sources[0];
  const double tol = 1e-9 * sceneScale(room);
  const std::vector<Tri> solid = solidTriangles(room);
  const ClosedParts parts = closedParts(solid, 1e3 * tol);
  for (const room::Listener& l : room.listeners) {
    const std::vector<char> outside = outsideClosedObject(solid, parts, l.position_m);
    for (std::size_t i = 0; i < solid.size(); ++i) {
      const Tri& t = solid[i];
      if (outside[i] || inOccluderPlane(room, t, tol)) continue;
      const Vec3 n = (t.b - t.a).cross(t.c - t.a).normalized();
      const double dl = (l.position_m - t.a).dot(n), ds = (s.position_m - t.a).dot(n);
      if (!(dl * ds < 0.0)) continue;
      const Vec3 foot = l.position_m - dl * n;
      if ((room::closestOnTriangle(foot, t.a, t.b, t.c) - foot).norm() > tol) continue;
      out.push_back(where(l) + " is outside the room: behind surface " + t.group + ", with source " + s.name +
                    " on its other side (no direct or reflected sound reaches it)");
      break;
    }
  }
  return out;
}

namespace {

// Whether the open segment p→q (its ends excluded by 1e-9 of its length) crosses a solid triangle.
bool segmentBlocked(const std::vector<Tri>& solid, const Vec3& p, const Vec3& q) {
  for (const Tri& t : solid)
    if (room::crossesTriangle(p, q - p, t.a, t.b, t.c, 1e-9, 1.0 - 1e-9)) return true;
  return false;
}

// Whether the segment p→q crosses one of the aim rectangles (an end on one counts: a ground reflection
// at the foot of a zone standing on the ground).
bool throughAim(const std::vector<AimRect>& aims, const Vec3& p, const Vec3& q) {
  for (const AimRect& aim : aims) {
    const Vec3 n = aim.ex.cross(aim.ey).normalized();
    const double dp = (p - aim.origin).dot(n), dq = (q - aim.origin).dot(n);
    if (!(dp * dq <= 0.0) || dp == dq) continue;
    const Vec3 x = p + dp / (dp - dq) * (q - p) - aim.origin;
    if (std::abs(x.dot(aim.ex)) <= aim.half_x_m && std::abs(x.dot(aim.ey)) <= aim.half_y_m) return true;
  }
  return false;
}

}  // namespace

void checkAimReachesListeners(const room::Room& room, const std::vector<AimRect>& aims, const AimGround& ground) {
  if (room.sources.empty()) return;
  const room::Source& s = room.sources[0];
  const std::vector<Tri> solid = solidTriangles(room);
  const double tol = 1e-9 * sceneScale(room);
  for (const room::Listener& l : room.listeners) {
    const Vec3 p = s.position_m, q = l.position_m;
    if (!segmentBlocked(solid, p, q) && !throughAim(aims, p, q))
      throw core::InputError("--aim", where(l) + " sees source " + s.name +
                                          " directly along a line that misses the occluder's aim rectangle, so no "
                                          "aimed ray reaches it; run without --aim (or move it)");
    if (!ground.present) continue;
    // The path reflected once off the ground: towards the listener's image, to the point r on the ground.
    const double hp = ground.normal.dot(p) - ground.offset, hq = ground.normal.dot(q) - ground.offset;
    if (!(hp * hq > 0.0)) continue;
    const Vec3 r = p + hp / (hp + hq) * ((q - 2.0 * hq * ground.normal) - p);
    // On a ground triangle, and on no other surface (the foot of a barrier standing on the ground stops it).
    bool on_ground = false, on_other = false;
    for (const Tri& t : solid) {
      const bool near = (room::closestOnTriangle(r, t.a, t.b, t.c) - r).norm() < 1e3 * tol;
      const bool in_ground = std::abs(ground.normal.dot(t.a) - ground.offset) < 1e3 * tol &&
                             std::abs(ground.normal.dot(t.b) - ground.offset) < 1e3 * tol &&
                             std::abs(ground.normal.dot(t.c) - ground.offset) < 1e3 * tol;
      (in_ground ? on_ground : on_other) |= near;
    }
    if (!on_ground || on_other || segmentBlocked(solid, p, r) || segmentBlocked(solid, r, q)) continue;
    if (!throughAim(aims, p, r) && !throughAim(aims, r, q))
      throw core::InputError("--aim", where(l) + " hears source " + s.name +
                                          " by a reflection off the ground that misses the occluder's aim "
                                          "rectangle, so no aimed ray takes it; run without --aim (or move it)");
  }
}

AimGround checkAimReflectors(const room::Room& room) {
  std::set<std::string> occluder_groups;
  for (const auto& o : room.occluders) occluder_groups.insert(o.group);
  // The floor planes that a door's model mirrors (OccluderAxis::mirror_lo): through the lo edge, normal to it.
  std::vector<std::pair<Vec3, Vec3>> sill_planes;  // point, unit normal
  for (const auto& o : room.occluders) {
    if (o.x.mirror_lo) sill_planes.push_back({o.origin_m + o.x.lo_m * o.ex, o.ex});
    if (o.y.mirror_lo) sill_planes.push_back({o.origin_m + o.y.lo_m * o.ey, o.ey});
  }
  const auto& m = room.mesh;
  double size = 1.0;  // the mesh's largest coordinate, for a plane tolerance in its float rounding's units
  for (const Vec3& v : m.vertices) size = std::max(size, v.cwiseAbs().maxCoeff());
  const double tol = 1e-6 * size;
  // A ground is possible under one edge or barrier (an edge axis across a uniform one), side zones and all.
  using Kind = room::OccluderAxis::Kind;
  const std::vector<const room::Occluder*> own = room::ownOccluders(room);
  const room::Occluder* edge =
      own.size() == 1 && own[0]->x.kind == Kind::Edge && own[0]->y.kind == Kind::Uniform ? own[0] : nullptr;
  AimGround ground;
  for (std::size_t t = 0; t < m.triangles.size(); ++t) {
    const std::string& g = t < room.group_of_triangle.size() ? room.group_of_triangle[t] : std::string();
    const int mat = m.object_of_triangle[t];
    if (occluder_groups.count(g) || room.isOpening(mat)) continue;
    const room::Material& material = room.materials[static_cast<std::size_t>(mat)];
    bool reflects = false, diffuse = false;
    for (int b = 0; b < room.bands.size(); ++b) {
      reflects = reflects || material.absorption[b] < 1.0;
      diffuse = diffuse || (material.absorption[b] < 1.0 && material.scattering[b] > 0.0);
    }
    if (!reflects) continue;
    const Vec3 v[3] = {m.vertices[m.triangles[t][0]], m.vertices[m.triangles[t][1]], m.vertices[m.triangles[t][2]]};
    bool on_sill = false;
    for (const auto& [p, n] : sill_planes)
      on_sill = on_sill || (std::abs((v[0] - p).dot(n)) < tol && std::abs((v[1] - p).dot(n)) < tol && std::abs((v[2] - p).dot(n)) < tol);
    // The screen around the occluder: what it reflects stays on the source's side, where --aim has no
    // listener (checkAimReachesListeners).
    if (on_sill || inOccluderPlane(room, {v[0], v[1], v[2], g}, tol)) continue;
    const std::string named = "surface " + g + " (" + material.name + ")";
    const Vec3 n = (v[1] - v[0]).cross(v[2] - v[0]);
    if (edge && n.norm() > 0.0) {
      const Vec3 u = n.normalized();
      const double offset = u.dot(v[0]);
      const bool in_ground = ground.present && std::abs(std::abs(u.dot(ground.normal)) - 1.0) < 1e-9 &&
                             std::abs(u.dot(ground.normal) * offset - ground.offset) < tol;
      double lo = 1e300, hi = -1e300;
      for (const room::Occluder& zone : room.occluders)  // the edge's zone and a barrier's side zones
        for (const Vec3& c : room::occluderCorners(zone))
          lo = std::min(lo, u.dot(c) - offset), hi = std::max(hi, u.dot(c) - offset);
      const bool cuts = lo < -tol && hi > tol;
      if (in_ground || (!ground.present && std::abs(u.dot(edge->normal)) < 1e-9 && !cuts)) {
        if (diffuse)
          throw core::InputError("--aim", named + " scatters sound diffusely, and aimed rays only follow its "
                                              "specular reflection; run without --aim (or give it scattering 0)");
        if (in_ground) continue;  // another part of the ground already found
        ground.present = true;
        ground.normal = u;
        ground.offset = offset;
        continue;
      }
    }
    throw core::InputError("--aim", named + " reflects, and aimed rays go straight at the occluder, so the paths "
                                            "that meet it first would be lost; run without --aim (or make it "
                                            "absorbing)");
  }
  return ground;
}

}  // namespace diffray::compare
