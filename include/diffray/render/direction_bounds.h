#pragma once
// Exact extremes of a direction's cosines over a set of vectors: what render/light_setup.cpp needs to size
// an occluder's table (the largest change of direction cosine between light arriving at the occluder and
// light leaving it for an object).
//
// The set is a parallelotope of vectors Z = {c + Σ_j s_j·g_j : |s_j| ≤ 1} (2 to 4 generators): the
// differences p − h between a point p of one rectangle and a point h of another (or of one rectangle and a
// fixed point). For a unit axis e, f(v) = v·e/|v| over Z is extreme either where v is parallel to ±e
// (f = ±1, inside Z: found exactly from the vertices of the slice of Z by v·w₁ = v·w₂ = 0, w₁, w₂ ⟂ e, on
// which v·e is linear), or on Z's boundary, whose extremes lie on its edges (segments along one generator):
// at an end, or where f' = 0, which on a segment A + s·d has the single root
// s* = (c·b − k·A²)/(k·b − c·D) (c = A·e, k = d·e, b = A·d, D = d·d). Segments are taken for every generator
// and every sign pattern of the others, a superset of Z's edges lying inside Z, so nothing is over- or
// under-counted. Corners alone are not enough: from h = 0, the square z = 1, |x|, |y| ≤ 1 has
// x/|v| = 1/√3 at a corner and 1/√2 at the middle of the edge x = 1.
// A set that reaches v = 0 (objects touching) gives the full range [−1, 1]. Pure functions; thread-safe.
#include <vector>

#include "diffray/core/math.h"

namespace diffray::render {

struct CosineRange {
  double lo = 1.0, hi = -1.0;  ///< empty until add()
  void add(double v) {
    lo = v < lo ? v : lo;
    hi = v > hi ? v : hi;
  }
  bool empty() const { return lo > hi; }
};

/// The range of v·e/|v| over Z = {c + Σ s_j·g_j : |s_j| ≤ 1}; e a unit vector, 2 ≤ g.size() ≤ 4.
CosineRange cosineRange(const core::Vec3& c, const std::vector<core::Vec3>& g, const core::Vec3& e);

}  // namespace diffray::render
