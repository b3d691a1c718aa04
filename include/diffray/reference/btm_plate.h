#pragma once
// The field around a thin rigid plate of finite size, to first order in edge diffraction: the geometric
// field (the direct wave where the plate does not block it, the plate's specular image where the reflection
// point lies on the plate) plus the BTM diffracted field of each of its edges (btm_edge.h, exterior angle
// 2π: each edge is a finite edge of a half-plane). Free field e^{−ikR}/R, time factor e^{+iωt}.
//
// Frame of an edge from vertex A to vertex B: z along B − A (0 at A, |B − A| at B), x in the plate's plane
// pointing into the plate, y = z × x; θ = atan2(y, x) in [0, 2π). The direct wave's and the image's zones
// switch exactly where one edge term's boundary lies, so the sum is continuous across every shadow and
// reflection boundary away from the plate's corners. What this leaves out: edge-to-edge (second-order)
// diffraction, which is what keeps the field continuous where a boundary passes a corner, and which
// matters where the edges' diffracted waves are strong at one another (small plates at low frequencies).
//
// Contract: an ORACLE like btm_edge.h (no code shared with UTD or the WBSDF). The plate is a convex planar
// polygon of at least 3 vertices, given in order; sources and receivers off its plane's polygon and off its
// edges. Units: metres, rad/m. Invalid input throws core::InputError. Thread-safety: pure functions.
#include <complex>
#include <vector>

#include "diffray/core/math.h"

namespace diffray::reference {

/// A thin rigid plate: a convex planar polygon, its vertices in order (either winding).
struct BtmPlate {
  std::vector<core::Vec3> vertices;
};

/// The parts of the field at `receiver` of a unit point source at `source`.
struct BtmPlateField {
  std::complex<double> direct{0.0, 0.0};    ///< e^{−ikR}/R where the segment misses the plate, else 0
  std::complex<double> specular{0.0, 0.0};  ///< the plate's image, where its reflection point is on the plate
  std::complex<double> diffracted{0.0, 0.0};  ///< Σ over the edges of the first-order BTM term
  std::complex<double> total() const { return direct + specular + diffracted; }
};

BtmPlateField btmPlateField(double wavenumber_rad_m, const BtmPlate& plate, const core::Vec3& source,
                            const core::Vec3& receiver);

}  // namespace diffray::reference
