#pragma once
// The WBSDF model's side of a comparison: the level at each listener, per band,
// relative to the free field of the same source at the same distance, from the room tracer with WBSDF
// occluders (transport/room_tracer.h, RoomTraceOptions::occluders). Every arrival counts (the steady-state
// energy), air absorption is left out (it would scale model and reference alike), and each listener's
// traced fluence is divided by the free-field fluence P·D(θ)/r² of a point source at the listener's centre.
// Units: dB re free field. Pure function of its arguments; uses every core (core/parallel.h).
#include <cstdint>
#include <functional>
#include <vector>

#include "diffray/room/room.h"

namespace diffray::compare {

struct BandLevel {
  double ratio = 0.0;            ///< traced fluence / free-field fluence (signed: noise can push it below 0)
  double ratio_std_error = 0.0;  ///< its standard error from the chunk scatter
  double level_db = 0.0;         ///< 10·log10(ratio); −inf when ratio ≤ 0
};

struct WbsdfRunOptions {
  std::uint64_t rays = 1'000'000;
  std::uint64_t seed = 1;
  double length_s = 0.5;  ///< arrivals later than this are left out
  bool diffraction = true;  ///< false: occluders are plain surfaces (geometric acoustics, "none")
  bool next_event = true;   ///< RoomTraceOptions::next_event
  std::function<void(std::uint64_t)> on_progress;
  /// Aim every ray at this rectangle (transport::EmissionTarget); unset: uniform emission.
  bool aim = false;
  core::Vec3 aim_origin{0, 0, 0}, aim_ex{1, 0, 0}, aim_ey{0, 1, 0};
  double aim_half_x_m = 0.0, aim_half_y_m = 0.0;
  double aim_edge_fraction = 0.0, aim_edge_scale_m = 0.01;
  /// Half the rays toward the rectangle's image in this ground plane (transport::EmissionTarget::mirrored).
  bool aim_mirrored = false;
  core::Vec3 aim_mirror_normal{0, 0, 1};
  double aim_mirror_offset = 0.0;
  /// More rectangles sharing the rays equally with the first (transport::EmissionTarget::also), each with
  /// the same edge sampling and ground image: a barrier's side zones.
  struct AimZone {
    core::Vec3 origin{0, 0, 0}, ex{1, 0, 0}, ey{0, 1, 0};
    double half_x_m = 0.0, half_y_m = 0.0;
  };
  std::vector<AimZone> aim_more;
};

struct WbsdfLevels {
  std::vector<std::vector<BandLevel>> listeners;  ///< [listener][band]
  std::uint64_t rays = 0, occluder_events = 0, evanescent = 0, escaped = 0;
  double seconds = 0.0;
};

/// Traces source `source` of `room` (with its occluders) and returns the level at every listener per band.
WbsdfLevels wbsdfLevels(const room::Room& room, int source, const WbsdfRunOptions& options);

/// Aims every ray of `w` at occluder `o`'s rectangle, or, for a door on a floor (sill), at the door and its
/// mirror image below the floor: rays toward the image half reflect off the floor in front of the door and
/// go through it (the image source's paths).
void aimAtOccluder(WbsdfRunOptions& w, const room::Occluder& o);

/// 10·log10(ratio), −inf when ratio ≤ 0.
double levelDb(double ratio);

}  // namespace diffray::compare
