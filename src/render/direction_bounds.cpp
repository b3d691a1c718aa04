#include "diffray/render/direction_bounds.h"

#include <cmath>

#include "diffray/core/error.h"

namespace diffray::render {

using core::Vec3;

namespace {

// Two unit vectors orthogonal to e and to each other.
void orthogonalPair(const Vec3& e, Vec3& w1, Vec3& w2) {
  const Vec3 seed = std::abs(e.x()) < 0.6 ? Vec3(1, 0, 0) : Vec3(0, 1, 0);
  w1 = e.cross(seed).normalized();
  w2 = e.cross(w1);
}

// Whether Z holds a vector parallel to e with v·e > 0 (sign +1) or < 0 (sign −1). The slice
// {v·w1 = v·w2 = 0} of Z is a polytope in s whose vertices have all but two coordinates at ±1; v·e is
// linear on it, so its extremes are at those vertices.
void parallelPoints(const Vec3& c, const std::vector<Vec3>& g, const Vec3& e, CosineRange& r) {
  Vec3 w1, w2;
  orthogonalPair(e, w1, w2);
  const int m = static_cast<int>(g.size());
  double scale = c.norm();
  for (const Vec3& v : g) scale += v.norm();
  const auto consider = [&](const Vec3& v) {
    const double along = v.dot(e);
    if (along > 1e-12 * scale) r.add(1.0);
    if (along < -1e-12 * scale) r.add(-1.0);
  };
  for (int i = 0; i < m; ++i)
    for (int j = i + 1; j < m; ++j) {
      const double a11 = g[i].dot(w1), a12 = g[j].dot(w1), a21 = g[i].dot(w2), a22 = g[j].dot(w2);
      const double det = a11 * a22 - a12 * a21;
      if (std::abs(det) <= 1e-14 * (std::abs(a11 * a22) + std::abs(a12 * a21)) || det == 0.0) continue;
      const int others = m - 2;
      for (int mask = 0; mask < (1 << others); ++mask) {
        Vec3 base = c;
        for (int q = 0, bit = 0; q < m; ++q) {
          if (q == i || q == j) continue;
          base += ((mask >> bit++) & 1 ? 1.0 : -1.0) * g[q];
        }
        const double r1 = -base.dot(w1), r2 = -base.dot(w2);
        const double si = (r1 * a22 - a12 * r2) / det, sj = (a11 * r2 - r1 * a21) / det;
        if (std::abs(si) <= 1.0 + 1e-12 && std::abs(sj) <= 1.0 + 1e-12) consider(base + si * g[i] + sj * g[j]);
      }
    }
}

}  // namespace

CosineRange cosineRange(const Vec3& c, const std::vector<Vec3>& g, const Vec3& e) {
  DIFFRAY_CHECK(g.size() >= 2 && g.size() <= 4);
  CosineRange r;
  const auto full = [] {
    CosineRange all;
    all.add(-1.0);
    all.add(1.0);
    return all;
  };
  const int m = static_cast<int>(g.size());
  // The edges: along generator j, from −g_j to +g_j, at every sign pattern of the others.
  for (int j = 0; j < m; ++j)
    for (int mask = 0; mask < (1 << (m - 1)); ++mask) {
      Vec3 a = c - g[j];
      for (int q = 0, bit = 0; q < m; ++q) {
        if (q == j) continue;
        a += ((mask >> bit++) & 1 ? 1.0 : -1.0) * g[q];
      }
      const Vec3 d = 2.0 * g[j];
      const auto at = [&](double s) {
        const Vec3 v = a + s * d;
        const double len = v.norm();
        if (!(len > 0.0)) return false;  // the set reaches 0: objects touch
        r.add(v.dot(e) / len);
        return true;
      };
      if (!at(0.0) || !at(1.0)) return full();
      const double ce = a.dot(e), k = d.dot(e), b = a.dot(d), dd = d.dot(d), a2 = a.dot(a);
      const double den = k * b - ce * dd;
      if (den != 0.0) {
        const double s = (ce * b - k * a2) / den;
        if (s > 0.0 && s < 1.0 && !at(s)) return full();
      }
    }
  parallelPoints(c, g, e, r);
  return r;
}

}  // namespace diffray::render
