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
