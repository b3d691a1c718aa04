// Fraunhofer references (Goodman, "Introduction to Fourier Optics", ch. 4). Self-contained: no code shared with the ray
// tracer.
#include "diffray/reference/fraunhofer.h"

#include <cmath>
#include <string>

#include "diffray/core/error.h"

namespace diffray::reference {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Normalised sinc, sin(πz)/(πz); the Taylor form near 0 keeps full precision.
double sincNormalised(double z) {
  const double pz = kPi * z;
  if (std::abs(pz) < 1e-4) return 1.0 - pz * pz / 6.0;
  return std::sin(pz) / pz;
}


}  // namespace

double slitFraunhofer(double u, double width_m) {
  core::requireFinite("slitFraunhofer: u", u);
  core::requirePositive("slitFraunhofer: width_m", width_m);
  const double t = width_m * sincNormalised(width_m * u);  // T(u) of rect(x/a), real
  return t * t;
}

double doubleSlitFraunhofer(double u, double width_m, double spacing_m) {
  core::requireFinite("doubleSlitFraunhofer: u", u);
  core::requirePositive("doubleSlitFraunhofer: width_m", width_m);
  core::requirePositive("doubleSlitFraunhofer: spacing_m", spacing_m);
  // T(u) = a sinc(au)·(e^{iπdu} + e^{−iπdu}) = 2a cos(πdu) sinc(au).
  const double t = 2.0 * width_m * std::cos(kPi * spacing_m * u) * sincNormalised(width_m * u);
  return t * t;
}

double nSlitFraunhofer(double u, double width_m, double spacing_m, int n) {
  core::requireFinite("nSlitFraunhofer: u", u);
  core::requirePositive("nSlitFraunhofer: width_m", width_m);
  core::requirePositive("nSlitFraunhofer: spacing_m", spacing_m);
  if (n < 1) throw core::InputError("nSlitFraunhofer: n", "must be >= 1, got " + std::to_string(n));
  // Centres x_j = (j − (n − 1)/2)·d are symmetric about 0, so Σ_j e^{−i2πu x_j} = Σ_j cos(2πu x_j) is real.
  double array_factor = 0.0;
  for (int j = 0; j < n; ++j) {
    const double centre_m = (j - 0.5 * (n - 1)) * spacing_m;
    array_factor += std::cos(2.0 * kPi * u * centre_m);
  }
  const double t = width_m * sincNormalised(width_m * u) * array_factor;
  return t * t;
}

double rectFraunhofer(double u, double v, double width_m, double height_m) {
  core::requireFinite("rectFraunhofer: u", u);
  core::requireFinite("rectFraunhofer: v", v);
  core::requirePositive("rectFraunhofer: width_m", width_m);
  core::requirePositive("rectFraunhofer: height_m", height_m);
  const double tx = width_m * sincNormalised(width_m * u);
  const double ty = height_m * sincNormalised(height_m * v);
  return tx * tx * ty * ty;
}

double phaseGratingOrderEfficiency(int q, double m) {
  core::requireFinite("phaseGratingOrderEfficiency: m", m);
  // exp(i z sin φ) = Σ_q J_q(z) e^{iqφ} (Jacobi–Anger) with z = m/2. J_{−q}(z) = (−1)^q J_q(z) and
  // J_q(−z) = (−1)^q J_q(z): the squared amplitude depends only on |q| and |z|.
  const double order = std::abs(static_cast<double>(q));
  const double j = std::cyl_bessel_j(order, 0.5 * std::abs(m));
  return j * j;
}

double screenU(double x_screen_m, double z_m, double wavelength_m) {
  core::requireFinite("screenU: x_screen_m", x_screen_m);
  core::requirePositive("screenU: z_m", z_m);
  core::requirePositive("screenU: wavelength_m", wavelength_m);
  const double r_m = std::hypot(x_screen_m, z_m);
  return x_screen_m / r_m / wavelength_m;
}

// Derivation (2D Rayleigh–Sommerfeld, first kind, rayleigh_sommerfeld.h): U(X, z) = ∫ t(x)(ik/2)(z/R)
// H1⁽¹⁾(kR) dx with R = √((X − x)² + z²). Far away, H1⁽¹⁾(kR) ≈ √(2/(πkR)) e^{i(kR − 3π/4)} and
// R ≈ r − x sinθ (r = √(X² + z²), sinθ = X/r, z/R ≈ cosθ), so U ≈ (ik/2) cosθ √(2/(πkr)) e^{i(kr − 3π/4)}
// ∫ t(x) e^{−i2πx sinθ/λ} dx = (...)·T(sinθ/λ), and |U|² = (k²/4) cos²θ · 2/(πkr) · |T|² = |T|² cos²θ/(λr).
// Power: with X = z tanθ, dX = z dθ/cos²θ and r = z/cosθ, |U|² dX = |T|² cosθ dθ/λ = |T|² du.
double farFieldScreenIntensity2D(double x_screen_m, double z_m, double wavelength_m, double transform_sq) {
  core::requireFinite("farFieldScreenIntensity2D: x_screen_m", x_screen_m);
  core::requirePositive("farFieldScreenIntensity2D: z_m", z_m);
  core::requirePositive("farFieldScreenIntensity2D: wavelength_m", wavelength_m);
  core::requireFinite("farFieldScreenIntensity2D: transform_sq", transform_sq);
  const double r_m = std::hypot(x_screen_m, z_m);
  const double cos_theta = z_m / r_m;
  return transform_sq * cos_theta * cos_theta / (wavelength_m * r_m);
}

}  // namespace diffray::reference
