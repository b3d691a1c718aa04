#pragma once
// A whole room run: the air (ISO 9613-1, room/air.h), the IR length, image sources up to
// the room's order for every source–listener pair and rays for the rest (transport/image_sources.h and
// room_tracer.h, which never count a path twice), summed over the sources into one ir::EnergyResponse per
// listener. The length is the room file's, or "auto": the time at which the energy in flight in the room
// has fallen by 60 dB in every band, measured by a pilot trace of up to 20,000 rays with the run's WBSDF
// occluders (Eyring's estimate misjudges non-diffuse rooms; 1.5 × Eyring if the pilot cannot tell), capped
// at max_length_s. Warnings (rays lost through gaps, a source outside the room) are returned, not thrown:
// the run goes on. Units: seconds, metres, J/m². Deterministic for a seed.
#include <cstdint>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "diffray/ir/response.h"
#include "diffray/receiver/energy_histogram.h"
#include "diffray/room/room.h"

namespace diffray::transport {

struct RoomSimulationOptions {
  std::uint64_t rays = 0;  ///< per source; 0 = the room file's output.rays
  std::uint64_t seed = 1;
  int ism_order = -2;      ///< −2 = the room file's; −1 = no image sources (rays alone)
  double length_s = 0.0;   ///< 0 = the room file's (or auto)
  bool brute_force = false;  ///< tests only: the brute-force intersector
  /// "none": occluders are plain surfaces (doorways pass rays straight); "wbsdf": rays diffract at the
  /// room's occluders (RoomTraceOptions::occluders) and image sources do not pass through them; "utd":
  /// geometric rays and image sources plus the UTD edge-diffraction paths of the mesh's edges, with their
  /// first-order reflections around the edges (utd/paths.h, default options), as exact arrivals.
  std::string diffraction = "none";
  int max_diffractions = 1;  ///< WBSDF scatterings per path (RoomTraceOptions::max_diffractions)
  /// "wbsdf": the rays that go on past an opening draw their direction from its far-field pattern
  /// (RoomTraceOptions::portal: positive, no signed noise in the reverberant field); false: from W(x,·) with
  /// signed weights (the plain estimator, for comparison).
  bool portal = true;
  /// Record where each listener's energy comes from (ir::EnergyResponse::directions, Arrival::direction is
  /// always set): three more numbers per band and bin and listener.
  bool directions = false;
  std::function<void(std::uint64_t)> on_progress;  ///< rays done (thread-safe)
  /// Called once every input check has passed, before any tracing (the CLI prints its warnings then, so
  /// that a refused run prints one line only).
  std::function<void()> on_start;
};

struct RoomSimulation {
  std::vector<ir::EnergyResponse> listeners;          ///< per room listener
  std::vector<receiver::EnergyHistogram> traced;      ///< the traced part with its standard errors
  double length_s = 0.0;
  double eyring_t60_s = 0.0;  ///< the longest band's Eyring estimate
  double pilot_t60_s = std::numeric_limits<double>::quiet_NaN();  ///< "auto": when the pilot reached −60 dB
  double speed_of_sound_m_s = 0.0;
  core::BandArray air_m_per_m = core::bandFill(0.0);
  int ism_order = 0;
  std::uint64_t rays = 0, segments = 0, escaped = 0, roulette_killed = 0, timed_out = 0;
  std::size_t image_sources = 0;  ///< valid image-source paths over all pairs
  std::uint64_t occluder_events = 0, evanescent = 0;  ///< WBSDF scatterings, and the rays they ended
  std::size_t diffraction_paths = 0;  ///< UTD: diffraction paths added as arrivals
  double trace_seconds = 0.0, ism_seconds = 0.0;
  std::vector<std::string> warnings;
};

/// Throws core::InputError before any tracing for a run estimated above 5e9 wall hits: per ray the path
/// over the mean free path 4V/S (at least 1 m when the mesh has open edges; 1 m when no enclosure holds a
/// source), or the bounces until Russian roulette ends it, whichever is fewer.
RoomSimulation simulateRoom(const room::Room& room, const RoomSimulationOptions& options);

/// The Eyring reverberation time per band of `room` (area-weighted mean absorption of its triangles, its
/// divergence-theorem volume, air absorption), T = 24 ln10 V / (c (−S ln(1 − ᾱ) + 4mV)).
core::BandArray eyringT60(const room::Room& room, double speed_of_sound_m_s, const core::BandArray& air_m_per_m);

}  // namespace diffray::transport
