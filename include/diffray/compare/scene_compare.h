#pragma once
// `diffray compare`: the level at each listener of a scene, relative to the
// free field at the same distance, from each model — the WBSDF ray tracer per band, UTD and the exact
// reference per band and on a fine frequency grid — with, per listener, its angle past the shadow boundary
// of the scene's occluder where one is defined. Source 0 of the scene; no air absorption (it would scale
// every model alike). Band levels of UTD and the exact reference are energy averages over the band and the
// listener's sphere (compare/point_models.h); fine-grid levels are at the listener's centre. Pure function
// of its arguments; the WBSDF run uses every core.
#include <cstdint>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "diffray/core/progress.h"
#include "diffray/room/room.h"

namespace diffray::compare {

struct CompareOptions {
  std::vector<std::string> models{"wbsdf", "utd", "exact"};
  std::uint64_t rays = 1'000'000;
  std::uint64_t seed = 1;
  int band_points = 32;        ///< frequencies per band for the band levels of UTD and exact
  int fine_per_octave = 24;    ///< fine-grid frequencies per octave (UTD, exact), log-spaced
  /// When not empty: the fine-grid frequencies (Hz) instead of the log-spaced grid.
  std::vector<double> freqs_hz;
  /// Aim every WBSDF ray at the scene's single occluder (its rectangle; a door on a floor with its mirror
  /// image): far fewer rays for the same noise, valid only when every path to the listeners crosses it.
  bool aim = false;
  std::function<void(std::uint64_t)> on_progress;
  /// Progress of the point models (UTD, exact), one callback per model, labelled by its name; each is
  /// called once per listener and band and once per listener's fine grid (e.g. core::progressOfUnknownSize).
  core::ProgressFactory model_progress;
};

struct LevelRow {
  int listener = 0;
  std::string model;       ///< "wbsdf", "utd", "exact" or "exact-incoherent-floor"
  double freq_hz = 0.0;    ///< the band's nominal centre for band rows
  bool band = true;        ///< a band level (else a fine-grid frequency)
  std::string band_label;  ///< "250" … for band rows
  double level_db = 0.0;
  double std_error_db = 0.0;  ///< WBSDF: the noise of the level (0 for the deterministic models)
  /// Fine-grid rows of UTD and the exact reference: the phase of p/p_free (degrees, (−180, 180], time factor
  /// e^{iωt}); NaN for band rows, the WBSDF and a reference that adds arrivals as energies.
  double phase_deg = std::numeric_limits<double>::quiet_NaN();
};

struct SceneComparison {
  std::vector<LevelRow> rows;
  /// Per listener: + into the shadow, in (−180, 180]; empty on the source's side of a door or slit (no
  /// shadow boundary there) and when the scene has no single occluder.
  std::vector<std::optional<double>> shadow_angle_deg;
  std::string exact_note;  ///< the reference's assumption, or why there is none
  bool exact_available = false;
  std::vector<std::string> warnings;  ///< e.g. listeners hidden behind a surface (compare/scene_checks.h)
  std::uint64_t rays = 0;
  double wbsdf_seconds = 0.0, utd_seconds = 0.0, exact_seconds = 0.0;
};

/// Throws core::InputError before any model runs for a listener that compare/scene_checks.h refuses (at the
/// source, on the screen, or, with `aim`, seeing the source past the aim rectangle), and, when "exact" is
/// asked for on a door or slit, for a listener on the source's side of it (the aperture reference holds
/// only beyond the opening's plane); each message names the listener (and the model). On a closed room
/// (compare/room_compare.h, isEnclosedRoom) the hidden-listener warnings give way to one note that the
/// comparison leaves out the room's reverberation.
SceneComparison compareScene(const room::Room& room, const CompareOptions& options);

/// The listener's angle past the shadow boundary of the room's single occluder, seen from the source:
/// an edge's (around the edge; for a barrier with side or foot edges, the least of its edges' angles, each
/// in the plane across its edge), a door's or slit's (across its nearer side edge, in the plane through
/// the source spanned by the occluder's normal and x axis). Empty when the scene has no single occluder.
std::optional<double> shadowAngleDeg(const room::Room& room, const core::Vec3& source, const core::Vec3& listener);

}  // namespace diffray::compare
