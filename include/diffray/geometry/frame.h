#pragma once
// A planar object's local frame: origin, two in-plane unit axes ex, ey and the normal n = ex × ey (world
// frame, metres, double precision). Local coordinates of a hit, (p − origin)·ex and ·ey, are what a WBSDF
// is indexed by, so the tracer computes them in double from the ray, never from Embree's
// float hit. Plain value type.
#include "diffray/core/math.h"

namespace diffray::geometry {

struct Frame {
  core::Vec3 origin{0, 0, 0};
  core::Vec3 ex{1, 0, 0};
  core::Vec3 ey{0, 1, 0};
  core::Vec3 n{0, 0, 1};

  /// Frame at `origin` with normal `normal` and in-plane x axis as close as possible to `x_hint`.
  static Frame make(const core::Vec3& origin, const core::Vec3& normal, const core::Vec3& x_hint);

};

}  // namespace diffray::geometry
