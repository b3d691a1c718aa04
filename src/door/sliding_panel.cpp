#include "diffray/door/sliding_panel.h"

#include <cmath>

#include "diffray/core/error.h"
#include "diffray/room/occluder_file.h"

namespace diffray::door {

int findDoor(const room::Room& room, const std::string& name) {
  int found = -1, doors = 0;
  for (int k = 0; k < static_cast<int>(room.occluders.size()); ++k) {
    const room::Occluder& o = room.occluders[k];
    if (o.type != "door") continue;
    ++doors;
    if (name.empty() || o.name == name) found = k;
  }
  if (!name.empty() && found < 0) throw core::InputError("--door", "the room has no door named \"" + name + "\"");
  if (doors == 0)
    throw core::InputError("--door", "the room has no door (an occluder of type \"door\", rooms/README.md)");
  if (name.empty() && doors > 1) throw core::InputError("--door", "the room has several doors: name one with --door");
  if (room.occluders[found].x.kind != room::OccluderAxis::Kind::Opening)
    throw core::InputError("--door", "door \"" + room.occluders[found].name + "\" is a slit array; only a single "
                                     "opening slides shut");
  return found;
}

room::Room withSlidingPanel(const room::Room& room, int door, double open_width_m, int panel_material) {
  if (door < 0 || door >= static_cast<int>(room.occluders.size())) throw core::InternalError("withSlidingPanel: bad door");
  const room::Occluder& d = room.occluders[door];
  const double width = 2.0 * d.half_x_m;
  if (!(open_width_m >= 0.0 && open_width_m <= width * (1.0 + 1e-12)))
    throw core::InputError("door " + d.name, "the gap must be in [0, " + std::to_string(width) + "] m");
  const int panel = panel_material >= 0 ? panel_material : d.panel_material;
  if (panel < 0 || panel >= static_cast<int>(room.materials.size()))
    throw core::InputError("door " + d.name, "has no panel material: add \"panel\": \"door-panel\" (or another "
                                             "material) to the door in the scene file");

  // The room without the door's opening (and leaf) triangles.
  room::Room out = room;
  const std::string leaf = "leaf:" + d.name;
  int opening_material = -1;
  out.mesh.triangles.clear();
  out.mesh.object_of_triangle.clear();
  out.group_of_triangle.clear();
  for (std::size_t t = 0; t < room.mesh.triangles.size(); ++t) {
    const std::string& g = room.group_of_triangle[t];
    if (g == d.group) opening_material = room.mesh.object_of_triangle[t];
    if (g == d.group || g == leaf) continue;
    out.mesh.triangles.push_back(room.mesh.triangles[t]);
    out.mesh.object_of_triangle.push_back(room.mesh.object_of_triangle[t]);
    out.group_of_triangle.push_back(g);
  }
  if (opening_material < 0) throw core::InternalError("withSlidingPanel: door " + d.name + " has no triangles");

  // Gap on [−hx, −hx + w], panel on [−hx + w, hx] (local x).
  const double gap = open_width_m < kShutGapM ? 0.0 : std::min(open_width_m, width);
  room::Occluder part = d;
  if (gap < width) {
    part.half_x_m = 0.5 * (width - gap);
    part.origin_m = d.origin_m + (d.half_x_m - part.half_x_m) * d.ex;
    out.addPolygon(room::occluderCorners(part), panel, "panel:" + d.name);
  }
  if (gap > 0.0) {
    room::Occluder& g = out.occluders[door];
    g.half_x_m = 0.5 * gap;
    g.origin_m = d.origin_m + (g.half_x_m - d.half_x_m) * d.ex;
    g.x.lo_m = -g.half_x_m, g.x.hi_m = g.half_x_m;
    out.addPolygon(room::occluderCorners(g), opening_material, d.group);
  } else {
    out.occluders.erase(out.occluders.begin() + door);
  }
  return out;
}

}  // namespace diffray::door
