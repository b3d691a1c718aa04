// compare/scene_checks.h and the refusals compareScene makes with them: every expectation is worked out by
// hand from the shipped scenes' geometry (rooms/barrier.json: a wall in the plane x = 0, base on z = 0 from
// y = −20 to 20, top edge at z = 3, its diffraction zone 3 m above the edge, source S at (−4, 0, 1) over an
// absorbing ground z = 0; rooms/doorway.json: a 0.9 × 2.1 m door centred on y = 0 in the wall x = 0, on a
// rigid floor, source S at (−2.5, 0, 1.5); rooms/screen.json: a 4 × 2 m panel in the plane y = 0, base on
// the rigid ground z = 0 from x = −2 to 2, its zone 2 m above the top edge, source S at (0, −2, 0.5)).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>

#include "diffray/compare/point_models.h"
#include "diffray/compare/scene_checks.h"
#include "diffray/compare/scene_compare.h"
#include "diffray/core/error.h"
#include "diffray/room/scene_file.h"
#include "temp_dir.h"

namespace {

namespace dc = diffray::compare;
namespace dr = diffray::room;
using diffray::core::InputError;
using diffray::core::Vec3;

const std::string kRooms = std::string(DIFFRAY_SOURCE_DIR) + "/rooms/";

// The scene with its listeners replaced by one named `name` at p (radius 0.15 m).
dr::Room withListener(const std::string& file, const std::string& name, const Vec3& p) {
  dr::Room room = dr::loadRoom(kRooms + file);
  room.listeners = {dr::Listener{name, p, 0.15}};
  return room;
}

// The message of the InputError `f` throws, or "" when it throws none.
template <class F>
std::string errorOf(F f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

// rooms/screen.json with the text `from` (which must occur) replaced by `to`, loaded from a copy in `dir`.
dr::Room screenWith(const diffray::test::TempDir& dir, const std::string& from, const std::string& to) {
  std::ifstream in(kRooms + "screen.json");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::size_t at = text.find(from);
  if (at == std::string::npos) throw std::runtime_error("screen.json has no " + from);
  text.replace(at, from.size(), to);
  std::ofstream(dir.file("screen.json")) << text;
  return dr::loadRoom(dir.file("screen.json"));
}

dc::CompareOptions wbsdfOnly(bool aim) {
  dc::CompareOptions o;
  o.models = {"wbsdf"};
  o.rays = 2000;
  o.aim = aim;
  return o;
}

TEST(CompareSceneChecks, AimRefusesAListenerThatSeesTheSourcePastTheZone) {
  // (6, 0, 20): the line from S crosses x = 0 at z = 1 + 19·0.4 = 8.6, above the zone (3 to 6 m): no aimed
  // ray reaches it directly, while the exact half-plane gives it the full direct sound.
  const dr::Room far = withListener("barrier.json", "high", Vec3(6, 0, 20));
  const std::string msg = errorOf([&] { dc::compareScene(far, wbsdfOnly(true)); });
  EXPECT_NE(msg.find("--aim"), std::string::npos) << msg;
  EXPECT_NE(msg.find("listener high"), std::string::npos) << msg;
  // Without --aim the same listener is fine.
  EXPECT_EQ(errorOf([&] { dc::compareScene(far, wbsdfOnly(false)); }), "");
  // (6, 0, 9): crossing at z = 1 + 8·0.4 = 4.2, inside the zone; (6, 0, 1): crossing at z = 1, on the wall.
  for (double z : {9.0, 1.0}) {
    const dr::Room ok = withListener("barrier.json", "ok", Vec3(6, 0, z));
    EXPECT_EQ(errorOf([&] { dc::compareScene(ok, wbsdfOnly(true)); }), "") << "z=" << z;
  }
  // The shipped scenes pass as they are.
  for (const char* file : {"barrier.json", "doorway.json"})
    EXPECT_EQ(errorOf([&] { dc::compareScene(dr::loadRoom(kRooms + file), wbsdfOnly(true)); }), "") << file;
}

TEST(CompareSceneChecks, AimRefusesAListenerOnTheSourcesSideOfTheDoor) {
  // (−1, 0, 1.5) on the source's side of the wall: its direct sound never goes through the door.
  const dr::Room room = withListener("doorway.json", "front", Vec3(-1, 0, 1.5));
  EXPECT_NE(errorOf([&] { dc::compareScene(room, wbsdfOnly(true)); }).find("listener front"), std::string::npos);
  // (2.5, 3, 1.5) behind the wall: its line crosses x = 0 at y = 1.5, on wall-right (blocked): accepted.
  const dr::Room hidden = withListener("doorway.json", "behind", Vec3(2.5, 3, 1.5));
  EXPECT_EQ(errorOf([&] { dc::compareScene(hidden, wbsdfOnly(true)); }), "");
}

TEST(CompareSceneChecks, AListenerAtTheSourceIsRefusedNamingBoth) {
  const dr::Room room = withListener("barrier.json", "atsrc", Vec3(-4, 0, 1));
  const std::string msg = errorOf([&] { dc::checkListeners(room); });
  EXPECT_NE(msg.find("listener atsrc"), std::string::npos) << msg;
  EXPECT_NE(msg.find("coincides with source S"), std::string::npos) << msg;
  // compareScene refuses before any model runs (the exact half-plane would fail on R = 0).
  dc::CompareOptions o;
  o.models = {"utd", "exact"};
  EXPECT_NE(errorOf([&] { dc::compareScene(room, o); }).find("coincides with source S"), std::string::npos);
}

TEST(CompareSceneChecks, AListenerWhoseSphereMeetsTheScreenIsRefused) {
  // Radius 0.15 m: on the wall at (0, 0, 1) and 0.1 m in front of it are refused; 0.2 m off is accepted,
  // and so is a listener in the plane above the edge (0, 0, 4), in open air in the diffraction zone.
  EXPECT_NE(errorOf([&] { dc::checkListeners(withListener("barrier.json", "onwall", Vec3(0, 0, 1))); })
                .find("listener onwall"),
            std::string::npos);
  EXPECT_NE(errorOf([&] { dc::checkListeners(withListener("barrier.json", "near", Vec3(0.1, 0, 1))); }), "");
  EXPECT_EQ(errorOf([&] { dc::checkListeners(withListener("barrier.json", "off", Vec3(0.2, 0, 1))); }), "");
  EXPECT_EQ(errorOf([&] { dc::checkListeners(withListener("barrier.json", "above", Vec3(0, 0, 4))); }), "");
  // The doorway: on wall-left refused, in the door's opening accepted.
  EXPECT_NE(errorOf([&] { dc::checkListeners(withListener("doorway.json", "wall", Vec3(0, -1, 1))); }), "");
  EXPECT_EQ(errorOf([&] { dc::checkListeners(withListener("doorway.json", "door", Vec3(0, 0, 1))); }), "");
}

TEST(CompareSceneChecks, AListenerBelowTheGroundIsWarnedAbout) {
  const auto below = dc::hiddenListenerWarnings(withListener("barrier.json", "underground", Vec3(6, 0, -1)));
  ASSERT_EQ(below.size(), 1u);
  EXPECT_NE(below[0].find("listener underground"), std::string::npos) << below[0];
  EXPECT_NE(below[0].find("outside the room"), std::string::npos) << below[0];
  // compareScene passes it on.
  dc::CompareOptions o;
  o.models = {"utd"};
  o.fine_per_octave = 1;
  EXPECT_EQ(dc::compareScene(withListener("barrier.json", "underground", Vec3(6, 0, -1)), o).warnings.size(), 1u);
  // Above the ground, behind the barrier (its own plane does not count), and the shipped scenes: none.
  EXPECT_TRUE(dc::hiddenListenerWarnings(withListener("barrier.json", "ok", Vec3(6, 0, 1))).empty());
  EXPECT_TRUE(dc::hiddenListenerWarnings(dr::loadRoom(kRooms + "barrier.json")).empty());
  EXPECT_TRUE(dc::hiddenListenerWarnings(dr::loadRoom(kRooms + "doorway.json")).empty());
  EXPECT_EQ(dc::hiddenListenerWarnings(withListener("doorway.json", "cellar", Vec3(2.5, 0, -0.5))).size(), 1u);
}

TEST(CompareSceneChecks, AListenerBehindAClosedObjectIsNotOutside) {
  // Behind the cupboard (a closed box on the ground) the listeners hear what diffracts round it: no warning.
  // Inside the box, or below the ground beside it, a listener is hidden: warned about.
  EXPECT_TRUE(dc::hiddenListenerWarnings(dr::loadRoom(kRooms + "cupboard.json")).empty());
  const auto inside = dc::hiddenListenerWarnings(withListener("cupboard.json", "in", Vec3(0.1, 0.1, 0.9)));
  ASSERT_EQ(inside.size(), 1u);
  EXPECT_NE(inside[0].find("listener in"), std::string::npos) << inside[0];
  EXPECT_NE(inside[0].find("cupboard/"), std::string::npos) << inside[0];
  EXPECT_EQ(dc::hiddenListenerWarnings(withListener("cupboard.json", "under", Vec3(2, 2, -0.5))).size(), 1u);
}

TEST(CompareSceneChecks, AimTakesTheSpecularGroundABarrierStandsOn) {
  // The screen's rigid ground is perpendicular to the panel and below its zone: --aim aims through it too.
  const dr::Room screen = dr::loadRoom(kRooms + "screen.json");
  const dc::AimGround g = dc::checkAimReflectors(screen);
  ASSERT_TRUE(g.present);
  EXPECT_NEAR(std::abs(g.normal.z()), 1.0, 1e-12);
  EXPECT_NEAR(g.offset, 0.0, 1e-12);
  EXPECT_EQ(errorOf([&] { dc::compareScene(screen, wbsdfOnly(true)); }), "");
  // A ground that scatters: aimed rays only follow its specular reflection.
  dr::Room rough = screen;
  for (auto& m : rough.materials)
    if (m.name == "rigid-ground") m.scattering = diffray::core::bandFill(0.2);
  const std::string diffuse = errorOf([&] { dc::checkAimReflectors(rough); });
  EXPECT_NE(diffuse.find("surface ground (rigid-ground) scatters sound diffusely"), std::string::npos) << diffuse;
  // A scattering patch on the same ground, beside the specular part: refused too.
  dr::Room patched = screen;
  dr::Material gravel = screen.materials[static_cast<std::size_t>(screen.mesh.object_of_triangle[0])];
  gravel.name = "gravel";
  gravel.scattering = diffray::core::bandFill(0.3);
  patched.materials.push_back(gravel);
  patched.addPolygon({Vec3(30, -30, 0), Vec3(40, -30, 0), Vec3(40, 30, 0), Vec3(30, 30, 0)},
                     static_cast<int>(patched.materials.size()) - 1, "patch");
  const std::string patch = errorOf([&] { dc::checkAimReflectors(patched); });
  EXPECT_NE(patch.find("surface patch (gravel) scatters sound diffusely"), std::string::npos) << patch;
  // A second reflector, the wall x = 1 across the zone: refused as before.
  dr::Room walled = screen;
  walled.addPolygon({Vec3(1, -5, 0), Vec3(1, 5, 0), Vec3(1, 5, 6), Vec3(1, -5, 6)}, screen.mesh.object_of_triangle[0], "wall");
  const std::string wall = errorOf([&] { dc::checkAimReflectors(walled); });
  EXPECT_NE(wall.find("surface wall"), std::string::npos) << wall;
  EXPECT_NE(wall.find("reflects"), std::string::npos) << wall;
}

TEST(CompareSceneChecks, AimRefusesAListenerReachedUnderAFloatingPanel) {
  // The screen lifted 1 m (panel z 1 to 3, zone 3 to 5). Listener (0, 2, 2): the straight line from S crosses
  // y = 0 at z = 1.25, on the panel (blocked). Reflected off the ground towards its image (0, 2, −2) it meets
  // the ground at t = 0.5/2.5, y = −2 + 4·0.2 = −1.2, and rises to cross y = 0 at z = 2·1.2/3.2 = 0.75,
  // through the gap under the panel: no aimed ray takes that path.
  diffray::test::TempDir dir("aim_floating");
  dr::Room room = screenWith(dir, "[[-2, 0, 0], [2, 0, 0]]", "[[-2, 0, 1], [2, 0, 1]]");
  room.listeners = {dr::Listener{"gap", Vec3(0, 2, 2), 0.15}};
  const std::string msg = errorOf([&] { dc::compareScene(room, wbsdfOnly(true)); });
  EXPECT_NE(msg.find("listener gap at (0, 2, 2) hears source S by a reflection off the ground"), std::string::npos) << msg;
  // (0, 2, 8): the straight line crosses y = 0 at z = 4.25; reflected, it meets the ground at y = −2 + 4/17
  // = −30/17 and crosses y = 0 at z = 8·(30/17)/(64/17) = 3.75: both through the zone (3 to 5).
  room.listeners = {dr::Listener{"high", Vec3(0, 2, 8), 0.15}};
  EXPECT_EQ(errorOf([&] { dc::compareScene(room, wbsdfOnly(true)); }), "");
}

TEST(CompareSceneChecks, ABarriersSideEdgesKeepItsExactModelAndItsAim) {
  // rooms/screen.json with "side_edges": three occluders, one object. The exact model is the same BTM plate
  // (equal values at a listener, 250 Hz and 1 kHz); --aim aims at the three zones.
  diffray::test::TempDir dir("side_edges");
  const dr::Room sides = screenWith(dir, "\"extent_m\": 2.0}", "\"extent_m\": 2.0, \"side_edges\": true}");
  const dr::Room plain = dr::loadRoom(kRooms + "screen.json");
  ASSERT_EQ(sides.occluders.size(), 3u);
  std::string why_not, assumption, why_not_plain, assumption_plain;
  const auto with = dc::exactModelFor(sides, 343.0, why_not, assumption, false);
  const auto without = dc::exactModelFor(plain, 343.0, why_not_plain, assumption_plain, false);
  ASSERT_TRUE(with) << why_not;
  ASSERT_TRUE(without) << why_not_plain;
  EXPECT_EQ(assumption, assumption_plain);
  const auto a = with->relativePressure(plain.sources[0].position_m, plain.listeners[0].position_m, {250.0, 1000.0});
  const auto b = without->relativePressure(plain.sources[0].position_m, plain.listeners[0].position_m, {250.0, 1000.0});
  for (std::size_t i = 0; i < a.size(); ++i) EXPECT_EQ(a[i], b[i]);
  EXPECT_EQ(errorOf([&] { dc::compareScene(sides, wbsdfOnly(true)); }), "");
  // (6, 2, 0.5): the line from S (0, −2, 0.5) crosses y = 0 at x = 3, in side1's zone (x 2 to 4): reached;
  // (10, 2, 0.5) crosses at x = 5, beyond every zone: refused.
  dr::Room side = sides;
  side.listeners = {dr::Listener{"side", Vec3(6, 2, 0.5), 0.15}};
  EXPECT_EQ(errorOf([&] { dc::compareScene(side, wbsdfOnly(true)); }), "");
  side.listeners = {dr::Listener{"far", Vec3(10, 2, 0.5), 0.15}};
  EXPECT_NE(errorOf([&] { dc::compareScene(side, wbsdfOnly(true)); }).find("listener far"), std::string::npos);
}

TEST(CompareSceneChecks, WrapDegreesIntoTheHalfOpenCircle) {
  EXPECT_DOUBLE_EQ(dc::wrapDegrees(0.0), 0.0);
  EXPECT_DOUBLE_EQ(dc::wrapDegrees(180.0), 180.0);
  EXPECT_DOUBLE_EQ(dc::wrapDegrees(-180.0), 180.0);
  EXPECT_DOUBLE_EQ(dc::wrapDegrees(540.0), 180.0);
  EXPECT_DOUBLE_EQ(dc::wrapDegrees(-190.0), 170.0);
  EXPECT_DOUBLE_EQ(dc::wrapDegrees(190.0), -170.0);
  EXPECT_DOUBLE_EQ(dc::wrapDegrees(-179.5), -179.5);
}

TEST(CompareSceneChecks, ShadowAngleOfAListenerUnderTheEdgeIsWrapped) {
  // Seen from the edge (0, 0, 3), a listener straight below it is at elevation −90°; the boundary leaves
  // the edge at atan(2/4): the angle past it is atan(0.5)·180/π + 90 = 116.57° (it printed −243.43°).
  const dr::Room room = dr::loadRoom(kRooms + "barrier.json");
  const auto a = dc::shadowAngleDeg(room, room.sources[0].position_m, Vec3(0, 0, 1));
  ASSERT_TRUE(a.has_value());
  EXPECT_NEAR(*a, std::atan(0.5) * 180.0 / 3.14159265358979323846 + 90.0, 1e-9);
}

}  // namespace

TEST(CompareSceneChecks, ShadowAngleOfAPlateIsPastTheEdgeNearestToLightingTheListener) {
  // Every angle below is worked out in the plane across one edge. From S (0, −2, 0.5) the top edge (z = 2)
  // casts its boundary up at atan(1.5/2); a side edge (x = ±2, in the plane z = 0.5) at 45° off the panel;
  // the free plate's foot (z = 0) down at atan(0.5/2).
  constexpr double kDeg = 180.0 / 3.14159265358979323846;
  diffray::test::TempDir dir("plate_angles");
  const dr::Room sides = screenWith(dir, "\"extent_m\": 2.0}", "\"extent_m\": 2.0, \"side_edges\": true}");
  const Vec3 s = sides.sources[0].position_m;
  const auto angle = [&](const dr::Room& room, const Vec3& p) {
    const auto a = dc::shadowAngleDeg(room, s, p);
    EXPECT_TRUE(a.has_value());
    return a.value_or(0.0);
  };
  // Behind the middle, 0.5 m high: the top edge's (atan(1.5/2) + atan(1.5/2)); the sides are 90° away.
  EXPECT_NEAR(angle(sides, Vec3(0, 2, 0.5)), 2.0 * std::atan(0.75) * kDeg, 1e-9);
  // 0.5 m past the side edge: the side's, atan(2/0.5) − 45°, not the top's 73.7°.
  EXPECT_NEAR(angle(sides, Vec3(2.5, 2, 0.5)), std::atan(4.0) * kDeg - 45.0, 1e-9);
  // Lit past the side edge (the line from S crosses y = 0 at x = 2.5): atan(2/3) − 45°, negative.
  EXPECT_NEAR(angle(sides, Vec3(5, 2, 0.5)), std::atan(2.0 / 3.0) * kDeg - 45.0, 1e-9);
  // The free plate (rooms/plate.json) also diffracts at its foot: behind the middle at 0.5 m the listener is
  // only 2·atan(0.5/2) past the foot's boundary.
  const dr::Room plate = dr::loadRoom(kRooms + "plate.json");
  EXPECT_NEAR(angle(plate, Vec3(0, 2, 0.5)), 2.0 * std::atan(0.25) * kDeg, 1e-9);
  // Above the plate, 10° into the light of its top edge.
  EXPECT_NEAR(angle(plate, Vec3(0, 2, 2.0 + 2.0 * std::tan(std::atan(0.75) + 10.0 / kDeg))), -10.0, 1e-9);
}
