#include "diffray/utd/apex.h"

#include <algorithm>
#include <cmath>

namespace diffray::utd {

namespace {

bool onSegment(const Edge& e, double& s) {
  const double tol = 1e-9 * std::max(e.length_m, 1e-12);
  if (s < -tol || s > e.length_m + tol) return false;
  s = std::clamp(s, 0.0, e.length_m);
  return true;
}

// Length of a → Q1(s1) → Q2(s2) → b, its gradient and Hessian in (s1, s2).
struct Objective {
  const Edge &e1, &e2;
  const Vec3 &a, &b;
  double eval(double s1, double s2, double g[2], double h[3]) const {
    const Vec3 q1 = e1.at(s1), q2 = e2.at(s2);
    const Vec3 u = q1 - a, v = q2 - q1, w = b - q2;
    const double lu = u.norm(), lv = v.norm(), lw = w.norm();
    const Vec3 uh = u / lu, vh = v / lv, wh = w / lw;
    const Vec3 &t1 = e1.tangent, &t2 = e2.tangent;
    g[0] = uh.dot(t1) - vh.dot(t1);
    g[1] = vh.dot(t2) - wh.dot(t2);
    // ∂²|x|/∂s∂s' = (dx·dx' − (x̂·dx)(x̂·dx'))/|x| for x linear in s.
    h[0] = (1.0 - uh.dot(t1) * uh.dot(t1)) / lu + (1.0 - vh.dot(t1) * vh.dot(t1)) / lv;
    h[1] = (-t1.dot(t2) + vh.dot(t1) * vh.dot(t2)) / lv;
    h[2] = (1.0 - vh.dot(t2) * vh.dot(t2)) / lv + (1.0 - wh.dot(t2) * wh.dot(t2)) / lw;
    return lu + lv + lw;
  }
};

}  // namespace

bool apexOnLine(const Edge& edge, const Vec3& a, const Vec3& b, double& s_m) {
  const Vec3 pa = a - edge.start, pb = b - edge.start;
  const double za = pa.dot(edge.tangent), zb = pb.dot(edge.tangent);
  const double ra = (pa - za * edge.tangent).norm(), rb = (pb - zb * edge.tangent).norm();
  if (!(ra + rb > 0.0)) return false;
  // Unfold the half-planes through a and through b about the edge into one plane: the straight line from
  // (za, ra) to (zb, −rb) crosses the edge at za + (zb − za)·ra/(ra + rb).
  s_m = za + (zb - za) * ra / (ra + rb);
  return true;
}

bool apexOnEdge(const Edge& edge, const Vec3& a, const Vec3& b, double& s_m) {
  return apexOnLine(edge, a, b, s_m) && onSegment(edge, s_m);
}

bool apexesOnEdges(const Edge& e1, const Edge& e2, const Vec3& a, const Vec3& b, double& s1_m, double& s2_m) {
  const Objective f{e1, e2, a, b};
  double s1 = 0.5 * e1.length_m, s2 = 0.5 * e2.length_m;
  double g[2], h[3];
  double len = f.eval(s1, s2, g, h);
  const double scale = std::max(e1.length_m, e2.length_m);
  for (int it = 0; it < 100; ++it) {
    if (std::hypot(g[0], g[1]) < 1e-13) break;
    // Newton step with a Levenberg shift when the Hessian is near singular, then backtracking: the
    // objective is convex, so a descent step always exists.
    const double mu = 1e-12 * (std::abs(h[0]) + std::abs(h[2]) + 1e-300);
    const double h0 = h[0] + mu, h2 = h[2] + mu, det = h0 * h2 - h[1] * h[1];
    double d1, d2;
    if (det > 1e-18 * (h0 * h2)) {
      d1 = -(h2 * g[0] - h[1] * g[1]) / det;
      d2 = -(h0 * g[1] - h[1] * g[0]) / det;
    } else {
      d1 = -g[0] * scale;
      d2 = -g[1] * scale;
    }
    double step = 1.0, g_new[2], h_new[3], len_new = 0.0;
    for (int k = 0; k < 60; ++k, step *= 0.5) {
      len_new = f.eval(s1 + step * d1, s2 + step * d2, g_new, h_new);
      if (len_new <= len + 1e-15 * len) break;
    }
    s1 += step * d1;
    s2 += step * d2;
    std::copy(g_new, g_new + 2, g);
    std::copy(h_new, h_new + 3, h);
    const bool tiny = std::abs(step * d1) + std::abs(step * d2) < 1e-14 * (scale + 1.0);
    len = len_new;
    if (tiny) break;
  }
  if (std::hypot(g[0], g[1]) > 1e-8) return false;
  s1_m = s1;
  s2_m = s2;
  return onSegment(e1, s1_m) && onSegment(e2, s2_m);
}

}  // namespace diffray::utd
