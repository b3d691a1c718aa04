// Next-event estimation at WBSDF occluders (RoomOccluders::expectedSphereScore): the expectation, over the
// edge kernel's draw (wbsdf/edge_kernel.h: W(x,u) du = sinc(w) dw, w = 4d·u), of what the scattered ray
// scores in a listener sphere on its next segment. Deep in a shadow that score is a small signed residue
// of many rays with weights of both signs; integrating the draw out by quadrature leaves only the noise
// of where and at which frequency rays meet the occluder.
#include <algorithm>
#include <cmath>
#include <limits>

#include "diffray/core/error.h"
#include "diffray/core/math.h"
#include "diffray/transport/room_occluders.h"
#include "diffray/wbsdf/edge_kernel.h"

namespace diffray::transport {

using core::Vec3;
using Kind = room::OccluderAxis::Kind;

namespace {

bool edgeAxis(const room::OccluderAxis& a) { return a.kind == Kind::Opening || a.kind == Kind::Edge; }

// Beyond this many kernel periods across a sphere next-event estimation is not used (expectedSphereScore).
constexpr double kMaxPeriods = 64.0;

// Gauss–Legendre panels (8 nodes each) for an integrand that oscillates through `periods` periods: one panel
// per period, at least 2 (8 nodes integrate a period of a sinusoid to ~1e-7).
int panelsFor(double periods) { return static_cast<int>(std::clamp(std::ceil(periods), 2.0, kMaxPeriods)); }

// The sphere's score of a chord at distance D from its centre: chordWeight/crossSection (receiver/sphere.h).
double chordScore(double radius_m, double dist2) {
  const double r2 = radius_m * radius_m;
  if (!(dist2 < r2)) return 0.0;
  const double chord = 2.0 * std::sqrt(r2 - dist2);
  return chord * 0.75 / radius_m / (core::kPi * r2);
}

}  // namespace

bool RoomOccluders::nextEventSupported(int k) const {
  // At least one edge axis; the other an edge too (a door: its shift is drawn, the first integrated) or
  // uniform (an edge, a barrier, a tall slit). Not gratings or slit arrays (tables).
  const Entry& e = occluders_[k];
  if (e.spec.reflect) return false;
  const bool ex = edgeAxis(e.x.spec), ey = edgeAxis(e.y.spec);
  const bool ux = e.x.spec.kind == Kind::Uniform, uy = e.y.spec.kind == Kind::Uniform;
  return (ex && (ey || uy)) || (ey && ux);
}

double RoomOccluders::expectedSphereScore(int k, const Vec3& p, const Vec3& dir, double lambda_m, const Vec3& centre,
                                          double radius_m, const double xi[2]) const {
  DIFFRAY_CHECK(nextEventSupported(k));
  const Entry& e = occluders_[k];
  const room::Occluder& o = e.spec;
  const Vec3 q = centre - p;
  const double L2 = q.squaredNorm(), L = std::sqrt(L2);
  if (!(L > radius_m)) return 0.0;  // inside the sphere: no finite next-event estimate (a rare corner)
  const double side = dir.dot(o.normal) >= 0.0 ? 1.0 : -1.0;  // the ray goes on through the plane
  if (q.dot(o.normal) * side <= 0.0) return 0.0;
  // The integrated axis a (x when it is an edge axis) and the other one, b: uniform (β' = β) or an edge
  // axis whose shift is drawn here, as scatter() would, within |β'| < 1 (its weight multiplies the result).
  const bool a_is_x = edgeAxis(e.x.spec);
  const Axis& ax_a = a_is_x ? e.x : e.y;
  const Axis& ax_b = a_is_x ? e.y : e.x;
  const Vec3& ea = a_is_x ? o.ex : o.ey;
  const Vec3& eb = a_is_x ? o.ey : o.ex;
  const Vec3 local = p - o.origin_m;
  double four_d = 0, open_a = 0;
  edgeDistance(ax_a, local.dot(ea), four_d, open_a);
  const double alpha_i = dir.dot(ea);
  double b = dir.dot(eb), weight_b = 1.0, open_b = 0.0;
  if (edgeAxis(ax_b.spec)) {
    double v;
    sampleAxis(ax_b, local.dot(eb), lambda_m, b, 1.0, xi, v, weight_b, open_b);
    b += lambda_m * v;
    if (weight_b == 0.0 || !(std::abs(b) < 1.0)) return 0.0;
  }
  // The kernel's density per unit of α' at an outgoing direction d, with the faces weighting of the nearer
  // edges (both axes: the b axis's factor depends on d too).
  const auto kernel = [&](const Vec3& d) {
    double v = four_d / lambda_m * wbsdf::edgeKernelEval(four_d * (d.dot(ea) - alpha_i) / lambda_m) *
               facesFactor(ax_a.spec.faces, open_a * ea, o.normal, dir, d);
    if (open_b != 0.0) v *= facesFactor(ax_b.spec.faces, open_b * eb, o.normal, dir, d);
    return v;
  };
  // With b fixed the outgoing directions form a cone, d(α') = α'·ea + b·eb + s·√(B² − α'²)·n, B² = 1 − b².
  // It crosses the sphere where q·d ≥ √(L² − R²): with α' = B cos ψ, q·d = B(qa cos ψ + qn sin ψ) + b·qb,
  // an interval of ψ around ψ0 = atan2(qn, qa).
  const double B = std::sqrt(std::max(0.0, 1.0 - b * b));
  const double qa = q.dot(ea), qb = q.dot(eb), qn = side * q.dot(o.normal);
  const double rho = std::hypot(qa, qn);
  const double need = std::sqrt(L2 - radius_m * radius_m) - b * qb;
  if (!(B > 0.0) || !(B * rho > need)) return 0.0;
  const double psi0 = std::atan2(qn, qa), delta = std::acos(std::clamp(need / (B * rho), -1.0, 1.0));
  const double psi_lo = std::max(0.0, psi0 - delta), psi_hi = std::min(core::kPi, psi0 + delta);
  if (!(psi_hi > psi_lo)) return 0.0;
  const double periods = four_d * B * (std::cos(psi_lo) - std::cos(psi_hi)) / lambda_m;
  // Far from the edges the kernel swings through many periods across the sphere and averages out: the ray
  // itself scores as well there, for nothing. The caller then scores the segment as usual.
  if (periods > kMaxPeriods) return std::numeric_limits<double>::quiet_NaN();
  // ∫ kernel(d)·score dα' with dα' = B sin ψ dψ.
  const auto f = [&](double psi) {
    const Vec3 d = B * std::cos(psi) * ea + b * eb + side * B * std::sin(psi) * o.normal;
    const double qd = q.dot(d);
    if (!(qd > 0.0)) return 0.0;
    return kernel(d) * chordScore(radius_m, L2 - qd * qd) * B * std::sin(psi);
  };
  // Substitution ψ = mid − half·cos τ puts the square-root ends of the chord into smooth sin τ factors.
  const double mid = 0.5 * (psi_lo + psi_hi), half = 0.5 * (psi_hi - psi_lo);
  return weight_b * core::integrate([&](double tau) { return f(mid - half * std::cos(tau)) * half * std::sin(tau); },
                                    0.0, core::kPi, panelsFor(periods));
}

}  // namespace diffray::transport
