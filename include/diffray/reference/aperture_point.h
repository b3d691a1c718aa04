#pragma once
// Non-paraxial 3D aperture reference (Goodman, "Introduction to Fourier Optics", ch. 3): the Rayleigh–Sommerfeld
// integral of the first kind for a POINT source in front of an opaque, infinitely thin plane screen with rectangular
// openings, with Kirchhoff boundary values (the free field of the source in the openings, zero on the screen):
//   U(P) = ∫_openings U_src(q)·(1/2π)(z_P/r)(1/r + ik)(e^{−ikr}/r) dA,   U_src(q) = e^{−ik·r_s}/r_s,
// r = |P − q|, r_s = |S − q|, time factor e^{+iωt}. Normalised like half_plane_point.h: the
// free field of the source is e^{−ikR}/R, and an opening much larger than the first Fresnel zone gives
// U ≈ e^{−ikR}/R up to the edge-wave ripple (exactly so for the whole plane).
//
// Frame: the screen is the plane z = 0; the openings are axis-aligned rectangles [x0, x1] × [y0, y1]
// (x0 < x1, y0 < y1, pairwise without overlap; shared edges are fine); the source is at z < 0, the receiver
// at z > 0. Optional rigid floor: the plane y = floor_y_m, perpendicular to the screen, with everything at
// y >= floor_y_m (openings entirely above it). It is handled exactly by images: the openings are unfolded
// into their mirror images below the floor and the source's image (mirrored in the floor) adds its own
// incident field, so U = Σ_{S, S'} ∫_{A ∪ A'} … over the unfolded openings. The "free field" that levels are
// relative to stays the direct source term e^{−ikR}/R alone (no floor reflection).
// Note: RS1 is not reciprocal. Swapping source and receiver (mirrored in z = 0) exchanges the obliquity
// factor of the receiver side for that of the source side: for a small opening U/U_swapped →
// [cosθ_P (1 + 1/(ikr))]/[cosθ_S (1 + 1/(ik·r_s))] (see the tests), 1 only for symmetric geometries.
//
// Quadrature: a tensor grid of composite 16-point Gauss–Legendre panels (reference/quadrature.h) per
// opening and source image. Along x (and likewise y) a panel's length is capped so that the phase
// k(r_s + r) changes by at most 4π across it (a bound on |∂(r_s + r)/∂x| over the panel: 8+ nodes per local
// wavelength of the integrand), and by the distance from the panel to the foot points of source
// and receiver on the screen, so panels grade geometrically where the kernel peaks (source or receiver
// close to the screen). Converged to ~1e-9 relative (tested against a brute-force uniform rule).
// The band average reuses one grid, built for the band's highest frequency, for all its frequencies and
// steps the phase factors e^{−ik_j L} by recurrence (re-seeded every 256 steps).
//
// Contract: an ORACLE sharing no code with the ray tracer (only core/error.h). Units: metres, hertz, m/s.
// Invalid input (non-finite values, wavelength <= 0, source not at z < 0 or receiver not at z > 0,
// no openings, an empty, reversed or overlapping rectangle, anything below the floor, grids above 5e7 nodes)
// throws core::InputError. Thread-safety: pure functions; safe to call concurrently.
#include <complex>
#include <optional>
#include <vector>

namespace diffray::reference {

/// A point in the screen frame above (metres).
struct CartesianPoint {
  double x_m = 0.0;
  double y_m = 0.0;
  double z_m = 0.0;
};

/// An opening [x0_m, x1_m] × [y0_m, y1_m] in the screen z = 0.
struct ApertureRect {
  double x0_m = 0.0;
  double x1_m = 0.0;
  double y0_m = 0.0;
  double y1_m = 0.0;
};

/// The screen z = 0 with its openings and an optional rigid floor y = floor_y_m.
struct ApertureScreen {
  std::vector<ApertureRect> openings;
  std::optional<double> floor_y_m;
};

/// U(P) at `receiver` for a unit point source at `source` (free field e^{−ikR}/R).
std::complex<double> aperturePointSource(double wavelength_m, const ApertureScreen& screen,
                                         const CartesianPoint& source, const CartesianPoint& receiver);

/// 20·log10(|U|·R), R = |receiver − source|: the level re the free field at the same distance, in dB.
double apertureLevelDb(double wavelength_m, const ApertureScreen& screen, const CartesianPoint& source,
                       const CartesianPoint& receiver);

/// 10·log10 of the mean of |U·R|² over the band grid of reference/band_grid.h (`points` midpoints of equal
/// parts of [f_lo_hz, f_hi_hz]), in dB re the free field at the same distance R.
double apertureBandLevelDb(double f_lo_hz, double f_hi_hz, int points, double sound_speed_m_s,
                           const ApertureScreen& screen, const CartesianPoint& source,
                           const CartesianPoint& receiver);

}  // namespace diffray::reference
