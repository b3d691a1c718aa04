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
  double operator()(double rho_s, double rho_r, double a, double b, double m, double l) const {
    return fromCoshTerm(coshTerm(rho_s, rho_r, a, b, m, l));
  }
  /// cosh(νη) − 1 at an edge point (the arguments as above): the part of β that depends on the points'
  /// distances only, the same for every pair of azimuths. For ν = ½ (a thin plate) it is the algebraic
  /// (t/2)/(√(1 + t/2) + 1), t = cosh η − 1, else 2·sinh²(νη/2).
  double coshTerm(double rho_s, double rho_r, double a, double b, double m, double l) const;
  /// β from coshTerm's value: Σ sin(νφ) / (cosh(νη) − 1 + 2sin²(νφ/2)) over the four angle terms.
  double fromCoshTerm(double cosh_term) const {
    double beta = 0.0;
    for (int i = 0; i < 4; ++i) {
      const double d = cosh_term + half_phi_sin2_[i];
      if (d > 0.0) beta += sin_phi_[i] / d;
    }
    return beta;
  }
  /// A first panel (m) that resolves the integrand's narrowest feature at the apex: 1e-2 of
  /// ρSρR/(ρS + ρR) times the smallest angular distance (rad, at most 1) of a kept term to its boundary,
  /// and at least 1e-10 of `scale`.
  double firstPanel(double rho_s, double rho_r, double scale) const;

 private:
  double nu_;
  double sin_phi_[4], half_phi_sin2_[4];
};

/// The nodes of the graded rule over [from, to] (metres along the edge; from < to or from > to), as in the
/// header: visit(z, w) for each node, so that Σ w·g(z) is ∫ g from `from` to `to`. The nodes depend on the
/// geometry and on `wavelength` only, so one set serves every wavelength at or above it.
template <class Visit>
void btmGradedNodes(double apex, double from, double to, double scale, double wavelength, double first_panel_m,
                    Visit&& visit, double sign = 1.0) {
  // Integrate outward from the end nearer the apex; a stretch that holds the apex is split there.
  if ((apex - from) * (apex - to) < 0.0) {
    btmGradedNodes(apex, apex, to, scale, wavelength, first_panel_m, visit, sign);
    btmGradedNodes(apex, apex, from, scale, wavelength, first_panel_m, visit, -sign);
    return;
  }
  const bool reversed = std::abs(to - apex) < std::abs(from - apex);
  const double near_end = reversed ? to : from, far_end = reversed ? from : to;
  const double dir = far_end > near_end ? 1.0 : -1.0;
  // Σ over u is ∫ from near_end to far_end times dir; the requested direction may be the reverse.
  const double orient = sign * dir * (reversed ? -1.0 : 1.0);
  const double u0 = std::abs(near_end - apex), u_end = std::abs(far_end - apex);
  const double h_max = std::min(0.5 * wavelength, scale);
  const GaussRule& rule = gaussRule16();
  double u = u0, h = std::max(first_panel_m, 1e-3 * u0);
  while (u < u_end) {
    const double len = std::min({h, h_max, u_end - u});
    const double mid = u + 0.5 * len, half = 0.5 * len;
    for (int i = 0; i < GaussRule::kNodes; ++i)
      visit(apex + dir * (mid + half * rule.nodes[static_cast<std::size_t>(i)]),
            orient * half * rule.weights[static_cast<std::size_t>(i)]);
    u += len;
    h = std::max(h, 2.0 * len);
  }
}

/// A point the graded rule grades toward (btmGradedNodesToward): where along the edge (m), and the first
/// panel there (m).
struct BtmGradePoint {
  double at, first_panel_m;
};

/// The graded rule over [from, to] (from < to) toward `count` points at once: the stretch is cut halfway
/// between neighbouring points and each piece is graded from its own point (btmGradedNodes, which grades
/// both ways from a point inside its piece). Pieces are visited in the points' order; of equal points the
/// last grades the piece around them with its own first panel.
template <class Visit>
void btmGradedNodesToward(const BtmGradePoint* points, int count, double from, double to, double scale,
                          double wavelength, Visit&& visit) {
  for (int k = 0; k < count; ++k) {
    const double p = points[k].at;
    double lo = from, hi = to;
    bool later_equal = false;
    for (int m = 0; m < count; ++m) {
      const double q = points[m].at;
      if (q < p) lo = std::max(lo, 0.5 * (p + q));
      if (q > p) hi = std::min(hi, 0.5 * (p + q));
      if (q == p && m > k) later_equal = true;
    }
    if (!later_equal && lo < hi) btmGradedNodes(p, lo, hi, scale, wavelength, points[k].first_panel_m, visit);
  }
}

/// ∫ g over [from, to] (metres along the edge; from < to or from > to) with panels graded from the apex, as
/// in the header. g(z) returns std::complex<double>.
template <class G>
std::complex<double> btmGradedIntegral(const G& g, double apex, double from, double to, double scale,
                                       double wavelength, double first_panel_m) {
  std::complex<double> sum(0.0, 0.0);
  btmGradedNodes(apex, from, to, scale, wavelength, first_panel_m, [&](double z, double w) { sum += w * g(z); });
  return sum;
}

}  // namespace diffray::reference
