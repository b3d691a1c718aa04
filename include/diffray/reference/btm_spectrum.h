#pragma once
// The thin plate's field (btm_plate.h) at many frequencies at once, for band levels and fine frequency
// grids: the quadrature nodes of every diffracted term depend on the geometry only, so they are built once,
// for the shortest wavelength (panels graded from the apex as in btm_kernel.h, at most two shortest
// wavelengths long), and each term Σ a·e^{−ik·L} is evaluated at every wavenumber from a uniform grid in
// path length L.
//
// Each node's amplitude is spread onto the grid L_n = L₀ + n·h with a Gaussian, φ(x) = e^{−x²/4} in units
// of h, over the 24 grid points nearest it, and the sum is read back as
//   Σ_q a_q·e^{−ik·L_q} = Σ_n g_n·e^{−ik·L_n} / φ̂(kh),   φ̂(ξ) = √(4π)·e^{−ξ²}
// (Poisson summation; the Gaussian gridding of a type-1 non-uniform Fourier transform, Greengard & Lee,
// SIAM Review 46, 2004). With h = λ_min/8 (kh ≤ π/4) the aliased images are below e^{−29.6} ≈ 1.4e-13 of
// each node's amplitude and the truncated tails below e^{−30} ≈ 7e-14, so the result differs from the node
// sum by ~1e-13 of Σ|a_q|. The geometric field (direct wave, specular image) is evaluated exactly.
//
// Contract: an ORACLE like btm_plate.h (no code shared with UTD or the WBSDF). The same input checks as
// btmPlateField / btmPlateOnGroundField, plus finite positive wavenumbers (at least one). Units: metres,
// rad/m. Thread-safety: a pure function; it runs its edge pairs on TBB's threads (all cores unless a
// core::ThreadLimit is alive), with a result independent of the thread count.
#include <vector>

#include "diffray/reference/btm_plate.h"

namespace diffray::reference {

/// The field at `receiver` of a unit point source at `source` at each of `wavenumbers_rad_m`, to `order`
/// (1 or 2) in edge diffraction: the plate in free field when `ground_z_m` is NaN, else standing on that
/// rigid ground (btmPlateOnGroundField). Element i belongs to wavenumbers_rad_m[i].
std::vector<BtmPlateField> btmPlateSpectrum(const std::vector<double>& wavenumbers_rad_m, const BtmPlate& plate,
                                            double ground_z_m, const core::Vec3& source, const core::Vec3& receiver,
                                            int order = 2);

}  // namespace diffray::reference
