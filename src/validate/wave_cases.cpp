// Validation cases two-rooms-wave and classroom-wave: whole-room ray simulations (WBSDF portal, and no
// diffraction) against the 3D FDTD wave reference (reference/fdtd.h) in two rooms joined by an open door,
// per listener and octave band, through compare::compareRoom (the figures of `diffray compare ROOM
// --models none,wbsdf,wave`). The FDTD shares no code with the ray transport.
// Targets: the WBSDF's strength G within 1 dB of the wave's at every listener and band; its T30 within 5 %
// of the wave's; at the listeners hidden from the source, its early energy (the 20 ms from the direct-sound
// time) and its C50 closer to the wave's than the ray model without diffraction.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>

#include "diffray/compare/room_compare.h"
#include "diffray/compare/wave_model.h"
#include "diffray/core/error.h"
#include "diffray/validate/case.h"
#include "diffray/validate/two_room_setup.h"

namespace diffray::validate {

namespace {

constexpr std::uint64_t kWaveCaseRays = 100000;
constexpr double kLevelTargetDb = 1.0, kT30TargetPct = 5.0;

// A criterion's count: met over total.
struct Count {
  int met = 0, total = 0;
  void add(bool ok) { met += ok ? 1 : 0, total += 1; }
  bool all() const { return total > 0 && met == total; }
};

// Whether a is closer to the reference than b (both finite), as a count entry; NaN figures are not counted.
void closer(Count& c, double a, double b, double ref) {
  if (std::isfinite(a) && std::isfinite(b) && std::isfinite(ref)) c.add(std::abs(a - ref) < std::abs(b - ref));
}

std::vector<ParamSpec> waveParams(const TwoRoomSpec& d, double length_s) {
  std::vector<ParamSpec> ps = twoRoomParams(d);
  ps.push_back({"bands", {125, 250, 500}, "octave bands simulated by the wave reference (nominal Hz, up to 500)"});
  ps.back().list = true;
  ps.push_back({"ppw", {10}, "wave reference: grid points per wavelength at each band's upper edge", 4.0, true, 100.0});
  ps.push_back({"length", {length_s}, "impulse response length of every model (s, up to 10)", 0.0, false, 10.0 + 1e-9});
  return ps;
}

CaseResult runWaveCase(const std::string& name, const Params& p, const RunOptions& o, const TwoRoomSpec& base) {
  const auto t0 = std::chrono::steady_clock::now();
  const TwoRoomSpec spec = twoRoomFromParams(p, base);
  room::Room room = makeTwoRooms(spec);
  room.name = name;
  room.output.ir_length_s = p.at("length")[0];
  room.output.seed = o.seed;
  compare::RoomCompareOptions co;
  co.models = {"none", "wbsdf"};
  co.rays = o.rays ? o.rays : kWaveCaseRays;
  co.seed = o.seed;
  co.free_field = false;
  co.on_progress = o.on_progress;
  reference::WaveOptions wo;
  wo.bands_hz = p.at("bands");
  wo.ppw = p.at("ppw")[0];
  co.wave = compare::waveModel(wo);
  const compare::RoomComparison cmp = compare::compareRoom(room, co);
  const compare::RoomModelResult &none = cmp.models[0], &wbsdf = cmp.models[1], &wave = cmp.models[2];

  CaseResult r;
  r.name = name;
  r.rays = wbsdf.rays;
  r.errors_in_db = true;
  r.target_rel_peak = kLevelTargetDb;
  Count level, t30, early, c50;
  double worst_db = 0.0, sum2 = 0.0, worst_t30 = 0.0;
  int n = 0;
  for (std::size_t l = 0; l < room.listeners.size(); ++l) {
    const bool hidden = hiddenFromSource(spec, l);
    for (int b = 0; b < room.bands.size(); ++b) {
      const auto bi = static_cast<std::size_t>(b);
      const compare::RoomFigures &fw = wave.figures[l][bi], &fr = wbsdf.figures[l][bi], &fn = none.figures[l][bi];
      if (!std::isfinite(fw.g_db)) continue;  // a band the wave reference does not simulate
      Row row;
      row.x_m = room.listeners[l].position_m.x();
      row.y_m = room.listeners[l].position_m.y();
      row.traced = fr.g_db;
      row.reference = fw.g_db;
      row.alt_reference = fn.g_db;
      row.label = room.listeners[l].name + (hidden ? " (hidden)" : "") + " f=" + room.bands.label(b) + "Hz";
      r.rows.push_back(row);
      const double d = wbsdf.vs_wave[l][bi].g_db;
      level.add(std::abs(d) <= kLevelTargetDb);
      worst_db = std::max(worst_db, std::abs(d));
      sum2 += d * d, ++n;
      const double dt = wbsdf.vs_wave[l][bi].t30_pct;
      t30.add(std::isfinite(dt) && std::abs(dt) <= kT30TargetPct);
      if (std::isfinite(dt)) worst_t30 = std::max(worst_t30, std::abs(dt));
      if (hidden) {
        closer(early, fr.early_db, fn.early_db, fw.early_db);
        closer(c50, fr.c50_db, fn.c50_db, fw.c50_db);
      }
    }
  }
  if (r.rows.empty()) throw core::InputError("--bands", "the wave reference simulated none of the room's bands");
  r.max_abs_error_rel_peak = worst_db;
  r.rms_error_rel_peak = std::sqrt(sum2 / n);
  const auto put = [&](const std::string& key, const Count& c) {
    r.extra[key + "_met"] = c.met;
    r.extra[key + "_total"] = c.total;
  };
  put("g_within_1db", level);
  put("t30_within_5pct", t30);
  put("hidden_early_closer_than_none", early);
  put("hidden_c50_closer_than_none", c50);
  r.extra["worst_t30_error_pct"] = worst_t30;
  r.extra["wave_seconds"] = wave.seconds;
  r.extra["wbsdf_seconds"] = wbsdf.seconds;
  r.extra["none_seconds"] = none.seconds;
  // Without a hidden listener the early-energy criterion has nothing to hold and does not block.
  const bool hidden_ok = early.total == 0 || (early.all() && c50.all());
  r.passed = level.all() && t30.all() && hidden_ok;
  char buf[512];
  std::snprintf(buf, sizeof buf,
                "WBSDF vs FDTD wave: G within %.0f dB at %d/%d listener-bands (worst %.2f dB), T30 within %.0f %% at "
                "%d/%d (worst %.0f %%; no T30 counts as missed), hidden listeners closer than no diffraction: early %d/%d, C50 %d/%d",
                kLevelTargetDb, level.met, level.total, worst_db, kT30TargetPct, t30.met, t30.total, worst_t30,
                early.met, early.total, c50.met, c50.total);
  r.detail = buf;
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

std::vector<double> band8(std::initializer_list<double> v) { return v; }

CaseInfo waveCase(const std::string& name, const std::string& summary, const TwoRoomSpec& d, double length_s) {
  CaseInfo c{name, summary, waveParams(d, length_s), kWaveCaseRays, {}};
  c.run = [name, d](const Params& p, const RunOptions& o) { return runWaveCase(name, p, o, d); };
  return c;
}

}  // namespace

CaseInfo twoRoomsWaveCase() {
  // rooms/two-rooms.json: room A 6 x 5 x 3 m (damped office), room B 4 x 4 x 3 m (hard), a 0.2 m partition
  // with a door 0.9 x 2.1 m at y in [1, 1.9]; the materials of rooms/materials.json.
  TwoRoomSpec d;
  d.axis = 0;
  d.dims_a_m = {6, 5, 3};
  d.dims_b_m = {4, 4, 3};
  d.door_pos_m = 1.0;
  d.source_m = {2.0, 2.5, 1.5};
  d.listeners_m = {{4.5, 3.5, 1.2}, {8.5, 1.4, 1.2}, {9.0, 3.3, 1.2}};
  d.listener_names = {"A", "B-in-view", "B-hidden"};
  const auto plasterboard = band8({0.15, 0.15, 0.1, 0.06, 0.04, 0.04, 0.05, 0.05});
  const auto hard_wall = band8({0.02, 0.02, 0.02, 0.03, 0.03, 0.04, 0.05, 0.05});
  d.absorption = {band8({0.03, 0.03, 0.09, 0.25, 0.31, 0.33, 0.44, 0.44}),  // carpet-foam-underlay
                  band8({0.49, 0.49, 0.53, 0.53, 0.75, 0.92, 0.99, 0.99}),  // acoustic-ceiling-tile
                  plasterboard, plasterboard, plasterboard, plasterboard,
                  band8({0.01, 0.01, 0.01, 0.01, 0.02, 0.02, 0.02, 0.02}),  // ceramic-tiles
                  band8({0.01, 0.01, 0.01, 0.02, 0.02, 0.02, 0.05, 0.05}),  // concrete-smooth
                  hard_wall,
                  band8({0.27, 0.27, 0.23, 0.22, 0.15, 0.1, 0.07, 0.06})};  // wood-lining
  return waveCase("two-rooms-wave",
                  "rooms/two-rooms.json built from parameters: WBSDF and no-diffraction room simulations vs the FDTD "
                  "wave reference, 125-500 Hz (G, T30, hidden listener's early energy and C50); about 2 min on 2 cores",
                  d, 4.0);
}

CaseInfo classroomWaveCase() {
  // rooms/classroom.json: classroom 9 x 7 x 3.2 m, corridor 12 x 2 x 3.2 m from x = -1.5 behind a 0.2 m
  // wall (y in [7, 7.2]) with a door 0.9 x 2.1 m at x in [7, 7.9].
  TwoRoomSpec d;
  d.axis = 1;
  d.dims_a_m = {9, 7, 3.2};
  d.dims_b_m = {12, 2, 3.2};
  d.b_offset_m = -1.5;
  d.door_pos_m = 7.0;
  d.source_m = {1.2, 3.5, 1.6};
  d.listeners_m = {{3.5, 2.0, 1.2}, {5.5, 4.5, 1.2}, {7.5, 2.5, 1.2}, {9.3, 8.2, 1.2}, {5.5, 8.4, 1.2}};
  d.listener_names = {"student-1", "student-2", "student-3", "corridor-in-view", "corridor-hidden"};
  const auto plasterboard = band8({0.15, 0.15, 0.1, 0.06, 0.04, 0.04, 0.05, 0.05});
  d.absorption = {band8({0.02, 0.02, 0.04, 0.08, 0.2, 0.35, 0.4, 0.4}),       // carpet-on-concrete
                  band8({0.49, 0.49, 0.53, 0.53, 0.75, 0.92, 0.99, 0.99}),    // acoustic-ceiling-tile
                  plasterboard,                                               // front wall (board)
                  band8({0.46, 0.46, 0.93, 1.0, 1.0, 1.0, 1.0, 1.0}),         // rear: mineral-wool-panel
                  band8({0.1, 0.1, 0.05, 0.04, 0.03, 0.03, 0.03, 0.03}),      // windows: glass-window
                  plasterboard,                                               // corridor wall
                  band8({0.01, 0.01, 0.03, 0.05, 0.02, 0.02, 0.02, 0.02}),    // concrete-floor
                  band8({0.01, 0.01, 0.01, 0.02, 0.02, 0.02, 0.05, 0.05}),    // concrete-smooth
                  band8({0.01, 0.01, 0.01, 0.02, 0.02, 0.02, 0.02, 0.02}),    // brick-painted
                  band8({0.27, 0.27, 0.23, 0.22, 0.15, 0.1, 0.07, 0.06})};    // wood-lining
  return waveCase("classroom-wave",
                  "rooms/classroom.json built from parameters: WBSDF and no-diffraction room simulations vs the FDTD "
                  "wave reference, 125-500 Hz (G, T30, hidden listener's early energy and C50); about 4 min on 2 cores",
                  d, 4.0);
}

}  // namespace diffray::validate
