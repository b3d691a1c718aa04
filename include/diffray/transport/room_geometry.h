#pragma once
// The room as the acoustic tracer sees it: the Embree scene of the room's triangles plus, per triangle, its
// plane in double precision (unit normal n and offset d with n·p = d, metres, world frame) and its
// material, and the triangles grouped into planes (coplanar triangles share one image-source plane).
// Embree's float hit distance is refined in double against the triangle's plane, so reflected rays start
// exactly on the surface. Built once; thread-safe for concurrent queries.
#include <embree3/rtcore.h>

#include <memory>
#include <vector>

#include "diffray/geometry/mesh.h"
#include "diffray/room/room.h"

namespace diffray::transport {

struct TrianglePlane {
  core::Vec3 normal{0, 0, 1};  ///< unit, the triangle's winding normal
  double offset = 0.0;          ///< normal·p for p on the plane
  int material = 0;
  int plane = 0;  ///< index into RoomGeometry::planes()
};

/// A set of coplanar triangles: the mirror of one image source.
struct MirrorPlane {
  core::Vec3 normal{0, 0, 1};
  double offset = 0.0;
  std::vector<int> triangles;
};

class RoomGeometry {
 public:
  /// Builds the intersector (Embree, or brute force for tests) and the planes. Throws InputError if the
  /// room has no triangles.
  explicit RoomGeometry(const room::Room& room, bool brute_force = false);

  const geometry::Intersector& intersector() const { return *intersector_; }
  /// The Embree scene for direct rtcIntersect1 calls in hot loops, or nullptr (brute force).
  RTCScene embreeScene() const { return embree_; }
  const TrianglePlane& triangle(int i) const { return triangles_[i]; }
  const std::vector<MirrorPlane>& planes() const { return planes_; }
  /// Largest coordinate extent of the room (m): scale for offsets and tolerances.
  double extent() const { return extent_; }
  /// Distance along the ray to the plane of triangle `tri`, in double (the refined hit distance).
  double planeDistance(int tri, const core::Vec3& origin, const core::Vec3& dir) const {
    const TrianglePlane& tp = triangles_[tri];
    return (tp.offset - tp.normal.dot(origin)) / tp.normal.dot(dir);
  }

 private:
  std::unique_ptr<geometry::Intersector> intersector_;
  RTCScene embree_ = nullptr;
  std::vector<TrianglePlane> triangles_;
  std::vector<MirrorPlane> planes_;
  double extent_ = 1.0;
};

}  // namespace diffray::transport
