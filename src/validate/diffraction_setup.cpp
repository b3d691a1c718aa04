#include "diffray/validate/diffraction_setup.h"

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
