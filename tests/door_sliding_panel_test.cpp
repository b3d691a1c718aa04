// door/sliding_panel.h: the two-rooms doorway (x = 6.1, y ∈ [1, 1.9], z ∈ [0, 2.1], as tools/make_rooms.py
// writes it) closed part-way. Checked against that rectangle: the gap's and the panel's areas, their extents
// along the door's width, that together they tile the doorway, that the rest of the mesh is untouched, and
// the narrowed occluder. Then the error paths.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>

#include "diffray/core/error.h"
#include "diffray/door/sliding_panel.h"
#include "diffray/room/scene_file.h"

namespace dd = diffray::door;
namespace dr = diffray::room;
namespace dc = diffray::core;

namespace {

const std::string kRooms = std::string(DIFFRAY_SOURCE_DIR) + "/rooms/";
constexpr double kWidth = 0.9, kHeight = 2.1, kPlaneX = 6.1, kYLo = 1.0, kYHi = 1.9;

struct GroupExtent {
  double area = 0.0, y_lo = 1e9, y_hi = -1e9, z_lo = 1e9, z_hi = -1e9, x_dev = 0.0;
  int triangles = 0;
};

GroupExtent extentOf(const dr::Room& r, const std::string& group) {
  GroupExtent e;
  for (std::size_t t = 0; t < r.mesh.triangles.size(); ++t) {
    if (r.group_of_triangle[t] != group) continue;
    const auto& tri = r.mesh.triangles[t];
    const dr::Vec3 a = r.mesh.vertices[tri[0]], b = r.mesh.vertices[tri[1]], c = r.mesh.vertices[tri[2]];
    e.area += 0.5 * (b - a).cross(c - a).norm();
    for (const dr::Vec3& p : {a, b, c}) {
      e.y_lo = std::min(e.y_lo, p.y()), e.y_hi = std::max(e.y_hi, p.y());
      e.z_lo = std::min(e.z_lo, p.z()), e.z_hi = std::max(e.z_hi, p.z());
      e.x_dev = std::max(e.x_dev, std::abs(p.x() - kPlaneX));
    }
    ++e.triangles;
  }
  return e;
}

dr::Room twoRooms() { return dr::loadRoom(kRooms + "two-rooms.json"); }

}  // namespace

TEST(SlidingPanel, GapAndPanelTileTheDoorway) {
  const dr::Room room = twoRooms();
  const int door = dd::findDoor(room, "");
  ASSERT_EQ(room.occluders[door].name, "doorway");
  const dr::Occluder& d = room.occluders[door];
  // The gap stays at the −ex jamb: which end of y that is follows from the door's ex.
  const bool gap_at_low_y = d.ex.y() > 0.0;
  ASSERT_NEAR(std::abs(d.ex.y()), 1.0, 1e-12);
  const std::size_t others = room.mesh.triangles.size() - static_cast<std::size_t>(extentOf(room, "doorway").triangles);
  for (double gap : {0.6, 0.3, 0.05}) {
    const dr::Room r = dd::withSlidingPanel(room, door, gap);
    const GroupExtent g = extentOf(r, "doorway"), p = extentOf(r, "panel:doorway");
    EXPECT_NEAR(g.area, gap * kHeight, 1e-12) << gap;
    EXPECT_NEAR(p.area, (kWidth - gap) * kHeight, 1e-12) << gap;
    EXPECT_LT(g.x_dev + p.x_dev, 1e-12);
    for (const GroupExtent& e : {g, p}) EXPECT_NEAR(e.z_hi - e.z_lo, kHeight, 1e-12);
    if (gap_at_low_y) {
      EXPECT_NEAR(g.y_lo, kYLo, 1e-12);
      EXPECT_NEAR(g.y_hi, kYLo + gap, 1e-12);
      EXPECT_NEAR(p.y_lo, kYLo + gap, 1e-12);
      EXPECT_NEAR(p.y_hi, kYHi, 1e-12);
    } else {
      EXPECT_NEAR(g.y_hi, kYHi, 1e-12);
      EXPECT_NEAR(g.y_lo, kYHi - gap, 1e-12);
      EXPECT_NEAR(p.y_hi, kYHi - gap, 1e-12);
      EXPECT_NEAR(p.y_lo, kYLo, 1e-12);
    }
    EXPECT_EQ(r.mesh.triangles.size(), others + static_cast<std::size_t>(g.triangles + p.triangles));
    // The occluder is the gap: centred on it, its width, the same frame and sill.
    const dr::Occluder& o = r.occluders[door];
    EXPECT_NEAR(o.half_x_m, 0.5 * gap, 1e-12);
    EXPECT_NEAR(o.x.lo_m, -0.5 * gap, 1e-12);
    EXPECT_NEAR(o.x.hi_m, 0.5 * gap, 1e-12);
    const double centre_y = gap_at_low_y ? kYLo + 0.5 * gap : kYHi - 0.5 * gap;
    EXPECT_NEAR((o.origin_m - dr::Vec3(kPlaneX, centre_y, 0.5 * kHeight)).norm(), 0.0, 1e-12);
    EXPECT_NEAR(o.half_y_m, d.half_y_m, 1e-15);
    EXPECT_TRUE(o.y.mirror_lo);
    EXPECT_EQ(r.materials[r.mesh.object_of_triangle[0]].name, room.materials[room.mesh.object_of_triangle[0]].name);
  }
}

TEST(SlidingPanel, ShutAndOpenEnds) {
  const dr::Room room = twoRooms();
  const int door = dd::findDoor(room, "doorway");
  const dr::Room shut = dd::withSlidingPanel(room, door, 0.0);
  EXPECT_EQ(extentOf(shut, "doorway").triangles, 0);
  EXPECT_NEAR(extentOf(shut, "panel:doorway").area, kWidth * kHeight, 1e-12);
  EXPECT_EQ(shut.occluders.size(), room.occluders.size() - 1);
  // A gap below kShutGapM is shut; the panel is in the door's panel material.
  const dr::Room almost = dd::withSlidingPanel(room, door, 0.5 * dd::kShutGapM);
  EXPECT_EQ(extentOf(almost, "doorway").triangles, 0);
  for (std::size_t t = 0; t < shut.mesh.triangles.size(); ++t)
    if (shut.group_of_triangle[t] == "panel:doorway") {
      EXPECT_EQ(shut.materials[shut.mesh.object_of_triangle[t]].name, "door-panel");
    }
  const dr::Room open = dd::withSlidingPanel(room, door, kWidth);
  EXPECT_EQ(extentOf(open, "panel:doorway").triangles, 0);
  EXPECT_NEAR(extentOf(open, "doorway").area, kWidth * kHeight, 1e-12);
  EXPECT_NEAR(open.occluders[door].half_x_m, 0.5 * kWidth, 1e-12);
}

namespace {

std::string errorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const dc::InputError& e) {
    return e.what();
  }
  return "(no error)";
}

dr::Room withDoors(const nlohmann::json& occluders) {
  nlohmann::json scene = nlohmann::json::parse(R"({
    "materials": {"m": {"absorption": 0.1, "scattering": 0.2}, "p": {"absorption": 0.2, "scattering": 0.1}},
    "geometry": [{"box": {"min": [0, 0, 0], "max": [10, 8, 3], "materials": {"all": "m"}}}],
    "sources": [{"position": [1, 1, 1]}], "listeners": [{"position": [8, 6, 1.2]}]})");
  scene["occluders"] = occluders;
  return dr::parseRoom(scene.dump(), "rooms/x.json", std::string(DIFFRAY_SOURCE_DIR) + "/rooms", nullptr);
}

}  // namespace

TEST(SlidingPanel, ErrorsNameTheProblem) {
  const dr::Room room = twoRooms();
  const int door = dd::findDoor(room, "");
  EXPECT_NE(errorOf([&] { dd::withSlidingPanel(room, door, 0.91); }).find("the gap must be in [0"), std::string::npos);
  EXPECT_NE(errorOf([&] { dd::withSlidingPanel(room, door, -0.1); }).find("the gap must be in [0"), std::string::npos);
  EXPECT_NE(errorOf([&] { dd::findDoor(room, "front"); }).find("no door named \"front\""), std::string::npos);

  const nlohmann::json a = {{"type", "door"}, {"name", "a"}, {"centre", {10, 2, 1}}, {"normal", {1, 0, 0}},
                            {"width_m", 0.8}, {"height_m", 2}};
  nlohmann::json b = a;
  b["name"] = "b", b["centre"] = {10, 5, 1}, b["panel"] = "p";
  const dr::Room two = withDoors({a, b});
  EXPECT_NE(errorOf([&] { dd::findDoor(two, ""); }).find("several doors"), std::string::npos);
  EXPECT_EQ(dd::findDoor(two, "b"), 1);
  EXPECT_NE(errorOf([&] { dd::withSlidingPanel(two, 0, 0.4); }).find("has no panel material"), std::string::npos);
  EXPECT_EQ(errorOf([&] { dd::withSlidingPanel(two, 1, 0.4); }), "(no error)");
  EXPECT_NE(errorOf([&] { withDoors({{{"type", "slit"}, {"centre", {10, 2, 1}}, {"normal", {1, 0, 0}}, {"width_m", 0.1},
                                      {"height_m", 1}, {"panel", "p"}}}); })
                .find("only a door has a panel"),
            std::string::npos);
  const dr::Room none = withDoors(nlohmann::json::array());
  EXPECT_NE(errorOf([&] { dd::findDoor(none, ""); }).find("has no door"), std::string::npos);
}
