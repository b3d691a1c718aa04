// `diffray compare` in room mode (compare/room_compare.h) and the shipped classroom: the figures of a
// histogram against closed forms of an exponential decay written here; the room comparison on the
// two-rooms scene at a few thousand rays (every model, every listener); the rule for where the free-field
// aperture reference applies, against the door's plane as the scene file states it; errors that name the
// listener and model; the wave-model slot with a stub whose histograms (and so whose figures) are known in
// closed form; rooms/classroom.json's listeners against its description, by a brute-force segment–triangle
// test (Möller–Trumbore, written here).
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "diffray/compare/point_models.h"
#include "diffray/compare/room_compare.h"
#include "diffray/compare/scene_compare.h"
#include "diffray/core/error.h"
#include "diffray/room/air.h"
#include "diffray/room/scene_file.h"

namespace {

namespace dc = diffray::compare;
namespace dr = diffray::room;
using diffray::core::Vec3;

const std::string kRooms = std::string(DIFFRAY_SOURCE_DIR) + "/rooms/";
constexpr double kLn10 = 2.302585092994046;

// Σ_{k=a}^{b−1} q^k.
double geometricSum(double q, long a, long b) { return (std::pow(q, a) - std::pow(q, b)) / (1.0 - q); }

// An exponential decay of reverberation time t60_s: q^k from bin `start` to bin `bins` − 1 (zero before), times amp.
std::vector<double> decay(double t60_s, double bin_s, long start, long bins, double amp) {
  const double q = std::exp(-6.0 * kLn10 / t60_s * bin_s);
  std::vector<double> h(static_cast<std::size_t>(bins), 0.0);
  for (long k = start; k < bins; ++k) h[static_cast<std::size_t>(k)] = amp * std::pow(q, k);
  return h;
}

// two-rooms.json made quick: a few thousand rays, first-order image sources, a fixed length.
dr::Room quickTwoRooms() {
  dr::Room room = dr::loadRoom(kRooms + "two-rooms.json");
  room.output.rays = 3000;
  room.output.ism_order = 1;
  room.output.ir_length_s = 0.4;
  return room;
}

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

// `none` against a stub wave model whose histogram of listener l in band b is band(l, b), bins of bin_s.
dc::RoomCompareOptions noneAgainstStub(std::function<std::vector<double>(std::size_t, int)> band, double bin_s) {
  dc::RoomCompareOptions o;
  o.models = {"none"};
  o.free_field = false;
  o.wave = [band = std::move(band), bin_s](const dr::Room& r) {
    dc::ListenerHistograms h;
    h.bin_s = bin_s;
    h.energy.resize(r.listeners.size());
    for (std::size_t l = 0; l < r.listeners.size(); ++l)
      for (int b = 0; b < r.bands.size(); ++b) h.energy[l].push_back(band(l, b));
    return h;
  };
  return o;
}

// ---- the figures of one listener's histograms ------------------------------------------------------------

TEST(CompareRoomFigures, ExponentialDecayGivesTheClosedForms) {
  // One band q^k from bin 0 (the onset), T = 0.8 s, 1 ms bins, 3 s long (the tail beyond is q^3000 ≈ 1e-23 of
  // the first bin); a second band empty. G = 10 log10(Σ/E10), early over bins 12..31 (direct time 12.5 ms),
  // C50 = 10 log10(Σ_{k<50}/Σ_{k≥50}) = 10 log10(q^−50 − 1); the Schroeder curve of an exponential is a line,
  // so EDT = T30 = T up to rounding.
  const double t60 = 0.8, bin = 0.001, e10 = 0.01;
  const double q = std::exp(-6.0 * kLn10 / t60 * bin);
  const std::vector<std::vector<double>> h{decay(t60, bin, 0, 3000, 1.0), {}};
  const auto f = dc::roomFigures(h, bin, 0.0125, e10);
  ASSERT_EQ(f.size(), 2u);
  EXPECT_NEAR(f[0].g_db, 10.0 * std::log10(geometricSum(q, 0, 3000) / e10), 1e-9);
  EXPECT_NEAR(f[0].early_db, 10.0 * std::log10(geometricSum(q, 12, 32) / e10), 1e-9);
  EXPECT_NEAR(f[0].c50_db, 10.0 * std::log10(std::pow(q, -50) - 1.0), 1e-6);
  EXPECT_NEAR(f[0].c80_db, 10.0 * std::log10(std::pow(q, -80) - 1.0), 1e-6);
  EXPECT_NEAR(f[0].t30_s, t60, 1e-6 * t60);
  EXPECT_NEAR(f[0].edt_s, t60, 1e-6 * t60);
  EXPECT_TRUE(std::isnan(f[1].g_db) && std::isnan(f[1].t30_s) && std::isnan(f[1].early_db));
}

TEST(CompareRoomFigures, TheEarlyWindowOpensItsLeadBeforeTheDirectSound) {
  // Direct-sound time 30.4 ms (bin 30), window to bin 49; a lead of 4.2 ms opens it at bin 26 (26.2 ms). One
  // unit of energy in each of bins 25 … 50: the early energy is bins 26 … 49, 24 units; without a lead 30 … 49.
  const double bin = 0.001, e10 = 1.0;
  const std::vector<std::vector<double>> h{[] {
    std::vector<double> v(80, 0.0);
    for (int k = 25; k <= 50; ++k) v[static_cast<std::size_t>(k)] = 1.0;
    return v;
  }()};
  EXPECT_NEAR(dc::roomFigures(h, bin, 0.0304, e10, {0.0042})[0].early_db, 10.0 * std::log10(24.0), 1e-12);
  EXPECT_NEAR(dc::roomFigures(h, bin, 0.0304, e10)[0].early_db, 10.0 * std::log10(20.0), 1e-12);
}

TEST(CompareRoomFigures, DifferencesAreDbAndPercent) {
  dc::RoomFigures m, r;
  m.g_db = 3.0, r.g_db = 1.0, m.early_db = -2.0, r.early_db = 1.0;
  m.edt_s = 1.1, r.edt_s = 1.0, m.t30_s = 0.9, r.t30_s = 1.2, m.c50_db = 2.0, r.c50_db = 0.5;
  const dc::FigureDifference d = dc::figureDifference(m, r);
  EXPECT_DOUBLE_EQ(d.g_db, 2.0);
  EXPECT_DOUBLE_EQ(d.early_db, -3.0);
  EXPECT_NEAR(d.edt_pct, 10.0, 1e-12);
  EXPECT_NEAR(d.t30_pct, -25.0, 1e-12);
  EXPECT_DOUBLE_EQ(d.c50_db, 1.5);
  EXPECT_TRUE(std::isnan(d.c80_db));
}

// ---- the room comparison ----------------------------------------------------------------------------------

TEST(CompareRoom, TwoRoomsRunsEveryModelForEveryListener) {
  const dr::Room room = quickTwoRooms();
  ASSERT_TRUE(dc::isEnclosedRoom(room));
  dc::RoomCompareOptions o;
  o.band_points = 1;
  const dc::RoomComparison c = dc::compareRoom(room, o);
  ASSERT_EQ(c.models.size(), 3u);
  for (std::size_t m = 0; m < 3; ++m) {
    EXPECT_EQ(c.models[m].model, o.models[m]);
    EXPECT_EQ(c.models[m].rays, 3000u);
    EXPECT_TRUE(c.models[m].vs_wave.empty());  // no wave model given
    ASSERT_EQ(c.models[m].figures.size(), room.listeners.size());
    for (std::size_t l = 0; l < room.listeners.size(); ++l) {
      ASSERT_EQ(c.models[m].figures[l].size(), static_cast<std::size_t>(room.bands.size()));
      // Listener A shares the source's room: every model hears its direct sound, so every band has energy.
      // (In room B the WBSDF's signed weights may leave a band ≤ 0 at 3000 rays: G is then NaN, not −inf.)
      for (const auto& f : c.models[m].figures[l])
        if (l == 0 || c.models[m].model != "wbsdf") {
          EXPECT_TRUE(std::isfinite(f.g_db)) << c.models[m].model << " " << l;
        }
    }
  }
  // The free-field reference: not for A (the source's room), for both listeners of room B; on the G scale it
  // is the reference's level re the free field at the listener's distance r plus 20 log10(10 m / r).
  ASSERT_EQ(c.free_field.size(), 3u);
  EXPECT_TRUE(c.free_field[0].g_db.empty());
  const double speed = dr::speedOfSound(room.air);
  std::string why, assumption;
  const auto exact = dc::exactModelFor(room, speed, why, assumption, true);
  ASSERT_TRUE(exact);
  for (std::size_t l : {1u, 2u}) {
    ASSERT_EQ(c.free_field[l].g_db.size(), static_cast<std::size_t>(room.bands.size()));
    const Vec3 s = room.sources[0].position_m, p = room.listeners[l].position_m;
    for (int b = 0; b < room.bands.size(); b += 7) {
      const double rel = dc::bandRelativeEnergy(*exact, s, p, room.listeners[l].radius_m, room.bands.lowerHz(b),
                                                room.bands.upperHz(b), 1);
      EXPECT_NEAR(c.free_field[l].g_db[static_cast<std::size_t>(b)], 10.0 * std::log10(rel) + 20.0 * std::log10(10.0 / (p - s).norm()), 1e-9);
    }
  }
  // The direct-sound time of each listener: its distance to the source over the speed of sound.
  for (std::size_t l = 0; l < 3; ++l)
    EXPECT_NEAR(c.direct_s[l], (room.listeners[l].position_m - room.sources[0].position_m).norm() / speed, 1e-12);
}

TEST(CompareRoom, WhichScenesAreRooms) {
  EXPECT_TRUE(dc::isEnclosedRoom(dr::loadRoom(kRooms + "two-rooms.json")));
  EXPECT_TRUE(dc::isEnclosedRoom(dr::loadRoom(kRooms + "classroom.json")));
  EXPECT_TRUE(dc::isEnclosedRoom(dr::loadRoom(kRooms + "shoebox.json")));
  EXPECT_FALSE(dc::isEnclosedRoom(dr::loadRoom(kRooms + "doorway.json")));
  EXPECT_FALSE(dc::isEnclosedRoom(dr::loadRoom(kRooms + "barrier.json")));
}

// ---- where the free-field reference applies ----------------------------------------------------------------

TEST(CompareRoom, FreeFieldReferenceOnlyBeyondTheDoorPlane) {
  // two-rooms.json: the doorway is the rectangle x = 6.1 (rooms/README.md); the source at x = 2. A listener applies
  // when its whole sphere (radius 0.5 m) lies at x > 6.1.
  dr::Room room = dr::loadRoom(kRooms + "two-rooms.json");
  const auto rule = [&](int l) { return dc::freeFieldApplicability(room, l); };
  for (int l = 0; l < 3; ++l) {
    const double x = room.listeners[static_cast<std::size_t>(l)].position_m.x();
    const bool beyond = x - 0.5 > 6.1;
    const dc::FreeFieldReference f = rule(l);
    EXPECT_EQ(f.applies, beyond) << l;
    EXPECT_EQ(f.shadow_angle_deg.has_value(), beyond) << l;
    EXPECT_EQ(f.why_not.empty(), beyond) << l;
  }
  EXPECT_TRUE(contains(rule(0).why_not, "source's side"));
  room.listeners[1].position_m = Vec3(6.4, 1.4, 1.2);  // beyond the plane, but its sphere reaches it
  EXPECT_FALSE(rule(1).applies);
  EXPECT_TRUE(contains(rule(1).why_not, "sphere"));
  room.occluders.clear();
  EXPECT_FALSE(rule(2).applies);
  EXPECT_TRUE(contains(rule(2).why_not, "exactly one"));
}

TEST(CompareRoom, FreeFieldModeGivesNoShadowAngleOnTheSourcesSide) {
  // The door's plane is x = 6.1 with the source at x = 2: listener A (x = 4.5) has no shadow boundary.
  dc::CompareOptions fo;
  fo.models = {"utd"};
  fo.band_points = 1;
  fo.fine_per_octave = 1;
  const dc::SceneComparison c = dc::compareScene(quickTwoRooms(), fo);
  ASSERT_EQ(c.shadow_angle_deg.size(), 3u);
  EXPECT_FALSE(c.shadow_angle_deg[0].has_value());
  EXPECT_TRUE(c.shadow_angle_deg[1].has_value() && c.shadow_angle_deg[2].has_value());
  ASSERT_EQ(c.warnings.size(), 1u);  // the closed-room note, not "B-hidden is outside the room"
  EXPECT_TRUE(contains(c.warnings[0], "closed room")) << c.warnings[0];
}

// ---- errors name the listener and the model ----------------------------------------------------------------

template <class F>
std::string inputErrorOf(F&& f) {
  try {
    f();
  } catch (const diffray::core::InputError& e) {
    return e.what();
  }
  return "";
}

TEST(CompareRoom, ErrorsNameTheListenerAndModel) {
  // Free-field mode on a room: the aperture reference for listener A (the source's room) is refused by name.
  dc::CompareOptions fo;
  fo.models = {"exact"};
  fo.band_points = 1;
  fo.fine_per_octave = 1;
  const std::string free = inputErrorOf([&] { dc::compareScene(quickTwoRooms(), fo); });
  EXPECT_TRUE(contains(free, "listener A") && contains(free, "model exact")) << free;

  // A wave model whose histograms do not fit the room, or hold a NaN.
  const dr::Room room = quickTwoRooms();
  dc::RoomCompareOptions o;
  o.models = {};
  o.free_field = false;
  o.wave = [](const dr::Room& r) {
    dc::ListenerHistograms h;
    h.energy.assign(r.listeners.size(), std::vector<std::vector<double>>(static_cast<std::size_t>(r.bands.size())));
    h.energy[1].pop_back();
    return h;
  };
  const std::string shape = inputErrorOf([&] { dc::compareRoom(room, o); });
  EXPECT_TRUE(contains(shape, "listener B-in-view") && contains(shape, "model wave")) << shape;
  o.wave = [](const dr::Room& r) {
    dc::ListenerHistograms h;
    h.energy.assign(r.listeners.size(), std::vector<std::vector<double>>(static_cast<std::size_t>(r.bands.size()),
                                                                        std::vector<double>(100, 1e-3)));
    h.energy[2][0][5] = std::numeric_limits<double>::quiet_NaN();
    return h;
  };
  const std::string nan = inputErrorOf([&] { dc::compareRoom(room, o); });
  EXPECT_TRUE(contains(nan, "listener B-hidden") && contains(nan, "model wave")) << nan;
}

// ---- the wave-model slot -----------------------------------------------------------------------------------

TEST(CompareRoom, TheEarlyWindowLeadsByTheSphereAndTheBandFilter) {
  // The stub: per listener and band one unit of energy in the first bin of the early window by its
  // definition (R/c + 1/Δf before the direct-sound time, Δf the band's width) and one in the bin before it.
  // Only the first is early energy.
  const dr::Room room = quickTwoRooms();
  const double speed = dr::speedOfSound(room.air), bin = 0.001;
  auto first = [&](std::size_t l, int b) {
    const dr::Listener& li = room.listeners[l];
    const double direct = (li.position_m - room.sources[0].position_m).norm() / speed;
    const double lead = li.radius_m / speed + 1.0 / (room.bands.upperHz(b) - room.bands.lowerHz(b));
    return static_cast<long>(std::floor((direct - lead) / bin));
  };
  const dc::RoomCompareOptions o = noneAgainstStub(
      [&](std::size_t l, int b) {
        std::vector<double> v(200, 0.0);
        const long k = first(l, b);
        if (k >= 1) v[static_cast<std::size_t>(k)] = v[static_cast<std::size_t>(k - 1)] = 1.0;
        else v[0] = 1.0;  // the window opens before emission (a near listener, a low band): all is early
        return v;
      },
      bin);
  const dc::RoomComparison c = dc::compareRoom(room, o);
  const double e10 = 1.0 / 100.0;
  int checked = 0;
  for (std::size_t l = 0; l < room.listeners.size(); ++l)
    for (int b = 0; b < room.bands.size(); ++b) {
      const dc::RoomFigures& w = c.models[1].figures[l][static_cast<std::size_t>(b)];
      EXPECT_NEAR(w.early_db, 10.0 * std::log10(1.0 / e10), 1e-9) << l << " " << b;
      EXPECT_NEAR(w.g_db, 10.0 * std::log10((first(l, b) >= 1 ? 2.0 : 1.0) / e10), 1e-9) << l << " " << b;
      checked += first(l, b) >= 1 ? 1 : 0;
    }
  EXPECT_GE(checked, 12);  // most listener-bands have a bin before the window
}

TEST(CompareRoom, WaveSlotGivesEachRayModelsDifference) {
  // The stub: per listener l, in the four bands 63–500 Hz, an exponential decay (T = 1.2 s) starting two bins
  // after the direct-sound bin, amplitude 0.05·(l + 1); the other bands empty (not covered). Its G, early
  // energy and T30 follow in closed form; the differences must be the ray model's figures minus those.
  dr::Room room = quickTwoRooms();
  room.output.ir_length_s = 3.0;  // T30 of room B (about 2.5 s) needs 45 dB of decay
  const double speed = dr::speedOfSound(room.air), bin = 0.001, t60 = 1.2, e10 = 1.0 / 100.0;
  const double q = std::exp(-6.0 * kLn10 / t60 * bin);
  const long bins = 4000;
  std::vector<long> k_direct;
  for (const auto& li : room.listeners)
    k_direct.push_back(static_cast<long>(std::floor((li.position_m - room.sources[0].position_m).norm() / speed / bin)));
  const dc::RoomCompareOptions o = noneAgainstStub(
      [&](std::size_t l, int b) {
        return b < 4 ? decay(t60, bin, k_direct[l] + 2, bins, 0.05 * static_cast<double>(l + 1)) : std::vector<double>();
      },
      bin);
  const dc::RoomComparison c = dc::compareRoom(room, o);
  ASSERT_EQ(c.models.size(), 2u);
  ASSERT_EQ(c.models[1].model, "wave");
  EXPECT_TRUE(c.models[1].vs_wave.empty());
  const dc::RoomModelResult& none = c.models[0];
  ASSERT_EQ(none.vs_wave.size(), room.listeners.size());
  int t30_checked = 0, c50_checked = 0;
  for (std::size_t l = 0; l < room.listeners.size(); ++l) {
    const double amp = 0.05 * static_cast<double>(l + 1);
    const long k0 = k_direct[l];
    const double wave_g = 10.0 * std::log10(amp * geometricSum(q, k0 + 2, bins) / e10);
    const double wave_early = 10.0 * std::log10(amp * geometricSum(q, k0 + 2, k0 + 20) / e10);
    for (std::size_t b = 0; b < static_cast<std::size_t>(room.bands.size()); ++b) {
      const dc::RoomFigures& m = none.figures[l][b];
      const dc::FigureDifference& d = none.vs_wave[l][b];
      if (b >= 4) {  // not covered by the wave model
        EXPECT_TRUE(std::isnan(d.g_db) && std::isnan(d.t30_pct) && std::isnan(c.models[1].figures[l][b].g_db));
        continue;
      }
      // The wave model's own figures are the closed forms (C50 = 10 log10(q^−50 − 1) from its onset) ...
      const dc::RoomFigures& w = c.models[1].figures[l][b];
      EXPECT_NEAR(w.g_db, wave_g, 1e-9) << l << " " << b;
      EXPECT_NEAR(w.early_db, wave_early, 1e-9) << l << " " << b;
      EXPECT_NEAR(w.t30_s, t60, 1e-6 * t60) << l << " " << b;
      EXPECT_NEAR(w.c50_db, 10.0 * std::log10(std::pow(q, -50) - 1.0), 1e-6) << l << " " << b;
      // ... and the differences are the ray model's figures minus them (NaN where the model has none).
      EXPECT_NEAR(d.g_db, m.g_db - wave_g, 1e-9) << l << " " << b;
      EXPECT_NEAR(d.early_db, m.early_db - wave_early, 1e-9) << l << " " << b;
      EXPECT_EQ(std::isfinite(d.t30_pct), std::isfinite(m.t30_s));
      EXPECT_EQ(std::isfinite(d.c50_db), std::isfinite(m.c50_db));
      if (std::isfinite(m.t30_s)) {
        EXPECT_NEAR(d.t30_pct, 100.0 * (m.t30_s - t60) / t60, 1e-4) << l << " " << b;
        ++t30_checked;
      }
      if (std::isfinite(m.c50_db)) {
        EXPECT_NEAR(d.c50_db, m.c50_db - 10.0 * std::log10(std::pow(q, -50) - 1.0), 1e-6) << l << " " << b;
        ++c50_checked;
      }
    }
  }
  EXPECT_GT(t30_checked, 6);  // the model's decays are long enough for most of them to be measured
  EXPECT_GT(c50_checked, 6);
}

// ---- rooms/classroom.json -----------------------------------------------------------------------------------

// Whether the open segment p → q crosses triangle abc (Möller–Trumbore, edges included).
bool segmentCrosses(const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 d = q - p, e1 = b - a, e2 = c - a, h = d.cross(e2);
  const double det = e1.dot(h);
  if (std::abs(det) < 1e-14) return false;
  const Vec3 s = p - a;
  const double u = s.dot(h) / det;
  if (u < 0.0 || u > 1.0) return false;
  const Vec3 qv = s.cross(e1);
  const double v = d.dot(qv) / det;
  if (v < 0.0 || u + v > 1.0) return false;
  const double t = e2.dot(qv) / det;
  return t > 1e-9 && t < 1.0 - 1e-9;
}

// The groups of the triangles the segment p → q crosses.
std::vector<std::string> crossedGroups(const dr::Room& room, const Vec3& p, const Vec3& q) {
  std::vector<std::string> out;
  const auto& m = room.mesh;
  for (std::size_t i = 0; i < m.triangles.size(); ++i) {
    const auto& t = m.triangles[i];
    if (segmentCrosses(p, q, m.vertices[static_cast<std::size_t>(t[0])], m.vertices[static_cast<std::size_t>(t[1])],
                       m.vertices[static_cast<std::size_t>(t[2])]))
      out.push_back(room.group_of_triangle[i]);
  }
  return out;
}

bool sphereInBox(const dr::Listener& l, const Vec3& lo, const Vec3& hi) {
  for (int i = 0; i < 3; ++i)
    if (l.position_m[i] - l.radius_m < lo[i] || l.position_m[i] + l.radius_m > hi[i]) return false;
  return true;
}

TEST(ClassroomScene, LoadsCleanAndItsListenersAreWhereTheDescriptionSays) {
  std::vector<std::string> warnings;
  const dr::Room room = dr::loadRoom(kRooms + "classroom.json", &warnings);
  EXPECT_TRUE(warnings.empty()) << warnings.front();
  // The boxes of the description (tools/make_rooms.py): classroom, corridor; the door x ∈ [7, 7.9], z ≤ 2.1.
  const Vec3 class_lo(0, 0, 0), class_hi(9, 7, 3.2), corr_lo(-1.5, 7.2, 0), corr_hi(10.5, 9.2, 3.2);
  EXPECT_NEAR(room.volume(), 9 * 7 * 3.2 + 12 * 2 * 3.2 + 0.9 * 0.2 * 2.1, 1e-6);
  ASSERT_EQ(room.sources.size(), 1u);
  const Vec3 s = room.sources[0].position_m;
  EXPECT_EQ(room.sources[0].name, "teacher");
  EXPECT_LT(s.x(), 2.0);  // at the front (the board wall x = 0)
  ASSERT_EQ(room.occluders.size(), 1u);
  const dr::Occluder& door = room.occluders[0];
  EXPECT_EQ(door.type, "door");
  EXPECT_NEAR(2 * door.half_x_m, 0.9, 1e-9);
  EXPECT_NEAR(2 * door.half_y_m, 2.1, 1e-9);
  EXPECT_NEAR(std::abs(door.normal.y()), 1.0, 1e-12);
  EXPECT_NEAR(door.origin_m.y(), 7.1, 1e-9);
  const std::vector<std::string> names{"student-1", "student-2", "student-3", "corridor-in-view", "corridor-hidden"};
  ASSERT_EQ(room.listeners.size(), names.size());
  for (std::size_t l = 0; l < names.size(); ++l) {
    const dr::Listener& li = room.listeners[l];
    EXPECT_EQ(li.name, names[l]);
    EXPECT_DOUBLE_EQ(li.radius_m, 0.5);
    const bool student = l < 3;
    EXPECT_TRUE(student ? sphereInBox(li, class_lo, class_hi) : sphereInBox(li, corr_lo, corr_hi)) << li.name;
    const std::vector<std::string> crossed = crossedGroups(room, s, li.position_m);
    if (student) {
      EXPECT_TRUE(crossed.empty()) << li.name << " does not see the teacher";
    }
  }
  // In view: the line from the teacher crosses the door's opening and nothing else.
  const std::vector<std::string> in_view = crossedGroups(room, s, room.listeners[3].position_m);
  EXPECT_FALSE(in_view.empty());
  for (const auto& g : in_view) EXPECT_EQ(g, "door");
  // Hidden: no point of its sphere (the centre, the six axis points, the eight diagonal points on the
  // surface) sees the teacher through the door: each line meets a wall.
  const dr::Listener& hidden = room.listeners[4];
  std::vector<Vec3> points{hidden.position_m};
  for (int i = 0; i < 3; ++i)
    for (double sg : {-1.0, 1.0}) points.push_back(hidden.position_m + sg * hidden.radius_m * Vec3::Unit(i));
  for (double a : {-1.0, 1.0})
    for (double b : {-1.0, 1.0})
      for (double cz : {-1.0, 1.0}) points.push_back(hidden.position_m + hidden.radius_m / std::sqrt(3.0) * Vec3(a, b, cz));
  for (const Vec3& p : points) {
    bool blocked = false;
    for (const auto& g : crossedGroups(room, s, p)) blocked = blocked || g != "door";
    EXPECT_TRUE(blocked) << "(" << p.x() << ", " << p.y() << ", " << p.z() << ")";
  }
  EXPECT_LT(hidden.position_m.x(), 7.0);  // beside the door's jamb at x = 7, on the side away from the view line
}

}  // namespace
