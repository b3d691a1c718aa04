#pragma once
// First-order edge diffraction by a rigid wedge, exact for finite edges: the Biot–Tolstoy–Medwin (BTM)
// edge-source integral (Biot & Tolstoy 1957; Medwin 1981; Svensson, Fred & Vanderkooy, J. Acoust. Soc. Am.
// 106(5), 1999, their eqs. for the finite-edge impulse response), in the frequency domain.
//
// Frame: the edge lies on the z axis, from z_start to z_end (±∞ for an infinite edge). One face of the
// wedge is the half-plane θ = 0, the other θ = θ_w (the EXTERIOR angle, measured through the air, in
// (π, 2π]; θ_w = 2π is a thin plate, the half-plane of half_plane_point.h in the same frame, 3π/2 a right-
// angled corner). Points are CylindricalPoint (ρ, θ, z) with θ in [0, θ_w] and ρ > 0.
// Time factor e^{+iωt}; the free field of a unit point source is e^{−ikR}/R. The edge's contribution is
//   u_d = −(ν/4π)·∫_{z_start}^{z_end} β(z)·e^{−ik(m + l)}/(m·l) dz,   ν = π/θ_w,
//   m = |S − (0,0,z)|, l = |R − (0,0,z)|,
//   β = Σ_{±,±} sin(ν(π ± θS ± θR)) / (cosh(νη) − cos(ν(π ± θS ± θR))),
//   η = acosh[(m·l + (z − zS)(z − zR)) / (ρS·ρR)],
// the Fourier transform of Svensson et al.'s h(t) = −(ν/4π)·∫ δ(t − (m + l)/c)·β/(m·l) dz (rigid faces).
// η vanishes at the apex point z_a = zS + (zR − zS)·ρS/(ρS + ρR), the point of least path m + l; near a
// shadow or reflection boundary one term of β peaks there with a width proportional to the angular distance
// to the boundary, and its integral tends to ∓½ of the geometric wave that the boundary switches.
// Quadrature (btm_kernel.h): the edge is split at the apex; Gauss–Legendre panels grow geometrically from a
// first panel sized to the integrand's narrowest feature there (boundaries resolved to about 1e-8 rad;
// closer than 1e-9 rad a receiver counts as on the boundary: the term 0, the geometric wave ½) to at most
// half a wavelength. An infinite end is integrated to 60 scales from the apex (scale = ρS + ρR + |zS − zR|)
// and the rest added as the first term of integration by parts, A(U)·e^{−ikΦ(U)}/(ikΦ'(U)); what that
// leaves out falls as U^{−3−2ν} (below 1e-10 of the diffracted field in the tests).
//
// Contract: an ORACLE, sharing no code with the ray tracers, the UTD model or the WBSDF (it uses only the
// module's own Gauss–Legendre rule). Units: metres, radians, rad/m. Invalid input (non-finite values, k <= 0,
// θ_w outside (π, 2π], ρ <= 0, θ outside [0, θ_w], z_start >= z_end) throws core::InputError.
// Thread-safety: pure functions; safe to call concurrently.
#include <complex>
#include <limits>
#include <vector>

#include "diffray/reference/half_plane_point.h"

namespace diffray::reference {

/// A rigid wedge's edge in the frame above.
struct BtmWedge {
  double exterior_angle_rad = 6.283185307179586;  ///< θ_w in (π, 2π]
  double z_start_m = -std::numeric_limits<double>::infinity();
  double z_end_m = std::numeric_limits<double>::infinity();
};

/// The first-order edge-diffracted field u_d at `receiver` of a unit point source at `source` (the formula
/// above), k the wavenumber (rad/m).
std::complex<double> btmEdgeDiffraction(double wavenumber_rad_m, const BtmWedge& wedge,
                                        const CylindricalPoint& source, const CylindricalPoint& receiver);

/// One node of a quadrature along edges: a term's value at every wavenumber k is Σ amplitude·e^{−ik·path}.
struct BtmNode {
  double path_m = 0.0;     ///< the path length through the node (m)
  double amplitude = 0.0;  ///< the node's weight times the integrand's amplitude, the factor −ν/4π included
};

/// btmEdgeDiffraction of a FINITE edge as nodes, appended to `nodes`: u_d(k) = Σ a·e^{−ik·L} for every k up
/// to 2π/min_wavelength_m (the panels are sized for the shortest wavelength, so the rule is at least as fine
/// at every longer one). The nodes depend on the geometry only.
void btmEdgeNodes(const BtmWedge& wedge, const CylindricalPoint& source, const CylindricalPoint& receiver,
                  double min_wavelength_m, std::vector<BtmNode>* nodes);

/// The total field around an INFINITE rigid wedge (the edge's extent in `wedge` is ignored): the direct wave
/// where |θR − θS| < π, the image in the face θ = 0 where θS + θR < π, the image in the face θ = θ_w where
/// θS + θR > 2θ_w − π (each e^{−ikR}/R, weighted ½ on its boundary), plus btmEdgeDiffraction. For
/// θ_w = 2π it is Macdonald's exact solution (halfPlanePointSource).
std::complex<double> btmInfiniteWedgeField(double wavenumber_rad_m, double exterior_angle_rad,
                                           const CylindricalPoint& source, const CylindricalPoint& receiver);

}  // namespace diffray::reference
