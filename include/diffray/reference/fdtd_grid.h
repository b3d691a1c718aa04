#pragma once
// The voxel grid of the FDTD wave reference (fdtd.h): a rectilinear lattice of nodes (spacing h) over the
// scene's bounding box plus a margin, which node-to-neighbour links a wall blocks, and which nodes are air.
//
// Contract. Node (i, j, k) sits at origin + h·(i, j, k), index i + nx·(j + ny·k). The domain is the bounding
// box of the mesh, the sources and the listeners' spheres (an open scene, a ground plane, may hold them
// outside the mesh's box) plus a margin; the origin is that box's lower corner minus (margin + ½)·h, so the faces of a box whose sides are whole multiples of h lie half-way
// between nodes (the finite-volume reading of the SRL boundary, Bilbao 2013). A LINK joins a node to its
// neighbour along one axis; it is BLOCKED where the segment between the two nodes crosses a triangle that
// is not an opening (room::Room::isOpening: an open doorway is transparent). Crossings are found per triangle
// by stabbing it with the grid lines of each axis (edges inclusive, so a line through an edge shared by two
// triangles blocks, never leaks); a crossing at a node's own coordinate blocks the link on the node's + side.
// So a wall thinner than h still separates its two sides. The links that leave the domain (the outer layer
// of nodes) are blocked too, with material −1: the absorbing outer boundary (fdtd_scheme.h). AIR is the set
// of nodes reachable from the seed nodes (the sources) through unblocked links (flood fill).
// Each blocked link remembers the material of the triangle that blocks it (the first in triangle order).
// Units: metres. Plain data once built; safe to share read-only between threads.
#include <cstdint>
#include <vector>

#include "diffray/core/math.h"
#include "diffray/room/room.h"

namespace diffray::reference {

/// Directions of a node's six links, in this order: −x, +x, −y, +y, −z, +z (bit d of FdtdGrid::flags).
inline constexpr int kFdtdDirections = 6;

struct FdtdGrid {
  static constexpr std::uint8_t kAir = 0x40;        ///< flag bit: the node is air
  static constexpr std::uint8_t kBlockedMask = 0x3f;  ///< flag bits 0–5: link d is blocked
  static constexpr int kAbsorbing = -1;             ///< material of the links that leave the domain

  core::Vec3 origin{0, 0, 0};
  double h = 0.1;
  int nx = 0, ny = 0, nz = 0;
  std::vector<std::uint8_t> flags;  ///< per node: blocked links (bits 0–5) and kAir
  /// Blocked links inside the domain as (node·6 + direction, material), sorted by key, both sides of each.
  std::vector<std::pair<std::uint64_t, int>> link_material;
  long air_nodes = 0;
  bool air_reaches_edge = false;  ///< some air node lies on the domain's outer layer (a scene open to free field)

  /// An empty domain of nx × ny × nz nodes (each ≥ 3): every inner link open, the outward links of the
  /// outer layer blocked (absorbing), no air yet.
  FdtdGrid(const core::Vec3& origin, double h, int nx, int ny, int nz);
  FdtdGrid() = default;

  std::size_t nodes() const { return static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny) * static_cast<std::size_t>(nz); }
  std::size_t index(int i, int j, int k) const {
    return static_cast<std::size_t>(i) + static_cast<std::size_t>(nx) * (static_cast<std::size_t>(j) + static_cast<std::size_t>(ny) * static_cast<std::size_t>(k));
  }
  /// Index offset of the neighbour in direction d (0…5).
  std::ptrdiff_t offset(int d) const;
  core::Vec3 position(std::size_t node) const;
  /// The node nearest to `p`, or −1 if it is outside the domain.
  long nearestNode(const core::Vec3& p) const;
  bool isAir(std::size_t node) const { return (flags[node] & kAir) != 0; }
  /// The material of the blocked link (node, d): a triangle's material, or kAbsorbing for the domain's edge.
  int materialOf(std::size_t node, int d) const;

  /// Blocks the links crossed by the triangles of `room` that are not openings (the stabbing above).
  void blockWalls(const room::Room& room);
  /// Marks as air every node reachable from `seeds` through unblocked links; sets air_nodes and
  /// air_reaches_edge.
  void floodFill(const std::vector<std::size_t>& seeds);
};

/// Grid dimensions for `room` at spacing h with `margin` cells around the bounding box of its mesh, sources
/// and listener spheres (no allocation).
struct FdtdGridSize {
  core::Vec3 origin{0, 0, 0};
  int nx = 0, ny = 0, nz = 0;
  double nodes() const { return double(nx) * double(ny) * double(nz); }
};
FdtdGridSize fdtdGridSize(const room::Room& room, double h, int margin);

/// The room voxelised: fdtdGridSize's domain with the walls blocked (no flood fill yet).
FdtdGrid voxelise(const room::Room& room, double h, int margin);

}  // namespace diffray::reference
