// 2D Rayleigh–Sommerfeld reference by direct quadrature (Goodman, "Introduction to Fourier Optics", ch. 3).
// Self-contained: its own Gauss–Legendre rule, no code shared with the ray tracer.
#include "diffray/reference/rayleigh_sommerfeld.h"
#include "diffray/reference/quadrature.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include "diffray/core/error.h"

namespace diffray::reference {
namespace {

using Complex = std::complex<double>;

constexpr double kPi = 3.14159265358979323846;
constexpr int kNodes = 16;              // Gauss–Legendre nodes per panel
constexpr double kPanelFraction = 0.5;  // panel length / min(local wavelength, r)
constexpr long kMaxPanels = 10000000;

// Everything the integrand needs for one field point.
struct FieldPoint {
  double X_m;
  double z_m;
  double k_per_m;      // 2π/λ
  double kx_incident;  // k·sinθi (aperture phase gradient, rad/m)
  double max_panel_m;  // kPanelFraction · λ/(1 + |sinθi|)
};

// U0(x)·(ik/2)(z/r)·H1⁽¹⁾(kr).
Complex integrand(const FieldPoint& p, double x_m) {
  const double r_m = std::hypot(p.X_m - x_m, p.z_m);
  const double kr = p.k_per_m * r_m;
  const Complex hankel(std::cyl_bessel_j(1.0, kr), std::cyl_neumann(1.0, kr));
  const Complex aperture = std::polar(1.0, p.kx_incident * x_m);
  return aperture * Complex(0.0, 0.5 * p.k_per_m) * (p.z_m / r_m) * hankel;
}

// ∫ from `start_m` to `end_m` (either order), marching away from `start_m`, which must be the end nearest to
// the foot point X. Panel length is kPanelFraction·min(λ_eff, r) at the panel's near end; r only grows
// along the march, so every panel resolves both the phase (≤ π per panel) and the amplitude scale r.
Complex integrateAway(const FieldPoint& p, double start_m, double end_m, long& panels) {
  const GaussRule& rule = gaussRule16();
  const double direction = end_m >= start_m ? 1.0 : -1.0;
  const double length_m = std::abs(end_m - start_m);
  Complex sum(0.0, 0.0);
  double done_m = 0.0;
  while (done_m < length_m) {
    const double x_m = start_m + direction * done_m;
    const double r_m = std::hypot(p.X_m - x_m, p.z_m);
    double h_m = std::min(p.max_panel_m, kPanelFraction * r_m);
    const bool last = done_m + h_m >= length_m;
    if (last) h_m = length_m - done_m;
    if (++panels > kMaxPanels)
      throw core::InputError("rayleighSommerfeld2D: openings_m",
                             "openings too wide for direct quadrature (more than 1e7 panels)");
    const double mid_m = x_m + direction * 0.5 * h_m;
    Complex panel(0.0, 0.0);
    for (int i = 0; i < kNodes; ++i) {
      const auto node = static_cast<std::size_t>(i);
      panel += rule.weights[node] * integrand(p, mid_m + 0.5 * h_m * rule.nodes[node]);
    }
    sum += 0.5 * h_m * panel;
    done_m = last ? length_m : done_m + h_m;
  }
  return direction * sum;
}


}  // namespace

Complex rayleighSommerfeld2D(const std::vector<std::pair<double, double>>& openings_m, double X_m, double z_m,
                             double wavelength_m, double sin_theta_i) {
  core::requireFinite("rayleighSommerfeld2D: X_m", X_m);
  core::requirePositive("rayleighSommerfeld2D: z_m", z_m);
  core::requirePositive("rayleighSommerfeld2D: wavelength_m", wavelength_m);
  core::requireFinite("rayleighSommerfeld2D: sin_theta_i", sin_theta_i);
  if (std::abs(sin_theta_i) > 1.0)
    throw core::InputError("rayleighSommerfeld2D: sin_theta_i",
                           "must lie in [-1, 1], got " + std::to_string(sin_theta_i));
  const double k_per_m = 2.0 * kPi / wavelength_m;
  const FieldPoint point{X_m, z_m, k_per_m, k_per_m * sin_theta_i,
                         kPanelFraction * wavelength_m / (1.0 + std::abs(sin_theta_i))};
  Complex field(0.0, 0.0);
  long panels = 0;
  for (const auto& [begin_m, end_m] : openings_m) {
    core::requireFinite("rayleighSommerfeld2D: opening begin", begin_m);
    core::requireFinite("rayleighSommerfeld2D: opening end", end_m);
    if (end_m < begin_m)
      throw core::InputError(
          "rayleighSommerfeld2D: openings_m",
          "interval [" + std::to_string(begin_m) + ", " + std::to_string(end_m) + "] is reversed");
    // March away from the foot point X, where the kernel peaks (width ~z) and its phase is stationary.
    if (X_m <= begin_m) {
      field += integrateAway(point, begin_m, end_m, panels);
    } else if (X_m >= end_m) {
      field -= integrateAway(point, end_m, begin_m, panels);  // ∫_begin^end = −∫_end^begin
    } else {
      field += integrateAway(point, X_m, end_m, panels);
      field -= integrateAway(point, X_m, begin_m, panels);
    }
  }
  return field;
}

double rayleighSommerfeldIntensity2D(const std::vector<std::pair<double, double>>& openings_m, double X_m,
                                     double z_m, double wavelength_m, double sin_theta_i) {
  return std::norm(rayleighSommerfeld2D(openings_m, X_m, z_m, wavelength_m, sin_theta_i));
}

}  // namespace diffray::reference
