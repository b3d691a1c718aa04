#pragma once
// Fresnel integrals and the two classic Fresnel-region references: the slit under a
// plane wave (paraxial; Goodman, "Introduction to Fourier Optics", ch. 4) and Sommerfeld's exact
// half-plane solution (Born & Wolf, "Principles of Optics", §11.5). Fresnel integrals: Abramowitz & Stegun
// ch. 7.
//
// Contract: these are ORACLES for the tests and for `diffray validate`. They share no code with the ray
// tracer (only diffray/core/error.h for InputError) and implement their own special functions.
// Units: lengths in metres (_m), angles in radians (_rad). Conventions:
//  - F(w) = C(w) + i S(w) = ∫_0^w exp(iπt²/2) dt (the "πt²/2" normalisation, F(±∞) = ±(1 + i)/2).
//  - G(a) = ∫_a^∞ exp(−iτ²) dτ (Sommerfeld's normalisation, G(−∞) = √π e^{−iπ/4}).
//  - The half-plane solution uses the time factor e^{+iωt}: the incident field e^{ikρcos(φ−φ0)}
//    arrives from the direction φ0, the diffracted wave behaves as e^{−ikρ}.
// Invalid arguments (non-finite, non-positive lengths, angles outside [0, 2π]) throw core::InputError.
// Thread-safety: pure functions with no shared state; safe to call concurrently.
#include <complex>

namespace diffray::reference {

/// C(w) + i S(w) = ∫_0^w exp(iπt²/2) dt for any finite real w (odd in w), absolute error ~1e-15.
/// Power series for |w| <= 1.5, Lentz continued fraction of the complementary integral beyond.
std::complex<double> fresnelIntegral(double w);

/// The complementary integral ∫_w^∞ exp(iπt²/2) dt = (1 + i)/2 − F(w), computed without cancellation for
/// large positive w (it decays like i·exp(iπw²/2)/(πw)).
std::complex<double> fresnelIntegralTail(double w);

/// Sommerfeld's G(a) = ∫_a^∞ exp(−iτ²) dτ = √(π/2)·conj(fresnelIntegralTail(a·√(2/π))).
std::complex<double> sommerfeldG(double a);

/// Fresnel (paraxial) diffraction by a slit of width `width_m` centred on x = 0, plane wave at normal
/// incidence, observed at lateral position `x_m` on a screen `z_m` behind the slit:
///   w1,2 = √(2/(λz))·(∓a/2 − x),  I/I0 = ½[(C(w2) − C(w1))² + (S(w2) − S(w1))²].
/// I0 is the incident intensity, so I/I0 → 1 deep inside the lit region of a wide slit.
double fresnelSlitIntensity(double x_m, double width_m, double wavelength_m, double z_m);

/// Sommerfeld's exact solution for a plane wave e^{ikρcos(φ−φ0)} on a perfectly thin half-plane whose two
/// faces are φ = 0 and φ = 2π, edge at ρ = 0; for φ0 < π the shadow is φ > π + φ0:
///   u = (e^{iπ/4}/√π)[e^{ikρcos(φ−φ0)} G(−√(2kρ)cos((φ−φ0)/2)) ± e^{ikρcos(φ+φ0)} G(−√(2kρ)cos((φ+φ0)/2))],
/// + for a rigid (Neumann, acoustically hard) screen, − for a soft (Dirichlet) one. Total field, unit
/// incident amplitude. Requires wavelength_m > 0, rho_m >= 0 and φ, φ0 in [0, 2π].
std::complex<double> sommerfeldHalfPlane(double wavelength_m, double rho_m, double phi_rad, double phi0_rad,
                                         bool rigid);

}  // namespace diffray::reference
