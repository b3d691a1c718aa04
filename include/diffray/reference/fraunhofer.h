#pragma once
// Fraunhofer (far-field) references (Goodman, "Introduction to Fourier Optics", ch. 4): exact Fourier transforms T(u)
// of simple transmittances t(x), returned as |T(u)|², plus the conversion from |T|² to intensity on a flat screen.
//
// Contract: these are ORACLES for the tests and for `diffray validate`; they share no code with the ray
// tracer (only diffray/core/error.h for InputError).
// Units and conventions:
//  - u (and v) are spatial frequencies in cycles per metre, u = (sinθo − sinθi)/λ (Cuypers et al. 2012, eq. 8–10);
//    T(u) = ∫ t(x) e^{−i2πux} dx, so |T(u)|² is the far-field energy per unit u for a unit-intensity plane
//    wave; ∫|T|² du = ∫|t|² dx (Parseval), the WDF's u-marginal (paper eq. 2).
//  - sinc(z) = sin(πz)/(πz). Widths, spacings and heights are in metres and must be > 0.
//  - Apertures are centred on x = 0: the double slit has slit centres at ±d/2, the n-slit array at
//    (j − (n − 1)/2)·d, j = 0..n−1.
// Invalid arguments throw core::InputError. Thread-safety: pure functions; safe to call concurrently.

namespace diffray::reference {

/// Slit of width a: |T(u)|² = a² sinc²(a u).
double slitFraunhofer(double u, double width_m);

/// Two slits of width a, centres ±d/2: |T(u)|² = 4 a² cos²(π d u) sinc²(a u).
double doubleSlitFraunhofer(double u, double width_m, double spacing_m);

/// n >= 1 equal slits of width a, spacing d (centre to centre):
/// |T(u)|² = a² sinc²(a u)·[sin(nπdu)/sin(πdu)]² (evaluated as an explicit phasor sum, so exact at the
/// principal maxima where the ratio is 0/0). n = 2 is doubleSlitFraunhofer; n = 1 is slitFraunhofer.
double nSlitFraunhofer(double u, double width_m, double spacing_m, int n);

/// Rectangle a × b (separable): |T(u, v)|² = a² sinc²(a u)·b² sinc²(b v). On a screen at
/// distance z (paraxial) this gives the classic I = (ab/λz)² sinc²(ax/λz) sinc²(by/λz) once divided by (λz)².
double rectFraunhofer(double u, double v, double width_m, double height_m);

/// Efficiency of diffraction order q of the sinusoidal phase grating t(x) = exp(i(m/2) sin(2πx/Λ))
/// (Cuypers et al. 2012, eq. 14–15): J_q(m/2)², by the Jacobi–Anger expansion. Any integer q (J_{−q} =
/// (−1)^q J_q) and any real m; Σ_q J_q(m/2)² = 1. Order q leaves at sinθq = sinθi + qλ/Λ.
double phaseGratingOrderEfficiency(int q, double m);

/// sinθ/λ for the point at lateral position x on a flat screen line at distance z behind the aperture
/// (θ = atan(x/z), the aperture centred on x = 0, normal incidence).
double screenU(double x_screen_m, double z_m, double wavelength_m);

/// Intensity at lateral position x on a flat screen line at distance z, from transform_sq = |T(u)|² at
/// u = screenU(x, z, λ) (normal incidence, unit-intensity plane wave on the aperture):
///   I(x) = |T(u)|²·cos²θ/(λ r),  r = √(x² + z²), cos θ = z/r.
/// This is the exact far-field limit of the 2D Rayleigh–Sommerfeld integral (see fraunhofer.cpp), and it
/// conserves power: ∫ I dx over the whole line = ∫_{|u| < 1/λ} |T(u)|² du.
double farFieldScreenIntensity2D(double x_screen_m, double z_m, double wavelength_m, double transform_sq);

}  // namespace diffray::reference
