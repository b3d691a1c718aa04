#pragma once
// Diffracting edges of a room mesh, for UTD (Kouyoumjian & Pathak 1974). An edge is a straight segment where the
// surface bends or ends, seen from the air: a wedge whose exterior (air) sector spans nπ with n > 1
// (convex as seen from the air). A free edge of a thin plate is a half-plane (n = 2); the edge of a box
// obstacle or of a doorway is a right-angled wedge (n = 1.5); the inside corners of a room are concave
// (n = 0.5) and do not diffract.
//
// Extraction: vertices are welded (tolerance relative to the room's extent); openings (Room::isOpening, an
// open doorway) are not surfaces; triangle edges are grouped into straight chains (collinear edges that
// touch, so T-junctions are handled), cut into elementary intervals, and around each interval the faces
// are sorted by angle. A line lying inside another surface's triangle (the foot of a panel standing on a
// ground meshed without the panel's vertices) has that triangle as a face on each side it covers, so the foot
// is two inside corners, not a free edge. Each angular gap between faces larger than π whose middle is air is a wedge;
// consecutive intervals with the same two faces are merged into one edge. Which side is air is not taken
// from the winding: a point is air when it lies on the same side as the air point (parity of crossings with
// the closed parts of the mesh, which is what encloses or excludes air; open parts such as thin plates
// have air on both sides). The air point is EdgeOptions::air_point, else the room's first source, else
// "inside the closed surfaces" when there are any (a room) and everywhere when there are none.
//
// Frame of an edge: tangent t from start to end; the air sector turns counter-clockwise about t from
// face 0 (φ = 0) to face n (φ = nπ); normal0 = t × face0_dir and normaln = facen_dir × t point into the air.
// Units: metres, radians. Plain data; extraction is a pure function of the room (thread-safe).
#include <optional>
#include <vector>

#include "diffray/core/math.h"
#include "diffray/room/room.h"
#include "diffray/transport/room_geometry.h"

namespace diffray::utd {

using core::Vec3;

struct Edge {
  Vec3 start{0, 0, 0}, end{0, 0, 0};
  Vec3 tangent{1, 0, 0};  ///< unit, start → end
  double length_m = 0.0;
  double wedge_n = 2.0;  ///< exterior (air) angle / π, > 1
  Vec3 face0_dir{0, 1, 0}, facen_dir{0, 1, 0};  ///< unit, ⊥ tangent, from the edge into each face
  Vec3 normal0{0, 0, 1}, normaln{0, 0, -1};     ///< unit face normals pointing into the air
  int triangle0 = -1, trianglen = -1;           ///< a triangle of each face (the same one for a plate)
  int material0 = -1, materialn = -1;           ///< material index of each face

  Vec3 at(double s_m) const { return start + s_m * tangent; }
  /// Angle of point p about the edge, measured from face 0 towards face n, in [0, 2π); in the air when
  /// it is in [0, nπ].
  double phi(const Vec3& p) const;
  /// Unit direction ⊥ tangent into the air, halfway between the faces (φ = nπ/2).
  Vec3 bisector() const;
};

struct EdgeOptions {
  std::optional<Vec3> air_point;  ///< a point known to be in the air (default: see the header)
  double weld_relative = 1e-6;    ///< vertex welding tolerance as a fraction of the room's extent
};

/// The diffracting edges (n > 1) of the room's surfaces, in a deterministic order.
std::vector<Edge> extractEdges(const room::Room& room, const transport::RoomGeometry& geometry,
                               const EdgeOptions& options = {});

}  // namespace diffray::utd
