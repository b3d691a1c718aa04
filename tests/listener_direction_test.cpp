// Directions at the listener: the scene's orientation against the rotation written out by hand; image
// sources' directions against mirror images computed here; the traced part's energy vector against the
// geometry of a sphere seen from a point source; the early direction behind the door of two-rooms against
// the direction of the doorway.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "diffray/core/error.h"
#include "diffray/ir/direction.h"
#include "diffray/room/scene_file.h"
#include "diffray/transport/room_simulation.h"

namespace dr = diffray::room;
namespace di = diffray::ir;
namespace dc = diffray::core;
using dc::Vec3;

namespace {

const std::string kRooms = std::string(DIFFRAY_SOURCE_DIR) + "/rooms/";
constexpr double kDeg = 3.14159265358979323846 / 180.0;

// A 10 x 7 x 3 m box with one listener whose JSON members beyond name and position are `extra`.
std::string boxScene(const std::string& listener_extra, const std::string& materials = "\"hard-wall\"",
                     const std::string& output = "\"ism_order\": 1") {
  return R"({"materials_library": "materials.json", "materials": {"m": )" + materials +
         R"(}, "geometry": [{"box": {"min": [0, 0, 0], "max": [10, 7, 3], "materials": {"walls": "m", "floor": "m", "ceiling": "m"}}}],
  "sources": [{"name": "S", "position": [2, 3.5, 1.5]}],
  "listeners": [{"name": "L", "position": [7, 4.2, 1.2])" +
         listener_extra + R"(}], "output": {)" + output + "}}";
}

dr::Listener listenerOf(const std::string& extra) {
  return dr::parseRoom(boxScene(extra), "scene.json", kRooms).listeners.at(0);
}

void expectVec(const Vec3& got, const Vec3& want, double tol, const std::string& what) {
  EXPECT_NEAR(got.x(), want.x(), tol) << what;
  EXPECT_NEAR(got.y(), want.y(), tol) << what;
  EXPECT_NEAR(got.z(), want.z(), tol) << what;
}

double angleDeg(const Vec3& a, const Vec3& b) {
  return std::acos(std::max(-1.0, std::min(1.0, a.normalized().dot(b.normalized())))) / kDeg;
}

}  // namespace

TEST(ListenerOrientation, DefaultFacesPlusXWithZUp) {
  const dr::Listener l = listenerOf("");
  expectVec(l.forward, {1, 0, 0}, 0.0, "forward");
  expectVec(l.left, {0, 1, 0}, 0.0, "left");
  expectVec(l.up, {0, 0, 1}, 0.0, "up");
}

TEST(ListenerOrientation, YawPitchRollTurnTheHeadAsDocumented) {
  // Yaw 90: facing +y, left is −x. Pitch 90: facing up, up is −x. Roll 90: head on the right shoulder,
  // up is −y (right), left is +z.
  dr::Listener l = listenerOf(R"(, "orientation": {"yaw_deg": 90})");
  expectVec(l.forward, {0, 1, 0}, 1e-15, "yaw forward");
  expectVec(l.left, {-1, 0, 0}, 1e-15, "yaw left");
  l = listenerOf(R"(, "orientation": {"pitch_deg": 90})");
  expectVec(l.forward, {0, 0, 1}, 1e-15, "pitch forward");
  expectVec(l.up, {-1, 0, 0}, 1e-15, "pitch up");
  l = listenerOf(R"(, "orientation": {"roll_deg": 90})");
  expectVec(l.up, {0, -1, 0}, 1e-15, "roll up");
  expectVec(l.left, {0, 0, 1}, 1e-15, "roll left");
  // Any angles: an orthonormal right-handed frame, forward at the stated azimuth and elevation.
  l = listenerOf(R"(, "orientation": {"yaw_deg": -130, "pitch_deg": 25, "roll_deg": 40})");
  EXPECT_NEAR(l.forward.norm(), 1.0, 1e-15);
  EXPECT_NEAR(l.left.norm(), 1.0, 1e-15);
  EXPECT_NEAR(l.forward.dot(l.left), 0.0, 1e-15);
  expectVec(l.forward.cross(l.left), l.up, 1e-15, "right-handed");
  EXPECT_NEAR(std::atan2(l.forward.y(), l.forward.x()) / kDeg, -130.0, 1e-12);
  EXPECT_NEAR(std::asin(l.forward.z()) / kDeg, 25.0, 1e-12);
  // toLocal: the forward axis is (1, 0, 0) in the listener's frame.
  expectVec(l.toLocal(l.forward), {1, 0, 0}, 1e-15, "toLocal");
}

TEST(ListenerOrientation, LookAtFacesThePointUpright) {
  const dr::Listener l = listenerOf(R"(, "look_at": [2, 3.5, 1.5])");
  expectVec(l.forward, (Vec3(2, 3.5, 1.5) - Vec3(7, 4.2, 1.2)).normalized(), 1e-15, "forward");
  EXPECT_NEAR(l.left.z(), 0.0, 1e-15);  // upright: the ears level
  EXPECT_GT(l.up.z(), 0.0);
  expectVec(l.forward.cross(l.left), l.up, 1e-15, "right-handed");
}

TEST(ListenerOrientation, BadOrientationsRefusedInOneLine) {
  const auto refuses = [](const std::string& extra, const std::string& words) {
    try {
      listenerOf(extra);
      ADD_FAILURE() << extra << " was accepted";
    } catch (const dc::InputError& e) {
      EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
    }
  };
  refuses(R"(, "look_at": [7, 4.2, 1.2])", "own position");
  refuses(R"(, "look_at": [7, 4.2, 2.5])", "straight up or down");
  refuses(R"(, "look_at": [1, 1, 1], "orientation": {})", "not both");
  refuses(R"(, "orientation": {"pitch_deg": 91})", "pitch_deg");
  refuses(R"(, "orientation": {"yaw": 10})", "yaw");
}

TEST(ArrivalDirections, ImageSourcesComeFromTheirMirrorImages) {
  // Order 0 and 1 in the box: the source and its six mirror images, found here by reflecting it in each wall.
  const dr::Room room = dr::parseRoom(boxScene(""), "scene.json", kRooms);
  diffray::transport::RoomSimulationOptions o;
  o.rays = 2000;
  const auto sim = diffray::transport::simulateRoom(room, o);
  const Vec3 s(2, 3.5, 1.5), l(7, 4.2, 1.2);
  std::vector<Vec3> images{s};
  const double lo[3] = {0, 0, 0}, hi[3] = {10, 7, 3};
  for (int axis = 0; axis < 3; ++axis)
    for (double wall : {lo[axis], hi[axis]}) {
      Vec3 img = s;
      img[axis] = 2.0 * wall - s[axis];
      images.push_back(img);
    }
  const auto& arrivals = sim.listeners.at(0).arrivals;
  ASSERT_EQ(arrivals.size(), images.size());
  for (const Vec3& img : images) {
    const double delay = (img - l).norm() / sim.speed_of_sound_m_s;
    bool found = false;
    for (const di::Arrival& a : arrivals)
      if (std::abs(a.delay_s - delay) < 1e-12) {
        expectVec(a.direction, (img - l).normalized(), 1e-12, "image");
        found = true;
      }
    EXPECT_TRUE(found) << "no arrival at " << delay << " s";
  }
}

TEST(ArrivalDirections, TracedDirectSoundPointsAtTheSource) {
  // Anechoic box, rays alone (no image sources): everything a listener sphere of radius a at distance r
  // scores comes straight from the source, within the sphere's half-angle asin(a/r). By symmetry the energy
  // vector points at the source; its length is a chord-weighted mean of cos θ over that cone, so at least
  // cos(asin(a/r)) = 0.995 for a/r = 0.1. Monte Carlo moves the direction by ~θmax/√(crossings).
  const std::string anechoic = R"({"absorption": [1, 1, 1, 1, 1, 1, 1, 1], "scattering": 0})";
  const dr::Room room =
      dr::parseRoom(boxScene(R"(, "radius_m": 0.5)", anechoic, "\"ism_order\": 0"), "scene.json", kRooms);
  diffray::transport::RoomSimulationOptions o;
  o.ism_order = -1;
  o.rays = 400000;
  o.seed = 5;
  o.directions = true;
  const auto sim = diffray::transport::simulateRoom(room, o);
  const dr::Listener& li = room.listeners[0];
  const Vec3 to_source = (Vec3(2, 3.5, 1.5) - li.position_m).normalized();
  const double r = (Vec3(2, 3.5, 1.5) - li.position_m).norm();
  ASSERT_NEAR(0.5 / r, 0.1, 0.002);
  for (int b = 0; b < room.bands.size(); ++b) {
    const di::EarlyDirection d = di::earlyDirection(sim.listeners[0], b, li.forward, li.left, li.up);
    EXPECT_GE(d.r_e, std::cos(std::asin(0.5 / r)) - 1e-3) << "band " << b;
    EXPECT_LE(d.r_e, 1.0 + 1e-12) << "band " << b;
    EXPECT_LT(angleDeg(d.world, to_source), 0.5) << "band " << b;
    EXPECT_NEAR(d.azimuth_deg, std::atan2(to_source.y(), to_source.x()) / kDeg, 0.5) << "band " << b;
  }
}

TEST(ArrivalDirections, EnergyVectorOfTwoArrivalsInTheListenersFrame) {
  // Two arrivals 2 ms apart inside the window, one after it: r = (e1·u1 + e2·u2)/(e1 + e2) by hand, seen
  // by a listener turned 90° to the left (its forward is world +y).
  di::EnergyResponse r;
  r.bands = dc::Bands::octave();
  r.bin_s = 0.001;
  r.traced.assign(8, std::vector<double>(100, 0.0));
  di::Arrival a1, a2, late;
  a1.delay_s = 0.0100, a2.delay_s = 0.0120, late.delay_s = 0.0300;
  a1.direction = Vec3(0, 1, 0), a2.direction = Vec3(1, 0, 0), late.direction = Vec3(0, 0, 1);
  a1.energy = dc::bandFill(3.0), a2.energy = dc::bandFill(1.0), late.energy = dc::bandFill(2.0);
  r.arrivals = {a1, a2, late};
  const di::EarlyDirection d = di::earlyDirection(r, 3, Vec3(0, 1, 0), Vec3(-1, 0, 0), Vec3(0, 0, 1));
  EXPECT_DOUBLE_EQ(d.energy, 4.0);
  EXPECT_NEAR(d.r_e, std::sqrt(3.0 * 3.0 + 1.0) / 4.0, 1e-15);
  // World (1, 3, 0)/√10: in the frame (forward +y, left −x), x' = 3, y' = −1: azimuth −18.43° (to the right).
  EXPECT_NEAR(d.azimuth_deg, std::atan2(-1.0, 3.0) / kDeg, 1e-12);
  EXPECT_NEAR(d.elevation_deg, 0.0, 1e-12);
}

TEST(ArrivalDirections, HiddenListenerHearsTheDoorwayWithWbsdf) {
  // two-rooms: B-hidden sees neither the source nor its images through the door; with the WBSDF its early
  // sound at 125–500 Hz (where diffraction through the 0.9 m doorway carries it) comes from the doorway's
  // centre (6.1, 1.45, 1.05) within 25° (the window's 10 ms also hold room B's first reflections off the
  // door's far side; 8.6–10.9° at this seed). Without diffraction the same check fails: the early sound is
  // then what few rays reach the listener after a reflection (40–43° away at this seed).
  const dr::Room room = dr::loadRoom(kRooms + "two-rooms.json");
  const dr::Listener& li = room.listeners.at(2);
  ASSERT_EQ(li.name, "B-hidden");
  const Vec3 doorway = (Vec3(6.1, 1.45, 1.05) - li.position_m).normalized();
  for (const std::string model : {"wbsdf", "none"}) {
    diffray::transport::RoomSimulationOptions o;
    o.diffraction = model;
    o.directions = true;
    o.rays = 250000;
    o.seed = 11;
    const auto sim = diffray::transport::simulateRoom(room, o);
    for (int b = 1; b <= 3; ++b) {
      const di::EarlyDirection d = di::earlyDirection(sim.listeners.at(2), b, li.forward, li.left, li.up);
      const double off = angleDeg(d.world, doorway);
      if (model == "wbsdf") EXPECT_LT(off, 25.0) << room.bands.label(b) << " Hz";
      else EXPECT_GT(off, 25.0) << room.bands.label(b) << " Hz";
    }
  }
}
