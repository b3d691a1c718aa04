#pragma once
// Listener placements that `diffray compare` cannot give a meaningful level for, found from the scene's
// geometry alone before any model runs: a listener at the source, a listener whose sphere meets the wall
// or screen around the occluder, a listener hidden behind a surface (below an absorbing ground), and, for
// `--aim`, a listener that the source sees directly past the aim rectangle (no aimed ray can reach it, so
// the WBSDF level would miss its direct sound). Source 0 of the room is the source. Positions in metres,
// the room's frame. Pure functions of their arguments (brute force over the mesh's triangles).
#include <string>
#include <vector>

#include "diffray/room/room.h"

namespace diffray::compare {

/// Throws core::InputError naming the listener when it coincides with source 0 (no level re free field
/// exists there) or when its sphere meets a surface lying in an occluder's plane outside that occluder's
/// rectangle: the screen of a barrier or the wall around a door.
void checkListeners(const room::Room& room);

/// One warning per listener hidden from source 0 behind a surface that is not in an occluder's plane: its
/// foot on the surface's plane lies inside the surface and the source is on the plane's other side (a
/// listener below the ground). Every model gives it no sound, or only what leaks round the surface's edges.
/// A face of a closed object the listener is outside of (a cupboard it stands behind) is no such surface.
std::vector<std::string> hiddenListenerWarnings(const room::Room& room);

/// The rectangle every aimed WBSDF ray goes through (transport::EmissionTarget's frame).
struct AimRect {
  core::Vec3 origin{0, 0, 0}, ex{1, 0, 0}, ey{0, 1, 0};
  double half_x_m = 0.0, half_y_m = 0.0;
};

/// The specular ground `--aim` also aims through (transport::EmissionTarget::mirrored): the plane
/// normal·p = offset, when `present`.
struct AimGround {
  bool present = false;
  core::Vec3 normal{0, 0, 1};
  double offset = 0.0;
};

/// `--aim`: throws core::InputError naming the first listener that an unblocked path from source 0 reaches
/// (the occluders' own rectangles aside) without passing through one of `aims`: the straight line, and with
/// a `ground` the path reflected once off it. No aimed ray takes such a path, so the listener's WBSDF level
/// would lack it.
void checkAimReachesListeners(const room::Room& room, const std::vector<AimRect>& aims, const AimGround& ground = {});

/// `--aim`: throws core::InputError naming the first reflecting surface (a material that does not absorb
/// everything in every band) outside the occluders' own groups that the aimed rays cannot take into
/// account: aimed rays go straight at the occluder, so the paths that meet such a surface first would be
/// dropped. Allowed: a door's sill floor (the door's model takes the floor in by the image principle), the
/// screen in the occluder's own plane (what it reflects stays on the source's side), and for an edge or a
/// barrier one plane perpendicular to its plane that leaves its zone on one side and reflects specularly in
/// every band (scattering 0): the ground it stands on, returned, which the rays are then aimed through too.
AimGround checkAimReflectors(const room::Room& room);

/// The angle `deg` wrapped into (−180°, 180°].
double wrapDegrees(double deg);

}  // namespace diffray::compare
