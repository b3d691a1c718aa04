#pragma once
// Numeric Wigner distribution of a sampled microstructure t(x) = a(x)·e^{iΦ(x)} (paper eq. eq:R_WDF,
// eq:microstructure), computed row by row with FFTW. Used for microstructures that have no closed form
// (a measured profile read by profile_csv.h, an arbitrary user function).
//
// Contract. Input: t sampled on a uniform grid x_j = x0 + j·dx (metres), t = 0 outside the samples.
// Output: the discrete pseudo-Wigner distribution
//     W(x_j, u) = 2·dx · Σ_m t[j+m]·t*[j−m]·e^{−i4πu·m·dx}                               (eq:R_WDF, x' = 2m·dx)
// on the sample rows x_j and on nu frequencies u_k = k/(2·nu·dx), k = −nu/2 … nu/2−1 (cycles per metre,
// the same local frame and sign convention as eq:R_WDF; no incidence shift is applied).
//  * Period and aliasing: the discrete W is periodic in u with period 1/(2dx), half the period of the
//    sampled spectrum T(u). The output therefore covers |u| < 1/(4dx) only, and it is free of aliasing
//    only if t is oversampled ×2: its spectrum must vanish for |u| ≥ 1/(4dx), i.e. dx ≤ 1/(4·u_max). For
//    a signal that is not band-limited, the u-integral over x is |T(u)|² + |T(u + 1/(2dx))|² (the alias).
//  * Lag truncation: lags m = −nu/2 … nu/2 are used (the two end lags ±nu/2 share one FFT bin and are
//    averaged, which keeps W exactly real). Pairs of samples more than nu·dx apart do not interfere, so
//    nu ≥ 2·(number of samples) gives the full (untruncated) pseudo-Wigner; smaller nu smooths W in u.
//  * Marginals: Σ_k W(x_j,u_k)·du = |t(x_j)|² exactly; Σ_j Σ_k W·dx·du = Σ_j |t_j|²·dx exactly.
// Thread-safety: wignerFFT and sampleProfile may be called concurrently; FFTW plan creation and
// destruction (not thread-safe in FFTW) are serialised through core::fftwPlannerMutex() (core/fftw_planner.h).
#include <complex>
#include <functional>
#include <vector>

namespace diffray::wbsdf {

/// t sampled at x_j = x0_m + j·dx_m, j = 0 … t.size()−1 (dimensionless complex transmittance).
struct SampledProfile {
  double x0_m = 0.0;
  double dx_m = 0.0;
  std::vector<std::complex<double>> t;
};

/// W(x_j, u_k), row-major: values[j*nu + k] (units: metres, i.e. W·du is dimensionless like |t|²).
struct WignerGrid {
  double x0_m = 0.0, dx_m = 0.0;          ///< row positions x_j = x0 + j·dx
  double u0_per_m = 0.0, du_per_m = 0.0;  ///< column frequencies u_k = u0 + k·du (cycles per metre)
  int nx = 0, nu = 0;
  std::vector<double> values;
  /// Largest |Im W| that was discarded (round-off only; a diagnostic, ~1e-16 of the peak).
  double max_abs_imag = 0.0;

  double at(int j, int k) const;
  double xAt(int j) const { return x0_m + j * dx_m; }
  double uAt(int k) const { return u0_per_m + k * du_per_m; }
};

/// The discrete pseudo-Wigner distribution of `profile` (see the header comment) with an FFT of nu lags.
/// u_keep_per_m = 0 returns all nu columns; u_keep > 0 returns only the 2·K columns k = −K … K−1,
/// K = min(nu/2, ⌈u_keep/du⌉), i.e. every u_k with |u_k| < u_keep (and the grid's nu is 2K).
/// nu must be even and ≥ 2; the profile needs ≥ 1 sample, finite x0, dx > 0, finite values.
/// Throws core::InputError otherwise.
WignerGrid wignerFFT(const SampledProfile& profile, int nu, double u_keep_per_m = 0.0);

/// Samples t at x_j = x0 + j·dx for every x_j ≤ x1 (up to a 1e-9·dx tolerance), j ≥ 0.
/// Throws core::InputError for non-finite bounds, x1 ≤ x0, dx ≤ 0, or a non-finite t(x).
SampledProfile sampleProfile(const std::function<std::complex<double>(double)>& t, double x0_m,
                             double x1_m, double dx_m);

/// In-place forward DFT with FFTW (FFTW_ESTIMATE): data[k] ← Σ_n data[n]·e^{−2πi·k·n/N}, N = data.size().
/// Thread-safe (the planner is serialised). Throws core::InputError if data is empty.
void forwardFFT(std::vector<std::complex<double>>& data);

}  // namespace diffray::wbsdf
