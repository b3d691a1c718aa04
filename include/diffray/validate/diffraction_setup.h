#pragma once
// Scenes of the diffraction validation cases (diffraction_cases.cpp), built in code from case parameters.
// Half-plane frame (the same as reference/fresnel.h's Sommerfeld solution): the edge is the world z axis,
// the screen the half-plane {y = 0, x ≥ 0} (faces φ = 0 and φ = 2π), angles φ measured from +x toward +y;
// a source at φ0 < π lights the face φ = 0 and the geometric shadow is φ > π + φ0. The screen is a rigid
// panel (absorption 0, no scattering) `panel_m` wide and tall; the WBSDF edge zone is the rectangle of the
// plane y = 0 from the edge to x = −zone_m. Octave bands 125 Hz–4 kHz, air 20 °C, no absorption by air.
// Units: metres, radians. Pure functions.
#include <vector>

#include "diffray/room/room.h"

namespace diffray::validate {

struct HalfPlaneSpec {
  double source_rho_m = 10.0, source_phi_rad = 1.0471975511965976;  ///< 60°
  double listener_rho_m = 5.0;
  std::vector<double> listener_phi_rad;  ///< one listener per angle
  double radius_m = 0.15;
  double panel_m = 60.0;
  double zone_m = 10.0;
  double absorption = 0.0;  ///< of the screen's faces
  room::OccluderAxis::Faces faces = room::OccluderAxis::Faces::Rigid;
};

room::Room makeHalfPlaneScene(const HalfPlaneSpec& spec);

}  // namespace diffray::validate

namespace diffray::validate {

/// A door in a thin black (absorbing) screen standing on a rigid floor, otherwise free field: the path
/// through a doorway between two rooms, without the rooms' reverberation. Frame: the screen is the plane
/// x = 0, the floor z = 0, the door spans y in [−width/2, width/2], z in [0, height]; the source is at
/// x < 0 (room A), the listeners at x > 0 (room B). The door is a WBSDF opening with sill "floor".
struct DoorSpec {
  double width_m = 0.9, height_m = 2.1;
  core::Vec3 source_m{-2.5, 0.0, 1.5};
  std::vector<core::Vec3> listeners_m;
  double radius_m = 0.15;
  double screen_m = 40.0;  ///< half-extent of the screen and the floor
  bool floor = true;       ///< false: no floor, the door is an opening in a free-standing screen (sill none)
};

room::Room makeDoorScene(const DoorSpec& spec);

/// The angle (degrees) by which `listener` lies in the shadow of the door's vertical jambs, seen from
/// `source` in the horizontal plane: > 0 hidden behind a jamb, < 0 in view through the opening.
double doorShadowAngleDeg(const DoorSpec& spec, const core::Vec3& listener);

}  // namespace diffray::validate
