#pragma once
// Non-paraxial aperture reference (Goodman, "Introduction to Fourier Optics", ch. 3): the 2D Rayleigh–Sommerfeld
// integral of the first kind, evaluated by direct composite Gauss–Legendre quadrature over the openings of an opaque
// screen.
//
// Contract: an ORACLE for the tests and for `diffray validate`, independent of everything the ray tracer
// does (own quadrature nodes; Bessel functions from <cmath>; only diffray/core/error.h is shared).
// Geometry: the screen is the line z = 0; the openings are intervals [x_begin, x_end] on it (metres); the
// field is evaluated at (X, z) with z > 0. The incident field is a unit-amplitude plane wave
// exp(ik(x sinθi + z cosθi)), so the aperture field is U0(x) = exp(i2π sinθi x/λ) inside the openings
// (Kirchhoff boundary values), 0 elsewhere. Then
//   U(X, z) = ∫_openings U0(x)·(ik/2)(z/r)·H1⁽¹⁾(kr) dx,   r = √((X − x)² + z²),   H1⁽¹⁾ = J1 + iY1.
// Time convention e^{−iωt} (H⁽¹⁾ is outgoing): with this sign an infinitely wide opening gives exactly
// U = e^{ikz}. The kernel is often written as −(ik/2)(z/r)H1⁽¹⁾(kr), which differs by the global factor
// −1 (it is the right sign for e^{+iωt} with H1⁽²⁾); |U|² is the same either way.
// |U|² is intensity relative to the incident plane wave. Far away it tends to
// farFieldScreenIntensity2D(|T(u)|²) of fraunhofer.h.
// Accuracy: panels are at most half of min(λ/(1 + |sinθi|), r) long (16 nodes each), graded geometrically
// toward the foot point x = X, so both the oscillation of the kernel (k·width/π half-periods) and its peak
// of width z (z ≪ λ) are resolved; the result converges to ~1e-8 relative or better (at kr ≳ 1e6 the
// accuracy of the Bessel functions limits it).
// Invalid arguments throw core::InputError: z <= 0, wavelength <= 0, |sinθi| > 1, reversed or non-finite
// intervals, openings needing more than 1e7 panels.
// Thread-safety: pure functions (the quadrature rule is a function-local constant); safe concurrently.
#include <complex>
#include <utility>
#include <vector>

namespace diffray::reference {

/// Complex field U(X, z) behind the openings (list of [x_begin, x_end] intervals, metres; may be empty or
/// touch; they should not overlap, as overlapping parts would be counted twice).
std::complex<double> rayleighSommerfeld2D(const std::vector<std::pair<double, double>>& openings_m,
                                          double X_m, double z_m, double wavelength_m,
                                          double sin_theta_i = 0.0);

/// |U(X, z)|², intensity relative to the incident plane wave.
double rayleighSommerfeldIntensity2D(const std::vector<std::pair<double, double>>& openings_m, double X_m,
                                     double z_m, double wavelength_m, double sin_theta_i = 0.0);

}  // namespace diffray::reference
