#pragma once
// The angle-impact WBSDF of an aperture: exact free-space transport with straight rays in 2D.
//
// The paper (section "Limitations") notes that its Wigner distribution is transported exactly only in the
// paraxial regime and that the angle-impact Wigner function (Alonso 2004) fixes this. For a propagating
// 2D field with angular spectrum A(u), u = sinθ/λ, the intensity at any point P is exactly
//     I(P) = ∫ dθ W_AI(θ, b_P(θ)),   b = x·cosθ − z·sinθ (the impact parameter, constant along a ray),
//     W_AI(θ, b) = ∫ dΔ (cosθ₁cosθ₂/λ²) A(sinθ₁/λ) A*(sinθ₂/λ) e^{i(4π/λ) sin(Δ/2) b},  θ₁,₂ = θ ± Δ/2,
// which follows from |U|² = ∫∫A(u₁)A*(u₂)e^{i2π[(u₁−u₂)x + (w₁−w₂)z]} with no approximation. Rays that
// leave the aperture plane at x₀ with u = sinθ/λ therefore have the density
//     W̃(x₀, u) = λ·W_AI(θ, x₀·cosθ)   (paraxially W̃ → the Wigner distribution W(x₀, u) of eq:R_WDF),
// whose u-marginal is cosθ·|A(u)|², the z-directed power of each plane wave. Such rays carry power; a
// receiver that wants the intensity |U|² weighs each ray by 1/|cos| to its normal (receiver/screen.h).
// Only propagating directions exist in W̃; evanescent waves are left out, as they carry no power.
//
// Here A is the spectrum of the aperture field under a normally incident plane wave (Rayleigh–Sommerfeld
// first kind: U(x, 0) = t(x)); the table is used with the angle-shift invariance of paper eq. 8 like any
// WBSDF, which is exact at normal incidence. Pure functions; thread-safe.
#include <complex>
#include <functional>
#include <memory>

#include "diffray/wbsdf/table.h"

namespace diffray::wbsdf {

struct AngleImpactOptions {
  double wavelength_m = 0.0;
  double x_lo_m = 0.0, x_hi_m = 0.0;  ///< where t ≠ 0 (the aperture)
  double margin_m = 0.0;              ///< rows beyond the aperture on each side (band-limited tails); 0 → 4λ
  int nu = 512;                       ///< u-cells over (−u_half, u_half)
  /// Half-range of tabulated u (cycles per metre); 0 → 1/λ, every propagating direction. Narrower ranges
  /// (directions that can reach the receivers) save work; what lies outside is left out.
  double u_half_range_per_m = 0.0;
  int nx = 256;                       ///< x-rows over the aperture plus margins
  std::size_t max_cells = 8'000'000;  ///< refuse (InputError) larger tables: each column costs FFTs
};

/// Tabulates W̃(x₀, u) for the angular spectrum `spectrum(u)` = T(u) = ∫ t(x) e^{−i2πux} dx.
std::shared_ptr<const WbsdfTable> angleImpactTable(const std::function<std::complex<double>(double)>& spectrum,
                                                   const AngleImpactOptions& options);

/// T(u) of openings [p_j, q_j] in an opaque screen (finite intervals): Σ_j (e^{−i2πup} − e^{−i2πuq})/(i2πu).
std::complex<double> openingsSpectrum(const Openings& openings, double u_per_m);

}  // namespace diffray::wbsdf
