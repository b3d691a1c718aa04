#pragma once
// The facade: the usual path through diffray in five calls, for programs that link the installed library
// (include/diffray/README.md). A scene file is loaded (loadScene), its room simulated (simulate), a
// listener's impulse response synthesized from the result (impulseResponse), its ISO 3382-1 metrics taken
// (metrics), and a dry recording convolved with the response (convolve). Each call is a thin wrapper over a
// module function with the room file's own settings filled in; the module headers named at each call hold
// the full contract (options, conventions, the physics). These functions are kept stable across releases;
// the module headers may change.
// Units: seconds, metres, Hz; energies in J/m² (Σ p[n]² over a span is its energy).
// Errors: bad input (a missing or malformed scene file, a listener index out of range, mismatched sample
// rates) throws core::InputError with a one-line message; core::InternalError means a bug in diffray.
// Thread-safety: free functions without shared state; calls on different data may run concurrently, and
// simulate() itself uses every core (TBB; core::ThreadLimit caps it).
#include <cstdint>
#include <string>
#include <vector>

#include "diffray/audio/wav.h"
#include "diffray/core/error.h"
#include "diffray/dsp/multichannel_convolver.h"
#include "diffray/ir/metrics.h"
#include "diffray/ir/synthesis.h"
#include "diffray/room/scene_file.h"
#include "diffray/transport/room_simulation.h"

namespace diffray {

/// A scene file (rooms/README.md) read into a room (room::loadRoom); non-fatal findings go to `warnings`.
inline room::Room loadScene(const std::string& path, std::vector<std::string>* warnings = nullptr) {
  return room::loadRoom(path, warnings);
}

/// The room's energy responses, one per listener (transport::simulateRoom): `rays` per source (0: the
/// file's output.rays), image sources and length as the file says. Deterministic for a seed.
inline transport::RoomSimulation simulate(const room::Room& room, std::uint64_t rays = 0, std::uint64_t seed = 1) {
  transport::RoomSimulationOptions options;
  options.rays = rays;
  options.seed = seed;
  return transport::simulateRoom(room, options);
}

/// Throws core::InputError unless `listener` indexes one of the simulation's listeners.
inline void requireListener(const transport::RoomSimulation& sim, std::size_t listener) {
  if (listener >= sim.listeners.size())
    throw core::InputError("listener", "index " + std::to_string(listener) + " out of range (the room has " +
                                           std::to_string(sim.listeners.size()) + " listeners)");
}

/// Listener `listener`'s impulse response at the room's output.sample_rate_hz over the simulated length
/// (ir::synthesize), as a one-channel buffer. The same seed gives the same samples, those of channel
/// `listener` of `diffray ir --seed SEED` (ir::listenerSeed).
inline audio::AudioBuffer impulseResponse(const room::Room& room, const transport::RoomSimulation& sim,
                                          std::size_t listener, std::uint64_t seed = 1) {
  requireListener(sim, listener);
  audio::AudioBuffer ir;
  ir.sample_rate_hz = room.output.sample_rate_hz;
  ir.samples = ir::synthesize(sim.listeners[listener], ir.sample_rate_hz, sim.length_s, room.volume(),
                              sim.speed_of_sound_m_s, ir::listenerSeed(seed, listener));
  return ir;
}

/// ISO 3382-1 figures per band of the room (T20, T30, EDT, C50, C80, D50, Ts; NaN where a figure cannot be
/// measured) from listener `listener`'s energy histogram (ir::metricsFromHistograms), in room.bands order.
inline std::vector<ir::BandMetrics> metrics(const transport::RoomSimulation& sim, std::size_t listener) {
  requireListener(sim, listener);
  const ir::EnergyResponse& response = sim.listeners[listener];
  std::vector<std::vector<double>> totals;
  for (int b = 0; b < response.bands.size(); ++b) totals.push_back(response.total(b));
  return ir::metricsFromHistograms(totals, response.bin_s);
}

/// The same figures measured on a sampled impulse response (ir::metricsFromSignal), for `bands`.
inline std::vector<ir::BandMetrics> metrics(const audio::AudioBuffer& impulse_response, int channel,
                                            const core::Bands& bands) {
  return ir::metricsFromSignal(impulse_response.channel(channel), impulse_response.sample_rate_hz, bands);
}

/// The whole linear convolution of `dry` with `impulse_response` (dry.frames() + ir.frames() − 1 frames;
/// channels paired as dsp/multichannel_convolver.h says), in single precision (dsp::PartitionedConvolver:
/// within 1e-6 of the peak). Throws core::InputError for different sample rates (resample first:
/// dsp/resample.h), an empty buffer, or a channel pairing the convolver refuses. Holds the whole input and
/// output in memory (for long files, stream them through audio::AudioReader and dsp::MultichannelConvolver
/// as `diffray auralize` does). Uses every core (processParallel).
inline audio::AudioBuffer convolve(const audio::AudioBuffer& dry, const audio::AudioBuffer& impulse_response) {
  if (dry.sample_rate_hz != impulse_response.sample_rate_hz)
    throw core::InputError("convolve", "the dry signal and the impulse response have different sample rates");
  if (dry.frames() < 1 || impulse_response.frames() < 1)
    throw core::InputError("convolve", "an empty signal or impulse response");
  std::vector<std::vector<float>> ir(static_cast<std::size_t>(impulse_response.channels));
  for (int c = 0; c < impulse_response.channels; ++c)
    for (double v : impulse_response.channel(c)) ir[static_cast<std::size_t>(c)].push_back(static_cast<float>(v));
  dsp::MultichannelConvolver convolver;
  convolver.init(4096, ir, dry.channels);
  const long frames = dry.frames() + impulse_response.frames() - 1;
  std::vector<float> in(static_cast<std::size_t>(frames * dry.channels), 0.0f);
  for (std::size_t i = 0; i < dry.samples.size(); ++i) in[i] = static_cast<float>(dry.samples[i]);
  std::vector<float> out(static_cast<std::size_t>(frames * convolver.outputChannels()));
  convolver.processParallel(in.data(), out.data(), frames);
  audio::AudioBuffer wet;
  wet.sample_rate_hz = dry.sample_rate_hz;
  wet.channels = convolver.outputChannels();
  wet.samples.assign(out.begin(), out.end());
  return wet;
}

}  // namespace diffray
