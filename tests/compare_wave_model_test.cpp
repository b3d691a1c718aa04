// The FDTD reference as a room comparison's wave model (compare/wave_model.h): its histograms land in their
// room bands (the others empty), and compareRoom runs it beside the ray models, its figures defined in the
// bands it simulates only.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "diffray/compare/wave_model.h"
#include "diffray/room/scene_file.h"

namespace dc = diffray::compare;
namespace dr = diffray::room;
namespace dref = diffray::reference;

TEST(CompareWaveModel, HistogramsLandInTheirRoomBands) {
  dr::Room room;
  room.listeners = {{"a", {0, 0, 0}, 0.1}, {"b", {1, 0, 0}, 0.1}};
  dref::WaveResult r;
  r.plan.bin_s = 0.002;
  r.plan.bands.resize(2);
  r.plan.bands[0].band = 1;
  r.plan.bands[1].band = 3;
  r.listeners.resize(2);
  for (int l = 0; l < 2; ++l) r.listeners[l].energy = {{1.0 + l, 2.0}, {3.0 + l}};
  const dc::ListenerHistograms h = dc::waveHistograms(room, r);
  EXPECT_EQ(h.bin_s, 0.002);
  ASSERT_EQ(h.energy.size(), 2u);
  for (int l = 0; l < 2; ++l) {
    ASSERT_EQ(h.energy[l].size(), static_cast<std::size_t>(room.bands.size()));
    EXPECT_EQ(h.energy[l][1], (std::vector<double>{1.0 + l, 2.0}));
    EXPECT_EQ(h.energy[l][3], (std::vector<double>{3.0 + l}));
    for (int b : {0, 2, 4, 5, 6, 7}) EXPECT_TRUE(h.energy[l][b].empty()) << b;
  }
}

TEST(CompareWaveModel, CompareRoomRunsTheWaveReferenceInItsBands) {
  dr::Room room = dr::loadRoom(std::string(DIFFRAY_SOURCE_DIR) + "/rooms/two-rooms.json");
  room.output.rays = 3000;
  room.output.ism_order = 1;
  room.output.ir_length_s = 0.3;
  dref::WaveOptions wo;
  wo.bands_hz = {63};
  dc::RoomCompareOptions o;
  o.models = {"none"};
  o.free_field = false;
  o.wave = dc::waveModel(wo);
  const dc::RoomComparison c = dc::compareRoom(room, o);
  ASSERT_EQ(c.models.size(), 2u);
  EXPECT_EQ(c.models[1].model, "wave");
  for (std::size_t l = 0; l < room.listeners.size(); ++l) {
    EXPECT_TRUE(std::isfinite(c.models[1].figures[l][0].g_db)) << l;
    EXPECT_TRUE(std::isnan(c.models[1].figures[l][1].g_db)) << l;
    EXPECT_TRUE(std::isfinite(c.models[0].vs_wave[l][0].g_db)) << l;
    EXPECT_TRUE(std::isnan(c.models[0].vs_wave[l][1].g_db)) << l;
  }
}
