#pragma once
// Importance sampling of wavelengths for spectral rendering. The density over [lo, hi] nm is
//   p(λ) = g(λ) / ∫_lo^hi g,   g = the piecewise-linear interpolant, on the 1 nm CIE knots (plus lo and hi),
//   of max(x̄ + ȳ + z̄, kWavelengthPdfFloor · peak), peak = max of x̄ + ȳ + z̄ over the knots in [lo, hi],
// so it follows the CIE 1931 matching functions (an XYZ estimate f(λ)·cmf(λ)/p(λ) has weights bounded by
// ∫g) and the floor keeps every wavelength of the range reachable (deep red and violet included).
// Sampling inverts the tabulated CDF exactly (a quadratic per 1 nm segment), so sample and pdf agree to
// rounding. Units: nm and 1/nm. WavelengthSampler is immutable after construction: share it across
// threads freely; the free functions use a cached sampler for the default range 380–780 nm.
#include <vector>

namespace diffray::color {

/// Fraction of the peak of x̄ + ȳ + z̄ below which the sampling density is held constant.
inline constexpr double kWavelengthPdfFloor = 0.01;

struct WavelengthSample {
  double wavelength_nm;  ///< in [lo, hi]
  double pdf_per_nm;     ///< p(wavelength_nm) > 0
};

class WavelengthSampler {
 public:
  /// Requires 360 ≤ lo_nm < hi_nm ≤ 830 (the CIE table); throws core::InputError("wavelength range") else.
  WavelengthSampler(double lo_nm = 380.0, double hi_nm = 780.0);

  /// λ for u in [0, 1) (clamped into it), by inverting the CDF; monotone in u.
  WavelengthSample sample(double u) const;
  /// p(λ) in 1/nm; 0 outside [lo, hi].
  double pdf(double wavelength_nm) const;

  double loNm() const { return knots_nm_.front(); }
  double hiNm() const { return knots_nm_.back(); }

 private:
  std::vector<double> knots_nm_;  ///< lo, the integer nm strictly inside, hi
  std::vector<double> g_;         ///< unnormalised density at the knots
  std::vector<double> cdf_;       ///< ∫ g up to each knot; cdf_.back() = total
};

/// One wavelength from the density above on [lo_nm, hi_nm]. The default range uses a sampler built once;
/// other ranges build one per call (about 500 knots): hold a WavelengthSampler in loops instead.
WavelengthSample sampleWavelength(double u, double lo_nm = 380.0, double hi_nm = 780.0);
/// The density sampleWavelength draws from, in 1/nm.
double wavelengthPdf(double wavelength_nm, double lo_nm = 380.0, double hi_nm = 780.0);

}  // namespace diffray::color
