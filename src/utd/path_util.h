#pragma once
// Small geometric helpers shared by the UTD path finders (paths.cpp, reflection_paths.cpp,
// diffraction_paths.cpp). Private to the utd module. Units: metres. Pure functions; thread-safe.
#include "diffray/transport/room_geometry.h"
#include "diffray/utd/paths.h"

namespace diffray::utd::detail {

using core::Vec3;

/// A point-in-triangle test in the triangle's plane (barycentric, tolerance relative to its size).
inline bool insideTriangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 n = (b - a).cross(c - a);
  const double n2 = n.squaredNorm();
  if (!(n2 > 0.0)) return false;
  const double u = (c - b).cross(p - b).dot(n) / n2, v = (a - c).cross(p - c).dot(n) / n2;
  const double w = 1.0 - u - v, tol = 1e-9;
  return u >= -tol && v >= -tol && w >= -tol;
}

/// Signed distance (m) of p from the plane, positive on the side its normal points to.
inline double signedDistance(const transport::MirrorPlane& pl, const Vec3& p) { return pl.normal.dot(p) - pl.offset; }

/// The mirror image of p in the plane.
inline Vec3 mirror(const transport::MirrorPlane& pl, const Vec3& p) { return p - 2.0 * signedDistance(pl, p) * pl.normal; }

/// A first-order specular path s → p → r off triangle `tri`, unfolded length `length_m`, amplitude `gain`.
inline Path reflectionPath(int tri, const Vec3& s, const Vec3& p, const Vec3& r, double length_m, double gain) {
  Path path;
  path.kind = PathKind::Reflection;
  path.order = 1;
  path.triangle = tri;
  path.points = {s, p, r};
  path.length_m = length_m;
  path.gain = gain;
  return path;
}

}  // namespace diffray::utd::detail
