#pragma once
// Real spherical harmonics in the AmbiX convention (Nachbar, Zotter, Deleflie & Sontacchi, "AmbiX - a
// suggested Ambisonics format", Ambisonics Symposium 2011), the basis of diffray's Ambisonic signals.
//
// Contract. Channels in ACN order: order n, degree m ∈ [−n, n] at index n² + n + m. SN3D normalisation
// without the Condon–Shortley phase:
//   Y_n^m(φ, θ) = N_n^|m| · P_n^|m|(sin θ) · (cos(|m|φ) for m ≥ 0, sin(|m|φ) for m < 0),
//   N_n^|m| = √((2 − δ_m0)·(n − |m|)!/(n + |m|)!),
// φ the azimuth counter-clockwise from +x (front) toward +y (left), θ the elevation toward +z (up); for a
// unit vector d = (x, y, z) = (cos φ cos θ, sin φ cos θ, sin θ). First order: W = 1, Y = y, Z = z, X = x,
// so every channel's largest value over the sphere is 1 at order 1, and the mean of Y_n^m² over the sphere
// is 1/(2n + 1). Evaluated without trigonometry: cos θ^|m|·(cos, sin)(|m|φ) = (Re, Im)((x + iy)^|m|), and
// P_n^|m|(t)/(1 − t²)^{|m|/2} by the standard three-term recurrence in n (Abramowitz & Stegun 8.5.3).
// Units: none (d is a direction; it is normalised here). Thread-safety: pure functions.
#include <vector>

#include "diffray/core/math.h"

namespace diffray::spatial {

/// The highest order the functions take.
inline constexpr int kMaxAmbisonicOrder = 7;

/// (order + 1)²: the channels of an Ambisonic signal of that order.
constexpr int ambisonicChannels(int order) { return (order + 1) * (order + 1); }

/// Y_n^m(d) for every n ≤ order in ACN order into out[0 … ambisonicChannels(order) − 1]. Throws
/// core::InputError for an order outside [0, kMaxAmbisonicOrder] or a zero or non-finite direction.
void realSphericalHarmonicsSn3d(int order, const core::Vec3& direction, double* out);
std::vector<double> realSphericalHarmonicsSn3d(int order, const core::Vec3& direction);

}  // namespace diffray::spatial
