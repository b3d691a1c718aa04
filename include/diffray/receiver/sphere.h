#pragma once
// A sphere receiver (a listener): centre and radius in metres, world frame. It is transparent: every
// ray segment that passes through it deposits the ray's signed energy once and goes on. The energy over
// the sphere's cross-section πR² estimates the intensity there (design.md §2: a sphere of radius R at
// distance r from a point source is hit by the fraction (1 − √(1 − R²/r²))/2 of the rays). As a finite
// aperture it integrates negative ray energies out (paper section 2.4). Immutable; thread-safe.
#include "diffray/core/math.h"

namespace diffray::receiver {

struct Sphere {
  core::Vec3 centre{0, 0, 0};
  double radius_m = 0.1;

  double crossSection() const { return core::kPi * radius_m * radius_m; }

  /// Whether the segment origin + t·dir, t in [t0, t1), passes through the sphere (dir a unit vector).
  bool crossedBy(const double* origin, const double* dir, double t0, double t1) const {
    const double oc[3] = {origin[0] - centre.x(), origin[1] - centre.y(), origin[2] - centre.z()};
    const double b = oc[0] * dir[0] + oc[1] * dir[1] + oc[2] * dir[2];
    const double c = oc[0] * oc[0] + oc[1] * oc[1] + oc[2] * oc[2] - radius_m * radius_m;
    const double disc = b * b - c;
    if (disc <= 0.0) return false;
    const double root = std::sqrt(disc);
    const double t_in = -b - root, t_out = -b + root;
    return t_out > t0 && t_in < t1;
  }
};

}  // namespace diffray::receiver
