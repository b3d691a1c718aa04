// door/closing.h: the schedule against its closed form; and, through a whole closing run in free field
// (rooms/doorway.json: an absorbing partition with a 0.9 × 2.1 m door on a rigid floor, given a panel whose
// transmission differs band by band), that the shut door is what its panel's transmission says and not
// silence: with the partition black and the panel reflecting away, the only energy behind a shut door is the
// panel's τ_b times the open door's, band by band; and a listener in view through the remaining gap keeps its
// direct sound while one whose line of sight the panel covers loses it.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "diffray/core/error.h"
#include "diffray/door/closing.h"
#include "diffray/door/sliding_panel.h"
#include "diffray/room/scene_file.h"

namespace dd = diffray::door;
namespace dr = diffray::room;
namespace di = diffray::ir;

TEST(DoorClosing, ScheduleHalvesTheGapAndMovesAtConstantSpeed) {
  const auto s = dd::closingSchedule(0.9, 1.0, 3.0, 8);
  ASSERT_EQ(s.size(), 8u);
  for (int k = 0; k < 7; ++k) {
    EXPECT_DOUBLE_EQ(s[k].gap_m, 0.9 / std::pow(2.0, k));
    EXPECT_NEAR(s[k].time_s, 1.0 + 2.0 * (1.0 - std::pow(2.0, -k)), 1e-15);
  }
  EXPECT_EQ(s[7].gap_m, 0.0);
  EXPECT_DOUBLE_EQ(s[7].time_s, 3.0);
  const auto two = dd::closingSchedule(2.0, 0.0, 0.5, 2);
  EXPECT_EQ(two[0].gap_m, 2.0);
  EXPECT_EQ(two[0].time_s, 0.0);
  EXPECT_EQ(two[1].gap_m, 0.0);
  EXPECT_EQ(two[1].time_s, 0.5);
  EXPECT_THROW(dd::closingSchedule(0.9, 2.0, 1.0, 8), diffray::core::InputError);
  EXPECT_THROW(dd::closingSchedule(0.9, 0.0, 1.0, 1), diffray::core::InputError);
  EXPECT_THROW(dd::closingSchedule(0.9, NAN, 1.0, 4), diffray::core::InputError);
}

TEST(DoorClosing, AddScaledAddsBandByBand) {
  di::EnergyResponse a, b;
  a.bands = b.bands = diffray::core::Bands::octave();
  a.traced.assign(a.bands.size(), std::vector<double>(4, 1.0));
  b.traced.assign(b.bands.size(), std::vector<double>(3, 2.0));
  di::Arrival arr;
  arr.delay_s = 0.002;
  arr.energy = diffray::core::bandFill(3.0);
  b.arrivals.push_back(arr);
  diffray::core::BandArray f = diffray::core::bandFill(0.0);
  for (int i = 0; i < a.bands.size(); ++i) f[i] = 0.1 * (i + 1);
  dd::addScaled(a, b, f);
  for (int i = 0; i < a.bands.size(); ++i) {
    EXPECT_DOUBLE_EQ(a.traced[i][0], 1.0 + 2.0 * f[i]);
    EXPECT_DOUBLE_EQ(a.traced[i][3], 1.0);  // beyond b's length
    EXPECT_DOUBLE_EQ(a.arrivals.at(0).energy[i], 3.0 * f[i]);
    EXPECT_DOUBLE_EQ(dd::bandEnergies(a)[i], 4.0 + 6.0 * f[i] + 3.0 * f[i]);
  }
}

namespace {

// rooms/doorway.json with a panel material (absorption 0.3, τ_b = 10^−(b+1)/2) on its door, and two listeners
// 2.5 m behind the wall at ±0.3 m across the door (the door spans y ∈ [−0.45, 0.45] at x = 0), 1.2 m high (at
// the source's 1.5 m the floor reflection would meet the floor exactly at the foot of the wall).
dr::Room doorwayWithPanel() {
  std::ifstream in(std::string(DIFFRAY_SOURCE_DIR) + "/rooms/doorway.json");
  std::stringstream text;
  text << in.rdbuf();
  nlohmann::json scene = nlohmann::json::parse(text.str());
  nlohmann::json tau = nlohmann::json::array();
  for (int b = 0; b < 8; ++b) tau.push_back(std::pow(10.0, -0.5 * (b + 1)));
  scene["materials"]["panel"] = {{"absorption", 0.4}, {"scattering", 0.0}, {"transmission", tau}};
  scene["occluders"][0]["panel"] = "panel";
  scene["listeners"] = {{{"name", "low-y"}, {"position", {2.5, -0.3, 1.2}}, {"radius_m", 0.15}},
                        {{"name", "high-y"}, {"position", {2.5, 0.3, 1.2}}, {"radius_m", 0.15}}};
  scene["sources"][0]["position"] = {-2.5, 0.0, 1.5};
  scene["output"] = {{"rays", 20000}, {"seed", 3}, {"ism_order", 1}, {"ir_length_s", 0.05}};
  return dr::parseRoom(scene.dump(), "rooms/doorway-panel.json", std::string(DIFFRAY_SOURCE_DIR) + "/rooms", nullptr);
}

}  // namespace

TEST(DoorClosing, ShutDoorPassesItsPanelsTransmissionAndTheGapKeepsItsLineOfSight) {
  const dr::Room room = doorwayWithPanel();
  const int door = dd::findDoor(room, "");
  const dr::Occluder& d = room.occluders[door];
  const auto schedule = dd::closingSchedule(2.0 * d.half_x_m, 0.0, 1.0, 3);  // gaps 0.9, 0.45, 0
  dd::ClosingOptions opt;
  opt.diffraction = "none";
  const dd::ClosingResponse r = dd::simulateClosing(room, door, schedule, opt);
  ASSERT_EQ(r.responses.size(), 3u);
  // Which listener looks through the gap (at the −ex jamb) and which at the panel.
  const int through_gap = d.ex.y() > 0.0 ? 0 : 1, behind_panel = 1 - through_gap;
  for (int l = 0; l < 2; ++l) {
    const auto open = dd::bandEnergies(r.responses[0][l]);
    const auto shut = dd::bandEnergies(r.responses[2][l]);
    for (int b = 0; b < room.bands.size(); ++b) {
      ASSERT_GT(open[b], 0.0);
      const double tau = std::pow(10.0, -0.5 * (b + 1));
      EXPECT_NEAR(shut[b] / open[b], tau, 1e-9 * tau) << "listener " << l << " band " << b;
      EXPECT_DOUBLE_EQ(r.panel_transmission[b], tau);
    }
  }
  // Half shut: the direct sound (the order-0 arrival, 1/r² from the 1 W source, ir/response.h) stays for the
  // listener in view through the gap; behind the panel only what the panel passes is left, τ_b times the half
  // of the open door's energy it covers. The transmission model adds that share to every listener (it does not
  // trace which part of the doorway a path crossed), so the listener in view gets it on top: a 1 + τ/2 excess
  // (here τ = 0.32 at 63 Hz; a real panel's τ ≤ 0.03 makes it ≤ 0.07 dB).
  auto direct = [&](int step, int l) {
    double e = 0.0;
    for (const di::Arrival& a : r.responses[step][l].arrivals)
      if (a.order == 0) e += a.energy[0];
    return e;
  };
  const double r2 = (room.listeners[through_gap].position_m - room.sources[0].position_m).squaredNorm();
  const double free_field = 1.0 / r2;
  EXPECT_NEAR(direct(0, through_gap), free_field, 1e-3 * free_field);  // air absorption at 63 Hz: < 1e-4
  const double tau0 = std::pow(10.0, -0.5);
  EXPECT_NEAR(direct(1, through_gap), (1.0 + 0.5 * tau0) * direct(0, through_gap), 1e-12 * free_field);
  EXPECT_NEAR(direct(1, behind_panel), 0.5 * tau0 * direct(0, behind_panel), 1e-12 * free_field);
}

// The crossfade's key frames must increase strictly; the halving schedule bunches them at the end of the
// close, so a short close at a low rate runs out of samples. keyFrames refuses before any tracing and names
// the largest count that fits: that count's frames increase strictly (checked here directly), one more's not.
TEST(DoorClosing, KeyFramesRefuseStepsWithinOneSampleAndNameWhatFits) {
  const double fs = 16000.0, start = 1.0, end = 1.001, width = 0.9;
  const auto strictly = [&](int steps) {
    long last = -1;
    for (const auto& s : dd::closingSchedule(width, start, end, steps)) {
      const long key = std::lround(s.time_s * fs);
      if (key <= last) return false;
      last = key;
    }
    return true;
  };
  ASSERT_FALSE(strictly(8));
  std::string message;
  try {
    dd::keyFrames(dd::closingSchedule(width, start, end, 8), fs, width, start, end);
  } catch (const diffray::core::InputError& e) {
    message = e.what();
  }
  ASSERT_NE(message.find("--steps"), std::string::npos) << message;
  const auto at = message.find("at most ");
  ASSERT_NE(at, std::string::npos) << message;
  const int fits = std::stoi(message.substr(at + 8));
  EXPECT_TRUE(strictly(fits)) << message;
  EXPECT_FALSE(strictly(fits + 1)) << message;
  const auto keys = dd::keyFrames(dd::closingSchedule(width, start, end, fits), fs, width, start, end);
  EXPECT_EQ(keys.size(), static_cast<std::size_t>(fits));
  EXPECT_EQ(keys.front(), 16000);
}

// A door's IR has the same gain as a filter, whatever the dry signal's rate: its in-band power gain is
// Σh²·rate/(2B) (Parseval, energy inside the band B), so Σh²·rate must be the same at every rate. At 24 and
// 48 kHz the bands fit below Nyquist and the IR is synthesized at that rate; at 22.05 kHz the 8 kHz octave
// does not and it is synthesized at 48 kHz and resampled. Before, the 24 kHz IR was 3 dB weak (ratio 0.5).
// Tolerance 3 %: the realisations differ by rate, and each matches the band's energy to about 1 %.
TEST(DoorClosing, ImpulseResponseKeepsTheRoomRatesGainAtAnySignalRate) {
  di::EnergyResponse r;
  r.bands = diffray::core::Bands::octave();
  r.bin_s = 1e-3;
  r.traced.assign(static_cast<std::size_t>(r.bands.size()), std::vector<double>(400, 0.0));
  const int k1 = r.bands.find(1000);
  for (int i = 5; i < 400; ++i) r.traced[k1][i] = 1e-3 * std::exp(-13.8 * i * 1e-3 / 0.5);
  const auto gain = [&](double fs) {
    double sum = 0.0;
    for (float v : dd::impulseResponseFor(r, 48000.0, fs, 0.4, 200.0, 343.0, 3)) sum += static_cast<double>(v) * v;
    return sum * fs;
  };
  const double at_room_rate = gain(48000.0);
  for (double fs : {24000.0, 22050.0}) EXPECT_NEAR(gain(fs) / at_room_rate, 1.0, 0.03) << fs << " Hz";
}
