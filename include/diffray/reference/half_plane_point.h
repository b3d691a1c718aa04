#pragma once
// Exact field of a POINT source near a perfectly thin half-plane (Macdonald 1915; Bowman–Senior–Uslenghi,
// "Electromagnetic and Acoustic Scattering by Simple Shapes", ch. 8), the 3D companion of
// sommerfeldHalfPlane in fresnel.h.
//
// Frame (the one of sommerfeldHalfPlane): the edge is the z axis, the screen is the half-plane
// {y = 0, x >= 0}; points are given in cylindrical coordinates (ρ, φ, z) with x = ρcosφ, y = ρsinφ and
// φ in [0, 2π], so the two faces of the screen are φ = 0 (the face y = +0) and φ = 2π (the face y = −0).
// Time factor e^{+iωt}: the free field of the source, WITHOUT the screen, is e^{−ikR}/R with
// R the source–receiver distance. With the screen (Macdonald's form, equivalent to the Biot–Tolstoy
// edge-source integral with ν = ½)
//   u = B(R, ε₋) ± B(R', ε₊),
//   B(R, ε) = H(ε)·e^{−ikR}/R − (ε/π)·∫_{R1}^∞ e^{−ikL} dL / ((L² − R²)·√(L² − R1²)),
//   ε∓ = 2√(ρρ0)·cos((φ ∓ φ0)/2)  (so ε² = R1² − R², and ε > 0 on the lit side of that branch's boundary),
// where R' is the distance from the image source (φ0 → −φ0), R1 = √((ρ + ρ0)² + (z − z0)²) the shortest
// path via the edge, H the unit step (B = ½e^{−ikR}/R on the boundary ε = 0, where B is continuous); + for
// a rigid (Neumann, acoustically hard) screen, − for a soft (Dirichlet) one. The integral is evaluated on
// the path L = R1 − iv² by Gauss–Legendre panels graded toward its near-pole (~1e-12 relative).
// The popular closed form with the Fresnel integral of σ = ±√(k(R1 − R)), i.e. (e^{−ikR}/R)·
// (e^{iπ/4}/√π)·∫_{−∞}^{σ} e^{−iτ²}dτ per branch, is only the leading uniform asymptotic term of B (it misses
// the Helmholtz equation by O(1/(kR)): percent level at kR ~ 10); both tend to Sommerfeld's plane-wave
// solution times e^{−ikρ0}/ρ0 as ρ0 → ∞. Level re free field: 20·log10(|u|·R).
//
// Contract: an ORACLE, sharing no code with the ray tracer or the UTD model (it uses only the module's
// own Gauss–Legendre rule). Units: metres, radians, hertz, m/s. Invalid input (non-finite values,
// wavelength or frequencies <= 0, ρ < 0, φ outside [0, 2π], source and receiver at the same point) throws
// core::InputError. Thread-safety: pure functions; safe to call concurrently.
#include <complex>

namespace diffray::reference {

/// A point in the half-plane frame above: ρ >= 0 (m) from the edge, φ in [0, 2π] (rad) from the face
/// y = +0 through the open space, z (m) along the edge.
struct CylindricalPoint {
  double rho_m = 0.0;
  double phi_rad = 0.0;
  double z_m = 0.0;
};

/// The half-plane frame coordinates of the Cartesian point (x, y, z) (metres). Points on the screen itself
/// map to φ = 0 when y = +0 and to φ = 2π when y = −0 (the sign of zero picks the face); points on the
/// half-line y = 0, x < 0 get φ = π.
CylindricalPoint halfPlaneFrameFromCartesian(double x_m, double y_m, double z_m);

/// Total field u at `receiver` of a unit point source at `source` (free field e^{−ikR}/R), screen rigid or
/// soft, as in the header paragraph.
std::complex<double> halfPlanePointSource(double wavelength_m, const CylindricalPoint& source,
                                          const CylindricalPoint& receiver, bool rigid);

/// 20·log10(|u|·R): the level re the free field at the same source–receiver distance R, in dB.
double halfPlaneLevelDb(double wavelength_m, const CylindricalPoint& source, const CylindricalPoint& receiver,
                        bool rigid);

/// Energy average across a band, what an octave-band measurement gives: 10·log10 of the mean of |u·R|² over
/// `points` frequencies at the midpoints of `points` equal parts of [f_lo_hz, f_hi_hz] (f_j = f_lo +
/// (j + ½)(f_hi − f_lo)/points; points = 1 is the arithmetic centre). Requires 0 < f_lo_hz <= f_hi_hz,
/// points >= 1, sound_speed_m_s > 0.
double halfPlaneBandLevelDb(double f_lo_hz, double f_hi_hz, int points, double sound_speed_m_s,
                            const CylindricalPoint& source, const CylindricalPoint& receiver, bool rigid);

}  // namespace diffray::reference
