#pragma once
// `diffray compare` on a room: the diffraction models run as whole room simulations
// (transport::simulateRoom with diffraction "none", "utd" and "wbsdf", one seed and ray count for all),
// each listener's figures per band taken from its energy histograms, and, when a wave model is given (a
// solver that returns energy histograms, e.g. a 3D FDTD), every ray model's difference from it.
//
// Figures per listener and band (RoomFigures):
// - G, the strength (ISO 3382-1 §A.2.1): 10·log10(E / E₁₀), E the band's whole histogram energy and E₁₀ =
//   ΣP / (10 m)², the free-field energy of the scene's sources (total power ΣP, omni) at 10 m, in the
//   histograms' units (J/m²: a 1 W omni source gives 1/r² in free field);
// - early: the energy in the 20 ms from the direct-sound time (the distance to the nearest source over the
//   speed of sound, whether or not the source is seen), re the same E₁₀ (dB): the 20 bins of 1 ms from the
//   bin holding that time, and before them the bins from R/c + 1/Δf earlier (R the listener's radius, Δf the
//   band's width): the listener sphere spreads an arrival over ±R/c about its centre's time and the wave
//   reference's band filter over about ±1/Δf, ahead of the direct-sound time as well as after it, and no
//   model has energy sooner. For a listener hidden from the source it is what diffraction brings early;
// - EDT, T30, C50, C80 by ir::metricsFromHistograms (ISO 3382-1; NaN where the decay cannot give them).
// The free-field aperture reference (compare/point_models.h: a point source through the door in an infinite
// screen, no room) is computed only for listeners it describes (FreeFieldReference): it is the direct sound
// through the door, to be read beside the early energy; no error against it is formed.
// Pure function of its arguments; the simulations use every core.
#include <cstdint>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "diffray/room/room.h"

namespace diffray::compare {

/// What a model that is not traced here gives (the wave reference): per listener of the room, per band of
/// room.bands, the energy histogram in J/m² per bin of width bin_s, time 0 at emission, the room's own
/// sources (a 1 W omni source gives 1/r² in free field). A band the model does not cover (a wave solver
/// stops at some frequency) is an empty vector: its figures are NaN and no difference is formed there.
struct ListenerHistograms {
  double bin_s = 0.001;
  std::vector<std::vector<std::vector<double>>> energy;  ///< [listener][band][bin]
};
/// A model run on the room, e.g. `[](const room::Room& r) { return toHistograms(reference::simulateWave(r, w)); }`.
using HistogramModel = std::function<ListenerHistograms(const room::Room&)>;

/// The figures of one listener in one band (NaN where not defined).
struct RoomFigures {
  static constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  double g_db = kNaN;      ///< strength G, dB re the free field at 10 m
  double early_db = kNaN;  ///< the 20 ms from the direct-sound time, dB re the free field at 10 m
  double edt_s = kNaN, t30_s = kNaN;
  double c50_db = kNaN, c80_db = kNaN;
};

/// A model's figures minus the wave reference's: dB for levels and clarities, % of the reference for times.
struct FigureDifference {
  static constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  double g_db = kNaN, early_db = kNaN, edt_pct = kNaN, t30_pct = kNaN, c50_db = kNaN, c80_db = kNaN;
};

struct RoomModelResult {
  std::string model;                              ///< "none", "utd", "wbsdf" or "wave"
  std::vector<std::vector<RoomFigures>> figures;  ///< [listener][band]
  /// Against the wave model when one was given (empty otherwise, and for the wave model itself).
  std::vector<std::vector<FigureDifference>> vs_wave;  ///< [listener][band]
  double seconds = 0.0;
  std::uint64_t rays = 0;  ///< 0 for the wave model
};

/// Whether the free-field aperture reference describes a listener, and its levels where it does.
struct FreeFieldReference {
  bool applies = false;
  std::string why_not;                         ///< one line, when it does not apply
  std::optional<double> shadow_angle_deg;      ///< past the door's shadow boundary (scene_compare.h), where it applies
  std::vector<double> g_db;                    ///< per band, the reference's level on the G scale (re E₁₀)
};

struct RoomComparison {
  std::vector<RoomModelResult> models;  ///< the ray models in the order asked, then "wave" if given
  std::vector<FreeFieldReference> free_field;  ///< per listener (empty when not asked for)
  std::string free_field_note;  ///< what the reference assumes, or why the scene has none
  double free_field_seconds = 0.0;
  std::vector<double> direct_s;  ///< per listener: the direct-sound time used for the early energy
  std::vector<std::string> warnings;
};

struct RoomCompareOptions {
  std::vector<std::string> models{"none", "utd", "wbsdf"};  ///< ray models (RoomSimulationOptions::diffraction)
  std::uint64_t rays = 0;  ///< per model; 0 = the room file's output.rays
  std::uint64_t seed = 1;
  int max_diffractions = 1;
  bool free_field = true;  ///< compute the free-field aperture reference where it applies
  int band_points = 32;    ///< its frequencies per band
  /// The wave reference; unset: none. When set, its figures and every ray model's difference are reported.
  /// It is given the room with output.ir_length_s set to the ray models' IR length when the room leaves the
  /// length automatic (so its decays are as long as theirs).
  HistogramModel wave;
  std::function<void(std::uint64_t)> on_progress;  ///< rays done, over all ray models
};

/// Whether `room` is a room for `diffray compare` (room mode) rather than a free-field scene: its enclosure
/// is closed (no open edge, room/checks.h) and holds its first source.
bool isEnclosedRoom(const room::Room& room);

/// Runs every model. Throws core::InputError naming the listener and model for a figure that cannot be
/// formed (a wave model's histograms of the wrong shape, non-finite energies).
RoomComparison compareRoom(const room::Room& room, const RoomCompareOptions& options);

/// The figures of one listener's histograms ([band][bin], bin_s wide, time 0 at emission): `e10` is E₁₀,
/// `direct_s` the direct-sound time, `lead_s` per band how long before it the early window opens (missing:
/// 0). An empty band gives NaN figures.
std::vector<RoomFigures> roomFigures(const std::vector<std::vector<double>>& energy_per_band, double bin_s,
                                     double direct_s, double e10, const std::vector<double>& lead_s = {});

/// model − reference (FigureDifference's units); NaN where either is NaN.
FigureDifference figureDifference(const RoomFigures& model, const RoomFigures& reference);

/// Whether the free-field aperture reference applies to listener `l` of `room` (source 0): the room has
/// exactly one occluder, a door or slit, and the listener's whole sphere lies on the other side of the
/// door's plane from the source (in the source's room the screen the reference assumes is not between
/// them). Fills applies, why_not and shadow_angle_deg, not the levels.
FreeFieldReference freeFieldApplicability(const room::Room& room, int l);

}  // namespace diffray::compare
