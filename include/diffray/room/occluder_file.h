#pragma once
// The scene file's "occluders" list (rooms/README.md): doors, slits, free edges, barriers and gratings
// turned into room::Occluder entries plus the geometry they need (an opening rectangle, a barrier panel,
// a grating panel), with errors naming the file and field. Not synchronised (it builds one Room).
#include <functional>
#include <string>
#include <vector>

#include "diffray/room/json_fields.h"
#include "diffray/room/room.h"

namespace diffray::room {

/// Default width (m) of the zone past a free edge in which rays diffract; past it they go straight.
inline constexpr double kDefaultEdgeZoneM = 10.0;

/// Parses `list` into room.occluders. `resolve` maps a material reference to its index in room.materials.
void parseOccluders(const JsonField& list, Room& room, const std::function<int(const JsonField&)>& resolve,
                    std::vector<std::string>& warnings);

/// Adds an occluder whose opening rectangle (or panel) is added to the mesh as group "occluder:<name>":
/// its triangles use `material`, or an added fully transmitting "occluder-opening" material when −1.
/// Used by the parser and by code that builds scenes (validation cases).
void addOccluderRect(Room& room, Occluder occ, int material = -1);

/// The occluders that are objects of their own: all but the zones of a barrier's other edges ("foot_edge",
/// "side_edges": type "barrier side"), which belong to the barrier listed before them.
std::vector<const Occluder*> ownOccluders(const Room& room);

/// The corners of the occluder's rectangle origin ± half_x·ex ± half_y·ey, in order (counter-clockwise seen
/// from the side the normal points to).
std::vector<Vec3> occluderCorners(const Occluder& o);

/// The occluder's frame from a normal and an up vector: ey = up projected on the plane, ex = ey × normal.
/// Throws InputError(field, ...) when up is parallel to the normal or either is zero.
void setOccluderFrame(Occluder& occ, const Vec3& normal, const Vec3& up, const std::string& field);

}  // namespace diffray::room
