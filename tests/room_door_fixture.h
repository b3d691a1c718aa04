#pragma once
// A door occluder shared by the room tests: 0.9 × 2.1 m, standing on the floor (its sill mirrored by the
// floor, as a scene file's "sill": "floor") in the plane x = x_m, centred on y = 1.5, facing +x.
#include "diffray/room/occluder_file.h"

namespace diffray::testing {

inline room::Occluder floorDoorAtX(double x_m) {
  room::Occluder d;
  d.name = "door";
  d.type = "door";
  room::setOccluderFrame(d, core::Vec3(1, 0, 0), core::Vec3(0, 0, 1), "test");
  d.origin_m = core::Vec3(x_m, 1.5, 1.05);
  d.half_x_m = 0.45;
  d.half_y_m = 1.05;
  d.x.kind = d.y.kind = room::OccluderAxis::Kind::Opening;
  d.x.lo_m = -0.45, d.x.hi_m = 0.45;
  d.y.lo_m = -1.05, d.y.hi_m = 1.05;
  d.y.mirror_lo = true;
  return d;
}

}  // namespace diffray::testing
