#pragma once
// The thin plate's geometry and its edge-diffraction paths as quadrature nodes, shared by the plate's field
// at one frequency (btm_plate.cpp) and at many at once (btm_spectrum.cpp). Private to the reference module.
//
// Each diffracted term is written as Σ a·e^{−ik·L} over nodes (L the path length through the node, a its
// real amplitude with the quadrature weight), so one set of nodes, built for the shortest wavelength, gives
// the term at every frequency. Frames and formulas: btm_plate.h. Pure functions; thread-safe.
#include <algorithm>
#include <cmath>
#include <vector>

#include "diffray/core/math.h"
#include "diffray/reference/btm_edge.h"
#include "diffray/reference/btm_kernel.h"
#include "diffray/reference/btm_plate.h"

namespace diffray::reference::btm_detail {

constexpr double kPi = 3.14159265358979323846;

/// The plate's unit normal (Newell's method), centroid and scale (the largest centroid–vertex distance).
struct PlateFrame {
  core::Vec3 normal, centroid;
  double scale = 0.0;
};

/// Checks that `plate` is a convex planar polygon with no three vertices in line (throws core::InputError).
PlateFrame checkPlate(const BtmPlate& plate);

/// Whether the point p of the plate's plane lies inside the polygon (convex: left of every edge).
bool insidePolygon(const BtmPlate& plate, const PlateFrame& f, const core::Vec3& p);

/// Where the segment from p to q crosses the plate's plane, if its ends lie strictly on opposite sides.
bool crossesPlane(const PlateFrame& f, const core::Vec3& p, const core::Vec3& q, core::Vec3* at);

/// An edge's frame (btm_plate.h): origin at its first vertex, z along it, x into the plate, y the normal.
struct EdgeFrame {
  core::Vec3 origin, x, y, z;
  double length = 0.0;
  CylindricalPoint of(const core::Vec3& p) const {
    const core::Vec3 d = p - origin;
    double theta = std::atan2(d.dot(y), d.dot(x));
    if (theta < 0.0) theta += 2.0 * kPi;
    return {std::hypot(d.dot(x), d.dot(y)), theta, d.dot(z)};
  }
};

std::vector<EdgeFrame> edgeFrames(const BtmPlate& plate, const PlateFrame& f);

/// The geometric field's path lengths at `receiver`: the direct wave's (NaN where the plate blocks it) and
/// the specular image's (NaN where the reflection point is off the plate). Throws when a point lies on the
/// plate.
struct GeometricPaths {
  double direct_m, specular_m;
};
GeometricPaths geometricPaths(const BtmPlate& plate, const PlateFrame& f, const core::Vec3& source,
                              const core::Vec3& receiver);

/// The plate standing on the ground z = ground_z_m joined with its mirror image (btmPlateOnGroundField).
/// Throws core::InputError when the plate does not stand on the ground so or a point is not above it.
BtmPlate groundUnion(const BtmPlate& plate, double ground_z_m, const core::Vec3& source, const core::Vec3& receiver);

/// Every edge's first-order term as nodes (btmEdgeNodes), panels sized for `wavelength_m`.
std::vector<BtmNode> firstOrderNodes(const std::vector<EdgeFrame>& edges, const core::Vec3& source,
                                     const core::Vec3& receiver, double wavelength_m);

/// The scale that sizes the second order's panels (the plate's plus the points' distances from it).
inline double pairScale(const PlateFrame& f, const core::Vec3& source, const core::Vec3& receiver) {
  return f.scale + (source - f.centroid).norm() + (receiver - f.centroid).norm();
}

/// u₂ of the ordered pair (ei, ej), the paths along both faces (azimuth 0 and 2π) together, as nodes:
/// emit(L, a) for each (btm_plate.h, the factor ½·ν²/16π² included). The faces share every distance and
/// cosh(νη), so one node serves both. The inner integral over edge j is graded toward the apex of P_i and R
/// on it; the outer one over edge i toward a corner the two edges share (where n → 0), else from edge i's
/// middle. Panels at most half of `wavelength_m`.
template <class Emit>
void edgePairNodes(const EdgeFrame& ei, const EdgeFrame& ej, const core::Vec3& source, const core::Vec3& receiver,
                   double scale, double wavelength_m, Emit&& emit) {
  const double nu = 0.5, factor = 0.5 * nu * nu / (16.0 * kPi * kPi);
  const CylindricalPoint s = ei.of(source), r = ej.of(receiver);
  const BtmBeta beta_i0(nu, s.phi_rad, 0.0), beta_i1(nu, s.phi_rad, 2.0 * kPi);
  const BtmBeta beta_j0(nu, 0.0, r.phi_rad), beta_j1(nu, 2.0 * kPi, r.phi_rad);
  double corner_i = 0.5 * ei.length, corner_j = -1.0;  // a corner the edges share, on each (else −1 on j)
  const double touch = 1e-9 * scale;
  if ((ei.origin + ei.length * ei.z - ej.origin).norm() < touch) corner_i = ei.length, corner_j = 0.0;
  else if ((ei.origin - (ej.origin + ej.length * ej.z)).norm() < touch) corner_i = 0.0, corner_j = ej.length;
  // P_j on edge j in edge i's frame is linear in z_j: its in-plane offset and its coordinate along edge i.
  const core::Vec3 o = ej.origin - ei.origin;
  const double ox = o.dot(ei.x), oz = o.dot(ei.z), dx = ej.z.dot(ei.x), dz = ej.z.dot(ei.z);
  btmGradedNodes(corner_i, 0.0, ei.length, scale, wavelength_m, 1e-8 * scale, [&](double zi, double wi) {
    const CylindricalPoint pi_j = ej.of(ei.origin + zi * ei.z);  // P_i in edge j's frame
    const double a_i = zi - s.z_m, m = std::hypot(s.rho_m, a_i);
    const auto inner = [&](double zj, double wj) {
      const double rho_ji = std::abs(ox + zj * dx), b_i = zi - (oz + zj * dz), n = std::hypot(rho_ji, b_i);
      const double a_j = zj - pi_j.z_m, b_j = zj - r.z_m, l = std::hypot(r.rho_m, b_j);
      const double ci = beta_i0.coshTerm(s.rho_m, rho_ji, a_i, b_i, m, n);
      const double cj = beta_j0.coshTerm(pi_j.rho_m, r.rho_m, a_j, b_j, n, l);
      const double both = beta_i0.fromCoshTerm(ci) * beta_j0.fromCoshTerm(cj) +
                          beta_i1.fromCoshTerm(ci) * beta_j1.fromCoshTerm(cj);
      emit(m + n + l, factor * wi * wj * both / (m * n * l));
    };
    const double apex =
        std::clamp(pi_j.z_m + (r.z_m - pi_j.z_m) * pi_j.rho_m / (pi_j.rho_m + r.rho_m), 0.0, ej.length);
    const double first_j = std::min(beta_j0.firstPanel(pi_j.rho_m, r.rho_m, scale),
                                    beta_j1.firstPanel(pi_j.rho_m, r.rho_m, scale));
    if (corner_j < 0.0) {
      btmGradedNodes(apex, 0.0, ej.length, scale, wavelength_m, first_j, inner);
      return;
    }
    // Near the shared corner n varies on the scale of P_i's distance from it: grade toward the corner too.
    const double split = 0.5 * (apex + corner_j);
    const double other_end = corner_j == 0.0 ? ej.length : 0.0;
    btmGradedNodes(corner_j, std::min(corner_j, split), std::max(corner_j, split), scale, wavelength_m, 1e-8 * scale,
                   inner);
    btmGradedNodes(apex, std::min(split, other_end), std::max(split, other_end), scale, wavelength_m, first_j, inner);
  });
}

}  // namespace diffray::reference::btm_detail
