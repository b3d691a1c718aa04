#pragma once
// What the BTM references of a thin plate (btm_plate.h) and of a box (btm_box.h) share, private to the
// reference module: an edge's frame, the second-order (edge-to-edge) term of two edges whose path runs along
// a common plane, as quadrature nodes, and the path-length grid that evaluates sums of nodes at many
// wavenumbers at once (btm_spectrum.h).
//
// Each diffracted term is written as Σ a·e^{−ik·L} over nodes (L the path length through the node, a its
// real amplitude with the quadrature weight), so one set of nodes, built for the shortest wavelength, gives
// the term at every frequency. Units: metres, rad/m. Pure functions and immutable data; thread-safe (a
// PathGrid is filled by one thread at a time).
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <utility>
#include <vector>

#include "diffray/core/math.h"
#include "diffray/reference/btm_edge.h"
#include "diffray/reference/btm_field.h"
#include "diffray/reference/btm_kernel.h"

namespace diffray::reference::btm_detail {

constexpr double kPi = 3.14159265358979323846;

/// An edge's frame (btm_edge.h): origin at its first vertex, z along the edge (0 … length), the wedge's
/// face θ = 0 along +x, the air on its +y side; θ = atan2(y, x) in [0, 2π). Right-handed: z = x × y.
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

/// The plane an edge-to-edge path runs along: both edges' wedge index ν, the unit vector `across_i` in that
/// plane perpendicular to edge i and pointing from it toward edge j (a point P_j of edge j lies at distance
/// (P_j − origin_i)·across_i ≥ 0 from edge i's line), and for each face of that plane the path may run along
/// (a thin plate has two, which share every distance; a solid's face one) P_j's azimuth in edge i's frame
/// and P_i's in edge j's. `every_feature` selects the finer grading of edgePairNodes.
struct PairFaces {
  double nu = 0.5;
  core::Vec3 across_i = core::Vec3::Zero();
  int count = 1;  ///< 1 or 2
  double theta_i[2] = {0.0, 0.0}, theta_j[2] = {0.0, 0.0};
  bool every_feature = false;
};

/// u₂ of the ordered pair (ei, ej) along `faces` as nodes: emit(L, a) for each. The second-order BTM term
/// (Svensson, Fred & Vanderkooy 1999) of a path along a plane,
///   u₂ = ½·Σ_faces (ν²/16π²)·∫_{edge i}∫_{edge j} β_i·β_j·e^{−ik(m + n + l)}/(m·n·l) dz_i dz_j,
/// m = |S − P_i|, n = |P_i − P_j|, l = |P_j − R|, β_i edge i's directivity from S to P_j, β_j edge j's from
/// P_i to R (btm_kernel.h); a point on a rigid face counts its own image, which the ½ of a path along a
/// plane takes back out. The faces share every distance and cosh(νη), so one node serves all. Panels at
/// most half of `wavelength_m`; `scale` sizes the longest panels and the first ones at a corner.
///
/// The inner integral over edge j is graded (btmGradedNodesToward) toward β_j's apex (P_i and R) and a
/// corner the two edges share (where n → 0); the outer one over edge i toward that corner, else from edge
/// i's middle. With `every_feature` both also grade toward what else is sharp in the integrand when a point
/// lies near a boundary or near an edge: the inner toward β_i's ridge (the z_j where edge i's apex of S and
/// P_j is z_i, as narrow as β_j's apex when S lies near the shared plane beyond edge i), toward R's foot on
/// edge j (l's branch point at ρR) and, for parallel edges, toward P_i's foot on edge j (n's branch point at
/// the edges' distance); the outer toward S's foot
/// on edge i (m's branch point at ρS), toward where β_i's ridge and β_j's apex leave edge j through its ends
/// (the inner integral steps there over the peak's width), and for parallel edges toward edge j's ends. The
/// plate's figures were measured without it.
template <class Emit>
void edgePairNodes(const EdgeFrame& ei, const EdgeFrame& ej, const PairFaces& faces, const core::Vec3& source,
                   const core::Vec3& receiver, double scale, double wavelength_m, Emit&& emit) {
  const double nu = faces.nu, factor = 0.5 * nu * nu / (16.0 * kPi * kPi);
  const CylindricalPoint s = ei.of(source), r = ej.of(receiver);
  const int last = faces.count - 1;
  const BtmBeta beta_i0(nu, s.phi_rad, faces.theta_i[0]), beta_i1(nu, s.phi_rad, faces.theta_i[last]);
  const BtmBeta beta_j0(nu, faces.theta_j[0], r.phi_rad), beta_j1(nu, faces.theta_j[last], r.phi_rad);
  // The first panels that resolve β_i's peak (S and a point at distance rho from edge i) and β_j's (a point
  // at distance rho from edge j and R).
  const auto first_i = [&](double rho) {
    return std::min(beta_i0.firstPanel(s.rho_m, rho, scale), beta_i1.firstPanel(s.rho_m, rho, scale));
  };
  const auto first_j = [&](double rho) {
    return std::min(beta_j0.firstPanel(rho, r.rho_m, scale), beta_j1.firstPanel(rho, r.rho_m, scale));
  };
  double corner_i = 0.5 * ei.length, corner_j = -1.0;  // a corner the edges share, on each (else −1 on j)
  const double touch = 1e-9 * scale;
  const core::Vec3 end_i = ei.origin + ei.length * ei.z, end_j = ej.origin + ej.length * ej.z;
  if ((end_i - ej.origin).norm() < touch) corner_i = ei.length, corner_j = 0.0;
  else if ((ei.origin - end_j).norm() < touch) corner_i = 0.0, corner_j = ej.length;
  else if ((ei.origin - ej.origin).norm() < touch) corner_i = 0.0, corner_j = 0.0;
  else if ((end_i - end_j).norm() < touch) corner_i = ei.length, corner_j = ej.length;
  // P_j on edge j in edge i's frame is linear in z_j: its distance ox + z_j·dx from edge i's line and its
  // coordinate oz + z_j·dz along edge i. Likewise P_i in edge j's frame: rho0 + z_i·drho, c0 + z_i·dc.
  const core::Vec3 o = ej.origin - ei.origin;
  const double ox = o.dot(faces.across_i), oz = o.dot(ei.z), dx = ej.z.dot(faces.across_i), dz = ej.z.dot(ei.z);
  const bool parallel = std::abs(dx) < 1e-12;
  const CylindricalPoint p0 = ej.of(ei.origin), p1 = ej.of(end_i);
  const double drho = (p1.rho_m - p0.rho_m) / ei.length, dc = (p1.z_m - p0.z_m) / ei.length;
  const auto apex_i = [&](double rho, double q) { return s.z_m + (q - s.z_m) * s.rho_m / (s.rho_m + rho); };

  // A point to grade toward, clamped to [0, length]; with `every_feature` equal points merge, keeping the
  // smaller first panel (btmGradedNodesToward grades equal points with the last one's).
  const auto grade = [&faces](BtmGradePoint* points, int* count, double at, double length, double first) {
    at = std::clamp(at, 0.0, length);
    for (int k = 0; faces.every_feature && k < *count; ++k)
      if (points[k].at == at) {
        points[k].first_panel_m = std::min(points[k].first_panel_m, first);
        return;
      }
    points[(*count)++] = {at, first};
  };
  // With `every_feature`, no first panel wider than 1e-2 of the distance to the nearest other point, whose
  // feature may be narrow: a wide first panel next to it would cover that feature's flank.
  const auto separate = [&faces](BtmGradePoint* points, int count) {
    for (int k = 0; faces.every_feature && k < count; ++k)
      for (int m = 0; m < count; ++m)
        if (m != k)
          points[k].first_panel_m = std::min(points[k].first_panel_m, 1e-2 * std::abs(points[m].at - points[k].at));
  };
  BtmGradePoint outer[9];
  int n_outer = 0;
  const auto grade_outer = [&](double at, double first) { grade(outer, &n_outer, at, ei.length, first); };
  if (!faces.every_feature || corner_j >= 0.0) grade_outer(corner_i, 1e-8 * scale);
  if (faces.every_feature) {
    grade_outer(s.z_m, 0.1 * s.rho_m);
    for (double end : {0.0, ej.length}) {
      const double rho = ox + end * dx, q = oz + end * dz;
      grade_outer(apex_i(rho, q), first_i(rho));
      // β_j's apex c + (zR − c)·ρ/(ρ + ρR) reaches `end` where ρR·(c − end) + ρ·(zR − end) = 0 (linear in z_i).
      const double den = r.rho_m * dc + drho * (r.z_m - end);
      if (den != 0.0) {
        const double z = -(r.rho_m * (p0.z_m - end) + p0.rho_m * (r.z_m - end)) / den;
        const double rho_z = p0.rho_m + z * drho, c = p0.z_m + z * dc, sum = rho_z + r.rho_m;
        const double slope = dc * r.rho_m / sum + drho * (r.z_m - c) * r.rho_m / (sum * sum);
        if (rho_z > 0.0) grade_outer(z, first_j(rho_z) / std::max(1.0, std::abs(slope)));
      }
      if (parallel) grade_outer(q, 0.1 * ox);
    }
  }
  separate(outer, n_outer);
  btmGradedNodesToward(outer, n_outer, 0.0, ei.length, scale, wavelength_m, [&](double zi, double wi) {
    const CylindricalPoint pi_j = ej.of(ei.origin + zi * ei.z);  // P_i in edge j's frame
    const double a_i = zi - s.z_m, m = std::hypot(s.rho_m, a_i);
    const auto inner = [&](double zj, double wj) {
      const double rho_ji = std::abs(ox + zj * dx), b_i = zi - (oz + zj * dz), n = std::hypot(rho_ji, b_i);
      if (n == 0.0) return;  // a node on the shared corner itself (panels narrower than its rounding)
      const double a_j = zj - pi_j.z_m, b_j = zj - r.z_m, l = std::hypot(r.rho_m, b_j);
      const double ci = beta_i0.coshTerm(s.rho_m, rho_ji, a_i, b_i, m, n);
      const double cj = beta_j0.coshTerm(pi_j.rho_m, r.rho_m, a_j, b_j, n, l);
      double both = beta_i0.fromCoshTerm(ci) * beta_j0.fromCoshTerm(cj);
      if (last > 0) both += beta_i1.fromCoshTerm(ci) * beta_j1.fromCoshTerm(cj);
      emit(m + n + l, factor * wi * wj * both / (m * n * l));
    };
    BtmGradePoint points[5];
    int n_points = 0;
    // Near the shared corner n varies on the scale of P_i's distance from it: grade toward the corner too.
    if (corner_j >= 0.0) grade(points, &n_points, corner_j, ej.length, 1e-8 * scale);
    grade(points, &n_points, pi_j.z_m + (r.z_m - pi_j.z_m) * pi_j.rho_m / (pi_j.rho_m + r.rho_m), ej.length,
          first_j(pi_j.rho_m));
    if (faces.every_feature) {
      // β_i's ridge: apex_i(P_j) = z_i, (z_i − zS)(ρS + ox + z_j·dx) = (oz + z_j·dz − zS)·ρS (linear in z_j).
      const double den = a_i * dx - dz * s.rho_m;
      if (den != 0.0) {
        const double zj = ((oz - s.z_m) * s.rho_m - a_i * (s.rho_m + ox)) / den;
        const double rho = ox + zj * dx, q = oz + zj * dz, sum = s.rho_m + rho;
        const double slope = s.rho_m * (dz * sum - (q - s.z_m) * dx) / (sum * sum);  // d apex_i / d z_j
        if (rho >= 0.0) grade(points, &n_points, zj, ej.length, first_i(rho) / std::max(1.0, std::abs(slope)));
      }
      grade(points, &n_points, r.z_m, ej.length, 0.1 * r.rho_m);
      if (parallel) grade(points, &n_points, pi_j.z_m, ej.length, 0.1 * ox);
    }
    separate(points, n_points);
    btmGradedNodesToward(points, n_points, 0.0, ej.length, scale, wavelength_m, inner);
  });
}

/// Amplitudes spread onto the uniform path-length grid L₀ + n·h with φ(x) = e^{−x²/4} over 24 points, and
/// read back at any wavenumber k ≤ π/(4h) (btm_spectrum.h: Gaussian gridding, Greengard & Lee 2004).
class PathGrid {
 public:
  static constexpr int kBelow = 11, kAbove = 12;  // taps n0 − 11 … n0 + 12 around n0 = ⌊x⌋

  /// A grid for paths in [lo_m, hi_m], step step_m.
  PathGrid(double lo_m, double hi_m, double step_m)
      : origin_(lo_m - (kBelow + 1) * step_m), step_(step_m),
        values_(static_cast<std::size_t>(std::ceil((hi_m - lo_m) / step_m)) + kBelow + kAbove + 4, 0.0) {
    for (int j = 0; j <= kBelow + 1; ++j) tap_[static_cast<std::size_t>(j)] = std::exp(-0.25 * j * j);
  }

  // e^{−(j − d)²/4} = e^{−j²/4}·(e^{d/2})^j·e^{−d²/4} (fast Gaussian gridding: two exponentials per node).
  void add(double path_m, double amplitude) {
    const double x = (path_m - origin_) / step_;
    const double n0 = std::floor(x), d = x - n0;
    double* v = values_.data() + static_cast<std::ptrdiff_t>(n0);
    const double grow = std::exp(0.5 * d), base = amplitude * std::exp(-0.25 * d * d);
    double p = base;
    for (int j = 0; j <= kAbove; ++j, p *= grow) v[j] += p * tap_[static_cast<std::size_t>(j)];
    p = base / grow;
    for (int j = 1; j <= kBelow; ++j, p /= grow) v[-j] += p * tap_[static_cast<std::size_t>(j)];
  }

  void merge(const PathGrid& other) {
    for (std::size_t i = 0; i < values_.size(); ++i) values_[i] += other.values_[i];
  }

  // Σ_q a_q·e^{−ik·L_q}: the grid's transform divided by the Gaussian's, φ̂(kh) = √(4π)·e^{−(kh)²}.
  std::complex<double> sum(double k) const {
    std::complex<double> s(0.0, 0.0);
    for (std::size_t n = 0; n < values_.size(); ++n)
      if (values_[n] != 0.0) s += std::polar(values_[n], -k * (origin_ + static_cast<double>(n) * step_));
    const double xi = k * step_;
    return s / (std::sqrt(4.0 * kPi) * std::exp(-xi * xi));
  }

 private:
  double origin_, step_;
  std::vector<double> values_;
  std::array<double, kBelow + 2> tap_{};
};

/// A spectrum's settings for `wavenumbers` (checked: at least one, each finite and > 0; `order` 1 or 2,
/// else core::InputError): the grid step λ_min/8 and the wavelength the nodes are built for, 4·λ_min, so
/// that the node builders (which cap panels at half the wavelength they are given) make panels up to two
/// shortest wavelengths (btm_spectrum.cpp says why that suffices).
struct SpectrumAxis {
  double step_m, panel_wavelength_m;
  SpectrumAxis(const std::vector<double>& wavenumbers, int order);
};

/// One geometric wave: its path length and its weight, 1 inside its zone and ½ on the zone's boundary
/// (where the edge term that switches it is dropped: btm_kernel.h).
struct GeometricWave {
  double path_m, weight;
};

/// The geometric waves of a spectrum: its direct waves and its specular images.
struct GeometricWaves {
  std::vector<GeometricWave> direct, specular;
};

/// The fields at `wavenumbers` from the geometric waves (exact) and the first- and second-order grids
/// (`second` null at order 1), one wavenumber per TBB task.
std::vector<BtmField> spectrumFields(const std::vector<double>& wavenumbers, const GeometricWaves& waves,
                                     const PathGrid& first, const PathGrid* second);

/// Runs one task per element of `second_order` on TBB's threads: task t spreads its nodes onto a grid of its
/// own through run(t, add), add(path_m, amplitude). Returns the sum of the grids of the tasks marked false
/// (first order) and that of the others, merged in task order, so that neither depends on the threads.
template <class Run>
std::pair<PathGrid, PathGrid> gridTasks(const std::vector<bool>& second_order, double lo_m, double hi_m, double step_m,
                                        const Run& run) {
  std::vector<PathGrid> grids(second_order.size(), PathGrid(lo_m, hi_m, step_m));
  tbb::parallel_for(std::size_t{0}, grids.size(), [&](std::size_t t) {
    PathGrid& grid = grids[t];
    run(t, [&grid](double path_m, double amplitude) { grid.add(path_m, amplitude); });
  });
  std::pair<PathGrid, PathGrid> sums{PathGrid(lo_m, hi_m, step_m), PathGrid(lo_m, hi_m, step_m)};
  for (std::size_t t = 0; t < grids.size(); ++t) (second_order[t] ? sums.second : sums.first).merge(grids[t]);
  return sums;
}

}  // namespace diffray::reference::btm_detail
