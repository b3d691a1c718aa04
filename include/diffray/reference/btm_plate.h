#pragma once
// The field around a thin rigid plate of finite size, to second order in edge diffraction: the geometric
// field (the direct wave where the plate does not block it, the plate's specular image where the reflection
// point lies on the plate), the BTM diffracted field of each of its edges (btm_edge.h, exterior angle 2π:
// each edge is a finite edge of a half-plane), and the edge-to-edge diffracted field of every ordered pair of
// edges (Svensson, Fred & Vanderkooy 1999, second order):
//   u₂ = ½·Σ_faces (ν²/16π²)·∫_{edge i}∫_{edge j} β_i·β_j·e^{−ik(m + n + l)}/(m·n·l) dz_i dz_j,   ν = ½,
// m = |S − P_i|, n = |P_i − P_j|, l = |P_j − R|; β_i is edge i's directivity from S to P_j, β_j edge j's from
// P_i to R (btm_kernel.h). The path between the edges runs along the plate, on its +n face (P_j at θ = 0 in
// edge i's frame, P_i at θ = 0 in edge j's) or its −n face (θ = 2π in both); a point on a rigid face counts
// its own image, which the ½ of a path along a plane takes back out. Free field e^{−ikR}/R, time factor
// e^{+iωt}.
//
// Frame of an edge from vertex A to vertex B: z along B − A (0 at A, |B − A| at B), x in the plate's plane
// pointing into the plate, y = z × x; θ = atan2(y, x) in [0, 2π). The direct wave's and the image's zones
// switch exactly where one edge term's boundary lies, so the first-order sum is continuous across every
// shadow and reflection boundary away from the plate's corners. Each edge's first-order term treats the
// plate as a half-plane without end, so it jumps where the receiver crosses the plate's plane beyond the
// plate; the second-order terms jump there by the opposite amount. Third and higher orders are left out.
//
// Contract: an ORACLE like btm_edge.h (no code shared with UTD or the WBSDF). The plate is a convex planar
// polygon of at least 3 vertices, given in order; sources and receivers off its plane's polygon and off its
// edges. Units: metres, rad/m. Invalid input throws core::InputError. Thread-safety: pure functions.
#include <complex>
#include <vector>

#include "diffray/core/math.h"
#include "diffray/reference/btm_field.h"

namespace diffray::reference {

/// A thin rigid plate: a convex planar polygon, its vertices in order (either winding).
struct BtmPlate {
  std::vector<core::Vec3> vertices;
};

/// The parts of the field at `receiver` of a unit point source at `source` (btm_field.h): `specular` is the
/// plate's image, `second_order` the sum over ordered pairs of edges of u₂.
using BtmPlateField = BtmField;

/// The field to `order` (1 or 2) in edge diffraction.
BtmPlateField btmPlateField(double wavenumber_rad_m, const BtmPlate& plate, const core::Vec3& source,
                            const core::Vec3& receiver, int order = 2);

/// The same plate standing on a rigid ground, the plane z = ground_z_m: one of its edges lies on the ground
/// and the plate is perpendicular to it. By the image principle the ground is replaced by the plate's mirror
/// image, which with the plate forms one plate (the union, twice as tall), and the source's mirror image:
/// u = u_union(S, R) + u_union(S', R), S' = S mirrored in the ground (exact for a rigid plane). Source and
/// receiver above the ground. Throws core::InputError when the plate does not stand on the ground so.
BtmPlateField btmPlateOnGroundField(double wavenumber_rad_m, const BtmPlate& plate, double ground_z_m,
                                    const core::Vec3& source, const core::Vec3& receiver, int order = 2);

/// 10·log10 of the mean of |u·R|² (R the source–receiver distance: the level re the free field) over
/// `points` frequencies at the midpoints of equal parts of [f_lo, f_hi] (band_grid.h): the energy average
/// of a band. `ground_z_m` NaN: the plate in free field, else standing on that ground.
double btmPlateBandLevelDb(double f_lo_hz, double f_hi_hz, int points, double sound_speed_m_s, const BtmPlate& plate,
                           double ground_z_m, const core::Vec3& source, const core::Vec3& receiver, int order = 2);

}  // namespace diffray::reference
