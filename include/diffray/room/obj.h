#pragma once
// Wavefront OBJ geometry for rooms. Read: `v x y z [w]`, `f` with any of the index forms v, v/vt,
// v/vt/vn, v//vn (only the vertex index is used; negative indices count back from the last vertex
// read), `g NAME`, `o NAME`, `usemtl NAME` and `#` comments; vt, vn, vp, s, mtllib, l, p and the
// other display-only statements are ignored; any other statement is an error. Every face belongs to a
// group: the current `usemtl` name if one was given (usemtl wins over g/o, as it names the surface),
// else the current `g`/`o` name, else "default". Errors name "FILE:LINE". Units are metres; the file's
// frame is the scene frame. Plain data and free functions; thread-safe.
#include <istream>
#include <string>
#include <vector>

#include "diffray/core/math.h"
#include "diffray/room/room.h"

namespace diffray::room {

struct ObjFace {
  std::vector<int> vertices;  ///< 0-based indices into ObjModel::vertices (≥ 3)
  int group = 0;              ///< index into ObjModel::groups
  int line = 0;               ///< 1-based line in the file, for messages
};

struct ObjModel {
  std::string file;
  std::vector<core::Vec3> vertices;
  std::vector<ObjFace> faces;
  std::vector<std::string> groups;  ///< group names in order of first use by a face
};

ObjModel parseObj(std::istream& in, const std::string& file);
/// Reads the file; a missing file throws core::InputError naming it.
ObjModel loadObj(const std::string& path);

/// Appends the model's faces to `room`, face group g getting material index material_of_group[g].
/// Triangles share the model's vertices; convex polygons (winding once) are fanned, others go through
/// Room::addPolygon (ear clipping). Faces of (near) zero area are skipped and counted in the return
/// value. A non-planar or self-intersecting polygon throws core::InputError naming FILE:LINE.
int addObjToRoom(const ObjModel& model, const std::vector<int>& material_of_group, Room& room);

}  // namespace diffray::room
