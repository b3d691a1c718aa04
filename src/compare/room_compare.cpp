#include "diffray/compare/room_compare.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include <tbb/parallel_for.h>

#include "diffray/compare/point_models.h"
#include "diffray/compare/scene_compare.h"
#include "diffray/core/error.h"
#include "diffray/ir/metrics.h"
#include "diffray/room/air.h"
#include "diffray/room/checks.h"
#include "diffray/transport/room_simulation.h"

namespace diffray::compare {

using core::Vec3;
using Kind = room::OccluderAxis::Kind;

namespace {

constexpr double kEarlyWindowS = 0.020;  // the early energy's window after the direct-sound time

double db(double ratio) { return ratio > 0.0 ? 10.0 * std::log10(ratio) : RoomFigures::kNaN; }

double percent(double model, double reference) {
  return std::isfinite(model) && std::isfinite(reference) && reference != 0.0 ? 100.0 * (model - reference) / reference
                                                                              : FigureDifference::kNaN;
}

// "listener NAME: model M" (every error about one listener's figures names both).
std::string where(const room::Room& room, int l, const std::string& model) {
  return "listener " + room.listeners[static_cast<std::size_t>(l)].name + ": model " + model;
}

// The figures of every listener of a model from its histograms, and its differences from the wave model.
std::vector<std::vector<RoomFigures>> figuresOf(const room::Room& room, const std::string& model,
                                                const std::vector<std::vector<std::vector<double>>>& energy,
                                                double bin_s, const std::vector<double>& direct_s, double e10) {
  std::vector<std::vector<RoomFigures>> out;
  const double c = room::speedOfSound(room.air);
  for (std::size_t l = 0; l < room.listeners.size(); ++l) {
    // The early window opens before the direct-sound time by what spreads an arrival ahead of it: the
    // listener sphere (an arrival crosses it over ±R/c about its centre's time) and the wave reference's
    // band filter (about ±1/Δf, Δf the band's width). No model has energy sooner than the direct sound's
    // time less R/c, so the lead only gathers what these spreads moved ahead (room_compare.h).
    std::vector<double> lead_s;
    for (int b = 0; b < room.bands.size(); ++b)
      lead_s.push_back(room.listeners[l].radius_m / c + 1.0 / (room.bands.upperHz(b) - room.bands.lowerHz(b)));
    try {
      out.push_back(roomFigures(energy[l], bin_s, direct_s[l], e10, lead_s));
    } catch (const core::InputError& e) {
      throw core::InputError(where(room, static_cast<int>(l), model), e.what());
    }
  }
  return out;
}

// The wave model's histograms, checked against the room's listeners and bands.
ListenerHistograms runWave(const room::Room& room, const HistogramModel& wave) {
  ListenerHistograms h = wave(room);
  if (!(h.bin_s > 0.0) || !std::isfinite(h.bin_s))
    throw core::InputError("model wave", "its histogram bin width must be > 0 s, got " + std::to_string(h.bin_s));
  if (h.energy.size() != room.listeners.size())
    throw core::InputError("model wave", "gave histograms for " + std::to_string(h.energy.size()) +
                                             " listeners, the room has " + std::to_string(room.listeners.size()));
  for (std::size_t l = 0; l < h.energy.size(); ++l)
    if (h.energy[l].size() != static_cast<std::size_t>(room.bands.size()))
      throw core::InputError(where(room, static_cast<int>(l), "wave"),
                             "gave " + std::to_string(h.energy[l].size()) + " bands, the room has " +
                                 std::to_string(room.bands.size()) + " (an empty histogram for a band not covered)");
  return h;
}

}  // namespace

bool isEnclosedRoom(const room::Room& room) {
  return !room.sources.empty() && room::openEdgeCount(room) == 0 && room::insideRoom(room, room.sources[0].position_m);
}

std::vector<RoomFigures> roomFigures(const std::vector<std::vector<double>>& energy_per_band, double bin_s,
                                     double direct_s, double e10, const std::vector<double>& lead_s) {
  const std::size_t nb = energy_per_band.size();
  std::vector<RoomFigures> out(nb);
  // The metrics share one onset over the bands they are given: pass the covered bands only.
  std::vector<std::vector<double>> covered;
  std::vector<std::size_t> index;
  for (std::size_t b = 0; b < nb; ++b)
    if (!energy_per_band[b].empty()) {
      covered.push_back(energy_per_band[b]);
      index.push_back(b);
    }
  if (covered.empty()) return out;
  const std::vector<ir::BandMetrics> m = ir::metricsFromHistograms(covered, bin_s);
  const auto k_direct = static_cast<long>(std::floor(direct_s / bin_s));
  const long k1 = k_direct + std::lround(kEarlyWindowS / bin_s);
  for (std::size_t i = 0; i < covered.size(); ++i) {
    const std::vector<double>& h = covered[i];
    const double lead = index[i] < lead_s.size() ? lead_s[index[i]] : 0.0;
    const auto k0 = static_cast<long>(std::floor((direct_s - lead) / bin_s));
    double all = 0.0, early = 0.0;
    for (std::size_t k = 0; k < h.size(); ++k) {
      all += h[k];
      const auto kk = static_cast<long>(k);
      if (kk >= k0 && kk < k1) early += h[k];
    }
    RoomFigures& f = out[index[i]];
    f.g_db = db(all / e10);
    f.early_db = db(early / e10);
    f.edt_s = m[i].edt;
    f.t30_s = m[i].t30;
    f.c50_db = m[i].c50;
    f.c80_db = m[i].c80;
  }
  return out;
}

FigureDifference figureDifference(const RoomFigures& m, const RoomFigures& r) {
  FigureDifference d;
  d.g_db = m.g_db - r.g_db;
  d.early_db = m.early_db - r.early_db;
  d.edt_pct = percent(m.edt_s, r.edt_s);
  d.t30_pct = percent(m.t30_s, r.t30_s);
  d.c50_db = m.c50_db - r.c50_db;
  d.c80_db = m.c80_db - r.c80_db;
  return d;
}

FreeFieldReference freeFieldApplicability(const room::Room& room, int l) {
  FreeFieldReference f;
  if (room.occluders.size() != 1) {
    f.why_not = "the free-field aperture reference needs exactly one door or slit; the room has " +
                std::to_string(room.occluders.size()) + " occluders";
    return f;
  }
  const room::Occluder& o = room.occluders[0];
  if (!(o.x.kind == Kind::Opening && o.y.kind == Kind::Opening && !o.x.mirror_lo)) {
    f.why_not = "the free-field aperture reference needs a door or slit; occluder " + o.name + " is a " + o.type;
    return f;
  }
  const room::Listener& li = room.listeners[static_cast<std::size_t>(l)];
  const double zs = (room.sources[0].position_m - o.origin_m).dot(o.normal);
  const double zl = (li.position_m - o.origin_m).dot(o.normal);
  if (zs * zl > 0.0) {
    f.why_not = "on the source's side of " + o.name +
                ": no screen stands between them, so the free-field aperture reference and a shadow boundary "
                "do not describe it";
    return f;
  }
  if (std::abs(zl) <= li.radius_m || zs == 0.0) {
    f.why_not = "its sphere reaches the plane of " + o.name + ": the free-field aperture reference needs it wholly behind";
    return f;
  }
  f.applies = true;
  f.shadow_angle_deg = shadowAngleDeg(room, room.sources[0].position_m, li.position_m);
  return f;
}

RoomComparison compareRoom(const room::Room& room, const RoomCompareOptions& o) {
  if (room.sources.empty() || room.listeners.empty()) throw core::InputError(room.file, "needs a source and a listener");
  const double c = room::speedOfSound(room.air);
  const std::size_t nl = room.listeners.size();
  const int nb = room.bands.size();
  RoomComparison out;
  double power = 0.0;
  for (const room::Source& s : room.sources) power += s.power_w;
  const double e10 = power / 100.0;  // ΣP / (10 m)²: the free field at 10 m in J/m²
  for (const room::Listener& li : room.listeners) {
    double r = INFINITY;
    for (const room::Source& s : room.sources) r = std::min(r, (li.position_m - s.position_m).norm());
    out.direct_s.push_back(r / c);
  }
  if (room.sources.size() > 1)
    out.warnings.push_back("the room has several sources: G is re their total power, the early window starts at the nearest one's direct sound, and the free-field reference uses the first");

  double length_s = 0.0;  // the ray models' IR length (the room's, or the pilot's automatic one)
  for (const std::string& model : o.models) {
    transport::RoomSimulationOptions so;
    so.rays = o.rays;
    so.seed = o.seed;
    so.diffraction = model;
    so.max_diffractions = o.max_diffractions;
    so.on_progress = o.on_progress;
    const auto t0 = std::chrono::steady_clock::now();
    const transport::RoomSimulation sim = transport::simulateRoom(room, so);
    length_s = std::max(length_s, sim.length_s);
    RoomModelResult res;
    res.model = model;
    res.rays = sim.rays;
    std::vector<std::vector<std::vector<double>>> energy(nl);
    double bin_s = 0.001;
    for (std::size_t l = 0; l < nl; ++l) {
      bin_s = sim.listeners[l].bin_s;
      for (int b = 0; b < nb; ++b) energy[l].push_back(sim.listeners[l].total(b));
    }
    res.figures = figuresOf(room, model, energy, bin_s, out.direct_s, e10);
    res.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    for (const std::string& w : sim.warnings) out.warnings.push_back("model " + model + ": " + w);
    out.models.push_back(std::move(res));
  }

  if (o.wave) {
    const auto t0 = std::chrono::steady_clock::now();
    // The wave model runs as long as the ray models did when the room leaves its length to them.
    room::Room timed = room;
    if (!(timed.output.ir_length_s > 0.0) && length_s > 0.0) timed.output.ir_length_s = length_s;
    const ListenerHistograms h = runWave(timed, o.wave);
    RoomModelResult wave;
    wave.model = "wave";
    wave.figures = figuresOf(room, "wave", h.energy, h.bin_s, out.direct_s, e10);
    wave.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    for (RoomModelResult& m : out.models) {
      m.vs_wave.assign(nl, std::vector<FigureDifference>(static_cast<std::size_t>(nb)));
      for (std::size_t l = 0; l < nl; ++l)
        for (int b = 0; b < nb; ++b) m.vs_wave[l][b] = figureDifference(m.figures[l][b], wave.figures[l][b]);
    }
    out.models.push_back(std::move(wave));
  }

  if (o.free_field) {
    const auto t0 = std::chrono::steady_clock::now();
    std::string why_not, assumption;
    // The room's models are energy tracers: a door on a floor is compared with the reference whose floor
    // reflection adds as energy (compare/point_models.h).
    const auto exact = exactModelFor(room, c, why_not, assumption, true);
    out.free_field_note = exact ? assumption : why_not;
    for (std::size_t l = 0; l < nl; ++l) out.free_field.push_back(freeFieldApplicability(room, static_cast<int>(l)));
    if (exact)
      for (FreeFieldReference& f : out.free_field)
        if (f.applies) f.g_db.assign(static_cast<std::size_t>(nb), RoomFigures::kNaN);
    // One task per listener and band (the bands' costs differ by the frequency: few listeners apply).
    tbb::parallel_for(std::size_t{0}, nl * static_cast<std::size_t>(nb), [&](std::size_t i) {
      const std::size_t l = i / static_cast<std::size_t>(nb);
      const int b = static_cast<int>(i % static_cast<std::size_t>(nb));
      FreeFieldReference& f = out.free_field[l];
      if (f.g_db.empty()) return;
      const room::Listener& li = room.listeners[l];
      const Vec3 src = room.sources[0].position_m;
      const double to_g = room.sources[0].power_w / (li.position_m - src).squaredNorm() / e10;
      double rel = 0.0;
      try {
        rel = bandRelativeEnergy(*exact, src, li.position_m, li.radius_m, room.bands.lowerHz(b), room.bands.upperHz(b),
                                 o.band_points);
      } catch (const core::InputError& e) {
        throw core::InputError(where(room, static_cast<int>(l), exact->name()), e.what());
      }
      f.g_db[static_cast<std::size_t>(b)] = db(rel * to_g);
    });
    out.free_field_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  }
  return out;
}

}  // namespace diffray::compare
