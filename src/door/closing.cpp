#include "diffray/door/closing.h"

#include <algorithm>
#include <cmath>

#include "diffray/core/error.h"
#include "diffray/door/sliding_panel.h"
#include "diffray/dsp/resample.h"
#include "diffray/ir/spatial_synthesis.h"
#include "diffray/ir/synthesis.h"
#include "diffray/spatial/hrtf.h"
#include "diffray/transport/room_simulation.h"

namespace diffray::door {

std::vector<ClosingStep> closingSchedule(double width_m, double start_s, double end_s, int steps) {
  if (!(std::isfinite(start_s) && std::isfinite(end_s) && start_s >= 0.0 && end_s > start_s))
    throw core::InputError("--close", "needs START:END in seconds with 0 <= START < END");
  if (steps < 2 || steps > 32) throw core::InputError("--steps", "must be in [2, 32]");
  if (!(width_m > 0.0)) throw core::InternalError("closingSchedule: the door has no width");
  std::vector<ClosingStep> out;
  for (int k = 0; k < steps; ++k) {
    ClosingStep s;
    s.gap_m = k + 1 < steps ? width_m * std::ldexp(1.0, -k) : 0.0;
    s.time_s = start_s + (1.0 - s.gap_m / width_m) * (end_s - start_s);
    out.push_back(s);
  }
  return out;
}

void addScaled(ir::EnergyResponse& response, const ir::EnergyResponse& other, const core::BandArray& factor) {
  const int bands = static_cast<int>(std::min(response.traced.size(), other.traced.size()));
  for (int b = 0; b < bands; ++b) {
    auto& h = response.traced[b];
    const auto& o = other.traced[b];
    for (std::size_t i = 0; i < std::min(h.size(), o.size()); ++i) h[i] += factor[b] * o[i];
    if (static_cast<int>(std::min(response.directions.size(), other.directions.size())) > b) {
      auto& v = response.directions[b];
      const auto& ov = other.directions[b];
      for (std::size_t i = 0; i < std::min(v.size(), ov.size()); ++i) v[i] += factor[b] * ov[i];
    }
  }
  for (ir::Arrival a : other.arrivals) {
    for (int b = 0; b < bands; ++b) a.energy[b] *= factor[b];
    response.arrivals.push_back(a);
  }
}

core::BandArray bandEnergies(const ir::EnergyResponse& response) {
  core::BandArray e = core::bandFill(0.0);
  for (std::size_t b = 0; b < response.traced.size(); ++b) {
    for (double v : response.traced[b]) e[b] += v;
    for (const ir::Arrival& a : response.arrivals) e[b] += a.energy[b];
  }
  return e;
}

ClosingResponse simulateClosing(const room::Room& room, int door, const std::vector<ClosingStep>& schedule,
                                const ClosingOptions& options) {
  if (schedule.empty()) throw core::InternalError("simulateClosing: empty schedule");
  const room::Occluder& d = room.occluders.at(door);
  const int panel = options.panel_material >= 0 ? options.panel_material : d.panel_material;
  ClosingResponse out;
  out.steps = schedule;
  out.width_m = 2.0 * d.half_x_m;
  out.volume_m3 = room.volume();
  // The panel as the tracer sees it: its material without transmission (what it transmits is added below).
  room::Room base = room;
  int traced_panel = -1;
  if (panel >= 0 && panel < static_cast<int>(room.materials.size())) {
    room::Material reflector = room.materials[panel];
    out.panel_transmission = reflector.transmission;
    out.panel_name = reflector.name;
    reflector.name += " (reflection only)";
    reflector.transmission = core::bandFill(0.0);
    traced_panel = base.addMaterial(reflector);
  }
  withSlidingPanel(base, door, 0.0, traced_panel);  // refuses a door with no panel before any tracing
  std::vector<ir::EnergyResponse> open;
  for (std::size_t k = 0; k < schedule.size(); ++k) {
    const room::Room r = withSlidingPanel(base, door, schedule[k].gap_m, traced_panel);
    transport::RoomSimulationOptions so;
    so.rays = options.rays;
    so.seed = options.seed;
    // Shut, the door is no occluder any more: nothing is left to diffract (and nothing to warn about).
    so.diffraction = options.diffraction == "wbsdf" && r.occluders.empty() ? "none" : options.diffraction;
    so.max_diffractions = options.max_diffractions;
    so.length_s = k == 0 ? options.length_s : out.length_s;
    so.on_progress = options.on_progress;
    so.directions = options.directions;
    transport::RoomSimulation sim = transport::simulateRoom(r, so);
    if (k == 0) {
      out.length_s = sim.length_s;
      out.speed_of_sound_m_s = sim.speed_of_sound_m_s;
      open = sim.listeners;
    }
    if (k == 0) out.warnings = sim.warnings;
    const double covered = 1.0 - schedule[k].gap_m / out.width_m;
    if (covered > 0.0) {
      core::BandArray factor = core::bandFill(0.0);
      for (int b = 0; b < room.bands.size(); ++b) factor[b] = covered * out.panel_transmission[b];
      for (std::size_t l = 0; l < sim.listeners.size(); ++l) addScaled(sim.listeners[l], open[l], factor);
    }
    out.responses.push_back(std::move(sim.listeners));
  }
  return out;
}

std::vector<long> keyFrames(const std::vector<ClosingStep>& schedule, double sample_rate_hz, double width_m,
                            double start_s, double end_s) {
  const auto frames = [&](const std::vector<ClosingStep>& steps) {
    std::vector<long> keys;
    for (const ClosingStep& s : steps) keys.push_back(std::lround(s.time_s * sample_rate_hz));
    return keys;
  };
  const auto increasing = [](const std::vector<long>& keys) {
    for (std::size_t k = 1; k < keys.size(); ++k)
      if (keys[k] <= keys[k - 1]) return false;
    return true;
  };
  std::vector<long> keys = frames(schedule);
  if (increasing(keys)) return keys;
  int fits = static_cast<int>(schedule.size()) - 1;
  while (fits >= 2 && !increasing(frames(closingSchedule(width_m, start_s, end_s, fits)))) --fits;
  const std::string most = fits >= 2 ? "at most " + std::to_string(fits) + " steps fit" : "not even 2 steps fit";
  throw core::InputError("--steps", std::to_string(schedule.size()) + " steps put two key times within one sample at " +
                                        std::to_string(static_cast<long>(sample_rate_hz)) + " Hz (the gaps halve): " +
                                        most + "; use fewer steps or a longer --close");
}

double synthesisRateHz(const core::Bands& bands, double room_hz, double signal_hz) {
  return bands.upperHz(bands.size() - 1) < 0.5 * signal_hz ? signal_hz : room_hz;
}

namespace {

// An IR synthesized at synthesisRateHz() as a float filter at signal_hz: scaled when it was made at the
// signal's rate (`fits`), resampled from the room's rate otherwise (impulseResponseFor).
std::vector<float> atSignalRate(const std::vector<double>& h, bool fits, double room_hz, double signal_hz) {
  if (!fits) return dsp::resampleImpulseResponse(std::vector<float>(h.begin(), h.end()), 1, room_hz, signal_hz);
  const double scale = std::sqrt(room_hz / signal_hz);
  std::vector<float> out(h.size());
  for (std::size_t i = 0; i < h.size(); ++i) out[i] = static_cast<float>(scale * h[i]);
  return out;
}

}  // namespace

std::vector<float> impulseResponseFor(const ir::EnergyResponse& response, double room_hz, double signal_hz,
                                      double length_s, double volume_m3, double speed_of_sound_m_s,
                                      std::uint64_t seed) {
  const double synth_hz = synthesisRateHz(response.bands, room_hz, signal_hz);
  const bool fits = synth_hz == signal_hz;
  return atSignalRate(ir::synthesize(response, synth_hz, length_s, volume_m3, speed_of_sound_m_s, seed,
                                     ir::Phasing::Coherent),
                      fits, room_hz, signal_hz);
}

std::vector<std::vector<float>> binauralResponsesFor(const ir::EnergyResponse& response, double room_hz,
                                                     double signal_hz, double length_s, double volume_m3,
                                                     double speed_of_sound_m_s, std::uint64_t seed,
                                                     const spatial::Hrtf& hrtf, const room::Listener& listener) {
  const double synth_hz = synthesisRateHz(response.bands, room_hz, signal_hz);
  std::vector<std::vector<float>> out;
  for (const std::vector<double>& ear :
       ir::synthesizeBinaural(response, synth_hz, length_s, volume_m3, speed_of_sound_m_s, seed, hrtf, listener.forward,
                              listener.left, listener.up, ir::Phasing::Coherent))
    out.push_back(atSignalRate(ear, synth_hz == signal_hz, room_hz, signal_hz));
  return out;
}

}  // namespace diffray::door
