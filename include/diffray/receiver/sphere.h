#pragma once
// A sphere receiver (a listener): centre and radius in metres, world frame. It is transparent: rays go
// on through it. Each ray segment deposits its signed energy times the length of the segment's chord
// inside the sphere over the mean chord 4R/3 (a track-length estimator). For rays that cross the whole
// sphere this has the mean of counting each crossing once, so energy / πR² estimates the intensity
// (a sphere of radius R at distance r from a point source is hit by the fraction
// (1 − √(1 − R²/r²))/2 of the rays, its solid angle over 4π); unlike counting, it stays right when a ray starts, ends
// or scatters inside the sphere. As a finite aperture it integrates negative ray energies out (paper section 2.4).
// Immutable; thread-safe.
#include <algorithm>
#include <cmath>

#include "diffray/core/math.h"

namespace diffray::receiver {

struct Sphere {
  core::Vec3 centre{0, 0, 0};
  double radius_m = 0.1;

  double crossSection() const { return core::kPi * radius_m * radius_m; }

  /// The part of the segment origin + t·dir, t in [t0, t1), inside the sphere (dir a unit vector): its entry
  /// and exit distances t_in < t_out, or false if the segment misses the sphere (t_in, t_out then unspecified).
  bool chordSpan(const double* origin, const double* dir, double t0, double t1, double& t_in, double& t_out) const {
    const double oc[3] = {origin[0] - centre.x(), origin[1] - centre.y(), origin[2] - centre.z()};
    const double b = oc[0] * dir[0] + oc[1] * dir[1] + oc[2] * dir[2];
    const double c = oc[0] * oc[0] + oc[1] * oc[1] + oc[2] * oc[2] - radius_m * radius_m;
    const double disc = b * b - c;
    if (disc <= 0.0) return false;
    const double root = std::sqrt(disc);
    t_in = std::max(-b - root, t0);
    t_out = std::min(-b + root, t1);
    return t_out > t_in;
  }
  /// Length of the part of the segment origin + t·dir, t in [t0, t1), inside the sphere (dir a unit vector).
  double chordLength(const double* origin, const double* dir, double t0, double t1) const {
    double t_in = 0.0, t_out = 0.0;
    return chordSpan(origin, dir, t0, t1, t_in, t_out) ? t_out - t_in : 0.0;
  }
  /// The weight of a chord of length `chord`: chord / (4R/3), the mean chord.
  double chordWeight(double chord) const { return chord * 0.75 / radius_m; }
};

}  // namespace diffray::receiver
