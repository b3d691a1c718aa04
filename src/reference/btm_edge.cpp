// The BTM edge-source integral in the frequency domain (see btm_edge.h for the formula, frame and quadrature).
#include "diffray/reference/btm_edge.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "diffray/core/error.h"
#include "diffray/reference/quadrature.h"

namespace diffray::reference {
namespace {

using Complex = std::complex<double>;

constexpr double kPi = 3.14159265358979323846;
// Angular distance (rad) below which a receiver counts as on a shadow or reflection boundary.
constexpr double kOnBoundaryRad = 1e-9;

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

// The integrand of btmEdgeDiffraction at edge point z, without the factor −ν/4π.
struct Integrand {
  double k, nu, rs, rr, zs, zr;
  double sin_phi[4], half_phi_sin2[4];  // sin(νφ_i) and 2·sin²(νφ_i/2) for the four φ_i = π ± θS ± θR

  Integrand(double k_, double nu_, const CylindricalPoint& s, const CylindricalPoint& r)
      : k(k_), nu(nu_), rs(s.rho_m), rr(r.rho_m), zs(s.z_m), zr(r.z_m) {
    const double phis[4] = {kPi + s.phi_rad + r.phi_rad, kPi + s.phi_rad - r.phi_rad, kPi - s.phi_rad + r.phi_rad,
                            kPi - s.phi_rad - r.phi_rad};
    for (int i = 0; i < 4; ++i) {
      const double h = std::sin(0.5 * nu * phis[i]);
      // A receiver within kOnBoundaryRad of a boundary is on it: the term's peak at the apex would be
      // narrower than the quadrature resolves; its limit is 0 there, and the geometric wave counts ½.
      sin_phi[i] = std::abs(h) < 0.5 * nu * kOnBoundaryRad ? 0.0 : std::sin(nu * phis[i]);
      half_phi_sin2[i] = 2.0 * h * h;
    }
  }

  // Returns β·e^{−ik(m+l)}/(m·l); `amplitude` gets |β|/(m·l) and `path_slope` d(m + l)/dz.
  Complex operator()(double z, double* amplitude = nullptr, double* path_slope = nullptr) const {
    const double a = z - zs, b = z - zr;
    const double m = std::hypot(rs, a), l = std::hypot(rr, b);
    // cosh η − 1 = (ρS·b + ρR·a)² / ((m·l + ρSρR − a·b)·ρSρR), free of cancellation near the apex.
    const double num = rs * b + rr * a;
    const double t = num * num / ((m * l + rs * rr - a * b) * rs * rr);
    const double eta = std::log1p(t + std::sqrt(t * (t + 2.0)));
    const double sh = std::sinh(0.5 * nu * eta);
    const double cosh_term = 2.0 * sh * sh;  // cosh(νη) − 1
    double beta = 0.0;
    for (int i = 0; i < 4; ++i) {
      // cosh(νη) − cos(νφ) = 2sinh²(νη/2) + 2sin²(νφ/2): no cancellation when both are small.
      const double d = cosh_term + half_phi_sin2[i];
      if (d > 0.0) beta += sin_phi[i] / d;
    }
    const double ml = m * l;
    if (amplitude) *amplitude = std::abs(beta) / ml;
    if (path_slope) *path_slope = a / m + b / l;
    return std::polar(beta / ml, -k * (m + l));
  }
};

// ∫ over [from, to] (from the point nearer the apex outward; to may be ±∞) of the integrand, with panels
// graded from the apex side: see the header.
Complex integrateFrom(const Integrand& f, double apex, double from, double to, double scale) {
  const double dir = to > from ? 1.0 : -1.0;
  const bool infinite = std::isinf(to);
  const double u0 = std::abs(from - apex);  // distance of the start from the apex
  const double u_end = infinite ? std::max(u0, 0.0) + 60.0 * scale : u0 + std::abs(to - from);
  const double wavelength = 2.0 * kPi / f.k;
  const double h_max = std::min(0.5 * wavelength, scale);
  const GaussRule& rule = gaussRule16();
  Complex sum(0.0, 0.0);
  double u = u0;
  double h = std::max(1e-10 * scale, 1e-3 * u0);
  while (u < u_end) {
    const double len = std::min({h, h_max, u_end - u});
    const double mid = u + 0.5 * len, half = 0.5 * len;
    Complex panel(0.0, 0.0);
    for (int i = 0; i < GaussRule::kNodes; ++i) {
      const double z = apex + dir * (mid + half * rule.nodes[static_cast<std::size_t>(i)]);
      panel += rule.weights[static_cast<std::size_t>(i)] * f(z);
    }
    sum += panel * half;
    u += len;
    h = std::max(h, 2.0 * len);
  }
  if (infinite) {
    // ∫_U^∞ A·e^{−ikΦ} ≈ A(U)·e^{−ikΦ(U)}/(ik·Φ'(U)), Φ' the slope along the direction of integration.
    const double z = apex + dir * u_end;
    double amplitude = 0.0, slope = 0.0;
    const Complex value = f(z, &amplitude, &slope);
    sum += value / (Complex(0.0, 1.0) * f.k * (dir * slope));
  }
  return dir * sum;  // ∫_from^to = dir·∫ over u
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
  const Integrand f(wavenumber_rad_m, nu, source, receiver);
  const double apex = source.z_m + (receiver.z_m - source.z_m) * source.rho_m / (source.rho_m + receiver.rho_m);
  const double scale = source.rho_m + receiver.rho_m + std::abs(receiver.z_m - source.z_m);
  Complex integral(0.0, 0.0);
  if (apex <= wedge.z_start_m) {
    integral = integrateFrom(f, apex, wedge.z_start_m, wedge.z_end_m, scale);
  } else if (apex >= wedge.z_end_m) {
    integral = integrateFrom(f, apex, wedge.z_end_m, wedge.z_start_m, scale);
    integral = -integral;  // integrateFrom returned ∫_end^start
  } else {
    integral = integrateFrom(f, apex, apex, wedge.z_end_m, scale) - integrateFrom(f, apex, apex, wedge.z_start_m, scale);
  }
  return -(nu / (4.0 * kPi)) * integral;
}

Complex btmInfiniteWedgeField(double wavenumber_rad_m, double exterior_angle_rad, const CylindricalPoint& source,
                              const CylindricalPoint& receiver) {
  BtmWedge wedge;
  wedge.exterior_angle_rad = exterior_angle_rad;
  Complex u = btmEdgeDiffraction(wavenumber_rad_m, wedge, source, receiver);
  const double k = wavenumber_rad_m, dz = receiver.z_m - source.z_m;
  const double ts = source.phi_rad, tr = receiver.phi_rad, tw = exterior_angle_rad;
  // Each geometric wave with its zone: weight 1 inside (margin > 0), ½ on the boundary (within
  // kOnBoundaryRad, as the diffracted term's).
  auto add = [&](double image_rad, double margin) {
    if (margin < -kOnBoundaryRad) return;
    const double r = distance(receiver.rho_m, source.rho_m, tr - image_rad, dz);
    u += (margin <= kOnBoundaryRad ? 0.5 : 1.0) * std::polar(1.0 / r, -k * r);
  };
  add(ts, kPi - std::abs(tr - ts));            // direct
  add(-ts, kPi - (ts + tr));                   // image in the face θ = 0
  add(2.0 * tw - ts, (ts + tr) - (2.0 * tw - kPi));  // image in the face θ = θ_w
  return u;
}

}  // namespace diffray::reference
