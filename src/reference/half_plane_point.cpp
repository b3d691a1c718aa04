// Macdonald's exact point-source solution for the thin half-plane (see the header for the
// source, the frame and the formula). Self-contained apart from the module's Gauss rule and core/error.h.
#include "diffray/reference/half_plane_point.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "diffray/core/error.h"
#include "diffray/reference/band_grid.h"
#include "diffray/reference/quadrature.h"

namespace diffray::reference {
namespace {

using Complex = std::complex<double>;

constexpr double kPi = 3.14159265358979323846;

void requirePoint(const std::string& where, const CylindricalPoint& p) {
  core::requireFinite(where + ".rho_m", p.rho_m);
  core::requireFinite(where + ".phi_rad", p.phi_rad);
  core::requireFinite(where + ".z_m", p.z_m);
  if (p.rho_m < 0.0) throw core::InputError(where + ".rho_m", "must be >= 0, got " + std::to_string(p.rho_m));
  const double slack_rad = 1e-12;
  if (p.phi_rad < -slack_rad || p.phi_rad > 2.0 * kPi + slack_rad)
    throw core::InputError(where + ".phi_rad", "must lie in [0, 2π] rad, got " + std::to_string(p.phi_rad));
}

// Distance between two points whose azimuths differ by `dphi_rad`, written without cancellation:
// R² = (ρ − ρ0)² + 4ρρ0 sin²(Δφ/2) + Δz².
double distance(double rho_m, double rho0_m, double dphi_rad, double dz_m) {
  const double s = std::sin(0.5 * dphi_rad);
  return std::sqrt((rho_m - rho0_m) * (rho_m - rho0_m) + 4.0 * rho_m * rho0_m * s * s + dz_m * dz_m);
}

// One branch (the direct source, or its image in the screen) of Macdonald's solution: the geometric wave
// e^{−ikR}/R where cos(Δφ/2) > 0, plus the diffracted wave −(ε/π)·I (ε = 2√(ρρ0)cos(Δφ/2), signed), with
//   I = ∫_{R1}^∞ e^{−ikL} dL / ((L² − R²)√(L² − R1²))
//     = −2i·e^{iπ/4}·e^{−ikR1} ∫_0^∞ e^{−kv²} dv / ((ε² − 2iR1v² − v⁴)·√(2R1 − iv²))
// after turning the path down to L = R1 − iv² (e^{−ikL} decays there; no singularity is crossed). The
// integrand has poles at v² = −i(R1 ∓ R), i.e. at |v| = √(R1 − R) = |σ|/√k near the boundaries, so the
// panels start at half that and double up to the Gaussian's reach V = √(45/k) (e^{−45} ≈ 3e-20), capped at
// V/16 and ½√R1 (the second pole). On the boundary itself (ε = 0) the branch is ½e^{−ikR}/R.
Complex macdonaldBranch(double k_per_m, double r_m, double via_edge_m, double epsilon_m) {
  if (epsilon_m == 0.0) return 0.5 * std::polar(1.0 / r_m, -k_per_m * r_m);
  const double eps2 = epsilon_m * epsilon_m;
  const double pole_m = std::sqrt(eps2 / (via_edge_m + r_m));  // √(R1 − R) without cancellation
  const double reach = std::sqrt(45.0 / k_per_m);
  const double cap = std::min(reach / 16.0, 0.5 * std::sqrt(via_edge_m));
  auto integrand = [&](double v) {
    const double v2 = v * v;
    const Complex denominator = Complex(eps2 - v2 * v2, -2.0 * via_edge_m * v2) *
                                std::sqrt(Complex(2.0 * via_edge_m, -v2));
    return std::exp(-k_per_m * v2) / denominator;
  };
  const GaussRule& rule = gaussRule16();
  Complex sum(0.0, 0.0);
  for (double a = 0.0; a < reach;) {
    const double h = std::min({cap, std::max(0.5 * pole_m, a), reach - a});
    Complex panel(0.0, 0.0);
    for (std::size_t i = 0; i < static_cast<std::size_t>(GaussRule::kNodes); ++i)
      panel += rule.weights[i] * integrand(a + 0.5 * h * (1.0 + rule.nodes[i]));
    sum += 0.5 * h * panel;
    a += h;
  }
  const Complex integral =
      Complex(0.0, -2.0) * std::polar(1.0, 0.25 * kPi - k_per_m * via_edge_m) * sum;
  const Complex geometric = epsilon_m > 0.0 ? std::polar(1.0 / r_m, -k_per_m * r_m) : Complex(0.0, 0.0);
  return geometric - (epsilon_m / kPi) * integral;
}

}  // namespace

CylindricalPoint halfPlaneFrameFromCartesian(double x_m, double y_m, double z_m) {
  core::requireFinite("halfPlaneFrameFromCartesian: x_m", x_m);
  core::requireFinite("halfPlaneFrameFromCartesian: y_m", y_m);
  core::requireFinite("halfPlaneFrameFromCartesian: z_m", z_m);
  double phi_rad = std::atan2(y_m, x_m);  // (−π, π]; ±0 for y = ±0 and x >= 0
  if (std::signbit(phi_rad)) phi_rad += 2.0 * kPi;
  return {std::hypot(x_m, y_m), phi_rad, z_m};
}

Complex halfPlanePointSource(double wavelength_m, const CylindricalPoint& source,
                             const CylindricalPoint& receiver, bool rigid) {
  core::requirePositive("halfPlanePointSource: wavelength_m", wavelength_m);
  requirePoint("halfPlanePointSource: source", source);
  requirePoint("halfPlanePointSource: receiver", receiver);
  const double k_per_m = 2.0 * kPi / wavelength_m;
  const double rho_m = receiver.rho_m, rho0_m = source.rho_m;
  const double dz_m = receiver.z_m - source.z_m;
  const double direct_m = distance(rho_m, rho0_m, receiver.phi_rad - source.phi_rad, dz_m);
  const double image_m = distance(rho_m, rho0_m, receiver.phi_rad + source.phi_rad, dz_m);
  if (!(direct_m > 0.0))
    throw core::InputError("halfPlanePointSource: receiver", "coincides with the source (R = 0)");
  const double via_edge_m = std::hypot(rho_m + rho0_m, dz_m);  // R1 >= R, R'
  // ε = 2√(ρρ0)cos(Δφ/2): R1² − R² = ε², and its sign tells the lit side of the boundary.
  const double root = 2.0 * std::sqrt(rho_m * rho0_m);
  const Complex direct = macdonaldBranch(k_per_m, direct_m, via_edge_m,
                                         root * std::cos(0.5 * (receiver.phi_rad - source.phi_rad)));
  // R' = 0 only when R = 0 too (the image of a source on a face is the source itself).
  const Complex image = macdonaldBranch(k_per_m, image_m, via_edge_m,
                                        root * std::cos(0.5 * (receiver.phi_rad + source.phi_rad)));
  return rigid ? direct + image : direct - image;
}

namespace {
// |u·R|²: the energy re the free field at the same distance.
double energyReFreeField(double wavelength_m, const CylindricalPoint& source,
                         const CylindricalPoint& receiver, bool rigid) {
  const Complex u = halfPlanePointSource(wavelength_m, source, receiver, rigid);
  const double r_m = distance(receiver.rho_m, source.rho_m, receiver.phi_rad - source.phi_rad,
                              receiver.z_m - source.z_m);
  return std::norm(u) * r_m * r_m;
}
}  // namespace

double halfPlaneLevelDb(double wavelength_m, const CylindricalPoint& source, const CylindricalPoint& receiver,
                        bool rigid) {
  return 10.0 * std::log10(energyReFreeField(wavelength_m, source, receiver, rigid));
}

double halfPlaneBandLevelDb(double f_lo_hz, double f_hi_hz, int points, double sound_speed_m_s,
                            const CylindricalPoint& source, const CylindricalPoint& receiver, bool rigid) {
  core::requirePositive("halfPlaneBandLevelDb: sound_speed_m_s", sound_speed_m_s);
  const std::vector<double> grid_hz = bandGridHz("halfPlaneBandLevelDb", f_lo_hz, f_hi_hz, points);
  double energy = 0.0;
  for (double f_hz : grid_hz) energy += energyReFreeField(sound_speed_m_s / f_hz, source, receiver, rigid);
  return 10.0 * std::log10(energy / static_cast<double>(grid_hz.size()));
}

}  // namespace diffray::reference
