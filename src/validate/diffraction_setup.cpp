#include "diffray/validate/diffraction_setup.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "diffray/room/occluder_file.h"

namespace diffray::validate {

using core::Vec3;

room::Room makeHalfPlaneScene(const HalfPlaneSpec& spec) {
  room::Room room;
  room.name = "half-plane";
  room.bands = core::Bands::octave(125.0, 4000.0);
  room::Material screen;
  screen.name = "rigid-screen";
  screen.absorption = core::bandFill(spec.absorption);
  const int m = room.addMaterial(screen);
  const double p = spec.panel_m;
  room.addPolygon({Vec3(0, 0, -0.5 * p), Vec3(p, 0, -0.5 * p), Vec3(p, 0, 0.5 * p), Vec3(0, 0, 0.5 * p)}, m, "screen");
  room::Occluder zone;
  zone.name = "edge";
  zone.type = "edge";
  zone.ex = Vec3(-1, 0, 0);  // toward the open side
  zone.ey = Vec3(0, 0, 1);   // along the edge
  zone.normal = zone.ex.cross(zone.ey);
  zone.half_x_m = 0.5 * spec.zone_m;
  zone.half_y_m = 0.5 * p;
  zone.origin_m = zone.half_x_m * zone.ex;
  zone.x.kind = room::OccluderAxis::Kind::Edge;
  zone.x.lo_m = -zone.half_x_m, zone.x.hi_m = zone.half_x_m;
  zone.x.faces = spec.faces;
  room::addOccluderRect(room, zone);
  room::Source s;
  s.name = "S";
  s.position_m = Vec3(spec.source_rho_m * std::cos(spec.source_phi_rad), spec.source_rho_m * std::sin(spec.source_phi_rad), 0);
  room.sources.push_back(s);
  for (std::size_t i = 0; i < spec.listener_phi_rad.size(); ++i) {
    room::Listener l;
    l.name = "R" + std::to_string(i + 1);
    const double phi = spec.listener_phi_rad[i];
    l.position_m = Vec3(spec.listener_rho_m * std::cos(phi), spec.listener_rho_m * std::sin(phi), 0);
    l.radius_m = spec.radius_m;
    room.listeners.push_back(l);
  }
  return room;
}

}  // namespace diffray::validate

namespace diffray::validate {

room::Room makeDoorScene(const DoorSpec& spec) {
  room::Room room;
  room.name = "door-room";
  room.bands = core::Bands::octave(125.0, 4000.0);
  room::Material black;
  black.name = "black-screen";
  black.absorption = core::bandFill(1.0);
  room::Material floor;
  floor.name = "rigid-floor";
  const int mb = room.addMaterial(black), mf = room.addMaterial(floor);
  const double s = spec.screen_m, hw = 0.5 * spec.width_m, h = spec.height_m;
  const double z0 = spec.floor ? 0.0 : -s;  // the screen's bottom: the floor, or far below the door
  if (spec.floor) room.addPolygon({Vec3(-s, -s, 0), Vec3(s, -s, 0), Vec3(s, s, 0), Vec3(-s, s, 0)}, mf, "floor");
  else room.addPolygon({Vec3(0, -hw, z0), Vec3(0, hw, z0), Vec3(0, hw, 0), Vec3(0, -hw, 0)}, mb, "screen");
  // The screen around the door: left, right and above it.
  room.addPolygon({Vec3(0, -s, z0), Vec3(0, -hw, z0), Vec3(0, -hw, s), Vec3(0, -s, s)}, mb, "screen");
  room.addPolygon({Vec3(0, hw, z0), Vec3(0, s, z0), Vec3(0, s, s), Vec3(0, hw, s)}, mb, "screen");
  room.addPolygon({Vec3(0, -hw, h), Vec3(0, hw, h), Vec3(0, hw, s), Vec3(0, -hw, s)}, mb, "screen");
  room::Occluder door;
  door.name = "door";
  door.type = "door";
  door.origin_m = Vec3(0, 0, 0.5 * h);
  room::setOccluderFrame(door, Vec3(1, 0, 0), Vec3(0, 0, 1), "door");
  door.half_x_m = hw;
  door.half_y_m = 0.5 * h;
  door.x.kind = room::OccluderAxis::Kind::Opening;
  door.x.lo_m = -hw, door.x.hi_m = hw;
  door.y.kind = room::OccluderAxis::Kind::Opening;
  door.y.lo_m = -0.5 * h, door.y.hi_m = 0.5 * h;
  door.y.mirror_lo = spec.floor;
  room::addOccluderRect(room, door);
  room.sources.push_back({"S", spec.source_m, 1.0, {}});
  for (std::size_t i = 0; i < spec.listeners_m.size(); ++i)
    room.listeners.push_back({"R" + std::to_string(i + 1), spec.listeners_m[i], spec.radius_m});
  return room;
}

double doorShadowAngleDeg(const DoorSpec& spec, const core::Vec3& listener) {
  // Horizontal plane: y across the door, x through it. Each jamb's shadow boundary continues the line from
  // the source through the jamb; the listener's angle past it, positive on the hidden side.
  const double hw = 0.5 * spec.width_m;
  double worst = -1e300;
  for (const double jamb : {-hw, hw}) {
    const double boundary = std::atan2(jamb - spec.source_m.y(), -spec.source_m.x());
    const double seen = std::atan2(listener.y() - jamb, listener.x());
    const double past = jamb > 0 ? seen - boundary : boundary - seen;
    worst = std::max(worst, past);
  }
  return worst * 180.0 / core::kPi;
}

}  // namespace diffray::validate
