#include "diffray/wbsdf/rough_surface.h"
#include "diffray/wbsdf/table.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <sstream>
#include <string>

#include "diffray/core/error.h"
#include "diffray/core/math.h"
#include "diffray/wbsdf/wigner_fft.h"

namespace diffray::wbsdf {

namespace {

// Half-width of the x' window, in correlation lengths. The diffuse correlation
// f(x') = γ(x') − e^{−g} = e^{−g(1−ρ)}·(1 − e^{−gρ}) ≤ g·ρ(x'), its peak is f(0) = 1 − e^{−g}, so
// f(x')/f(0) ≤ (1 + g)·ρ(x'); with ρ(8ℓ) = e^{−64} ≈ 1.6e-28 the truncation is negligible for any g < 1e12.
constexpr double kWindowHalfWidthInCorrLengths = 8.0;
// Largest internal FFT: far above anything physical (an optical surface needs ~1e4 points).
constexpr double kMaxFftLength = 1u << 24;

/// f(x') = γ(x') − e^{−g} with γ = exp(−g(1 − ρ_h)), ρ_h = exp(−x'²/ℓ²), written without cancellation and
/// without 0·∞ when e^{−g} underflows: 1 − ρ = −expm1(−x'²/ℓ²), 1 − e^{−gρ} = −expm1(−gρ).
double diffuseCorrelation(double x_m, double corr_length_m, double g) {
  const double s = (x_m / corr_length_m) * (x_m / corr_length_m);
  const double rho = std::exp(-s);
  return std::exp(g * std::expm1(-s)) * -std::expm1(-g * rho);
}

/// Spectral half-extent beyond which the diffuse lobe is < ~1e-17 of its peak. The lobe is a Poisson(g)
/// mixture of Gaussians e^{−π²ℓ²u²/n} (see the test's closed-form series); terms with n above
/// n_max = g + 10√g + 20 carry negligible weight, and e^{−π²ℓ²U²/n_max} = 1e-18 at U ≈ 2.04√n_max/ℓ.
double lobeExtentPerM(double g, double corr_length_m) {
  const double n_max = g + 10.0 * std::sqrt(g) + 20.0;
  return 2.1 * std::sqrt(n_max) / corr_length_m;
}

}  // namespace

double roughPhaseVariance(double sigma_h_m, double wavelength_m, double cos_theta_i) {
  const double sigma_alpha = core::kTwoPi * (sigma_h_m / wavelength_m) * (1.0 + cos_theta_i);
  return sigma_alpha * sigma_alpha;
}

RoughSurfaceWdf roughSurfaceWdf(double sigma_h_m, double corr_length_m, double wavelength_m,
                                double cos_theta_i, int nu, double u_max_per_m) {
  const std::string where = "roughSurfaceWdf";
  core::requirePositive(where + ": sigma_h_m", sigma_h_m);
  core::requirePositive(where + ": corr_length_m", corr_length_m);
  core::requirePositive(where + ": wavelength_m", wavelength_m);
  core::requirePositive(where + ": u_max_per_m", u_max_per_m);
  core::requireFinite(where + ": cos_theta_i", cos_theta_i);
  if (cos_theta_i < 0.0 || cos_theta_i > 1.0) {
    std::ostringstream s;
    s << "cos_theta_i must be in [0, 1], got " << cos_theta_i;
    throw core::InputError(where, s.str());
  }
  if (nu < 2 || nu % 2 != 0) {
    throw core::InputError(where, "nu must be even and >= 2, got " + std::to_string(nu));
  }

  RoughSurfaceWdf result;
  const double g = roughPhaseVariance(sigma_h_m, wavelength_m, cos_theta_i);
  result.phase_variance = g;
  result.specular_weight = std::exp(-g);       // the δ(u) part of eq:WDF_gamma
  result.diffuse_weight = -std::expm1(-g);     // 1 − e^{−g}, exact
  result.du_per_m = 2.0 * u_max_per_m / nu;
  result.u0_per_m = -u_max_per_m;

  // Internal FFT grid: frequency step du/q (q integer, so every output u_k is an FFT bin) with the
  // period 1/(du/q) in x' covering the window ±8ℓ, and a Nyquist frequency covering both ±u_max and the
  // whole lobe (so nothing aliases back into the output).
  const double du = result.du_per_m;
  const double q_real = std::ceil(2.0 * kWindowHalfWidthInCorrLengths * corr_length_m * du);
  const double nyquist_per_m = std::max(u_max_per_m, lobeExtentPerM(g, corr_length_m));
  const double n_real = 2.0 * std::ceil(std::max(nyquist_per_m / du, 0.5 * nu + 1.0)) * q_real;
  if (!(n_real <= kMaxFftLength)) {
    std::ostringstream s;
    s << "the diffuse lobe needs an FFT of " << n_real << " points (limit " << kMaxFftLength
      << "): reduce u_max_per_m·corr_length_m or the roughness";
    throw core::InputError(where, s.str());
  }
  const int q = static_cast<int>(q_real);
  const int n = static_cast<int>(n_real);  // even
  const double du_int = du / q;
  const double dx_m = 1.0 / (n * du_int);  // x' step; n·dx = 1/du_int ≥ 2·8ℓ

  // Samples of f at x'_m = m·dx, m = −n/2 … n/2−1, stored at bin m mod n; f is even, so the DFT is real.
  std::vector<std::complex<double>> samples(static_cast<size_t>(n));
  for (int m = -n / 2; m < n / 2; ++m) {
    samples[static_cast<size_t>((m + n) % n)] = diffuseCorrelation(m * dx_m, corr_length_m, g);
  }
  forwardFFT(samples);  // bin b: Σ_m f_m e^{−2πi·b·m/n} = Σ_m f(x'_m) e^{−i2π(b·du_int)x'_m}

  result.diffuse.resize(static_cast<size_t>(nu));
  double peak = 0.0;
  for (int k = 0; k < nu; ++k) {
    // u_k = (k − nu/2)·du = (k − nu/2)·q·du_int: FFT bin (k − nu/2)·q mod n (eq:WDF_gamma).
    const long bin = ((static_cast<long>(k) - nu / 2) * q % n + n) % n;
    const double value = dx_m * samples[static_cast<size_t>(bin)].real();
    result.diffuse[static_cast<size_t>(k)] = value;
    peak = std::max(peak, std::abs(value));
  }
  // W_γ ≥ 0 exactly; the FFT leaves round-off of order 1e-16·Σ|f|·dx in the far tails. Clear it, and
  // treat anything larger as a bug.
  const double noise = 1e-10 * std::max(peak, corr_length_m * result.diffuse_weight);
  for (double& value : result.diffuse) {
    DIFFRAY_CHECK(value >= -noise);
    value = std::max(value, 0.0);
  }
  return result;
}

std::shared_ptr<const WbsdfTable> roughSurfaceTable(const RoughSurfaceWdf& wdf) {
  TableLayout L;
  L.nx = 1;
  L.dx_m = 1.0;
  L.periodic = true;  // one row, whatever x
  L.nu = static_cast<int>(wdf.diffuse.size());
  L.du_per_m = wdf.du_per_m;
  L.u0_per_m = wdf.u0_per_m - 0.5 * wdf.du_per_m;
  std::vector<double> masses(wdf.diffuse.size());
  for (std::size_t k = 0; k < masses.size(); ++k) masses[k] = wdf.diffuse[k] * wdf.du_per_m;
  const int centre = static_cast<int>(std::lround(-wdf.u0_per_m / wdf.du_per_m));
  DIFFRAY_CHECK(centre >= 0 && centre < L.nu);
  masses[static_cast<std::size_t>(centre)] += wdf.specular_weight;
  return std::make_shared<WbsdfTable>(L, std::move(masses));
}

}  // namespace diffray::wbsdf
