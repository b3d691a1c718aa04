#pragma once
// A WBSDF occluder in a room: a planar rectangle whose microstructure t(x, y) makes
// the rays that cross (or, for gratings, meet) it diffract, by the separable Wigner distribution
// W(x,y,u,v) = W_x(x,u)·W_y(y,v) of its two local axes. Doors and slits are openings in a
// wall, an edge is the open side of a half-plane (the zone beyond a barrier's free edge), a grating is a
// reflecting phase profile (a diffuser). The surrounding wall keeps its own material and transmission: an
// occluder covers only its opening (or its grating panel), which is a set of triangles of the room's mesh
// named by `group`. Frame: world metres; local x = (p − origin)·ex, y = (p − origin)·ey, normal = ex × ey.
// Plain data, built by the scene parser (room/occluder_file.h) or in code; safe to share between threads.
#include <string>

#include "diffray/core/math.h"

namespace diffray::room {

using core::Vec3;

/// How the microstructure varies along one local axis.
struct OccluderAxis {
  enum class Kind {
    Uniform,  ///< t = 1 along this axis (no diffraction across it)
    Opening,  ///< open on [lo, hi], opaque outside: a slit or the width / height of a door
    Edge,     ///< a half-plane edge at lo, open toward +: the zone past a barrier's free edge
    Slits,    ///< `count` openings of width hi − lo, centres `spacing_m` apart, centred on 0
    Grating,  ///< sinusoidal phase grating t = exp(i(m/2)·sin(2πx/Λ)) (paper eq. 14–15)
  };
  Kind kind = Kind::Uniform;
  double lo_m = 0.0, hi_m = 0.0;
  /// Opening only: the lo side stands on a rigid floor perpendicular to the occluder (a door's sill); by the
  /// image principle the opening is [2·lo − hi, hi] mirrored, so only the hi edge diffracts.
  bool mirror_lo = false;
  /// Opening and Edge: the faces next to each diffracting edge. Kirchhoff: the plain WBSDF (it lands between
  /// the soft and rigid exact solutions, as Kirchhoff theory does); Rigid / Soft: each ray's energy is also weighted by
  /// |1 ± cos((φ − φ0)/2)/cos((φ + φ0)/2)|², the ratio of the rigid (soft) half-plane's diffraction coefficient
  /// to the Kirchhoff one (Sommerfeld's two terms; Born & Wolf, "Principles of Optics", §11.5), with φ0, φ the incident
  /// and outgoing directions in the plane across the nearer edge, measured from its screen face.
  enum class Faces { Kirchhoff, Rigid, Soft };
  Faces faces = Faces::Kirchhoff;
  int count = 1;
  double spacing_m = 0.0;
  double period_m = 0.0, modulation_m = 0.0;
};

struct Occluder {
  std::string name;
  std::string type;   ///< "door", "slit", "edge", "barrier", "grating" (for messages and outputs)
  std::string group;  ///< the mesh group whose triangles the occluder covers
  Vec3 origin_m{0, 0, 0};
  Vec3 ex{1, 0, 0}, ey{0, 1, 0}, normal{0, 0, 1};
  double half_x_m = 0.0, half_y_m = 0.0;  ///< the rectangle [−hx, hx] × [−hy, hy] around origin
  OccluderAxis x, y;
  /// Gratings: the diffracted wave leaves on the incident side (paper eq. 9–10), scaled by the reflectance
  /// 1 − α of `material`; openings and edges transmit.
  bool reflect = false;
  int material = -1;
  /// Doors: the material of the panel that slides across the opening to close it (`diffray door`,
  /// door/sliding_panel.h), or −1 when the scene gives none.
  int panel_material = -1;
};

}  // namespace diffray::room
