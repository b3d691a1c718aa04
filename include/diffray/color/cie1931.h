#pragma once
// The CIE 1931 2° standard observer: colour-matching functions x̄(λ), ȳ(λ), z̄(λ), tabulated at 1 nm from
// 360 to 830 nm (src/color/cie1931_table.cpp, with its source) and interpolated linearly between the
// knots. Zero outside [360, 830] nm. λ is the wavelength in vacuum in nm; the functions are dimensionless
// with ȳ(555 nm) = 1, so X = ∫ S(λ) x̄(λ) dλ carries S's unit times nm. Pure functions: thread-safe.
namespace diffray::color {

/// CIE XYZ tristimulus values (or the three matching functions at one wavelength).
struct Xyz {
  double x, y, z;
};

inline constexpr int kCieFirstNm = 360;   ///< first table knot
inline constexpr int kCieLastNm = 830;    ///< last table knot
inline constexpr int kCieSamples = kCieLastNm - kCieFirstNm + 1;  ///< knots, 1 nm apart

/// (x̄, ȳ, z̄) at `wavelength_nm`: linear interpolation of the 1 nm table; {0, 0, 0} outside [360, 830] nm
/// and for NaN.
Xyz cie1931(double wavelength_nm);

/// ∫ ȳ(λ) dλ over [360, 830] nm of the interpolated table (trapezoid rule on the knots, exact for the
/// piecewise-linear interpolant): the normalisation that makes Y of an equal-energy spectrum 1 (≈ 106.857).
double cieYIntegralNm();

namespace detail {
/// The table knots: entry i is at kCieFirstNm + i nm.
extern const double kCieX[kCieSamples];
extern const double kCieY[kCieSamples];
extern const double kCieZ[kCieSamples];
}  // namespace detail

}  // namespace diffray::color
