// Next-event estimation at occluders (RoomOccluders::expectedSphereScore, RoomTraceOptions::next_event):
// the quadrature's value against brute-force sampling of the same scattering at one hit point (the oracle:
// RoomOccluders::scatter and the sphere's own chord, averaged over many draws), and whole traces with and
// without it agreeing within their standard errors (it must change the noise, not the mean), and on a
// barrier standing on a rigid ground, the estimate through the ground and rays aimed through it as well,
// and with zones beside the barrier's side edges.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>

#include "diffray/compare/scene_checks.h"
#include "diffray/compare/wbsdf_levels.h"
#include "diffray/room/scene_file.h"
#include "diffray/receiver/sphere.h"
#include "diffray/transport/room_occluders.h"
#include "diffray/validate/diffraction_setup.h"
#include "temp_dir.h"

namespace dt = diffray::transport;
namespace dv = diffray::validate;
namespace dr = diffray::room;
using diffray::core::Vec3;

namespace {

constexpr double kPi = 3.14159265358979323846;

dr::Room edgeScene(dr::OccluderAxis::Faces faces) {
  dv::HalfPlaneSpec spec;
  spec.source_rho_m = 5.0;
  spec.listener_rho_m = 4.0;
  spec.listener_phi_rad = {(180.0 + 60.0 - 10.0) * kPi / 180.0, (180.0 + 60.0 + 20.0) * kPi / 180.0};
  spec.radius_m = 0.3;
  spec.zone_m = 3.0;
  spec.faces = faces;
  return dv::makeHalfPlaneScene(spec);
}

// Every listener and band of two runs agree within 4.5 combined standard errors.
void expectSameMeans(const dr::Room& room, const diffray::compare::WbsdfLevels& a_run,
                     const diffray::compare::WbsdfLevels& b_run) {
  for (std::size_t l = 0; l < room.listeners.size(); ++l)
    for (int b = 0; b < room.bands.size(); ++b) {
      const auto& a = a_run.listeners[l][b];
      const auto& c = b_run.listeners[l][b];
      EXPECT_NEAR(a.ratio, c.ratio, 4.5 * std::hypot(a.ratio_std_error, c.ratio_std_error))
          << "listener " << l << " band " << b;
    }
}

// Aims w's rays at the room's first occluder, its other zones (a barrier's side zones, whole) and their
// images below the specular ground (as compare --aim does); false when the room has no such ground.
bool aimThroughTheGround(const dr::Room& room, diffray::compare::WbsdfRunOptions& w) {
  const diffray::compare::AimGround ground = diffray::compare::checkAimReflectors(room);
  if (!ground.present) return false;
  diffray::compare::aimAtOccluder(w, room.occluders[0]);
  w.aim_mirrored = true;
  w.aim_mirror_normal = ground.normal;
  w.aim_mirror_offset = ground.offset;
  for (std::size_t k = 1; k < room.occluders.size(); ++k) {
    const dr::Occluder& z = room.occluders[k];
    w.aim_more.push_back({z.origin_m, z.ex, z.ey, z.half_x_m, z.half_y_m});
  }
  return true;
}

}  // namespace

TEST(StatOccluderNextEvent, QuadratureMatchesSampledScatterings) {
  // One hit point on the edge zone, one incident direction, two spheres (lit side, shadow side), three
  // wavelengths and both face models: the expected score against the mean of sampled scatterings.
  for (const auto faces : {dr::OccluderAxis::Faces::Kirchhoff, dr::OccluderAxis::Faces::Rigid}) {
    const dr::Room room = edgeScene(faces);
    const dt::RoomOccluders occ(room, 0.02);
    ASSERT_TRUE(occ.nextEventSupported(0));
    const Vec3 hit(-0.4, 0.0, 0.05);  // 0.4 m from the edge, in the zone (plane y = 0)
    const Vec3 dir = (hit - room.sources[0].position_m).normalized();
    for (const double lambda : {1.37, 0.343, 0.0857}) {
      for (const dr::Listener& l : room.listeners) {
        const diffray::receiver::Sphere sphere{l.position_m, l.radius_m};
        const double none[2] = {0.5, 0.5};  // unused: one edge axis
        const double expected = occ.expectedSphereScore(0, hit, dir, lambda, l.position_m, l.radius_m, none);
        std::mt19937_64 rng(99);
        std::uniform_real_distribution<double> uni(0.0, 1.0);
        const int n = 400000;
        double sum = 0, sum_sq = 0;
        for (int i = 0; i < n; ++i) {
          const double xi[4] = {uni(rng), uni(rng), uni(rng), uni(rng)};
          const dt::RoomOccluders::Scatter s = occ.scatter(0, hit, dir, lambda, xi);
          double v = 0.0;
          if (s.alive) {
            const double o[3] = {hit.x(), hit.y(), hit.z()}, d[3] = {s.dir.x(), s.dir.y(), s.dir.z()};
            const double chord = sphere.chordLength(o, d, 0.0, 1e9);
            v = s.weight * sphere.chordWeight(chord) / sphere.crossSection();
          }
          sum += v;
          sum_sq += v * v;
        }
        const double mean = sum / n, se = std::sqrt((sum_sq / n - mean * mean) / n);
        EXPECT_NEAR(expected, mean, 4.5 * se + 1e-12) << "lambda " << lambda << " listener " << l.name;
      }
    }
  }
}

TEST(StatOccluderNextEvent, TracesWithAndWithoutAgree) {
  const dr::Room room = edgeScene(dr::OccluderAxis::Faces::Rigid);
  diffray::compare::WbsdfRunOptions w;
  w.rays = 300000;
  diffray::compare::aimAtOccluder(w, room.occluders[0]);
  w.aim_half_y_m = 0.3;  // the listeners' height band along the edge
  const auto with = diffray::compare::wbsdfLevels(room, 0, w);
  w.next_event = false;
  w.rays = 1200000;
  w.seed = 7;
  const auto without = diffray::compare::wbsdfLevels(room, 0, w);
  expectSameMeans(room, with, without);
  // The point of it: less noise in the shadow (listener 1) for a quarter of the rays.
  for (int b = 0; b < room.bands.size(); ++b)
    EXPECT_LT(with.listeners[1][b].ratio_std_error, without.listeners[1][b].ratio_std_error) << "band " << b;
}

TEST(StatOccluderNextEvent, DoorOnAFloorWithAndWithoutAgree) {
  // A door with a sill: next-event estimation also reaches the listener through one specular bounce off the
  // floor (its image below the floor); traces with and without it must agree.
  dv::DoorSpec spec;
  spec.listeners_m = {Vec3(2.5, 0.0, 1.5), Vec3(2.0, 1.8, 1.2)};  // in view; hidden behind the jamb
  spec.radius_m = 0.3;
  const dr::Room room = dv::makeDoorScene(spec);
  diffray::compare::WbsdfRunOptions w;
  diffray::compare::aimAtOccluder(w, room.occluders[0]);  // the door and its image in the floor
  w.rays = 200000;
  const auto with = diffray::compare::wbsdfLevels(room, 0, w);
  w.next_event = false;
  w.rays = 800000;
  w.seed = 11;
  const auto without = diffray::compare::wbsdfLevels(room, 0, w);
  expectSameMeans(room, with, without);
}

TEST(StatOccluderNextEvent, BarrierOnAGroundPlainEstimatedAndAimedAgree) {
  // rooms/screen.json (a 4 × 2 m rigid panel in the plane y = 0 on a rigid ground), with two wide listener
  // spheres behind it, clear of the panel and the ground (less noise for the plain estimator). Next-event
  // estimation at the top edge reaches them directly and through the ground (its image); --aim sends half
  // the rays toward the zone's image below the ground. Uniform emission with next-event estimation, aimed
  // rays with it, and aimed plain rays (the scattered rays scored where they cross the spheres) must agree.
  dr::Room room = dr::loadRoom(std::string(DIFFRAY_SOURCE_DIR) + "/rooms/screen.json");
  room.listeners = {dr::Listener{"behind", Vec3(0, 3, 1.6), 1.1}, dr::Listener{"side", Vec3(1.5, 3, 1.6), 1.1}};
  diffray::compare::WbsdfRunOptions w;
  w.rays = 1000000;
  w.seed = 3;
  const auto uniform = diffray::compare::wbsdfLevels(room, 0, w);
  ASSERT_TRUE(aimThroughTheGround(room, w));
  w.rays = 200000;
  w.seed = 5;
  const auto aimed = diffray::compare::wbsdfLevels(room, 0, w);
  expectSameMeans(room, uniform, aimed);
  w.next_event = false;
  w.rays = 2000000;
  w.seed = 7;
  const auto plain = diffray::compare::wbsdfLevels(room, 0, w);
  expectSameMeans(room, aimed, plain);
  // What aiming through the ground buys: at 63 Hz, a fifth of the rays for a smaller standard error.
  for (std::size_t l = 0; l < room.listeners.size(); ++l)
    EXPECT_LT(aimed.listeners[l][0].ratio_std_error, uniform.listeners[l][0].ratio_std_error) << "listener " << l;
}

TEST(StatOccluderNextEvent, BarrierSideEdgesPlainEstimatedAndAimedAgree) {
  // rooms/screen.json with "side_edges": the top edge's zone and one beside each side edge, all on the
  // rigid ground. Two wide spheres clear of the panel and the ground, one behind the middle and one past the
  // side edge at x = 2; uniform emission with and without next-event estimation, and rays aimed at the three
  // zones and their images below the ground, must agree.
  nlohmann::json scene = nlohmann::json::parse(std::ifstream(std::string(DIFFRAY_SOURCE_DIR) + "/rooms/screen.json"));
  scene["occluders"][0]["side_edges"] = true;
  diffray::test::TempDir dir("nee_sides");
  std::ofstream(dir.file("sides.json")) << scene.dump();
  dr::Room room = dr::loadRoom(dir.file("sides.json"));
  ASSERT_EQ(room.occluders.size(), 3u);
  room.listeners = {dr::Listener{"behind", Vec3(0, 3, 1.6), 1.1}, dr::Listener{"past", Vec3(2.8, 3, 1.1), 1.0}};
  diffray::compare::WbsdfRunOptions w;
  w.rays = 1000000;
  w.seed = 3;
  const auto estimated = diffray::compare::wbsdfLevels(room, 0, w);
  w.next_event = false;
  w.rays = 4000000;
  w.seed = 5;
  const auto plain = diffray::compare::wbsdfLevels(room, 0, w);
  expectSameMeans(room, estimated, plain);
  ASSERT_TRUE(aimThroughTheGround(room, w));
  w.next_event = true;
  w.rays = 300000;
  w.seed = 7;
  const auto aimed = diffray::compare::wbsdfLevels(room, 0, w);
  expectSameMeans(room, estimated, aimed);
}
