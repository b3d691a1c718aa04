#include "diffray/reference/angular_spectrum.h"

#include <algorithm>
#include <cmath>
#include <complex>

#include "diffray/core/error.h"
#include "diffray/reference/quadrature.h"

namespace diffray::reference {

namespace {
constexpr double kPi = 3.14159265358979323846;

// T(u) = Σ ∫_p^q e^{−i2πux} dx = Σ (q − p)·sin(πu(q − p))/(πu(q − p))·e^{−iπu(p + q)}.
std::complex<double> spectrum(const std::vector<std::pair<double, double>>& openings, double u) {
  std::complex<double> sum = 0.0;
  for (const auto& [p, q] : openings) {
    const double w = q - p;
    const double arg = kPi * u * w;
    const double sinc = std::abs(arg) < 1e-8 ? 1.0 : std::sin(arg) / arg;
    sum += w * sinc * std::polar(1.0, -kPi * u * (p + q));
  }
  return sum;
}
}  // namespace

double propagatingIntensity2D(const std::vector<std::pair<double, double>>& openings, double X, double z,
                              double lambda) {
  if (!(z > 0) || !std::isfinite(z)) throw core::InputError("z", "must be > 0");
  if (!(lambda > 0) || !std::isfinite(lambda)) throw core::InputError("wavelength", "must be > 0");
  double extent = 0.0;
  for (const auto& [p, q] : openings) {
    if (!(q > p) || !std::isfinite(p) || !std::isfinite(q))
      throw core::InputError("openings", "need finite intervals with end > start");
    extent = std::max({extent, std::abs(p - X), std::abs(q - X)});
  }
  // The phase (2π/λ)(X sinθ + z cosθ) and T's phase change at most 2π(r + extent)/λ per radian: panels of
  // of at most half a period (π of phase), 16 nodes each.
  const double rate = 2.0 * kPi * (std::hypot(X, z) + extent + std::abs(X)) / lambda;
  const long panels = 8 + static_cast<long>(std::ceil(rate));  // total phase rate·π: π per panel
  const GaussRule& rule = gaussRule16();
  const double h = kPi / static_cast<double>(panels);
  std::complex<double> u_p = 0.0;
  for (long i = 0; i < panels; ++i) {
    const double mid = -0.5 * kPi + (static_cast<double>(i) + 0.5) * h;
    for (int n = 0; n < GaussRule::kNodes; ++n) {
      const double theta = mid + 0.5 * h * rule.nodes[static_cast<std::size_t>(n)];
      const double s = std::sin(theta), c = std::cos(theta);
      u_p += rule.weights[static_cast<std::size_t>(n)] * spectrum(openings, s / lambda) *
             std::polar(1.0, 2.0 * kPi / lambda * (X * s + z * c)) * (c / lambda);
    }
  }
  return std::norm(0.5 * h * u_p);
}

}  // namespace diffray::reference
