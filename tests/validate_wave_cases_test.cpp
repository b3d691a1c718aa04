// The wave validation cases (two-rooms-wave, classroom-wave) on a small scene: their room built from
// parameters is closed with the closed-form volume, the listener hidden from the source is found by
// geometry, a door that does not fit is refused in one line, and a coarse run (one band, 125 Hz) gives rows
// and counts that agree with each other and, in the source's room, ray and wave levels within the spread a
// reverberant band level has at one point.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "diffray/core/error.h"
#include "diffray/room/checks.h"
#include "diffray/validate/case.h"
#include "diffray/validate/two_room_setup.h"
#include "validate_fixtures.h"

namespace dv = diffray::validate;

namespace {

// Room A 3 x 2.5 x 2.4 m, a 0.2 m partition, room B 2 x 2 x 2.4 m, door 0.8 x 2 m at y in [0.8, 1.6].
// Listeners: in room A, in room B in view through the door, in room B behind the partition.
dv::Params smallRooms() {
  return {{"room-a", {3, 2.5, 2.4}}, {"room-b", {2, 2, 2.4}}, {"door-width", {0.8}}, {"door-height", {2.0}},
          {"door-position", {0.8}},  {"source", {1.0, 1.2, 1.5}},
          {"listeners", {2.0, 1.8, 1.2, 4.6, 1.2, 1.2, 4.6, 0.4, 1.2}}, {"radius", {0.3}},
          {"bands", {125}}, {"ppw", {6}}, {"length", {1.0}}};
}

dv::TwoRoomSpec specOf(const dv::Params& given) {
  const dv::CaseInfo* info = dv::findCase("two-rooms-wave");
  return dv::twoRoomFromParams(dv::resolveParams(*info, given), dv::TwoRoomSpec{});
}

}  // namespace

TEST(ValidateWaveRooms, BuiltRoomIsClosedWithTheBoxesVolume) {
  const dv::TwoRoomSpec s = specOf(smallRooms());
  const diffray::room::Room room = dv::makeTwoRooms(s);
  EXPECT_EQ(diffray::room::openEdgeCount(room), 0);
  // A + B + the door's passage through the partition (the opening rectangle bounds nothing).
  EXPECT_NEAR(room.volume(), 3 * 2.5 * 2.4 + 2 * 2 * 2.4 + 0.8 * 0.2 * 2.0, 1e-9);
  ASSERT_EQ(room.occluders.size(), 1u);
  EXPECT_TRUE(room.occluders[0].y.mirror_lo);  // the door stands on the floor
  // The shipped classroom: corridor along y, shifted by -1.5 m.
  const dv::CaseInfo* cls = dv::findCase("classroom-wave");
  ASSERT_NE(cls, nullptr);
  dv::TwoRoomSpec base;
  base.axis = 1;
  const diffray::room::Room c = dv::makeTwoRooms(dv::twoRoomFromParams(dv::resolveParams(*cls, {}), base));
  EXPECT_EQ(diffray::room::openEdgeCount(c), 0);
  EXPECT_NEAR(c.volume(), 9 * 7 * 3.2 + 12 * 2 * 3.2 + 0.9 * 0.2 * 2.1, 1e-9);
}

TEST(ValidateWaveRooms, HiddenListenerByGeometry) {
  const dv::TwoRoomSpec s = specOf(smallRooms());
  // Source (1, 1.2, 1.5); mid-plane x = 3.1. To (4.6, 1.2): crosses at y = 1.2, inside [0.8, 1.6], z < 2.
  // To (4.6, 0.4): crosses at y = 1.2 - 0.8·2.1/3.6 = 0.733 < 0.8, behind the jamb.
  EXPECT_FALSE(dv::hiddenFromSource(s, 0));
  EXPECT_FALSE(dv::hiddenFromSource(s, 1));
  EXPECT_TRUE(dv::hiddenFromSource(s, 2));
}

TEST(ValidateWaveRooms, DoorThatDoesNotFitIsRefusedInOneLine) {
  dv::Params p = smallRooms();
  p["door-position"] = {1.5};  // [1.5, 2.3] runs past room B's 2 m
  try {
    specOf(p);
    FAIL() << "a door past room B's wall was accepted";
  } catch (const diffray::core::InputError& e) {
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("door"), std::string::npos);
  }
  p = smallRooms();
  p["door-height"] = {2.5};  // above the 2.4 m ceilings
  EXPECT_THROW(specOf(p), diffray::core::InputError);
}

TEST(ValidateWaveRooms, CoarseRunRowsCountsAndVisibleLevel) {
  const dv::CaseResult r = diffray::testing::runCase("two-rooms-wave", 20000, smallRooms(), 7);
  ASSERT_EQ(r.rows.size(), 3u);  // 3 listeners x the one band simulated
  EXPECT_TRUE(r.errors_in_db);
  int within = 0;
  for (const dv::Row& row : r.rows) {
    ASSERT_TRUE(std::isfinite(row.traced) && std::isfinite(row.reference) && std::isfinite(row.alt_reference));
    within += std::abs(row.traced - row.reference) <= 1.0;
  }
  EXPECT_EQ(r.extra.at("g_within_1db_total"), 3.0);
  EXPECT_EQ(r.extra.at("g_within_1db_met"), within);
  EXPECT_EQ(r.extra.at("t30_within_5pct_total"), 3.0);
  EXPECT_EQ(r.extra.at("hidden_early_closer_than_none_total"), 1.0);
  const bool all = within == 3 && r.extra.at("t30_within_5pct_met") == 3.0 &&
                   r.extra.at("hidden_early_closer_than_none_met") == 1.0 && r.extra.at("hidden_c50_closer_than_none_met") == 1.0;
  EXPECT_EQ(r.passed, all);
  // Room A holds the source: both models see the direct sound and the same reverberant field. A band level
  // at one point of a reverberant room scatters about the energy mean with σ ≈ 4.34 / √(1 + B·T/6.9) dB
  // (Lubman 1968, JASA 44, "Fluctuations of sound with position in a reverberant room"), B the bandwidth,
  // T the reverberation time. Octave 125 Hz: B = 88 Hz. Room A's Sabine T at 125 Hz with the default
  // absorptions (floor 0.03 x 7.5 m², ceiling 0.49 x 7.5 m², walls 0.15 x 26.4 m²) and the door counted as
  // fully absorbing (1.6 m²): A = 9.5 m², T = 0.161·18/9.5 = 0.31 s (room B only lengthens it), so
  // σ ≤ 4.34/√(1 + 88·0.31/6.9) = 1.95 dB; the sphere's recording points only lower it. 3σ ≈ 6 dB.
  EXPECT_NEAR(r.rows[0].traced, r.rows[0].reference, 6.0);
}
