#include "diffray/room/occluder_file.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <tuple>

#include "diffray/core/error.h"
#include "diffray/room/checks.h"

namespace diffray::room {
namespace {

std::string inQuotes(const std::string& s) { return "\"" + s + "\""; }

int openingMaterial(Room& room) {
  for (int m = 0; m < static_cast<int>(room.materials.size()); ++m)
    if (room.materials[m].name == "occluder-opening") return m;
  Material open;
  open.name = "occluder-opening";
  open.absorption = core::bandFill(1.0);
  open.transmission = core::bandFill(1.0);
  open.reference = "an open occluder: transmits everything";
  return room.addMaterial(open);
}

Vec3 unitVector(const JsonField& f) {
  const Vec3 v = f.vec3();
  if (!(v.norm() > 0.0)) f.fail("must not be the zero vector");
  return v.normalized();
}

// "faces": the boundary condition the WBSDF's edge rays are weighted for (room/occluder.h).
OccluderAxis::Faces faces(const JsonField& o, OccluderAxis::Faces fallback) {
  if (!o.has("faces")) return fallback;
  const std::string f = o["faces"].string();
  if (f == "rigid") return OccluderAxis::Faces::Rigid;
  if (f == "soft") return OccluderAxis::Faces::Soft;
  if (f == "kirchhoff") return OccluderAxis::Faces::Kirchhoff;
  o["faces"].fail("must be \"rigid\", \"soft\" or \"kirchhoff\", got \"" + f + "\"");
}

double edgeZone(const JsonField& o) { return o.has("extent_m") ? o["extent_m"].length() : kDefaultEdgeZoneM; }

// A door or slit given by an existing opening group of the mesh: its frame and rectangle from the group's
// triangles, which must be coplanar.
void fromGroup(const JsonField& g, Room& room, Occluder& occ, const Vec3& up) {
  occ.group = g.string();
  std::vector<int> tris;
  for (std::size_t t = 0; t < room.group_of_triangle.size(); ++t)
    if (room.group_of_triangle[t] == occ.group) tris.push_back(static_cast<int>(t));
  if (tris.empty()) g.fail("no face group " + inQuotes(occ.group) + " in the geometry");
  const auto& tri = room.mesh.triangles[tris[0]];
  const Vec3& a = room.mesh.vertices[tri[0]];
  const Vec3 n = (room.mesh.vertices[tri[1]] - a).cross(room.mesh.vertices[tri[2]] - a).normalized();
  setOccluderFrame(occ, n, up, g.where());
  double lo[2] = {1e300, 1e300}, hi[2] = {-1e300, -1e300}, area = 0.0, scale = 0.0;
  for (int t : tris) {
    const auto& v = room.mesh.triangles[t];
    const Vec3 &p0 = room.mesh.vertices[v[0]], &p1 = room.mesh.vertices[v[1]], &p2 = room.mesh.vertices[v[2]];
    area += 0.5 * (p1 - p0).cross(p2 - p0).norm();
    for (const Vec3* p : {&p0, &p1, &p2}) {
      scale = std::max(scale, p->cwiseAbs().maxCoeff());
      if (std::abs((*p - a).dot(n)) > 1e-6 * std::max(1.0, scale))
        g.fail("face group " + inQuotes(occ.group) + " is not planar: an occluder's opening must be flat");
      const double c[2] = {p->dot(occ.ex), p->dot(occ.ey)};
      for (int k = 0; k < 2; ++k) lo[k] = std::min(lo[k], c[k]), hi[k] = std::max(hi[k], c[k]);
    }
  }
  occ.half_x_m = 0.5 * (hi[0] - lo[0]);
  occ.half_y_m = 0.5 * (hi[1] - lo[1]);
  occ.origin_m = a + (0.5 * (lo[0] + hi[0]) - a.dot(occ.ex)) * occ.ex + (0.5 * (lo[1] + hi[1]) - a.dot(occ.ey)) * occ.ey;
  const double rect = 4.0 * occ.half_x_m * occ.half_y_m;
  if (!(rect > 0.0) || std::abs(area - rect) > 1e-3 * rect)
    g.fail("face group " + inQuotes(occ.group) + " is not a rectangle aligned with \"up\" (area " +
           formatNumber(area) + " m² against its bounding rectangle's " + formatNumber(rect) + " m²)");
}

// An opening occluder (door or slit): from a group, or an explicit rectangle added to the mesh.
Occluder opening(const JsonField& o, Room& room, const std::string& type) {
  Occluder occ;
  occ.type = type;
  const Vec3 up = o.has("up") ? unitVector(o["up"]) : Vec3(0, 0, 1);
  const bool explicit_rect = !o.has("group");
  if (explicit_rect) {
    occ.origin_m = o["centre"].vec3();
    // "up" is optional: name the occluder itself when it was not given (o["up"] would fail as missing).
    setOccluderFrame(occ, unitVector(o["normal"]), up, o.has("up") ? o["up"].where() : o.where());
    occ.half_x_m = 0.5 * o["width_m"].length();
    occ.half_y_m = 0.5 * o["height_m"].length();
  } else {
    for (const char* k : {"centre", "normal", "width_m", "height_m"})
      if (o.has(k)) o[k].fail("give either \"group\" or an explicit rectangle (centre, normal, width_m, height_m)");
    fromGroup(o["group"], room, occ, up);
  }
  const std::string sill = o.has("sill") ? o["sill"].string() : (type == "door" ? "floor" : "none");
  if (sill != "floor" && sill != "none") o["sill"].fail("must be \"floor\" or \"none\", got " + inQuotes(sill));
  if (o.has("slits")) {
    occ.x.kind = OccluderAxis::Kind::Slits;
    occ.x.count = static_cast<int>(o["slits"].integerIn(1, 64));
    const double w = o["slit_width_m"].length();
    occ.x.lo_m = -0.5 * w, occ.x.hi_m = 0.5 * w;
    occ.x.spacing_m = occ.x.count > 1 ? o["spacing_m"].length() : 0.0;
    if (occ.x.count > 1 && occ.x.spacing_m <= w) o["spacing_m"].fail("must exceed slit_width_m");
    if ((occ.x.count - 1) * occ.x.spacing_m + w > 2.0 * occ.half_x_m * (1 + 1e-9))
      o["slits"].fail("the slits do not fit in the occluder's width");
  } else {
    occ.x.kind = OccluderAxis::Kind::Opening;
    occ.x.lo_m = -occ.half_x_m, occ.x.hi_m = occ.half_x_m;
  }
  occ.y.kind = OccluderAxis::Kind::Opening;
  occ.y.lo_m = -occ.half_y_m, occ.y.hi_m = occ.half_y_m;
  occ.y.mirror_lo = sill == "floor";
  if (o.has("name")) occ.name = o["name"].string();
  if (explicit_rect) occ.group.clear();
  return occ;
}

// A door's leaf: a panel the size of the opening, hinged on its "left" jamb (the one toward −ex in the door's
// frame) or its "right" one (+ex), turned by angle_deg from shut toward the side `opens` ("front": the side
// the door's normal points to, or "back"). Plain geometry in its own material: it reflects and absorbs what
// reaches it; the opening's WBSDF stays the full opening's.
void addLeaf(const JsonField& leaf, Room& room, const Occluder& door,
             const std::function<int(const JsonField&)>& resolve) {
  leaf.allowKeys({"angle_deg", "hinge", "opens", "material"});
  const double angle = leaf["angle_deg"].numberIn(1.0, 180.0) * core::kPi / 180.0;
  const std::string hinge = leaf.has("hinge") ? leaf["hinge"].string() : "left";
  if (hinge != "left" && hinge != "right") leaf["hinge"].fail("must be \"left\" or \"right\", got \"" + hinge + "\"");
  const std::string opens = leaf.has("opens") ? leaf["opens"].string() : "front";
  if (opens != "front" && opens != "back") leaf["opens"].fail("must be \"front\" or \"back\", got \"" + opens + "\"");
  const int material = resolve(leaf["material"]);
  const double s_hinge = hinge == "left" ? -1.0 : 1.0, s_side = opens == "front" ? 1.0 : -1.0;
  const Vec3 h = door.origin_m + s_hinge * door.half_x_m * door.ex;  // on the hinge line, mid-height
  const Vec3 along = -s_hinge * std::cos(angle) * door.ex + s_side * std::sin(angle) * door.normal;
  const Vec3 up = door.half_y_m * door.ey, across = 2.0 * door.half_x_m * along;
  room.addPolygon({h - up, h + across - up, h + across + up, h + up}, material, "leaf:" + door.name);
}

Occluder edgeZoneOccluder(const Vec3& start, const Vec3& end, const Vec3& open_toward, double extent_m,
                          const std::string& field) {
  Occluder occ;
  occ.type = "edge";
  const Vec3 along = end - start;
  if (!(along.norm() > 0.0)) throw core::InputError(field, "the edge has zero length");
  occ.ey = along.normalized();
  occ.ex = open_toward - open_toward.dot(occ.ey) * occ.ey;
  if (!(occ.ex.norm() > 1e-6 * open_toward.norm())) throw core::InputError(field, "open_toward is parallel to the edge");
  occ.ex.normalize();
  occ.normal = occ.ex.cross(occ.ey);
  occ.half_x_m = 0.5 * extent_m;
  occ.half_y_m = 0.5 * along.norm();
  occ.origin_m = 0.5 * (start + end) + occ.half_x_m * occ.ex;
  occ.x.kind = OccluderAxis::Kind::Edge;
  occ.x.lo_m = -occ.half_x_m, occ.x.hi_m = occ.half_x_m;
  return occ;
}

// Claims `name` for entry `o`; a duplicate fails on "name", or on the entry when the name is its default.
void claimName(std::set<std::string>& names, const std::string& name, const JsonField& o) {
  if (names.insert(name).second) return;
  (o.has("name") ? o["name"] : o).fail("duplicate occluder name " + inQuotes(name));
}

}  // namespace

std::vector<const Occluder*> ownOccluders(const Room& room) {
  std::vector<const Occluder*> out;
  for (const Occluder& o : room.occluders)
    if (o.type != "barrier side") out.push_back(&o);
  return out;
}

std::vector<Vec3> occluderCorners(const Occluder& o) {
  const Vec3 hx = o.half_x_m * o.ex, hy = o.half_y_m * o.ey;
  return {o.origin_m - hx - hy, o.origin_m + hx - hy, o.origin_m + hx + hy, o.origin_m - hx + hy};
}

void setOccluderFrame(Occluder& occ, const Vec3& normal, const Vec3& up, const std::string& field) {
  if (!(normal.norm() > 0.0) || !(up.norm() > 0.0)) throw core::InputError(field, "normal and up must not be zero");
  occ.normal = normal.normalized();
  Vec3 ey = up.normalized() - up.normalized().dot(occ.normal) * occ.normal;
  if (!(ey.norm() > 1e-6)) throw core::InputError(field, "\"up\" must not be parallel to the occluder's normal");
  occ.ey = ey.normalized();
  occ.ex = occ.ey.cross(occ.normal);
}

void addOccluderRect(Room& room, Occluder occ, int material) {
  occ.group = "occluder:" + occ.name;
  room.addPolygon(occluderCorners(occ), material >= 0 ? material : openingMaterial(room), occ.group);
  room.occluders.push_back(std::move(occ));
}

void parseOccluders(const JsonField& list, Room& room, const std::function<int(const JsonField&)>& resolve,
                    std::vector<std::string>& warnings) {
  std::set<std::string> names;
  for (std::size_t i = 0; i < list.arraySize(); ++i) {
    const JsonField o = list.at(i);
    const std::string type = o["type"].string();
    const std::string fallback = type + std::to_string(i + 1);
    if (type == "door" || type == "slit") {
      o.allowKeys({"type", "name", "group", "centre", "normal", "up", "width_m", "height_m", "sill", "faces", "slits",
                   "slit_width_m", "spacing_m", "leaf", "panel"});
      Occluder occ = opening(o, room, type);
      occ.x.faces = occ.y.faces = faces(o, OccluderAxis::Faces::Kirchhoff);
      if (occ.name.empty()) occ.name = fallback;
      claimName(names, occ.name, o);
      if (occ.group.empty()) {
        addOccluderRect(room, occ);
      } else {
        for (std::size_t t = 0; t < room.group_of_triangle.size(); ++t)
          if (room.group_of_triangle[t] == occ.group && !room.isOpening(room.mesh.object_of_triangle[t]))
            o["group"].fail("face group " + inQuotes(occ.group) + " must have a fully transmitting material (an "
                            "opening, absorption = transmission = 1), the door's hole");
        room.occluders.push_back(occ);
      }
      if (o.has("leaf")) {
        if (type != "door") o["leaf"].fail("only a door has a leaf");
        addLeaf(o["leaf"], room, occ, resolve);
      }
      if (o.has("panel")) {
        if (type != "door") o["panel"].fail("only a door has a panel");
        const int panel = resolve(o["panel"]);
        if (room.isOpening(panel)) o["panel"].fail("the panel must be a solid material, not an opening");
        room.occluders.back().panel_material = panel;
      }
    } else if (type == "edge" || type == "barrier") {
      Occluder zone;
      std::vector<Occluder> more;  // a barrier's other edges' zones ("foot_edge", "side_edges")
      std::string name = o.has("name") ? o["name"].string() : fallback;
      claimName(names, name, o);
      if (type == "edge") {
        o.allowKeys({"type", "name", "start", "end", "open_toward", "extent_m", "faces"});
        zone = edgeZoneOccluder(o["start"].vec3(), o["end"].vec3(), o["open_toward"].vec3(), edgeZone(o), o.where());
      } else {
        o.allowKeys({"type", "name", "base", "height_m", "up", "material", "extent_m", "faces", "side_edges",
                     "foot_edge"});
        const JsonField base = o["base"];
        base.arraySize(2);
        const Vec3 p0 = base.at(0).vec3(), p1 = base.at(1).vec3();
        const Vec3 up = o.has("up") ? unitVector(o["up"]) : Vec3(0, 0, 1);
        const double h = o["height_m"].length();
        // Checked here so that the message names the field (Room::addPolygon only knows the group).
        if (!((p1 - p0).norm() > 0.0)) base.fail("the barrier's base has zero length");
        if (!(up.cross((p1 - p0).normalized()).norm() > 1e-6))
          (o.has("up") ? o["up"] : o).fail("\"up\" (default +z) must not be parallel to the barrier's base");
        const int material = resolve(o["material"]);
        room.addPolygon({p0, p1, p1 + h * up, p0 + h * up}, material, "barrier:" + name);
        zone = edgeZoneOccluder(p0 + h * up, p1 + h * up, up, edgeZone(o), o.where());
        zone.type = "barrier";
        // Its foot (a barrier standing free) and its two sides, each with a zone of the same extent beside the
        // edge in the panel's plane, open away from the panel (the corners' quarter-planes beyond two zones
        // stay plain).
        if (o.has("foot_edge") && o["foot_edge"].boolean()) {
          // A foot standing on a surface is no edge: the zone would lie under it, where no sound goes.
          const Vec3 mid = 0.5 * (p0 + p1);
          const double tol = 1e-9 * (1.0 + mid.cwiseAbs().maxCoeff() + (p1 - p0).norm());
          for (std::size_t t = 0; t < room.mesh.triangles.size(); ++t) {
            const auto& tri = room.mesh.triangles[t];
            const Vec3 a = room.mesh.vertices[tri[0]], b = room.mesh.vertices[tri[1]], c = room.mesh.vertices[tri[2]];
            const Vec3 n = (b - a).cross(c - a);
            if (room.isOpening(room.mesh.object_of_triangle[t]) || !(n.norm() > 0.0) ||
                std::abs(n.normalized().dot(up)) < 1.0 - 1e-9 || (closestOnTriangle(mid, a, b, c) - mid).norm() > tol)
              continue;
            const std::string group = t < room.group_of_triangle.size() ? room.group_of_triangle[t] : std::string();
            o["foot_edge"].fail("the barrier's foot stands on surface " + group +
                                ", so it is no edge (a zone under it would get no sound); leave foot_edge out");
          }
          more.push_back(edgeZoneOccluder(p0, p1, -up, edgeZone(o), o.where()));
          more.back().name = name + "/foot";
        }
        if (o.has("side_edges") && o["side_edges"].boolean())
          for (const auto& [at, other, tag] : {std::make_tuple(p0, p1, "/side0"), std::make_tuple(p1, p0, "/side1")}) {
            more.push_back(edgeZoneOccluder(at, at + h * up, at - other, edgeZone(o), o.where()));
            more.back().name = name + tag;
          }
      }
      zone.x.faces = faces(o, OccluderAxis::Faces::Rigid);
      zone.name = name;
      addOccluderRect(room, zone);
      for (Occluder& edge : more) {
        edge.type = "barrier side";
        edge.x.faces = zone.x.faces;
        claimName(names, edge.name, o);
        addOccluderRect(room, edge);
      }
    } else if (type == "grating") {
      o.allowKeys({"type", "name", "centre", "normal", "up", "width_m", "height_m", "period_m", "modulation_m",
                   "material"});
      Occluder occ;
      occ.type = type;
      occ.name = o.has("name") ? o["name"].string() : fallback;
      claimName(names, occ.name, o);
      occ.origin_m = o["centre"].vec3();
      setOccluderFrame(occ, unitVector(o["normal"]), o.has("up") ? unitVector(o["up"]) : Vec3(0, 0, 1), o.where());
      occ.half_x_m = 0.5 * o["width_m"].length();
      occ.half_y_m = 0.5 * o["height_m"].length();
      occ.x.kind = OccluderAxis::Kind::Grating;
      occ.x.period_m = o["period_m"].length();
      // The phase amplitude m/2 (radians) wbsdf::PhaseGrating accepts; checked here to name the field.
      occ.x.modulation_m = o["modulation_m"].length();
      if (occ.x.modulation_m > 1000.0) o["modulation_m"].fail("must be at most 1000 (phase amplitude m/2 ≤ 500 rad)");
      occ.reflect = true;
      occ.material = resolve(o["material"]);
      addOccluderRect(room, occ, occ.material);
    } else {
      o["type"].fail("unknown occluder type " + inQuotes(type) + " (one of door, slit, edge, barrier, grating)");
    }
  }
  if (!room.occluders.empty() && room.listeners.empty())
    warnings.push_back(list.where() + ": occluders but no listener");
}

}  // namespace diffray::room
