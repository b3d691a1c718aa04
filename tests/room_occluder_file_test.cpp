// The scene file's "occluders" list (room/occluder_file.h, rooms/README.md): every type parsed into the
// frame and rectangle the file describes, checked against values worked out by hand from the file (a door
// taken from the two-rooms doorway group against the rectangle tools/make_rooms.py writes), and one test
// per error path, checking that the single-line message names the file and the field.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <set>
#include <string>

#include "diffray/core/error.h"
#include "diffray/room/occluder_file.h"
#include "diffray/room/scene_file.h"

namespace dr = diffray::room;
namespace dc = diffray::core;
using Kind = dr::OccluderAxis::Kind;

namespace {

const std::string kRooms = std::string(DIFFRAY_SOURCE_DIR) + "/rooms/";
const std::string kData = std::string(DIFFRAY_SOURCE_DIR) + "/tests/data/rooms";

// A 10 × 8 × 3 m box split by nothing, with an opening material and a hard one; occluders are added per test.
nlohmann::json baseScene() {
  return nlohmann::json::parse(R"({
    "materials": {"m": {"absorption": 0.1, "scattering": 0.2},
                  "hole": {"absorption": 1, "scattering": 0, "transmission": 1}},
    "geometry": [{"box": {"min": [0, 0, 0], "max": [10, 8, 3], "materials": {"all": "m"}}}],
    "sources": [{"position": [1, 1, 1]}],
    "listeners": [{"position": [8, 6, 1.2]}]})");
}

dr::Room parse(const nlohmann::json& scene, std::vector<std::string>* warnings = nullptr) {
  return dr::parseRoom(scene.dump(), "rooms/x.json", kData, warnings);
}

std::string errorOf(const nlohmann::json& scene) {
  try {
    parse(scene);
  } catch (const dc::InputError& e) {
    return e.what();
  }
  return "(no error)";
}

// The scene with one occluder.
std::string errorOfOccluder(const nlohmann::json& occ, nlohmann::json scene = baseScene()) {
  scene["occluders"] = nlohmann::json::array({occ});
  return errorOf(scene);
}

void expectMessage(const std::string& msg, std::initializer_list<const char*> pieces) {
  EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
  for (const char* p : pieces) EXPECT_NE(msg.find(p), std::string::npos) << "missing \"" << p << "\" in: " << msg;
}

void expectVec(const dr::Vec3& got, const dr::Vec3& want, const std::string& what) {
  EXPECT_NEAR((got - want).norm(), 0.0, 1e-12) << what << ": got (" << got.transpose() << ")";
}

// ex, ey orthonormal and normal = ex × ey: the frame every occluder promises.
void expectRightHandedFrame(const dr::Occluder& o) {
  EXPECT_NEAR(o.ex.norm(), 1.0, 1e-12) << o.name;
  EXPECT_NEAR(o.ey.norm(), 1.0, 1e-12) << o.name;
  EXPECT_NEAR(o.ex.dot(o.ey), 0.0, 1e-12) << o.name;
  expectVec(o.ex.cross(o.ey), o.normal, o.name + " ex × ey");
}

// Triangles of `group`, their total area and the set of materials they use.
struct GroupInfo {
  int triangles = 0;
  double area_m2 = 0.0;
  std::set<int> materials;
};
GroupInfo groupInfo(const dr::Room& room, const std::string& group) {
  GroupInfo g;
  for (std::size_t t = 0; t < room.group_of_triangle.size(); ++t) {
    if (room.group_of_triangle[t] != group) continue;
    const auto& v = room.mesh.triangles[t];
    const auto &a = room.mesh.vertices[v[0]], &b = room.mesh.vertices[v[1]], &c = room.mesh.vertices[v[2]];
    ++g.triangles;
    g.area_m2 += 0.5 * (b - a).cross(c - a).norm();
    g.materials.insert(room.mesh.object_of_triangle[t]);
  }
  return g;
}

int materialIndex(const dr::Room& room, const std::string& name) {
  for (std::size_t m = 0; m < room.materials.size(); ++m)
    if (room.materials[m].name == name) return static_cast<int>(m);
  return -1;
}

}  // namespace

TEST(RoomOccluderFile, DoorFromTheTwoRoomsDoorwayGroup) {
  std::vector<std::string> warnings;
  const dr::Room room = dr::loadRoom(kRooms + "two-rooms.json", &warnings);
  EXPECT_TRUE(warnings.empty()) << warnings[0];
  ASSERT_EQ(room.occluders.size(), 1u);
  const dr::Occluder& d = room.occluders[0];
  EXPECT_EQ(d.name, "doorway");
  EXPECT_EQ(d.type, "door");
  EXPECT_EQ(d.group, "doorway");  // the mesh's own opening: no rectangle added
  EXPECT_EQ(groupInfo(room, "occluder:doorway").triangles, 0);
  // rooms/README.md: the doorway is x = 6.1, y in [1, 1.9], z in [0, 2.1]; "up" defaults to +z.
  expectRightHandedFrame(d);
  expectVec(d.ey, dr::Vec3(0, 0, 1), "ey");
  EXPECT_NEAR(std::abs(d.normal.x()), 1.0, 1e-12);
  expectVec(d.origin_m, dr::Vec3(6.1, 1.45, 1.05), "centre");
  EXPECT_NEAR(d.half_x_m, 0.45, 1e-12);  // width 0.9 m
  EXPECT_NEAR(d.half_y_m, 1.05, 1e-12);  // height 2.1 m
  EXPECT_EQ(d.x.kind, Kind::Opening);
  EXPECT_NEAR(d.x.lo_m, -0.45, 1e-12);
  EXPECT_NEAR(d.x.hi_m, 0.45, 1e-12);
  EXPECT_FALSE(d.x.mirror_lo);
  EXPECT_EQ(d.y.kind, Kind::Opening);
  EXPECT_NEAR(d.y.lo_m, -1.05, 1e-12);
  EXPECT_NEAR(d.y.hi_m, 1.05, 1e-12);
  EXPECT_TRUE(d.y.mirror_lo);  // "sill": "floor": the bottom edge stands on the floor
  EXPECT_FALSE(d.reflect);
}

TEST(RoomOccluderFile, DoorDefaultsToAFloorSillAndTakesAnyUp) {
  // A door opening in a wall group "hole" at y = 8 (the box's y+ wall plane), 1 × 2 m, x in [2, 3].
  auto scene = baseScene();
  scene["geometry"].push_back(
      {{"polygon", {{"name", "hole"}, {"vertices", {{2, 8, 0}, {3, 8, 0}, {3, 8, 2}, {2, 8, 2}}}, {"material", "hole"}}}});
  scene["occluders"] = {{{"type", "door"}, {"group", "hole"}}};
  dr::Room room = parse(scene);
  ASSERT_EQ(room.occluders.size(), 1u);
  const dr::Occluder& d = room.occluders[0];
  EXPECT_EQ(d.name, "door1");  // unnamed: type and position in the list
  EXPECT_TRUE(d.y.mirror_lo);
  expectRightHandedFrame(d);
  expectVec(d.origin_m, dr::Vec3(2.5, 8, 1), "centre");
  EXPECT_NEAR(d.half_x_m, 0.5, 1e-12);
  EXPECT_NEAR(d.half_y_m, 1.0, 1e-12);
  // "up" along +x makes the 1 m side the height: ey = +x, and x runs along z.
  scene["occluders"] = {{{"type", "door"}, {"group", "hole"}, {"up", {3, 0, 0}}, {"sill", "none"}}};
  room = parse(scene);
  const dr::Occluder& r = room.occluders[0];
  expectRightHandedFrame(r);
  expectVec(r.ey, dr::Vec3(1, 0, 0), "ey");
  EXPECT_NEAR(std::abs(r.ex.z()), 1.0, 1e-12);
  EXPECT_NEAR(r.half_x_m, 1.0, 1e-12);
  EXPECT_NEAR(r.half_y_m, 0.5, 1e-12);
  EXPECT_FALSE(r.y.mirror_lo);
}

TEST(RoomOccluderFile, ExplicitDoorAddsItsOpeningRectangle) {
  // "up" is optional (default +z): a door given by its rectangle alone.
  const std::string err = errorOfOccluder(
      {{"type", "door"}, {"name", "d"}, {"centre", {5, 4, 1}}, {"normal", {0, 2, 0}}, {"width_m", 0.8}, {"height_m", 2}});
  ASSERT_EQ(err, "(no error)");
  auto scene = baseScene();
  scene["occluders"] = {{{"type", "door"}, {"name", "d"}, {"centre", {5, 4, 1}}, {"normal", {0, 2, 0}},
                         {"width_m", 0.8}, {"height_m", 2}}};
  const dr::Room room = parse(scene);
  ASSERT_EQ(room.occluders.size(), 1u);
  const dr::Occluder& d = room.occluders[0];
  expectRightHandedFrame(d);
  expectVec(d.normal, dr::Vec3(0, 1, 0), "normal");
  expectVec(d.ey, dr::Vec3(0, 0, 1), "ey");
  expectVec(d.ex, dr::Vec3(0, 0, 1).cross(dr::Vec3(0, 1, 0)), "ex = ey × normal");
  expectVec(d.origin_m, dr::Vec3(5, 4, 1), "centre");
  EXPECT_DOUBLE_EQ(d.half_x_m, 0.4);
  EXPECT_DOUBLE_EQ(d.half_y_m, 1.0);
  EXPECT_TRUE(d.y.mirror_lo);
  // Its rectangle joins the mesh as group "occluder:d", 0.8 × 2 m, in an added fully open material.
  EXPECT_EQ(d.group, "occluder:d");
  const GroupInfo g = groupInfo(room, "occluder:d");
  EXPECT_EQ(g.triangles, 2);
  EXPECT_NEAR(g.area_m2, 1.6, 1e-12);
  ASSERT_EQ(g.materials.size(), 1u);
  const int open = *g.materials.begin();
  EXPECT_EQ(room.materials[open].name, "occluder-opening");
  EXPECT_TRUE(room.isOpening(open));
}

TEST(RoomOccluderFile, DoorLeafIsAPanelTurnedAboutItsHinge) {
  // Door at (5, 4, 1), normal +y, up +z: ey = +z, ex = ey × normal = −x, so the "left" jamb (−ex) is at
  // x = 5.4. Turned 90° toward the front (+y), the leaf stands in the plane x = 5.4, y from 4 to 4.8.
  auto scene = baseScene();
  scene["occluders"] = {{{"type", "door"}, {"name", "d"}, {"centre", {5, 4, 1}}, {"normal", {0, 1, 0}},
                         {"width_m", 0.8}, {"height_m", 2},
                         {"leaf", {{"angle_deg", 90}, {"hinge", "left"}, {"opens", "front"}, {"material", "m"}}}}};
  const dr::Room room = parse(scene);
  const GroupInfo g = groupInfo(room, "leaf:d");
  EXPECT_EQ(g.triangles, 2);
  EXPECT_NEAR(g.area_m2, 1.6, 1e-12);
  ASSERT_EQ(g.materials.size(), 1u);
  EXPECT_EQ(*g.materials.begin(), materialIndex(room, "m"));
  dr::Vec3 lo(1e9, 1e9, 1e9), hi(-1e9, -1e9, -1e9);
  for (std::size_t t = 0; t < room.group_of_triangle.size(); ++t) {
    if (room.group_of_triangle[t] != "leaf:d") continue;
    for (int k = 0; k < 3; ++k) {
      lo = lo.cwiseMin(room.mesh.vertices[room.mesh.triangles[t][k]]);
      hi = hi.cwiseMax(room.mesh.vertices[room.mesh.triangles[t][k]]);
    }
  }
  expectVec(lo, dr::Vec3(5.4, 4.0, 0.0), "leaf's lower corner");
  expectVec(hi, dr::Vec3(5.4, 4.8, 2.0), "leaf's upper corner");
  // Errors: a leaf on a slit, an angle out of (1°, 180°), an unknown hinge.
  expectMessage(errorOfOccluder({{"type", "slit"}, {"centre", {5, 4, 1}}, {"normal", {0, 1, 0}}, {"width_m", 0.8},
                                 {"height_m", 2}, {"leaf", {{"angle_deg", 90}, {"material", "m"}}}}),
                {"rooms/x.json", "occluders[0].leaf", "only a door"});
  expectMessage(errorOfOccluder({{"type", "door"}, {"centre", {5, 4, 1}}, {"normal", {0, 1, 0}}, {"width_m", 0.8},
                                 {"height_m", 2}, {"leaf", {{"angle_deg", 0}, {"material", "m"}}}}),
                {"occluders[0].leaf.angle_deg"});
  expectMessage(errorOfOccluder({{"type", "door"}, {"centre", {5, 4, 1}}, {"normal", {0, 1, 0}}, {"width_m", 0.8},
                                 {"height_m", 2}, {"leaf", {{"angle_deg", 90}, {"hinge", "top"}, {"material", "m"}}}}),
                {"occluders[0].leaf.hinge", "left"});
}

TEST(RoomOccluderFile, SlitsDefaultToNoSillAndFormArrays) {
  auto scene = baseScene();
  scene["occluders"] = {
      {{"type", "slit"}, {"centre", {5, 4, 1.5}}, {"normal", {1, 0, 0}}, {"width_m", 0.1}, {"height_m", 1}},
      {{"type", "slit"}, {"name", "array"}, {"centre", {7, 4, 1.5}}, {"normal", {1, 0, 0}}, {"width_m", 1},
       {"height_m", 1}, {"slits", 3}, {"slit_width_m", 0.1}, {"spacing_m", 0.3}},
      {{"type", "slit"}, {"name", "one"}, {"centre", {3, 4, 1.5}}, {"normal", {1, 0, 0}}, {"width_m", 0.5},
       {"height_m", 1}, {"slits", 1}, {"slit_width_m", 0.5}, {"sill", "floor"}}};
  const dr::Room room = parse(scene);
  ASSERT_EQ(room.occluders.size(), 3u);
  const dr::Occluder& s = room.occluders[0];
  EXPECT_EQ(s.name, "slit1");
  EXPECT_EQ(s.type, "slit");
  expectRightHandedFrame(s);
  EXPECT_EQ(s.x.kind, Kind::Opening);
  EXPECT_DOUBLE_EQ(s.x.hi_m, 0.05);
  EXPECT_FALSE(s.y.mirror_lo);  // slits: "sill" defaults to none
  const dr::Occluder& a = room.occluders[1];
  EXPECT_EQ(a.x.kind, Kind::Slits);
  EXPECT_EQ(a.x.count, 3);
  EXPECT_DOUBLE_EQ(a.x.hi_m - a.x.lo_m, 0.1);
  EXPECT_DOUBLE_EQ(a.x.lo_m, -0.05);
  EXPECT_DOUBLE_EQ(a.x.spacing_m, 0.3);
  EXPECT_EQ(a.y.kind, Kind::Opening);
  EXPECT_DOUBLE_EQ(a.half_x_m, 0.5);
  const dr::Occluder& one = room.occluders[2];
  EXPECT_EQ(one.x.kind, Kind::Slits);
  EXPECT_EQ(one.x.count, 1);
  EXPECT_TRUE(one.y.mirror_lo);
  EXPECT_EQ(groupInfo(room, "occluder:array").triangles, 2);
}

TEST(RoomOccluderFile, EdgeZoneLiesPastTheEdgeOnTheOpenSide) {
  auto scene = baseScene();
  scene["occluders"] = {{{"type", "edge"}, {"name", "e"}, {"start", {2, 4, 0}}, {"end", {2, 4, 3}},
                         {"open_toward", {1, 0, 0.5}}},
                        {{"type", "edge"}, {"start", {2, 4, 0}}, {"end", {2, 4, 3}}, {"open_toward", {-1, 0, 0}},
                         {"extent_m", 2}}};
  const dr::Room room = parse(scene);
  ASSERT_EQ(room.occluders.size(), 2u);
  const dr::Occluder& e = room.occluders[0];
  EXPECT_EQ(e.type, "edge");
  expectRightHandedFrame(e);
  expectVec(e.ey, dr::Vec3(0, 0, 1), "ey along the edge");
  expectVec(e.ex, dr::Vec3(1, 0, 0), "ex: open_toward without its part along the edge");
  // extent_m defaults to 10 m: the zone [edge, edge + 10 m] along ex, the edge's length along ey.
  EXPECT_DOUBLE_EQ(e.half_x_m, 0.5 * dr::kDefaultEdgeZoneM);
  EXPECT_DOUBLE_EQ(e.half_y_m, 1.5);
  expectVec(e.origin_m, dr::Vec3(2 + 0.5 * dr::kDefaultEdgeZoneM, 4, 1.5), "zone centre");
  EXPECT_EQ(e.x.kind, Kind::Edge);
  EXPECT_DOUBLE_EQ(e.x.lo_m, -0.5 * dr::kDefaultEdgeZoneM);  // the edge itself, in local x
  EXPECT_EQ(e.y.kind, Kind::Uniform);
  const GroupInfo g = groupInfo(room, "occluder:e");
  EXPECT_NEAR(g.area_m2, 3.0 * dr::kDefaultEdgeZoneM, 1e-9);
  const dr::Occluder& e2 = room.occluders[1];
  EXPECT_EQ(e2.name, "edge2");
  EXPECT_DOUBLE_EQ(e2.half_x_m, 1.0);
  expectVec(e2.origin_m, dr::Vec3(1, 4, 1.5), "zone centre, extent 2");
}

TEST(RoomOccluderFile, ABarrierAloneNeedsNoGeometry) {
  // Free field: the barrier brings its panel, so "geometry" may be left out; without occluders it may not.
  auto scene = baseScene();
  scene.erase("geometry");
  scene["occluders"] = {{{"type", "barrier"}, {"name", "b"}, {"base", {{2, 5, 0}, {6, 5, 0}}}, {"height_m", 2},
                         {"material", "m"}, {"extent_m", 1}}};
  const dr::Room room = parse(scene);
  EXPECT_NEAR(groupInfo(room, "barrier:b").area_m2, 8.0, 1e-12);
  ASSERT_EQ(room.occluders.size(), 1u);
  scene.erase("occluders");
  EXPECT_THROW(parse(scene), diffray::core::InputError);
}

TEST(RoomOccluderFile, BarrierAddsItsPanelAndAnEdgeZoneAboveIt) {
  auto scene = baseScene();
  scene["occluders"] = {{{"type", "barrier"}, {"name", "b"}, {"base", {{2, 5, 0}, {6, 5, 0}}}, {"height_m", 2},
                         {"material", "m"}, {"extent_m", 1}}};
  const dr::Room room = parse(scene);
  ASSERT_EQ(room.occluders.size(), 1u);
  const dr::Occluder& b = room.occluders[0];
  EXPECT_EQ(b.type, "barrier");
  // The panel: 4 × 2 m in the plane y = 5, in the barrier's material.
  const GroupInfo panel = groupInfo(room, "barrier:b");
  EXPECT_NEAR(panel.area_m2, 8.0, 1e-12);
  ASSERT_EQ(panel.materials.size(), 1u);
  EXPECT_EQ(*panel.materials.begin(), materialIndex(room, "m"));
  // The zone: the 1 m above the top edge (z in [2, 3]), open toward "up", fully transmitting.
  expectRightHandedFrame(b);
  expectVec(b.ey, dr::Vec3(1, 0, 0), "ey along the top edge");
  expectVec(b.ex, dr::Vec3(0, 0, 1), "ex toward up");
  expectVec(b.origin_m, dr::Vec3(4, 5, 2.5), "zone centre");
  EXPECT_DOUBLE_EQ(b.half_x_m, 0.5);
  EXPECT_DOUBLE_EQ(b.half_y_m, 2.0);
  EXPECT_EQ(b.x.kind, Kind::Edge);
  EXPECT_DOUBLE_EQ(b.x.lo_m, -0.5);
  EXPECT_EQ(b.group, "occluder:b");
  const GroupInfo zone = groupInfo(room, "occluder:b");
  EXPECT_NEAR(zone.area_m2, 4.0, 1e-12);
  ASSERT_EQ(zone.materials.size(), 1u);
  EXPECT_TRUE(room.isOpening(*zone.materials.begin()));
}

TEST(RoomOccluderFile, BarrierWithSideEdgesAddsAZoneBesideEach) {
  // The 4 × 2 m panel from (2, 5, 0) to (6, 5, 0): side0 at x = 2 opens toward −x, side1 at x = 6 toward +x,
  // each a 1 × 2 m zone in the plane y = 5 beside its edge (x in [1, 2] and [6, 7], z in [0, 2]).
  auto scene = baseScene();
  scene["occluders"] = {{{"type", "barrier"}, {"name", "b"}, {"base", {{2, 5, 0}, {6, 5, 0}}}, {"height_m", 2},
                         {"material", "m"}, {"extent_m", 1}, {"side_edges", true}}};
  const dr::Room room = parse(scene);
  ASSERT_EQ(room.occluders.size(), 3u);
  EXPECT_EQ(room.occluders[0].type, "barrier");
  const double centre_x[2] = {1.5, 6.5}, open_x[2] = {-1.0, 1.0};
  for (int i = 1; i <= 2; ++i) {
    const dr::Occluder& s = room.occluders[static_cast<std::size_t>(i)];
    EXPECT_EQ(s.name, "b/side" + std::to_string(i - 1));
    EXPECT_EQ(s.type, "barrier side");
    EXPECT_EQ(s.x.kind, Kind::Edge);
    EXPECT_EQ(s.x.faces, room.occluders[0].x.faces);
    expectRightHandedFrame(s);
    expectVec(s.ex, dr::Vec3(open_x[i - 1], 0, 0), "ex away from the panel");
    expectVec(s.ey, dr::Vec3(0, 0, 1), "ey up the side edge");
    expectVec(s.origin_m, dr::Vec3(centre_x[i - 1], 5, 1), "zone centre");
    EXPECT_DOUBLE_EQ(s.half_x_m, 0.5);
    EXPECT_DOUBLE_EQ(s.half_y_m, 1.0);
    EXPECT_NEAR(groupInfo(room, s.group).area_m2, 2.0, 1e-12);
  }
  const auto own = dr::ownOccluders(room);
  ASSERT_EQ(own.size(), 1u);
  EXPECT_EQ(own[0], &room.occluders[0]);
  scene["occluders"][0]["side_edges"] = 1;
  EXPECT_THROW(parse(scene), diffray::core::InputError);
  // "foot_edge": refused while the foot stands on the room's floor (z = 0); in free field, a 4 × 1 m zone
  // below the foot (z in [−1, 0]), open toward −z, along the base.
  scene["occluders"][0]["side_edges"] = false;
  scene["occluders"][0]["foot_edge"] = true;
  expectMessage(errorOf(scene), {"occluders[0].foot_edge: the barrier's foot stands on surface"});
  scene.erase("geometry");
  const dr::Room footed = parse(scene);
  ASSERT_EQ(footed.occluders.size(), 2u);
  const dr::Occluder& f = footed.occluders[1];
  EXPECT_EQ(f.name, "b/foot");
  EXPECT_EQ(f.type, "barrier side");
  expectRightHandedFrame(f);
  expectVec(f.ex, dr::Vec3(0, 0, -1), "ex away from the panel");
  expectVec(f.ey, dr::Vec3(1, 0, 0), "ey along the foot");
  expectVec(f.origin_m, dr::Vec3(4, 5, -0.5), "zone centre");
  EXPECT_DOUBLE_EQ(f.half_x_m, 0.5);
  EXPECT_DOUBLE_EQ(f.half_y_m, 2.0);
  EXPECT_EQ(dr::ownOccluders(footed).size(), 1u);
}

TEST(RoomOccluderFile, GratingReflectsInItsMaterial) {
  auto scene = baseScene();
  scene["occluders"] = {{{"type", "grating"}, {"name", "g"}, {"centre", {9.5, 4, 1.5}}, {"normal", {-1, 0, 0}},
                         {"width_m", 2}, {"height_m", 1.5}, {"period_m", 0.3}, {"modulation_m", 2.4},
                         {"material", "m"}}};
  const dr::Room room = parse(scene);
  ASSERT_EQ(room.occluders.size(), 1u);
  const dr::Occluder& g = room.occluders[0];
  EXPECT_TRUE(g.reflect);
  EXPECT_EQ(g.material, materialIndex(room, "m"));
  expectRightHandedFrame(g);
  expectVec(g.normal, dr::Vec3(-1, 0, 0), "normal");
  EXPECT_EQ(g.x.kind, Kind::Grating);
  EXPECT_DOUBLE_EQ(g.x.period_m, 0.3);
  EXPECT_DOUBLE_EQ(g.x.modulation_m, 2.4);
  EXPECT_EQ(g.y.kind, Kind::Uniform);
  const GroupInfo panel = groupInfo(room, "occluder:g");
  EXPECT_NEAR(panel.area_m2, 3.0, 1e-12);
  EXPECT_EQ(panel.materials, std::set<int>{materialIndex(room, "m")});
}

// ---- Bad input: one line naming the file, the field and what is wrong. ----

TEST(RoomOccluderFileErrors, UnknownTypeAndKey) {
  expectMessage(errorOfOccluder({{"type", "window"}}),
                {"rooms/x.json: occluders[0].type: unknown occluder type \"window\"", "door, slit, edge"});
  expectMessage(errorOfOccluder({{"type", "door"}, {"group", "doorway"}, {"sil", "none"}}),
                {"rooms/x.json: occluders[0].sil: unknown key", "did you mean \"sill\""});
  expectMessage(errorOfOccluder({{"type", "edge"}, {"start", {0, 0, 0}}, {"end", {0, 0, 1}}, {"open_toward", {1, 0, 0}},
                                 {"height_m", 1}}),
                {"rooms/x.json: occluders[0].height_m: unknown key"});
  expectMessage(errorOfOccluder({{"name", "x"}}), {"rooms/x.json: occluders[0].type: missing"});
  auto scene = baseScene();
  scene["occluders"] = {{"type", "door"}};  // an object, not a list
  expectMessage(errorOf(scene), {"rooms/x.json: occluders: must be an array"});
}

TEST(RoomOccluderFileErrors, GroupMustBeAFlatOpenRectangle) {
  auto scene = baseScene();
  // Two open rectangles of one group in different planes.
  scene["geometry"].push_back(
      {{"polygon", {{"name", "bent"}, {"vertices", {{2, 8, 0}, {3, 8, 0}, {3, 8, 2}, {2, 8, 2}}}, {"material", "hole"}}}});
  scene["geometry"].push_back(
      {{"polygon", {{"name", "bent"}, {"vertices", {{0, 5, 0}, {0, 6, 0}, {0, 6, 2}, {0, 5, 2}}}, {"material", "hole"}}}});
  // An open triangle: flat, but not a rectangle.
  scene["geometry"].push_back(
      {{"polygon", {{"name", "tri"}, {"vertices", {{5, 8, 0}, {6, 8, 0}, {5, 8, 2}}}, {"material", "hole"}}}});
  // A rectangle tilted against "up" (a diamond seen from the default up).
  scene["geometry"].push_back({{"polygon",
                                {{"name", "diamond"},
                                 {"vertices", {{8, 8, 1}, {8.5, 8, 1.5}, {8, 8, 2}, {7.5, 8, 1.5}}},
                                 {"material", "hole"}}}});
  // A rectangle in a hard material.
  scene["geometry"].push_back(
      {{"polygon", {{"name", "wall"}, {"vertices", {{2, 0, 0}, {3, 0, 0}, {3, 0, 2}, {2, 0, 2}}}, {"material", "m"}}}});
  expectMessage(errorOfOccluder({{"type", "door"}, {"group", "bent"}}, scene),
                {"rooms/x.json: occluders[0].group: face group \"bent\" is not planar"});
  expectMessage(errorOfOccluder({{"type", "door"}, {"group", "tri"}}, scene),
                {"rooms/x.json: occluders[0].group: face group \"tri\" is not a rectangle"});
  expectMessage(errorOfOccluder({{"type", "slit"}, {"group", "diamond"}}, scene),
                {"rooms/x.json: occluders[0].group: face group \"diamond\" is not a rectangle aligned with \"up\""});
  expectMessage(errorOfOccluder({{"type", "door"}, {"group", "wall"}}, scene),
                {"rooms/x.json: occluders[0].group: face group \"wall\" must have a fully transmitting material"});
  expectMessage(errorOfOccluder({{"type", "door"}, {"group", "nowhere"}}, scene),
                {"rooms/x.json: occluders[0].group: no face group \"nowhere\""});
  expectMessage(errorOfOccluder({{"type", "door"}, {"group", "tri"}, {"width_m", 1}}, scene),
                {"rooms/x.json: occluders[0].width_m: give either \"group\" or an explicit rectangle"});
}

TEST(RoomOccluderFileErrors, FramesAndSizes) {
  const nlohmann::json door = {{"type", "door"}, {"centre", {5, 4, 1}}, {"normal", {0, 1, 0}}, {"width_m", 0.8},
                               {"height_m", 2}};
  auto bad = door;
  bad["up"] = {0, -3, 0};
  expectMessage(errorOfOccluder(bad), {"rooms/x.json: occluders[0].up: \"up\" must not be parallel to the occluder's normal"});
  bad = door;
  bad["normal"] = {0, 0, 0};
  expectMessage(errorOfOccluder(bad), {"rooms/x.json: occluders[0].normal: must not be the zero vector"});
  bad = door;
  bad["width_m"] = 0;
  expectMessage(errorOfOccluder(bad), {"rooms/x.json: occluders[0].width_m: must be > 0, got 0"});
  bad = door;
  bad["sill"] = "threshold";
  expectMessage(errorOfOccluder(bad), {"rooms/x.json: occluders[0].sill: must be \"floor\" or \"none\""});
  bad = door;
  bad.erase("height_m");
  expectMessage(errorOfOccluder(bad), {"rooms/x.json: occluders[0].height_m: missing (required)"});
  const nlohmann::json grating = {{"type", "grating"}, {"centre", {9.5, 4, 1.5}}, {"normal", {0, 0, 1}},
                                  {"width_m", 2},      {"height_m", 1.5},        {"period_m", 0.3},
                                  {"modulation_m", 2}, {"material", "m"}};
  expectMessage(errorOfOccluder(grating), {"rooms/x.json: occluders[0]", "must not be parallel"});
  bad = grating;
  bad["up"] = {1, 0, 0};
  bad["modulation_m"] = 5000;  // wbsdf::PhaseGrating's limit, named here rather than at the first trace
  expectMessage(errorOfOccluder(bad), {"rooms/x.json: occluders[0].modulation_m: must be at most 1000"});
  bad["modulation_m"] = 2;
  bad["material"] = "nope";
  expectMessage(errorOfOccluder(bad), {"rooms/x.json: occluders[0].material:", "\"nope\""});
}

TEST(RoomOccluderFileErrors, EdgesAndBarriers) {
  expectMessage(errorOfOccluder({{"type", "edge"}, {"start", {2, 4, 1}}, {"end", {2, 4, 1}}, {"open_toward", {1, 0, 0}}}),
                {"rooms/x.json: occluders[0]: the edge has zero length"});
  expectMessage(errorOfOccluder({{"type", "edge"}, {"start", {2, 4, 0}}, {"end", {2, 4, 3}}, {"open_toward", {0, 0, -2}}}),
                {"rooms/x.json: occluders[0]: open_toward is parallel to the edge"});
  expectMessage(errorOfOccluder({{"type", "edge"}, {"start", {2, 4, 0}}, {"end", {2, 4, 3}}, {"open_toward", {1, 0, 0}},
                                 {"extent_m", -1}}),
                {"rooms/x.json: occluders[0].extent_m: must be > 0"});
  const nlohmann::json barrier = {{"type", "barrier"}, {"base", {{2, 5, 0}, {6, 5, 0}}}, {"height_m", 2}, {"material", "m"}};
  auto bad = barrier;
  bad["base"] = {{2, 5, 0}, {2, 5, 0}};
  expectMessage(errorOfOccluder(bad), {"rooms/x.json: occluders[0].base: the barrier's base has zero length"});
  bad = barrier;
  bad["up"] = {1, 0, 0};  // along the base: no panel
  expectMessage(errorOfOccluder(bad), {"rooms/x.json: occluders[0].up: \"up\" (default +z) must not be parallel to the barrier's base"});
  bad = barrier;
  bad["base"] = {{2, 5, 0}, {2, 5, 2}};  // a vertical base and the default up
  expectMessage(errorOfOccluder(bad), {"rooms/x.json: occluders[0]: \"up\" (default +z) must not be parallel"});
  bad = barrier;
  bad["base"] = {{2, 5, 0}};
  expectMessage(errorOfOccluder(bad), {"rooms/x.json: occluders[0].base: must have 2 elements, got 1"});
  bad = barrier;
  bad.erase("material");
  expectMessage(errorOfOccluder(bad), {"rooms/x.json: occluders[0].material: missing (required)"});
}

TEST(RoomOccluderFileErrors, DuplicateNames) {
  auto scene = baseScene();
  const nlohmann::json edge = {{"type", "edge"}, {"name", "e"}, {"start", {2, 4, 0}}, {"end", {2, 4, 3}},
                               {"open_toward", {1, 0, 0}}};
  const nlohmann::json slit = {{"type", "slit"}, {"name", "e"}, {"centre", {5, 4, 1.5}}, {"normal", {1, 0, 0}},
                               {"width_m", 0.1}, {"height_m", 1}};
  scene["occluders"] = {edge, slit};
  expectMessage(errorOf(scene), {"rooms/x.json: occluders[1].name: duplicate occluder name \"e\""});
  scene["occluders"] = {slit, edge};
  expectMessage(errorOf(scene), {"rooms/x.json: occluders[1].name: duplicate occluder name \"e\""});
  // A given name equal to another entry's default name is a duplicate too.
  auto named = edge;
  named["name"] = "edge2";
  auto unnamed = edge;
  unnamed.erase("name");
  scene["occluders"] = {named, unnamed};
  expectMessage(errorOf(scene), {"rooms/x.json: occluders[1]", "duplicate occluder name \"edge2\""});
}

TEST(RoomOccluderFileErrors, SlitsThatDoNotFit) {
  const nlohmann::json array = {{"type", "slit"}, {"centre", {7, 4, 1.5}}, {"normal", {1, 0, 0}}, {"width_m", 0.6},
                                {"height_m", 1},  {"slits", 3},            {"slit_width_m", 0.1}, {"spacing_m", 0.3}};
  // 2 × 0.3 + 0.1 = 0.7 m of slits in a 0.6 m wide occluder.
  expectMessage(errorOfOccluder(array), {"rooms/x.json: occluders[0].slits: the slits do not fit"});
  auto bad = array;
  bad["spacing_m"] = 0.1;
  expectMessage(errorOfOccluder(bad), {"rooms/x.json: occluders[0].spacing_m: must exceed slit_width_m"});
  bad = array;
  bad["slits"] = 0;
  expectMessage(errorOfOccluder(bad), {"rooms/x.json: occluders[0].slits: must be in [1, 64], got 0"});
  bad = array;
  bad["slits"] = 2.5;
  expectMessage(errorOfOccluder(bad), {"rooms/x.json: occluders[0].slits: must be a whole number"});
  bad = array;
  bad.erase("spacing_m");
  expectMessage(errorOfOccluder(bad), {"rooms/x.json: occluders[0].spacing_m: missing (required)"});
  bad = array;
  bad["width_m"] = 0.7;  // exactly fits
  EXPECT_EQ(errorOfOccluder(bad), "(no error)");
}
