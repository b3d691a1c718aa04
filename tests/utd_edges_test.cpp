// Edge extraction (utd/edges.h) on scenes whose diffracting edges are known by construction: a box room
// (none: every edge is concave from inside), a thin plate (4 free edges, half-planes), a box obstacle in
// free field and inside a room (12 convex right-angled edges), and the shipped two-rooms scene (the six
// edges of the doorway: two jambs and the lintel on each side of the 0.2 m partition); and lines inside another
// surface: the foot of a panel standing on a ground (two 90° inside corners, no edge, while the part of the
// foot beyond the ground is a free edge again) and a box standing on a ground (its bottom edges are inside
// corners).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "diffray/room/scene_file.h"
#include "diffray/transport/room_geometry.h"
#include "diffray/utd/edges.h"
#include "utd_fixtures.h"

namespace {

using namespace utd_fixtures;

std::vector<utd::Edge> edgesOf(const dr::Room& room, const utd::EdgeOptions& options = {}) {
  const diffray::transport::RoomGeometry geometry(room);
  return utd::extractEdges(room, geometry, options);
}

// Checks the frame of every edge: unit vectors, faces ⊥ tangent, normals into the air, and the angle
// between the faces equal to nπ measured from face 0 to face n.
void expectConsistentFrames(const std::vector<utd::Edge>& edges) {
  for (const auto& e : edges) {
    EXPECT_NEAR(e.tangent.norm(), 1.0, 1e-12);
    EXPECT_NEAR(e.face0_dir.dot(e.tangent), 0.0, 1e-12);
    EXPECT_NEAR(e.facen_dir.dot(e.tangent), 0.0, 1e-12);
    EXPECT_NEAR((e.end - e.start).norm(), e.length_m, 1e-12);
    EXPECT_NEAR(e.phi(e.start + e.facen_dir), std::fmod(e.wedge_n * kPi, 2 * kPi), 1e-9);
    EXPECT_NEAR(e.phi(e.start + e.face0_dir + 1e-3 * e.normal0), 1e-3, 1e-6);
  }
}

}  // namespace

TEST(UtdEdges, BoxRoomHasNoDiffractingEdges) {
  dr::Room room;
  addBox(room, Vec3(0, 0, 0), Vec3(5, 4, 3), rigidMaterial(room));
  room.sources.push_back({"S", Vec3(1, 1, 1), 1.0, {}});
  EXPECT_TRUE(edgesOf(room).empty());
  room.sources.clear();  // without a source the inside of the closed surface is the air
  EXPECT_TRUE(edgesOf(room).empty());
}

TEST(UtdEdges, ThinPlateHasFourHalfPlaneEdges) {
  dr::Room room;
  addPlate(room, Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(0, 0, 1), rigidMaterial(room));
  const auto edges = edgesOf(room);
  ASSERT_EQ(edges.size(), 4u);
  double total = 0.0;
  for (const auto& e : edges) {
    EXPECT_NEAR(e.wedge_n, 2.0, 1e-12);
    EXPECT_EQ(e.triangle0, e.trianglen);
    EXPECT_NEAR(e.face0_dir.dot(e.facen_dir), 1.0, 1e-12);
    EXPECT_NEAR(e.normal0.dot(e.normaln), -1.0, 1e-12);
    total += e.length_m;
  }
  EXPECT_NEAR(total, 6.0, 1e-12);  // the diagonal of the two triangles is flat and not an edge
  expectConsistentFrames(edges);
}

TEST(UtdEdges, BoxObstacleHasTwelveConvexEdgesWhateverItsWinding) {
  // addBox winds the faces inwards, as for a room: for an obstacle that is the wrong way round, and
  // extraction must not care. In free field with a source outside, and inside a larger room.
  for (bool in_room : {false, true}) {
    dr::Room room;
    const int m = rigidMaterial(room);
    addBox(room, Vec3(1, 1, 0.5), Vec3(2, 1.5, 1.7), m);
    if (in_room) addBox(room, Vec3(-2, -2, 0), Vec3(5, 5, 3), m);
    room.sources.push_back({"S", Vec3(3, 3, 1), 1.0, {}});
    const auto edges = edgesOf(room);
    ASSERT_EQ(edges.size(), 12u) << in_room;
    double total = 0.0;
    for (const auto& e : edges) {
      EXPECT_NEAR(e.wedge_n, 1.5, 1e-12);
      // The air is outside the obstacle: the bisector points away from its centre.
      EXPECT_GT(e.bisector().dot(0.5 * (e.start + e.end) - Vec3(1.5, 1.25, 1.1)), 0.0);
      total += e.length_m;
    }
    EXPECT_NEAR(total, 4 * (1.0 + 0.5 + 1.2), 1e-9);
    expectConsistentFrames(edges);
  }
}

TEST(UtdEdges, CollinearPiecesMergeAndTJunctionsAreNotFreeEdges) {
  // A plate made of a 2 × 1 rectangle and two 1 × 1 squares beside it: the long side is cut at a T-junction
  // (the vertex at x = 1 exists on one side only) and the free edges are split into collinear pieces.
  dr::Room room;
  const int m = rigidMaterial(room);
  addPlate(room, Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(0, 1, 0), m);
  addPlate(room, Vec3(0, 1, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), m);
  addPlate(room, Vec3(1, 1, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), m);
  const auto edges = edgesOf(room);
  ASSERT_EQ(edges.size(), 4u);  // the outline of the 2 × 2 square
  for (const auto& e : edges) EXPECT_NEAR(e.length_m, 2.0, 1e-12);
}

TEST(UtdEdges, TwoRoomsDoorway) {
  const dr::Room room = dr::loadRoom(std::string(DIFFRAY_SOURCE_DIR) + "/rooms/two-rooms.json");
  const auto edges = edgesOf(room);
  std::printf("two-rooms: %zu diffracting edges\n", edges.size());
  ASSERT_EQ(edges.size(), 6u);
  int jambs = 0, lintels = 0;
  for (const auto& e : edges) {
    EXPECT_NEAR(e.wedge_n, 1.5, 1e-12);
    const Vec3 mid = 0.5 * (e.start + e.end);
    EXPECT_TRUE(std::abs(mid.x() - 6.0) < 1e-9 || std::abs(mid.x() - 6.2) < 1e-9) << mid.transpose();
    if (std::abs(e.tangent.z()) > 0.999) {  // a jamb: y = 1 or 1.9, z from 0 to 2.1
      ++jambs;
      EXPECT_TRUE(std::abs(mid.y() - 1.0) < 1e-9 || std::abs(mid.y() - 1.9) < 1e-9);
      EXPECT_NEAR(e.length_m, 2.1, 1e-9);
    } else {  // the lintel: z = 2.1, y from 1 to 1.9
      ++lintels;
      EXPECT_NEAR(std::abs(e.tangent.y()), 1.0, 1e-12);
      EXPECT_NEAR(mid.z(), 2.1, 1e-9);
      EXPECT_NEAR(e.length_m, 0.9, 1e-9);
    }
  }
  EXPECT_EQ(jambs, 4);
  EXPECT_EQ(lintels, 2);
  expectConsistentFrames(edges);
}

TEST(UtdEdges, ShippedRoomsCounts) {
  // shoebox: a box, nothing convex. l-hall: the 1 m stage front, the L's inside corner, and the four
  // edges of each of the four floor-to-ceiling columns: 1 + 1 + 16.
  const std::string dir = std::string(DIFFRAY_SOURCE_DIR) + "/rooms/";
  EXPECT_EQ(edgesOf(dr::loadRoom(dir + "shoebox.json")).size(), 0u);
  const auto hall = edgesOf(dr::loadRoom(dir + "l-hall.json"));
  std::printf("l-hall: %zu diffracting edges\n", hall.size());
  EXPECT_EQ(hall.size(), 18u);
  expectConsistentFrames(hall);
}

TEST(UtdEdges, FootOfAPanelStandingOnAGroundIsNotAnEdge) {
  // A 4 × 2 m panel standing on a 60 × 60 m ground whose two triangles do not share the panel's vertices
  // (their diagonal crosses the foot at its middle): the foot lies inside the ground, where the air sees two
  // 90° inside corners; the top and the two sides are the panel's free edges (half-planes). With the ground
  // ending at x = −1 the foot's piece from x = −2 to −1 stands in the air: a free edge again.
  for (double ground_from : {-30.0, -1.0}) {
    dr::Room room;
    const int m = rigidMaterial(room);
    addPlate(room, Vec3(ground_from, -30, 0), Vec3(30 - ground_from, 0, 0), Vec3(0, 60, 0), m);
    addPlate(room, Vec3(-2, 0, 0), Vec3(4, 0, 0), Vec3(0, 0, 2), m);
    room.sources.push_back({"S", Vec3(0, -2, 0.5), 1.0, {}});
    int panel_edges = 0, on_ground = 0;
    for (const auto& e : edgesOf(room)) {
      if (std::abs(e.start.y()) > 1e-9 || std::abs(e.end.y()) > 1e-9) continue;  // the ground's own outline
      ++panel_edges;
      EXPECT_NEAR(e.wedge_n, 2.0, 1e-12);
      if (std::abs(e.start.z()) < 1e-9 && std::abs(e.end.z()) < 1e-9) {
        ++on_ground;
        EXPECT_NEAR(std::min(e.start.x(), e.end.x()), -2.0, 1e-9);
        EXPECT_NEAR(std::max(e.start.x(), e.end.x()), -1.0, 1e-9);
      }
    }
    EXPECT_EQ(on_ground, ground_from < -2.0 ? 0 : 1) << ground_from;
    EXPECT_EQ(panel_edges, ground_from < -2.0 ? 3 : 4) << ground_from;
  }
}

TEST(UtdEdges, BoxStandingOnAGroundHasNoBottomEdges) {
  // A 1 × 0.5 × 1.2 m box on a 20 × 20 m ground plate: its four top edges and four vertical edges are
  // right-angled wedges; its bottom edges lie inside the ground (inside corners); the ground's outline is
  // four half-plane edges.
  dr::Room room;
  const int m = rigidMaterial(room);
  addPlate(room, Vec3(-10, -10, 0), Vec3(20, 0, 0), Vec3(0, 20, 0), m);
  addBox(room, Vec3(1, 1, 0), Vec3(2, 1.5, 1.2), m);
  room.sources.push_back({"S", Vec3(3, 3, 1), 1.0, {}});
  const auto edges = edgesOf(room);
  int wedges = 0, plates = 0;
  for (const auto& e : edges) {
    if (std::abs(e.wedge_n - 1.5) < 1e-12) {
      ++wedges;
      EXPECT_GT(std::max(e.start.z(), e.end.z()), 1.0);  // a top or a vertical edge
    } else {
      EXPECT_NEAR(e.wedge_n, 2.0, 1e-12);
      EXPECT_NEAR(std::max(std::abs(e.start.x()), std::abs(e.start.y())), 10.0, 1e-9);
      ++plates;
    }
  }
  EXPECT_EQ(wedges, 8);
  EXPECT_EQ(plates, 4);
  expectConsistentFrames(edges);
}
