// Fresnel integrals, the Fresnel slit and Sommerfeld's half-plane (Goodman, "Introduction to Fourier Optics", ch. 4;
// Born & Wolf, "Principles of Optics", §11.5). Self-contained: no code shared with the ray tracer.
#include "diffray/reference/fresnel.h"

#include <cmath>
#include <limits>
#include <string>

#include "diffray/core/error.h"

namespace diffray::reference {
namespace {

using Complex = std::complex<double>;

constexpr double kPi = 3.14159265358979323846;
constexpr double kSeriesLimit = 1.5;      // |w| below this: power series; above: continued fraction
constexpr double kAsymptoticLimit = 1e8;  // w above this: leading asymptotic term (relative error < 1e-17)

// exp(iπw²/2) for w >= 0 with the phase reduced exactly: w = n + f (n integer), and
// πw²/2 = (π/2)(n² + 2nf + f²), where n² mod 4 is computed exactly and 2nf, f² are reduced mod 4. The
// remaining rounding error of the phase is ~eps·w, which multiplies a tail of size ~1/(πw): the absolute
// error of the tail stays ~eps for every w.
Complex halfPiSquarePhase(double w) {
  const double n = std::floor(w);
  const double f = w - n;                   // exact
  const double n_mod4 = std::fmod(n, 4.0);  // exact
  const double w_squared_mod4 =
      std::fmod(std::fmod(n_mod4 * n_mod4, 4.0) + std::fmod(2.0 * n * f, 4.0) + f * f, 4.0);
  const double phase_rad = 0.5 * kPi * w_squared_mod4;
  return {std::cos(phase_rad), std::sin(phase_rad)};
}

// F(w) = w·Σ_n (iπw²/2)^n / (n!(2n+1)) for 0 <= w <= kSeriesLimit. The terms never exceed w·e^{πw²/2}
// < 35·w while |F(w)| > 0.55·w there, so cancellation costs under two digits.
Complex fresnelSeries(double w) {
  const Complex z(0.0, 0.5 * kPi * w * w);
  Complex power(1.0, 0.0);  // z^n / n!
  Complex sum(1.0, 0.0);
  for (int n = 1; n < 200; ++n) {
    power *= z / static_cast<double>(n);
    const Complex term = power / static_cast<double>(2 * n + 1);
    sum += term;
    if (std::abs(term) < 1e-18 * std::abs(sum)) break;
  }
  return w * sum;
}

// ∫_w^∞ exp(iπt²/2) dt for w >= kSeriesLimit. This is the complementary error function of a complex
// argument: with b = 1 − iπw², the modified Lentz evaluation of the continued fraction
//   h = 1/(b − 1·2/(b + 4 − 3·4/(b + 8 − 5·6/(b + 12 − ...))))
// gives tail = w·exp(iπw²/2)·h (Numerical Recipes §6.9 writes F = (1 + i)/2·(1 − (1 − i)w·e^{iπw²/2}h)).
Complex fresnelTailContinuedFraction(double w) {
  const double tiny = 1e-300;
  const Complex one(1.0, 0.0);
  Complex b(1.0, -kPi * w * w);
  Complex c(1.0 / tiny, 0.0);
  Complex d = one / b;
  Complex h = d;
  double n = -1.0;
  for (int k = 2; k < 2000; ++k) {
    n += 2.0;
    const double a = -n * (n + 1.0);
    b += Complex(4.0, 0.0);
    d = one / (a * d + b);
    c = b + a / c;
    const Complex del = c * d;
    h *= del;
    if (std::abs(del.real() - 1.0) + std::abs(del.imag()) < 1e-16) break;
  }
  return w * halfPiSquarePhase(w) * h;
}

// Tail for w >= 0, accurate in absolute terms and, beyond kSeriesLimit, in relative terms as well.
Complex positiveTail(double w) {
  if (w > kAsymptoticLimit) return Complex(0.0, 1.0) * halfPiSquarePhase(w) / (kPi * w);
  if (w >= kSeriesLimit) return fresnelTailContinuedFraction(w);
  return Complex(0.5, 0.5) - fresnelSeries(w);
}

// F(w2) − F(w1) for w1 <= w2 without the cancellation of two values near ±(1 + i)/2.
Complex fresnelDifference(double w1, double w2) {
  if (w1 >= 0.0) return positiveTail(w1) - positiveTail(w2);
  if (w2 <= 0.0) return positiveTail(-w2) - positiveTail(-w1);
  return fresnelIntegral(w2) - fresnelIntegral(w1);
}


void requireAngleInRange(const char* where, double angle_rad) {
  core::requireFinite(where, angle_rad);
  const double slack_rad = 1e-12;
  if (angle_rad < -slack_rad || angle_rad > 2.0 * kPi + slack_rad)
    throw core::InputError(where, "must lie in [0, 2π] rad, got " + std::to_string(angle_rad));
}

}  // namespace

Complex fresnelIntegral(double w) {
  core::requireFinite("fresnelIntegral: w", w);
  const double aw = std::abs(w);
  Complex f;
  if (aw < kSeriesLimit)
    f = fresnelSeries(aw);
  else
    f = Complex(0.5, 0.5) - positiveTail(aw);
  return w < 0.0 ? -f : f;
}

Complex fresnelIntegralTail(double w) {
  core::requireFinite("fresnelIntegralTail: w", w);
  if (w >= 0.0) return positiveTail(w);
  return Complex(1.0, 1.0) - positiveTail(-w);  // (1 + i)/2 + F(|w|) = (1 + i) − tail(|w|)
}

Complex sommerfeldG(double a) {
  core::requireFinite("sommerfeldG: a", a);
  // τ = t·√(π/2) turns exp(−iτ²) into exp(−iπt²/2), the conjugate of the Fresnel kernel.
  return std::sqrt(0.5 * kPi) * std::conj(fresnelIntegralTail(a * std::sqrt(2.0 / kPi)));
}

double fresnelSlitIntensity(double x_m, double width_m, double wavelength_m, double z_m) {
  core::requireFinite("fresnelSlitIntensity: x_m", x_m);
  core::requirePositive("fresnelSlitIntensity: width_m", width_m);
  core::requirePositive("fresnelSlitIntensity: wavelength_m", wavelength_m);
  core::requirePositive("fresnelSlitIntensity: z_m", z_m);
  const double scale = std::sqrt(2.0 / (wavelength_m * z_m));
  const double w1 = scale * (-0.5 * width_m - x_m);
  const double w2 = scale * (0.5 * width_m - x_m);
  return 0.5 * std::norm(fresnelDifference(w1, w2));
}

Complex sommerfeldHalfPlane(double wavelength_m, double rho_m, double phi_rad, double phi0_rad, bool rigid) {
  core::requirePositive("sommerfeldHalfPlane: wavelength_m", wavelength_m);
  core::requireFinite("sommerfeldHalfPlane: rho_m", rho_m);
  if (rho_m < 0.0)
    throw core::InputError("sommerfeldHalfPlane: rho_m", "must be >= 0, got " + std::to_string(rho_m));
  requireAngleInRange("sommerfeldHalfPlane: phi_rad", phi_rad);
  requireAngleInRange("sommerfeldHalfPlane: phi0_rad", phi0_rad);
  const double k = 2.0 * kPi / wavelength_m;
  const double root = std::sqrt(2.0 * k * rho_m);
  const double diff_rad = phi_rad - phi0_rad;  // incident term
  const double sum_rad = phi_rad + phi0_rad;   // image (reflected) term
  const Complex incident =
      std::polar(1.0, k * rho_m * std::cos(diff_rad)) * sommerfeldG(-root * std::cos(0.5 * diff_rad));
  const Complex image =
      std::polar(1.0, k * rho_m * std::cos(sum_rad)) * sommerfeldG(-root * std::cos(0.5 * sum_rad));
  const Complex prefactor = std::polar(1.0 / std::sqrt(kPi), 0.25 * kPi);
  return prefactor * (rigid ? incident + image : incident - image);
}

}  // namespace diffray::reference
