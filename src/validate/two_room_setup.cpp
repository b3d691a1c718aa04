#include "diffray/validate/two_room_setup.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "diffray/core/error.h"
#include "diffray/room/json_fields.h"
#include "diffray/room/occluder_file.h"

namespace diffray::validate {

using core::Vec3;

namespace {

const char* const kSurfaceParam[kTwoRoomSurfaces] = {"abs-a-floor", "abs-a-ceiling", "abs-a-side-lo", "abs-a-side-hi",
                                                    "abs-a-far",   "abs-a-partition", "abs-b-floor", "abs-b-ceiling",
                                                    "abs-b-walls", "abs-reveal"};
const char* const kSurfaceHelp[kTwoRoomSurfaces] = {
    "room A floor", "room A ceiling", "room A wall at the lateral start", "room A wall at the lateral end",
    "room A wall facing the partition", "room A side of the partition", "room B floor", "room B ceiling",
    "room B walls (partition side included)", "the door's reveal (jambs, lintel, floor)"};

struct Box {
  std::array<double, 3> lo, hi;
  bool contains(const std::array<double, 3>& p) const {
    for (int i = 0; i < 3; ++i)
      if (!(p[i] > lo[i] && p[i] < hi[i])) return false;
    return true;
  }
  bool holdsSphere(const std::array<double, 3>& p, double r) const {
    for (int i = 0; i < 3; ++i)
      if (!(p[i] - r > lo[i] && p[i] + r < hi[i])) return false;
    return true;
  }
};

struct Layout {
  Box a, b, door;
  double mid = 0;  // the partition's mid-plane along the join axis
};

Layout layoutOf(const TwoRoomSpec& s) {
  const int ax = s.axis, lat = 1 - s.axis;
  Layout L;
  L.a = {{0, 0, 0}, s.dims_a_m};
  L.b.lo = {0, 0, 0};
  L.b.lo[ax] = s.dims_a_m[ax] + s.wall_m;
  L.b.lo[lat] = s.b_offset_m;
  for (int i = 0; i < 3; ++i) L.b.hi[i] = L.b.lo[i] + s.dims_b_m[i];
  L.door.lo = {0, 0, 0};
  L.door.hi = {0, 0, s.door_height_m};
  L.door.lo[ax] = s.dims_a_m[ax];
  L.door.hi[ax] = L.b.lo[ax];
  L.door.lo[lat] = s.door_pos_m;
  L.door.hi[lat] = s.door_pos_m + s.door_width_m;
  L.mid = 0.5 * (L.door.lo[ax] + L.door.hi[ax]);
  return L;
}

}  // namespace

std::vector<ParamSpec> twoRoomParams(const TwoRoomSpec& d) {
  std::vector<double> listeners;
  for (const auto& l : d.listeners_m) listeners.insert(listeners.end(), l.begin(), l.end());
  std::vector<ParamSpec> ps{
      {"room-a", {d.dims_a_m.begin(), d.dims_a_m.end()}, "room A size x y z (m), from the origin"},
      {"room-b", {d.dims_b_m.begin(), d.dims_b_m.end()}, "room B size x y z (m), behind the partition"},
      {"room-b-offset", {d.b_offset_m}, "room B's start along the partition (m)", -1e6},
      {"wall", {d.wall_m}, "partition thickness (m)"},
      {"door-width", {d.door_width_m}, "door width (m)"},
      {"door-height", {d.door_height_m}, "door height (m), from the floor"},
      {"door-position", {d.door_pos_m}, "the door's start along the partition (m)", -1e6},
      {"source", {d.source_m.begin(), d.source_m.end()}, "source position (m)"},
      {"listeners", listeners, "listener positions, x y z each (m)"},
      {"radius", {d.radius_m}, "listener sphere radius (m)"},
      {"scattering", {d.scattering}, "scattering coefficient of every surface", 0.0, true, 1.0 + 1e-12}};
  for (ParamSpec& p : ps) p.list = p.name == "room-a" || p.name == "room-b" || p.name == "source" || p.name == "listeners";
  for (int k = 0; k < kTwoRoomSurfaces; ++k) {
    ParamSpec a{kSurfaceParam[k], d.absorption[k], std::string("absorption of ") + kSurfaceHelp[k] + ": one value, or 8 (63 Hz-8 kHz)", 0.0, true, 1.0 + 1e-12};
    a.list = true;
    ps.push_back(a);
  }
  return ps;
}

TwoRoomSpec twoRoomFromParams(const Params& p, const TwoRoomSpec& base) {
  TwoRoomSpec s = base;
  const auto xyz = [&](const std::string& name) {
    const auto& v = p.at(name);
    if (v.size() != 3) throw core::InputError("--" + name, "needs three values (x y z)");
    return std::array<double, 3>{v[0], v[1], v[2]};
  };
  s.dims_a_m = xyz("room-a");
  s.dims_b_m = xyz("room-b");
  s.source_m = xyz("source");
  s.b_offset_m = p.at("room-b-offset")[0];
  s.wall_m = p.at("wall")[0];
  s.door_width_m = p.at("door-width")[0];
  s.door_height_m = p.at("door-height")[0];
  s.door_pos_m = p.at("door-position")[0];
  s.radius_m = p.at("radius")[0];
  s.scattering = p.at("scattering")[0];
  const auto& ls = p.at("listeners");
  if (ls.empty() || ls.size() % 3 != 0) throw core::InputError("--listeners", "needs x y z per listener");
  s.listeners_m.clear();
  for (std::size_t i = 0; i + 2 < ls.size(); i += 3) s.listeners_m.push_back({ls[i], ls[i + 1], ls[i + 2]});
  if (s.listener_names.size() != s.listeners_m.size()) {
    s.listener_names.clear();
    for (std::size_t i = 0; i < s.listeners_m.size(); ++i) s.listener_names.push_back("L" + std::to_string(i + 1));
  }
  for (int k = 0; k < kTwoRoomSurfaces; ++k) {
    s.absorption[k] = p.at(kSurfaceParam[k]);
    if (s.absorption[k].size() != 1 && s.absorption[k].size() != 8)
      throw core::InputError(std::string("--") + kSurfaceParam[k], "needs 1 or 8 values (octave bands 63 Hz-8 kHz)");
  }
  const Layout L = layoutOf(s);
  const int lat = 1 - s.axis;
  const double wall_lo = std::max(L.a.lo[lat], L.b.lo[lat]), wall_hi = std::min(L.a.hi[lat], L.b.hi[lat]);
  if (!(L.door.lo[lat] > wall_lo && L.door.hi[lat] < wall_hi && s.door_height_m < std::min(s.dims_a_m[2], s.dims_b_m[2])))
    throw core::InputError("--door-position", "the door (" + room::formatNumber(L.door.lo[lat]) + " to " +
                                                  room::formatNumber(L.door.hi[lat]) + " m along the partition, " +
                                                  room::formatNumber(s.door_height_m) +
                                                  " m high) does not fit in the wall the two rooms share (" +
                                                  room::formatNumber(wall_lo) + " to " + room::formatNumber(wall_hi) +
                                                  " m, below both ceilings)");
  if (!L.a.contains(s.source_m) && !L.b.contains(s.source_m)) throw core::InputError("--source", "must be inside room A or B");
  for (const auto& l : s.listeners_m)
    if (!L.a.holdsSphere(l, s.radius_m) && !L.b.holdsSphere(l, s.radius_m))
      throw core::InputError("--listeners", "each listener sphere must be inside room A or B");
  return s;
}

room::Room makeTwoRooms(const TwoRoomSpec& s) {
  const Layout L = layoutOf(s);
  const int ax = s.axis, lat = 1 - s.axis;
  room::Room r;
  r.name = "two-rooms";
  int mat[kTwoRoomSurfaces];
  for (int k = 0; k < kTwoRoomSurfaces; ++k) {
    room::Material m;
    m.name = kSurfaceParam[k] + 4;  // without "abs-"
    for (int b = 0; b < r.bands.size(); ++b) {
      m.absorption[b] = s.absorption[k].size() == 1 ? s.absorption[k][0] : s.absorption[k][static_cast<std::size_t>(b)];
      m.scattering[b] = s.scattering;
    }
    mat[k] = r.addMaterial(m);
  }
  // The grid's cuts: every box face and the partition's mid-plane (where the opening's corners sit).
  std::array<std::vector<double>, 3> cut;
  for (int i = 0; i < 3; ++i) {
    for (const Box* b : {&L.a, &L.b, &L.door}) cut[i].insert(cut[i].end(), {b->lo[i], b->hi[i]});
    if (i == ax) cut[i].push_back(L.mid);
    std::sort(cut[i].begin(), cut[i].end());
    cut[i].erase(std::unique(cut[i].begin(), cut[i].end()), cut[i].end());
  }
  const int n[3] = {static_cast<int>(cut[0].size()) - 1, static_cast<int>(cut[1].size()) - 1, static_cast<int>(cut[2].size()) - 1};
  const auto centre = [&](const std::array<int, 3>& c) {
    std::array<double, 3> p;
    for (int i = 0; i < 3; ++i) p[i] = 0.5 * (cut[i][static_cast<std::size_t>(c[i])] + cut[i][static_cast<std::size_t>(c[i]) + 1]);
    return p;
  };
  const auto air = [&](const std::array<int, 3>& c) {
    for (int i = 0; i < 3; ++i)
      if (c[i] < 0 || c[i] >= n[i]) return false;
    const auto p = centre(c);
    return L.a.contains(p) || L.b.contains(p) || L.door.contains(p);
  };
  // Which material a face of air cell `c` gets; `up` whether its normal (into the air) points along +axis.
  const auto material = [&](const std::array<int, 3>& c, int axis, bool up) {
    const auto p = centre(c);
    if (L.door.contains(p)) return mat[kReveal];
    const bool in_a = p[ax] < L.a.hi[ax];
    if (axis == 2) return mat[in_a ? (up ? kAFloor : kACeiling) : (up ? kBFloor : kBCeiling)];
    if (!in_a) return mat[kBWalls];
    if (axis == lat) return mat[up ? kASideLo : kASideHi];
    return mat[up ? kAFar : kAPartition];
  };
  std::array<int, 3> c;
  for (c[0] = 0; c[0] < n[0]; ++c[0])
    for (c[1] = 0; c[1] < n[1]; ++c[1])
      for (c[2] = 0; c[2] < n[2]; ++c[2]) {
        if (!air(c)) continue;
        for (int axis = 0; axis < 3; ++axis)
          for (int sign : {-1, 1}) {
            std::array<int, 3> nb = c;
            nb[axis] += sign;
            if (air(nb)) continue;
            // The face toward the solid neighbour; its corners ordered so that the normal points into c.
            const int b = (axis + 1) % 3, e = (axis + 2) % 3;
            const double plane = cut[axis][static_cast<std::size_t>(c[axis] + (sign > 0 ? 1 : 0))];
            std::vector<Vec3> q;
            for (const auto& [db, de] : {std::pair{0, 0}, {1, 0}, {1, 1}, {0, 1}}) {
              double v[3];
              v[axis] = plane;
              v[b] = cut[b][static_cast<std::size_t>(c[b] + db)];
              v[e] = cut[e][static_cast<std::size_t>(c[e] + de)];
              q.emplace_back(v[0], v[1], v[2]);
            }
            if (sign > 0) std::reverse(q.begin(), q.end());
            r.addPolygon(q, material(c, axis, sign < 0), "surface");
          }
      }
  room::Occluder door;
  door.name = "door";
  door.type = "door";
  Vec3 origin(0, 0, 0.5 * s.door_height_m), normal(0, 0, 0);
  origin[ax] = L.mid;
  origin[lat] = s.door_pos_m + 0.5 * s.door_width_m;
  normal[ax] = 1.0;
  door.origin_m = origin;
  room::setOccluderFrame(door, normal, Vec3(0, 0, 1), "door");
  door.half_x_m = 0.5 * s.door_width_m;
  door.half_y_m = 0.5 * s.door_height_m;
  door.x.kind = door.y.kind = room::OccluderAxis::Kind::Opening;
  door.x.lo_m = -door.half_x_m, door.x.hi_m = door.half_x_m;
  door.y.lo_m = -door.half_y_m, door.y.hi_m = door.half_y_m;
  door.y.mirror_lo = true;  // sill "floor"
  room::addOccluderRect(r, door);
  r.sources.push_back({"S", Vec3(s.source_m[0], s.source_m[1], s.source_m[2]), 1.0, {}});
  for (std::size_t i = 0; i < s.listeners_m.size(); ++i) {
    const auto& l = s.listeners_m[i];
    r.listeners.push_back({s.listener_names[i], Vec3(l[0], l[1], l[2]), s.radius_m});
  }
  r.output.ism_order = 3;
  return r;
}

bool hiddenFromSource(const TwoRoomSpec& s, std::size_t l) {
  const Layout L = layoutOf(s);
  const int ax = s.axis, lat = 1 - s.axis;
  const auto& p = s.listeners_m[l];
  const auto& q = s.source_m;
  if ((p[ax] - L.mid) * (q[ax] - L.mid) >= 0.0) return false;  // same side of the partition
  const double t = (L.mid - q[ax]) / (p[ax] - q[ax]);
  const double y = q[lat] + t * (p[lat] - q[lat]), z = q[2] + t * (p[2] - q[2]);
  return !(y > L.door.lo[lat] && y < L.door.hi[lat] && z > 0.0 && z < s.door_height_m);
}

}  // namespace diffray::validate
