#pragma once
// The field around a rigid axis-aligned box (a cupboard, a table block) to second order in edge
// diffraction, in free field or standing on a rigid ground, by the Biot–Tolstoy–Medwin edge-source
// integrals of Svensson, Fred & Vanderkooy (J. Acoust. Soc. Am. 106(5), 1999) in the frequency domain. Every
// edge of a box is a right-angled wedge: exterior angle θ_w = 3π/2 through the air, ν = π/θ_w = 2/3.
//
// The field is the sum of
// - the direct wave e^{−ikR}/R where the segment from source to receiver does not enter the box;
// - the specular image in each face where the source and the receiver lie strictly on its outer side and
//   the reflection point lies on the face (a convex box: such a path never crosses the box);
// - the first-order BTM term of each edge both points see (btm_edge.h, a finite edge). A point sees an edge
//   exactly when it lies on the outer side of at least one of the edge's two faces; otherwise the box hides
//   the edge from it and the term is 0. Frame of an edge: z along it, θ measured from one adjacent face
//   (θ = 0) through the air to the other (θ = 3π/2);
// - the second-order (edge-to-edge) term of every ordered pair of edges that share a face, the path between
//   them running along that face (Svensson et al. 1999, second order; the factor ½ of a path along a plane,
//   as btm_plate.h):
//     u₂ = ½·(ν²/16π²)·∫_{edge i}∫_{edge j} β_i·β_j·e^{−ik(m + n + l)}/(m·n·l) dz_i dz_j,
//   m = |S − P_i|, n = |P_i − P_j|, l = |P_j − R|, β_i edge i's directivity from S to P_j (P_j on the shared
//   face: θ = 0 or 3π/2 in edge i's frame), β_j edge j's from P_i to R; the term is 0 unless S sees edge i
//   and R sees edge j. Two edges that share no face are joined only through the box (the segment between
//   any of their points crosses its interior): no term. A convex box has no other second-order path: a
//   specular reflection sends its wave away from every edge not on the reflecting face, and a reflection at
//   a face's own edge is part of that edge's wedge term.
// Third and higher orders are left out. As for the plate (btm_plate.h), each first-order term takes its
// wedge for one without end: it jumps where the receiver crosses a face's plane beyond the box (from seeing
// the edge to not seeing it), and the second-order terms along that face jump by about the opposite amount.
// Between such planes the first-order sum is continuous across every shadow and reflection boundary away
// from the box's corners: the direct wave's and the images' zones switch exactly where an edge term's
// boundary lies. A point on an edge's line beyond the box (ρ = 0) gets that edge's limit there, 0.
//
// On a rigid ground (btmBoxOnGroundField) the box's bottom face lies on the ground plane; by the image
// principle the ground is replaced by the box's mirror image, which with the box forms one box twice as
// tall (the bottom face gone), and by the source's image: u = u_union(S, R) + u_union(S', R), S' = S
// mirrored in the ground (exact for a rigid plane), each to the order asked.
//
// Many frequencies at once (btmBoxSpectrum): as btmPlateSpectrum (btm_spectrum.h), the nodes of every
// diffracted term built once for the highest frequency and summed at every wavenumber from a Gaussian-
// gridded path-length axis (~1e-13 of Σ|a|); the geometric waves are exact. Its edge terms and edge pairs
// run on TBB's threads (all cores unless a core::ThreadLimit is alive), the result independent of the
// thread count.
//
// Contract: an ORACLE like btm_edge.h, sharing no code with the ray tracers, UTD or the WBSDF. Units:
// metres, rad/m; free field e^{−ikR}/R, time factor e^{+iωt}. Invalid input throws core::InputError (one
// line): non-finite values, wavenumbers not > 0, order not 1 or 2, a box of zero extent in any axis (below
// 1e-9 of its largest), a source or receiver inside or on the box, on a ground a box not standing on it or
// a point not above it. Thread-safety: pure functions; safe to call concurrently.
#include <vector>

#include "diffray/core/math.h"
#include "diffray/reference/btm_field.h"

namespace diffray::reference {

/// A rigid axis-aligned box: min_m < max_m in every axis (metres).
struct BtmBox {
  core::Vec3 min_m = core::Vec3::Zero(), max_m = core::Vec3::Ones();
};

/// The parts of the box's field (btm_field.h): `specular` sums the faces' images.
using BtmBoxField = BtmField;

/// The field at `receiver` of a unit point source at `source`, the box in free field, to `order` (1 or 2)
/// in edge diffraction, at wavenumber k (rad/m).
BtmBoxField btmBoxField(double wavenumber_rad_m, const BtmBox& box, const core::Vec3& source,
                        const core::Vec3& receiver, int order = 2);

/// The same box standing on the rigid ground z = ground_z_m (its bottom face on it; the image principle
/// above). Source and receiver above the ground.
BtmBoxField btmBoxOnGroundField(double wavenumber_rad_m, const BtmBox& box, double ground_z_m,
                                const core::Vec3& source, const core::Vec3& receiver, int order = 2);

/// The field at each of `wavenumbers_rad_m` (element i belongs to wavenumbers_rad_m[i]): the box in free
/// field when `ground_z_m` is NaN, else standing on that ground. Equal to btmBoxField /
/// btmBoxOnGroundField at each wavenumber to ~1e-12 of the free field.
std::vector<BtmBoxField> btmBoxSpectrum(const std::vector<double>& wavenumbers_rad_m, const BtmBox& box,
                                        double ground_z_m, const core::Vec3& source, const core::Vec3& receiver,
                                        int order = 2);

}  // namespace diffray::reference
