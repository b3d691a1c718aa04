#pragma once
// The thin plate's geometry and its edge-diffraction paths as quadrature nodes, shared by the plate's field
// at one frequency (btm_plate.cpp) and at many at once (btm_spectrum.cpp). Private to the reference module.
//
// Each diffracted term is a sum of quadrature nodes (btm_paths.h). Frames and formulas: btm_plate.h. Pure
// functions; thread-safe.
#include <vector>

#include "btm_paths.h"
#include "diffray/core/math.h"
#include "diffray/reference/btm_edge.h"
#include "diffray/reference/btm_plate.h"

namespace diffray::reference::btm_detail {

/// The plate's unit normal (Newell's method), centroid and scale (the largest centroid–vertex distance).
struct PlateFrame {
  core::Vec3 normal, centroid;
  double scale = 0.0;
};

/// Checks that `plate` is a convex planar polygon with no three vertices in line (throws core::InputError).
PlateFrame checkPlate(const BtmPlate& plate);

/// Whether the point p of the plate's plane lies inside the polygon (convex: left of every edge).
bool insidePolygon(const BtmPlate& plate, const PlateFrame& f, const core::Vec3& p);

/// The plate's edge frames (btm_plate.h): x in the plate's plane pointing into the plate, y the normal.
std::vector<EdgeFrame> edgeFrames(const BtmPlate& plate, const PlateFrame& f);

/// The geometric field at `receiver`: the direct wave and the specular image, each with weight 1 in its
/// zone, ½ where its line grazes an edge (within kBtmOnBoundaryRad: that edge's first-order term is dropped
/// there, btm_kernel.h, and the half wave keeps the total field continuous, as btmInfiniteWedgeField's) and
/// 0 outside (the plate blocks the direct wave; the reflection point is off the plate); `edges` are the
/// plate's edgeFrames. Throws when a point lies on the plate.
struct GeometricPaths {
  GeometricWave direct, specular;
};
GeometricPaths geometricPaths(const BtmPlate& plate, const PlateFrame& f, const std::vector<EdgeFrame>& edges,
                              const core::Vec3& source, const core::Vec3& receiver);

/// The plate standing on the ground z = ground_z_m joined with its mirror image (btmPlateOnGroundField).
/// Throws core::InputError when the plate does not stand on the ground so or a point is not above it.
BtmPlate groundUnion(const BtmPlate& plate, double ground_z_m, const core::Vec3& source, const core::Vec3& receiver);

/// Every edge's first-order term as nodes (btmEdgeNodes), panels sized for `wavelength_m`.
std::vector<BtmNode> firstOrderNodes(const std::vector<EdgeFrame>& edges, const core::Vec3& source,
                                     const core::Vec3& receiver, double wavelength_m);

/// The scale that sizes the second order's panels (the plate's plus the points' distances from it).
inline double pairScale(const PlateFrame& f, const core::Vec3& source, const core::Vec3& receiver) {
  return f.scale + (source - f.centroid).norm() + (receiver - f.centroid).norm();
}

/// The two faces of the plate an edge-to-edge path from edge `ei` runs along (btm_paths.h): ν = ½, the
/// plate's plane across edge i is its x, the +n face at azimuth 0 in both edges' frames, the −n face at 2π.
inline PairFaces plateFaces(const EdgeFrame& ei) {
  PairFaces faces;
  faces.nu = 0.5;
  faces.across_i = ei.x;
  faces.count = 2;
  faces.theta_i[1] = faces.theta_j[1] = 2.0 * kPi;
  return faces;
}

}  // namespace diffray::reference::btm_detail
