// The BTM edge-source directivity β (see btm_kernel.h).
#include "diffray/reference/btm_kernel.h"

namespace diffray::reference {
namespace {
constexpr double kPi = 3.14159265358979323846;
}  // namespace

BtmBeta::BtmBeta(double nu, double theta_s_rad, double theta_r_rad) : nu_(nu) {
  const double phis[4] = {kPi + theta_s_rad + theta_r_rad, kPi + theta_s_rad - theta_r_rad,
                          kPi - theta_s_rad + theta_r_rad, kPi - theta_s_rad - theta_r_rad};
  for (int i = 0; i < 4; ++i) {
    const double h = std::sin(0.5 * nu * phis[i]);
    sin_phi_[i] = std::abs(h) < 0.5 * nu * kBtmOnBoundaryRad ? 0.0 : std::sin(nu * phis[i]);
    half_phi_sin2_[i] = 2.0 * h * h;
  }
}

double BtmBeta::firstPanel(double rho_s, double rho_r, double scale) const {
  double closest = 1.0;  // rad
  for (int i = 0; i < 4; ++i)
    if (sin_phi_[i] != 0.0) closest = std::min(closest, 2.0 * std::asin(std::sqrt(0.5 * half_phi_sin2_[i])) / nu_);
  return std::max(1e-2 * closest * rho_s * rho_r / (rho_s + rho_r), 1e-10 * scale);
}

double BtmBeta::coshTerm(double rho_s, double rho_r, double a, double b, double m, double l) const {
  const double num = rho_s * b + rho_r * a;
  const double t = num * num / ((m * l + rho_s * rho_r - a * b) * rho_s * rho_r);  // cosh η − 1
  if (nu_ == 0.5) return 0.5 * t / (std::sqrt(1.0 + 0.5 * t) + 1.0);  // cosh(η/2) = √(1 + t/2)
  const double eta = std::log1p(t + std::sqrt(t * (t + 2.0)));
  const double sh = std::sinh(0.5 * nu_ * eta);
  return 2.0 * sh * sh;
}

}  // namespace diffray::reference
