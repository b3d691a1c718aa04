#pragma once
// The two pieces the BTM edge-diffraction reference (btm_edge.h, btm_plate.h) is made of: the edge-source
// directivity β of a wedge, and a quadrature along an edge that resolves its peak at the apex point.
//
// β for a wedge of index ν = π/θ_w, a source at (ρS, θS, zS) and a receiver at (ρR, θR, zR) in the edge's
// frame, at the edge point z (Svensson, Fred & Vanderkooy 1999):
//   β = Σ_{±,±} sin(ν(π ± θS ± θR)) / (cosh(νη) − cos(ν(π ± θS ± θR))),
//   cosh η = (m·l + (z − zS)(z − zR)) / (ρS·ρR),  m = √(ρS² + (z − zS)²), l = √(ρR² + (z − zR)²).
// cosh η − 1 is formed as (ρS·(z − zR) + ρR·(z − zS))² / ((m·l + ρSρR − (z − zS)(z − zR))·ρSρR) and each
// denominator as 2sinh²(νη/2) + 2sin²(νφ/2), so nothing cancels near the apex (η = 0) or near a boundary
// (νφ a multiple of 2π). A term within kBtmOnBoundaryRad of its boundary is dropped: its peak would be
// narrower than the quadrature resolves, its limit there is 0, and the geometric wave it switches then
// counts ½.
//
// btmGradedIntegral integrates along an edge with 16-point Gauss–Legendre panels that start small at the
// apex (or at the end nearer to it) and double outward up to half a wavelength and `scale`. The first
// panel's length is `first_panel_m`: BtmBeta::firstPanel() sizes it to the narrowest feature of the
// integrand at the apex, whose width along the edge is about ρSρR/(ρS + ρR) times the angular distance to
// the nearest boundary (or times 1 away from boundaries).
// Units: metres, radians. Thread-safety: BtmBeta is immutable after construction; the functions are pure.
#include <algorithm>
#include <cmath>
#include <complex>

#include "diffray/reference/quadrature.h"

namespace diffray::reference {

/// Angular distance (rad) below which a point counts as on a shadow or reflection boundary.
inline constexpr double kBtmOnBoundaryRad = 1e-9;

class BtmBeta {
 public:
  /// β's four angle terms for wedge index ν and the azimuths θS, θR (rad) of the two points.
  BtmBeta(double nu, double theta_s_rad, double theta_r_rad);
  /// β at an edge point: ρS, ρR the points' distances from the edge line, a = z − zS, b = z − zR, m and l
  /// their distances from the edge point.
  double operator()(double rho_s, double rho_r, double a, double b, double m, double l) const;
  /// A first panel (m) that resolves the integrand's narrowest feature at the apex: 1e-2 of
  /// ρSρR/(ρS + ρR) times the smallest angular distance (rad, at most 1) of a kept term to its boundary,
  /// and at least 1e-10 of `scale`.
  double firstPanel(double rho_s, double rho_r, double scale) const;

 private:
  double nu_;
  double sin_phi_[4], half_phi_sin2_[4];
};

/// ∫ g over [from, to] (metres along the edge; from < to or from > to) with panels graded from the apex, as
/// in the header. g(z) returns std::complex<double>.
template <class G>
std::complex<double> btmGradedIntegral(const G& g, double apex, double from, double to, double scale,
                                       double wavelength, double first_panel_m) {
  // Integrate outward from the end nearer the apex; a stretch that holds the apex is split there.
  if ((apex - from) * (apex - to) < 0.0)
    return btmGradedIntegral(g, apex, apex, to, scale, wavelength, first_panel_m) -
           btmGradedIntegral(g, apex, apex, from, scale, wavelength, first_panel_m);
  const bool reversed = std::abs(to - apex) < std::abs(from - apex);
  const double near_end = reversed ? to : from, far_end = reversed ? from : to;
  const double dir = far_end > near_end ? 1.0 : -1.0;
  const double u0 = std::abs(near_end - apex), u_end = std::abs(far_end - apex);
  const double h_max = std::min(0.5 * wavelength, scale);
  const GaussRule& rule = gaussRule16();
  std::complex<double> sum(0.0, 0.0);
  double u = u0, h = std::max(first_panel_m, 1e-3 * u0);
  while (u < u_end) {
    const double len = std::min({h, h_max, u_end - u});
    const double mid = u + 0.5 * len, half = 0.5 * len;
    std::complex<double> panel(0.0, 0.0);
    for (int i = 0; i < GaussRule::kNodes; ++i)
      panel += rule.weights[static_cast<std::size_t>(i)] * g(apex + dir * (mid + half * rule.nodes[static_cast<std::size_t>(i)]));
    sum += panel * half;
    u += len;
    h = std::max(h, 2.0 * len);
  }
  // Σ over u is ∫ from near_end to far_end times dir; the requested direction may be the reverse.
  const std::complex<double> near_to_far = dir * sum;
  return reversed ? -near_to_far : near_to_far;
}

}  // namespace diffray::reference
