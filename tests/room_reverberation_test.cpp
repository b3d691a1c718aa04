// room::statisticalReverberation against Sabine's and Eyring's formulas evaluated by hand for a shoebox
// whose walls differ (so a wall mix-up or a wrong area shows), and a room with an open doorway to a second
// box (the doorway is not part of either enclosure, so it must not count as absorbing area).
#include <gtest/gtest.h>

#include <cmath>

#include "diffray/room/air.h"
#include "diffray/room/reverberation.h"
#include "diffray/room/room.h"

namespace {

using diffray::core::Vec3;
namespace dr = diffray::room;

int addMaterial(dr::Room& room, const char* name, double alpha) {
  dr::Material m;
  m.name = name;
  for (int b = 0; b < room.bands.size(); ++b) m.absorption[b] = alpha * (1.0 + 0.1 * b);  // band-dependent
  return room.addMaterial(m);
}

TEST(RoomReverberation, ShoeboxMatchesSabineAndEyringByHand) {
  dr::Room room;
  room.air.humidity_percent = 40;
  const int wall = addMaterial(room, "wall", 0.05), floor = addMaterial(room, "floor", 0.3),
            ceiling = addMaterial(room, "ceiling", 0.6);
  const int walls[6] = {wall, wall, wall, wall, floor, ceiling};
  room.addBox(Vec3(0, 0, 0), Vec3(10, 7, 3), walls);
  const dr::StatisticalReverberation st = dr::statisticalReverberation(room);

  const double volume = 10.0 * 7 * 3, walls_area = 2 * (10.0 * 3 + 7.0 * 3), plan = 10.0 * 7;
  const double surface = walls_area + 2 * plan;  // 242 m²
  EXPECT_NEAR(st.volume_m3, volume, 1e-9);
  EXPECT_NEAR(st.surface_m2, surface, 1e-9);
  const double c = dr::speedOfSound(room.air);
  const auto m = dr::airAttenuationPerM(room.air, room.bands);
  ASSERT_EQ(st.sabine_s.size(), static_cast<std::size_t>(room.bands.size()));
  for (int b = 0; b < room.bands.size(); ++b) {
    const double k = 1.0 + 0.1 * b;
    const double a = walls_area * 0.05 * k + plan * 0.3 * k + plan * 0.6 * k;  // Σ S_i α_i
    const double mean = a / surface;
    const double sabine = 24 * std::log(10.0) / c * volume / (a + 4 * m[b] * volume);
    const double eyring = 24 * std::log(10.0) / c * volume / (-surface * std::log(1 - mean) + 4 * m[b] * volume);
    EXPECT_NEAR(st.mean_alpha[b], mean, 1e-12) << "band " << b;
    EXPECT_NEAR(st.sabine_s[b], sabine, 1e-9 * sabine) << "band " << b;
    EXPECT_NEAR(st.eyring_s[b], eyring, 1e-9 * eyring) << "band " << b;
    EXPECT_LT(st.eyring_s[b], st.sabine_s[b]);  // Eyring is always the shorter
  }
}

TEST(RoomReverberation, ADoorwayBetweenTwoRoomsIsNotAbsorbingArea) {
  // Two 4 × 4 × 3 m boxes side by side sharing the plane x = 4, joined by a 1 × 2 m opening (α = τ = 1):
  // the enclosure is both boxes without the opening and its partition (the partition is two walls here).
  dr::Room room;
  const int wall = addMaterial(room, "wall", 0.1);
  dr::Material open;
  open.name = "open";
  for (int b = 0; b < room.bands.size(); ++b) open.absorption[b] = open.transmission[b] = 1.0;
  const int opening = room.addMaterial(open);
  const int walls[6] = {wall, wall, wall, wall, wall, wall};
  room.addBox(Vec3(0, 0, 0), Vec3(4, 4, 3), walls);
  room.addBox(Vec3(4, 0, 0), Vec3(8, 4, 3), walls);
  room.addPolygon({Vec3(4, 1, 0), Vec3(4, 2, 0), Vec3(4, 2, 2), Vec3(4, 1, 2)}, opening, "doorway");
  const dr::StatisticalReverberation st = dr::statisticalReverberation(room);
  const double box_area = 2 * (16.0 + 12.0 + 12.0);
  EXPECT_NEAR(st.surface_m2, 2 * box_area, 1e-9);  // the 2 m² opening left out
  EXPECT_NEAR(st.mean_alpha[0], 0.1, 1e-12);
}

}  // namespace
