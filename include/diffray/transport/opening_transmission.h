#pragma once
// The part τ of the energy arriving at a rectangular opening that its far-field pattern carries past it, per
// band and direction of incidence, for the openings that return the rest (RoomOccluders::returnsEnergy).
//
// An opening of lengths L_x, L_y (a door's width, and its height doubled by the floor's mirror) radiates
// what arrives along direction cosines (α, β) with the pattern p(α', β') = (L_x/λ)·sinc²((α' − α)L_x/λ) ·
// (L_y/λ)·sinc²((β' − β)L_y/λ) (wbsdf/far_field.h: the Wigner distribution's marginal over the opening),
// which integrates to 1 over the plane; only α'² + β'² < 1 propagates:
//   τ(α, β; λ) = ∫_{−1}^{1} p_x(α') [F((√(1 − α'²) − β)L_y/λ) − F((−√(1 − α'²) − β)L_y/λ)] dα',
// F(w) = ∫_0^w sinc² (wbsdf::farFieldMass). The outer integral runs along the shorter axis (the wider
// pattern), in φ with α' = sin φ (so that the integrand stays smooth at the rim), by composite Simpson with
// at least 8 nodes per unit of w = (α' − α)L/λ (sinc² has period 1) and 64 in all.
// A uniform axis (L = 0: no diffraction across it) keeps its cosine: τ = ∫_{|α'| < √(1 − β²)} p_x.
//
// The table holds τ averaged over each band (4 frequencies at the midpoints of quarters of the band, as the
// tracer draws a ray's frequency uniformly inside its band) on a 17 × 17 grid of (t, ψ): t = √γ (γ the
// cosine of incidence to the normal, so that nodes crowd toward grazing incidence, where τ falls fastest)
// and ψ ∈ [0, π/2] the azimuth from the x axis (τ is even in α and in β); read by bilinear interpolation
// (measured within 0.005 of the band average, tested within 0.01). Immutable once built; thread-safe.
#include <vector>

#include "diffray/core/bands.h"

namespace diffray::transport {

class OpeningTransmission {
 public:
  OpeningTransmission() = default;
  /// `length_x_m`, `length_y_m`: the opening's lengths (0: a uniform axis); not both 0. `c`: speed of sound (m/s).
  OpeningTransmission(double length_x_m, double length_y_m, const core::Bands& bands, double c);

  /// τ̄ of band b for incidence direction cosines (α, β) along the opening's axes.
  double at(int band, double alpha, double beta) const;

  /// τ at one wavelength (the quadrature above), for incidence (α, β) with α² + β² ≤ 1.
  static double exact(double length_x_m, double length_y_m, double lambda_m, double alpha, double beta);

  static constexpr int kNodes = 17;  ///< grid nodes per axis

 private:
  std::vector<double> table_;  ///< [band][i][j], t = i/(kNodes − 1), ψ = (π/2)·j/(kNodes − 1)
};

}  // namespace diffray::transport
