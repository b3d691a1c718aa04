// Geometric checks: open edges counted by hand on boxes with a face missing, point-in-room against
// the known inside of boxes and an L, distances against closed forms, and the warnings they give.
// Also the volume and area of Room::addBox / addPolygon against closed forms.
#include <gtest/gtest.h>

#include <cmath>

#include "diffray/room/checks.h"
#include "diffray/room/room.h"

namespace dr = diffray::room;
using diffray::core::Vec3;

namespace {

dr::Material material(const std::string& name, double transmission = 0.0) {
  dr::Material m;
  m.name = name;
  m.absorption = diffray::core::bandFill(std::max(0.1, transmission));
  m.transmission = diffray::core::bandFill(transmission);
  return m;
}

// The box [0,a]x[0,b]x[0,c] as six polygons (quads), any of them left out or given material 1.
dr::Room boxOfPolygons(double a, double b, double c, int skip = -1, int opening = -1) {
  dr::Room room;
  room.addMaterial(material("wall"));
  room.addMaterial(material("opening", 1.0));
  const std::vector<std::vector<Vec3>> faces = {
      {{0, 0, 0}, {0, b, 0}, {0, b, c}, {0, 0, c}}, {{a, 0, 0}, {a, 0, c}, {a, b, c}, {a, b, 0}},
      {{0, 0, 0}, {0, 0, c}, {a, 0, c}, {a, 0, 0}}, {{0, b, 0}, {a, b, 0}, {a, b, c}, {0, b, c}},
      {{0, 0, 0}, {a, 0, 0}, {a, b, 0}, {0, b, 0}}, {{0, 0, c}, {0, b, c}, {a, b, c}, {a, 0, c}}};
  for (int f = 0; f < 6; ++f)
    if (f != skip) room.addPolygon(faces[f], f == opening ? 1 : 0, "face" + std::to_string(f));
  return room;
}

dr::Room box(const Vec3& lo, const Vec3& hi) {
  dr::Room room;
  room.addMaterial(material("wall"));
  const int m[6] = {0, 0, 0, 0, 0, 0};
  room.addBox(lo, hi, m);
  return room;
}

}  // namespace

TEST(RoomGeometry, BoxVolumeAndAreaMatchClosedForms) {
  const dr::Room room = box({-1, 2, 0.5}, {3, 7, 3.5});  // 4 x 5 x 3
  EXPECT_EQ(room.mesh.triangles.size(), 12u);
  EXPECT_NEAR(room.volume(), 60.0, 1e-12);
  EXPECT_NEAR(room.surfaceArea(), 2 * (20 + 12 + 15), 1e-12);
  EXPECT_EQ(dr::openEdgeCount(room), 0);
  // Inward-facing walls: each triangle's normal points towards the centre.
  const Vec3 centre(1, 4.5, 2);
  for (const auto& t : room.mesh.triangles) {
    const Vec3 &p0 = room.mesh.vertices[t[0]], &p1 = room.mesh.vertices[t[1]], &p2 = room.mesh.vertices[t[2]];
    EXPECT_GT((p1 - p0).cross(p2 - p0).dot(centre - p0), 0.0);
  }
}

TEST(RoomGeometry, PolygonVolumeAndArea) {
  const dr::Room room = boxOfPolygons(2, 3, 4);
  EXPECT_NEAR(room.volume(), 24.0, 1e-12);
  EXPECT_NEAR(room.surfaceArea(), 2 * (6 + 8 + 12), 1e-12);
  // A regular pentagon of circumradius r has area (5/2) r² sin 72°.
  dr::Room pent;
  pent.addMaterial(material("m"));
  std::vector<Vec3> v;
  for (int i = 0; i < 5; ++i) v.emplace_back(2 * std::cos(2 * M_PI * i / 5), 0.3, 2 * std::sin(2 * M_PI * i / 5));
  pent.addPolygon(v, 0, "pentagon");
  EXPECT_EQ(pent.mesh.triangles.size(), 3u);
  EXPECT_NEAR(pent.surfaceArea(), 2.5 * 4 * std::sin(2 * M_PI / 5), 1e-12);
}

TEST(RoomChecks, OpenEdgesOfABoxWithAFaceMissing) {
  EXPECT_EQ(dr::openEdgeCount(boxOfPolygons(2, 3, 4)), 0);
  // Without the ceiling the four rim edges (one triangle edge each) are open.
  const dr::Room open = boxOfPolygons(2, 3, 4, 5);
  EXPECT_EQ(dr::openEdgeCount(open), 4);
  const auto w = dr::roomWarnings(open);
  ASSERT_FALSE(w.empty());
  EXPECT_NE(w[0].find("not closed: 4 edge(s)"), std::string::npos) << w[0];
  // An opening (transmission 1) that closes the box is part of the enclosure: no hole, same volume.
  const dr::Room window = boxOfPolygons(2, 3, 4, -1, 5);
  EXPECT_EQ(dr::openEdgeCount(window), 0);
  EXPECT_NEAR(window.volume(), 24.0, 1e-12);
}

TEST(RoomChecks, AnOpeningInsideTheRoomBoundsNothing) {
  dr::Room room = boxOfPolygons(2, 3, 4);
  room.addPolygon({{1, 0, 0}, {1, 3, 0}, {1, 3, 4}, {1, 0, 4}}, 1, "doorway");  // a full-height opening
  EXPECT_NEAR(room.volume(), 24.0, 1e-12);
  EXPECT_EQ(dr::openEdgeCount(room), 0);
  EXPECT_TRUE(dr::insideRoom(room, {0.5, 1, 1}));  // the opening does not flip the parity
  EXPECT_TRUE(dr::insideRoom(room, {1.5, 1, 1}));
}

TEST(RoomChecks, InsideAnLShapedRoom) {
  // Floor plan: [0,2]x[0,1] ∪ [0,1]x[1,2], height 1, as an extruded L (concave polygons).
  dr::Room room;
  room.addMaterial(material("wall"));
  const std::vector<Vec3> plan = {{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {1, 1, 0}, {1, 2, 0}, {0, 2, 0}};
  std::vector<Vec3> floor = plan, ceiling;
  for (auto it = plan.rbegin(); it != plan.rend(); ++it) ceiling.push_back(*it + Vec3(0, 0, 1));
  room.addPolygon(floor, 0, "floor");
  room.addPolygon(ceiling, 0, "ceiling");
  for (std::size_t i = 0; i < plan.size(); ++i) {
    const Vec3 &a = plan[i], &b = plan[(i + 1) % plan.size()];
    room.addPolygon({a, a + Vec3(0, 0, 1), b + Vec3(0, 0, 1), b}, 0, "wall");
  }
  EXPECT_NEAR(room.volume(), 3.0, 1e-12);
  EXPECT_EQ(dr::openEdgeCount(room), 0);
  EXPECT_TRUE(dr::insideRoom(room, {0.5, 0.5, 0.5}));
  EXPECT_TRUE(dr::insideRoom(room, {1.7, 0.3, 0.2}));
  EXPECT_TRUE(dr::insideRoom(room, {0.3, 1.7, 0.9}));
  EXPECT_FALSE(dr::insideRoom(room, {1.5, 1.5, 0.5}));  // the notch
  EXPECT_FALSE(dr::insideRoom(room, {0.5, 0.5, 1.5}));  // above
  EXPECT_FALSE(dr::insideRoom(room, {-3, 0.5, 0.5}));
}

TEST(RoomChecks, DistanceToSurface) {
  const dr::Room room = box({0, 0, 0}, {4, 3, 2});
  EXPECT_NEAR(dr::distanceToSurface(room, {1, 1, 0.005}), 0.005, 1e-15);
  EXPECT_NEAR(dr::distanceToSurface(room, {2, 1.5, 1}), 1.0, 1e-15);
  // Outside, past a corner: the distance to the corner.
  EXPECT_NEAR(dr::distanceToSurface(room, {5, 4, 3}), std::sqrt(3.0), 1e-12);
}

TEST(RoomChecks, WarningsForSourcesAndListeners) {
  dr::Room room = box({0, 0, 0}, {4, 3, 2});
  EXPECT_TRUE(dr::roomWarnings(room).empty());
  dr::Source s;
  s.name = "S1";
  s.position_m = {2, 1, 1};
  room.sources.push_back(s);
  s.name = "near";
  s.position_m = {2, 1, 0.004};
  room.sources.push_back(s);
  s.name = "out";
  s.position_m = {5, 1, 1};
  room.sources.push_back(s);
  dr::Listener l;
  l.name = "R1";
  l.position_m = {3, 2, 1};
  room.listeners.push_back(l);
  l.name = "cut";
  l.position_m = {3.95, 2, 1};
  room.listeners.push_back(l);
  const auto w = dr::roomWarnings(room);
  ASSERT_EQ(w.size(), 3u);
  EXPECT_NE(w[0].find("source near at (2, 1, 0.004) is 4 mm from a surface"), std::string::npos) << w[0];
  EXPECT_NE(w[1].find("source out at (5, 1, 1) is outside the room"), std::string::npos) << w[1];
  EXPECT_NE(w[2].find("listener cut"), std::string::npos) << w[2];
  EXPECT_NE(w[2].find("cut by a surface 0.05 m from its centre"), std::string::npos) << w[2];
  // A source inside a listener's sphere (radius 0.1 m by default) is named; at its centre, the direct
  // sound is left out.
  l.name = "on-source";
  l.position_m = {2, 1, 1};
  room.listeners.push_back(l);
  const auto w2 = dr::roomWarnings(room);
  ASSERT_EQ(w2.size(), 4u);
  EXPECT_NE(w2[3].find("listener on-source"), std::string::npos) << w2[3];
  EXPECT_NE(w2[3].find("source S1 lies inside its sphere, 0 m from the centre: the direct sound is left out"),
            std::string::npos)
      << w2[3];
}
