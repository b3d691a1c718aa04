// The BTM edge-source integral in the frequency domain (see btm_edge.h for the formula, frame and quadrature).
#include "diffray/reference/btm_edge.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "diffray/core/error.h"
#include "diffray/reference/btm_kernel.h"

namespace diffray::reference {
namespace {

using Complex = std::complex<double>;

constexpr double kPi = 3.14159265358979323846;

void requirePoint(const std::string& where, const CylindricalPoint& p, double wedge_rad) {
  core::requireFinite(where + ".rho_m", p.rho_m);
  core::requireFinite(where + ".phi_rad", p.phi_rad);
  core::requireFinite(where + ".z_m", p.z_m);
  if (!(p.rho_m > 0.0)) throw core::InputError(where + ".rho_m", "must be > 0 (off the edge), got " + std::to_string(p.rho_m));
  const double slack_rad = 1e-12;
  if (p.phi_rad < -slack_rad || p.phi_rad > wedge_rad + slack_rad)
    throw core::InputError(where + ".phi_rad", "must lie in [0, θ_w] = [0, " + std::to_string(wedge_rad) + "] rad, got " +
                                                   std::to_string(p.phi_rad));
}

double requireWedge(double wavenumber, double wedge_rad) {
  core::requireFinite("wavenumber", wavenumber);
  if (!(wavenumber > 0.0)) throw core::InputError("wavenumber", "must be > 0, got " + std::to_string(wavenumber));
  core::requireFinite("exterior angle", wedge_rad);
  if (!(wedge_rad > kPi && wedge_rad <= 2.0 * kPi * (1.0 + 1e-15)))
    throw core::InputError("exterior angle", "must lie in (π, 2π] rad, got " + std::to_string(wedge_rad));
  return kPi / wedge_rad;
}

// The integrand's geometry along an edge: the apex (the point of least path), the scale of the
// integration and the first panel (btm_kernel.h).
struct EdgeGeometry {
  double apex, scale, first_panel;
  EdgeGeometry(const BtmBeta& beta, const CylindricalPoint& s, const CylindricalPoint& r)
      : apex(s.z_m + (r.z_m - s.z_m) * s.rho_m / (s.rho_m + r.rho_m)),
        scale(s.rho_m + r.rho_m + std::abs(r.z_m - s.z_m)),
        first_panel(beta.firstPanel(s.rho_m, r.rho_m, scale)) {}
};

// The graded rule's nodes over [lo, hi] as (path m + l, w·β/(m·l)): the integral without the factor −ν/4π.
void appendNodes(const BtmBeta& beta, const EdgeGeometry& geo, const CylindricalPoint& s, const CylindricalPoint& r,
                 double lo, double hi, double wavelength, std::vector<BtmNode>* nodes) {
  const double rs = s.rho_m, rr = r.rho_m, zs = s.z_m, zr = r.z_m;
  btmGradedNodes(geo.apex, lo, hi, geo.scale, wavelength, geo.first_panel, [&](double z, double w) {
    const double a = z - zs, b = z - zr, m = std::hypot(rs, a), l = std::hypot(rr, b);
    nodes->push_back({m + l, w * beta(rs, rr, a, b, m, l) / (m * l)});
  });
}

// ∫ over the edge of β·e^{−ik(m+l)}/(m·l), without the factor −ν/4π. Infinite ends are integrated to 60
// scales from the apex and closed with the first term of integration by parts: ∫_U^∞ A·e^{−ikΦ} ≈
// A(U)·e^{−ikΦ(U)}/(ik·Φ'(U)), Φ' the slope of m + l away from the apex.
Complex edgeIntegral(double k, double nu, const BtmWedge& wedge, const CylindricalPoint& s, const CylindricalPoint& r) {
  const BtmBeta beta(nu, s.phi_rad, r.phi_rad);
  const EdgeGeometry geo(beta, s, r);
  const double reach = 60.0 * geo.scale;
  const double lo = std::max(wedge.z_start_m, std::min(geo.apex, wedge.z_end_m) - reach);
  const double hi = std::min(wedge.z_end_m, std::max(geo.apex, wedge.z_start_m) + reach);
  std::vector<BtmNode> nodes;
  appendNodes(beta, geo, s, r, lo, hi, 2.0 * kPi / k, &nodes);
  Complex sum(0.0, 0.0);
  for (const BtmNode& q : nodes) sum += std::polar(q.amplitude, -k * q.path_m);
  const auto tail = [&](double z, double outward) {
    const double a = z - s.z_m, b = z - r.z_m, m = std::hypot(s.rho_m, a), l = std::hypot(r.rho_m, b);
    const Complex g = std::polar(beta(s.rho_m, r.rho_m, a, b, m, l) / (m * l), -k * (m + l));
    return g / (Complex(0.0, 1.0) * k * (outward * (a / m + b / l)));
  };
  if (std::isinf(wedge.z_end_m)) sum += tail(hi, 1.0);
  if (std::isinf(wedge.z_start_m)) sum += tail(lo, -1.0);
  return sum;
}

double distance(double rho_m, double rho0_m, double dphi_rad, double dz_m) {
  const double s = std::sin(0.5 * dphi_rad);
  return std::sqrt((rho_m - rho0_m) * (rho_m - rho0_m) + 4.0 * rho_m * rho0_m * s * s + dz_m * dz_m);
}

}  // namespace

Complex btmEdgeDiffraction(double wavenumber_rad_m, const BtmWedge& wedge, const CylindricalPoint& source,
                           const CylindricalPoint& receiver) {
  const double nu = requireWedge(wavenumber_rad_m, wedge.exterior_angle_rad);
  requirePoint("source", source, wedge.exterior_angle_rad);
  requirePoint("receiver", receiver, wedge.exterior_angle_rad);
  if (std::isnan(wedge.z_start_m) || std::isnan(wedge.z_end_m) || !(wedge.z_start_m < wedge.z_end_m))
    throw core::InputError("edge", "z_start must be below z_end");
  const Complex integral = edgeIntegral(wavenumber_rad_m, nu, wedge, source, receiver);
  return -(nu / (4.0 * kPi)) * integral;
}

void btmEdgeNodes(const BtmWedge& wedge, const CylindricalPoint& source, const CylindricalPoint& receiver,
                  double min_wavelength_m, std::vector<BtmNode>* nodes) {
  const double nu = requireWedge(2.0 * kPi / min_wavelength_m, wedge.exterior_angle_rad);
  requirePoint("source", source, wedge.exterior_angle_rad);
  requirePoint("receiver", receiver, wedge.exterior_angle_rad);
  if (!std::isfinite(wedge.z_start_m) || !std::isfinite(wedge.z_end_m) || !(wedge.z_start_m < wedge.z_end_m))
    throw core::InputError("edge", "must be finite, z_start below z_end");
  const BtmBeta beta(nu, source.phi_rad, receiver.phi_rad);
  const std::size_t first = nodes->size();
  appendNodes(beta, EdgeGeometry(beta, source, receiver), source, receiver, wedge.z_start_m, wedge.z_end_m,
              min_wavelength_m, nodes);
  for (std::size_t i = first; i < nodes->size(); ++i) (*nodes)[i].amplitude *= -nu / (4.0 * kPi);
}

Complex btmInfiniteWedgeField(double wavenumber_rad_m, double exterior_angle_rad, const CylindricalPoint& source,
                              const CylindricalPoint& receiver) {
  BtmWedge wedge;
  wedge.exterior_angle_rad = exterior_angle_rad;
  Complex u = btmEdgeDiffraction(wavenumber_rad_m, wedge, source, receiver);
  const double k = wavenumber_rad_m, dz = receiver.z_m - source.z_m;
  const double ts = source.phi_rad, tr = receiver.phi_rad, tw = exterior_angle_rad;
  // Each geometric wave with its zone: weight 1 inside (margin > 0), ½ on the boundary (within
  // kBtmOnBoundaryRad, as the diffracted term's).
  auto add = [&](double image_rad, double margin) {
    if (margin < -kBtmOnBoundaryRad) return;
    const double r = distance(receiver.rho_m, source.rho_m, tr - image_rad, dz);
    u += (margin <= kBtmOnBoundaryRad ? 0.5 : 1.0) * std::polar(1.0 / r, -k * r);
  };
  add(ts, kPi - std::abs(tr - ts));            // direct
  add(-ts, kPi - (ts + tr));                   // image in the face θ = 0
  add(2.0 * tw - ts, (ts + tr) - (2.0 * tw - kPi));  // image in the face θ = θ_w
  return u;
}

}  // namespace diffray::reference
