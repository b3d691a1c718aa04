#pragma once
// The statistical WBSDF of a randomly rough surface (paper section "Creating a Statistical WBSDF",
// eq:surface … eq:WDF_gamma).
//
// Model. Surface heights h(x) are Gaussian with standard deviation σ_h and autocorrelation
// R_h(x') = σ_h²·exp(−x'²/ℓ²) (ℓ: correlation length). In the tangent-plane approximation (eq:surface) the
// surface imposes the phase α(x) = (2π/λ)(1 + cosθ_i)·h(x), with variance
//     g = σ_α² = [2π(σ_h/λ)(1 + cosθ_i)]²,
// and the field correlation is γ(x') = exp(−g·(1 − ρ_h(x'))), ρ_h = R_h/σ_h². Its Fourier transform
//     W_γ(u) = ∫ γ(x') e^{−i2πux'} dx'                                                     (eq:WDF_gamma)
// is stationary (independent of x), real and non-negative (γ is a characteristic function), of unit
// integral (γ(0) = 1). Since γ → e^{−g} as |x'| → ∞, W_γ is split into
//     e^{−g}·δ(u)            the specular part (specular_weight), and
//     F[γ − e^{−g}](u)       a smooth diffuse lobe of total weight 1 − e^{−g} (diffuse, a density in u).
//
// Frame and units: u is in cycles per metre and is measured from the specular direction (the factor
// e^{ik_i x'} of eq:surface is left out): a ray arriving with u_i leaves with u_i + u' (transmission,
// eq:transmission) or mirrored (reflection, eq:reflection), u' drawn from W_γ. The dependence on the
// incidence enters only through cosθ_i in g, as in the paper; it is evaluated once per call.
// Validity: the tangent-plane approximation without shadowing or multiple scattering (paper: σ ≫ 1); for
// σ_h ≪ λ the result tends to the physically sensible mirror limit (specular weight → 1).
// Grid: diffuse[k] = W_γ(u_k), u_k = −u_max + k·du, du = 2·u_max/nu, k = 0 … nu−1 (u = 0 at k = nu/2).
// The lobe is computed on an internal grid fine and wide enough for the FFT to be accurate to about
// 1e-12 of the peak, whatever nu and u_max are; the caller chooses u_max (weight beyond ±u_max, often
// evanescent, is diffuse_weight − Σ diffuse·du).
// Thread-safety: a pure function; may be called concurrently.
#include <memory>
#include <vector>

namespace diffray::wbsdf {

struct RoughSurfaceWdf {
  double specular_weight = 1.0;  ///< e^{−σ_α²}: weight of δ(u) (dimensionless)
  double diffuse_weight = 0.0;   ///< 1 − e^{−σ_α²}: exact total of the diffuse lobe over all u
  double u0_per_m = 0.0;         ///< u of diffuse[0] (= −u_max)
  double du_per_m = 0.0;         ///< column spacing (= 2·u_max/nu)
  std::vector<double> diffuse;   ///< W_γ − e^{−g}δ at u_k: density per unit u (metres), ≥ 0
  /// σ_α² (the "g" of the closed-form series), kept for diagnostics.
  double phase_variance = 0.0;
};

/// The statistical WBSDF of eq:WDF_gamma. sigma_h_m, corr_length_m, wavelength_m, u_max_per_m must be
/// finite and > 0, cos_theta_i in [0, 1], nu even and ≥ 2; otherwise core::InputError.
RoughSurfaceWdf roughSurfaceWdf(double sigma_h_m, double corr_length_m, double wavelength_m,
                                double cos_theta_i, int nu, double u_max_per_m);

/// The phase variance σ_α² = [2π(σ_h/λ)(1 + cosθ_i)]² (paper, after eq:surface).
double roughPhaseVariance(double sigma_h_m, double wavelength_m, double cos_theta_i);

class WbsdfTable;
/// The rough surface as a WBSDF table (for one wavelength and incidence): one row valid at every x (the
/// statistics are stationary), cells centred on the lobe's columns, the specular δ put in the centre
/// cell (so the mirror direction is blurred by at most du). Sampling it is importance sampling of the lobe.
std::shared_ptr<const WbsdfTable> roughSurfaceTable(const RoughSurfaceWdf& wdf);

}  // namespace diffray::wbsdf
