#pragma once
// The impulse responses of a closing door: a sliding panel (door/sliding_panel.h) narrows
// the door's opening from its full width W to shut while the sound plays; the room is traced at K gaps and
// the responses are crossfaded in time (dsp/crossfade_convolver.h).
//  * Schedule: gaps W·2^−k for k = 0 … K−2, then 0 (shut). Halving the gap puts most steps where it narrows to
//    the scale of the wavelengths (0.9 m door, K = 8: 0.9, 0.45, … 0.014 m, 0), which is where the spectrum
//    changes; the panel moves at constant speed, so step k's key time is START + (1 − gap/W)·(END − START).
//  * Each step is one transport::simulateRoom run of the room with the panel at that gap, the same seed and
//    the same IR length (the fully open step's), so that neighbouring responses differ by the door only.
//  * Transmission: the panel is traced as a reflector (its material with the transmission taken out: that
//    energy counts as absorbed), and what it transmits is added as τ_b·(1 − gap/W) times the fully open
//    door's response, band by band: the power a panel of transmission coefficient τ passes is τ times the
//    power incident on its area, and with the door open that power goes on through the same area. It ignores
//    the direction dependence of τ and that a shut door no longer drains the far room's reverberation into
//    the near one (its decay there is a little longer than this gives). So the shut door is muffled (a mass
//    law panel passes the low bands), not silent.
// Units: metres, seconds, J/m². Deterministic for a seed. Thread-safe (each call builds its own rooms).
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "diffray/ir/response.h"
#include "diffray/room/room.h"

namespace diffray::spatial {
class Hrtf;
}

namespace diffray::door {

struct ClosingStep {
  double gap_m = 0.0;   ///< the opening left beside the panel
  double time_s = 0.0;  ///< when the panel leaves that gap (the key time of this step's response)
};

/// The schedule above for a door `width_m` wide closing between start_s and end_s in `steps` ≥ 2 steps.
/// Throws core::InputError (naming --close or --steps) for a bad range or count.
std::vector<ClosingStep> closingSchedule(double width_m, double start_s, double end_s, int steps);

struct ClosingOptions {
  std::string diffraction = "wbsdf";  ///< as transport::RoomSimulationOptions::diffraction
  int max_diffractions = 1;
  std::uint64_t rays = 0;  ///< per source and step; 0 = the room file's
  std::uint64_t seed = 1;
  double length_s = 0.0;   ///< 0 = the room file's (or auto, from the open door)
  int panel_material = -1; ///< index into room.materials; −1 = the door's own (Occluder::panel_material)
  bool directions = false; ///< record where the energy comes from (for binaural IRs)
  std::function<void(std::uint64_t)> on_progress;  ///< rays done (thread-safe)
};

struct ClosingResponse {
  std::vector<ClosingStep> steps;
  /// [step][listener]: the response with the panel at that step's gap, its transmission included.
  std::vector<std::vector<ir::EnergyResponse>> responses;
  double width_m = 0.0;
  double length_s = 0.0;
  double volume_m3 = 0.0;  ///< of the open room (the air does not change as the door closes)
  double speed_of_sound_m_s = 0.0;
  core::BandArray panel_transmission = core::bandFill(0.0);
  std::string panel_name;
  /// The open door's simulation's warnings. The later steps' are left out: the same room gives the same ones,
  /// except that a far-side listener reached by few rays as the gap narrows is what closing the door means.
  std::vector<std::string> warnings;
};

/// Traces the room of door `door` (door::findDoor) at every step of `schedule`.
ClosingResponse simulateClosing(const room::Room& room, int door, const std::vector<ClosingStep>& schedule,
                                const ClosingOptions& options);

/// response += factor_b · other, band by band: the traced histograms add bin by bin (`other` may be shorter)
/// and other's arrivals are appended with their energies scaled.
void addScaled(ir::EnergyResponse& response, const ir::EnergyResponse& other, const core::BandArray& factor);

/// Energy per band of a response (traced + arrivals), J/m².
core::BandArray bandEnergies(const ir::EnergyResponse& response);

/// The key frames of `schedule` at `sample_rate_hz`: round(time·rate). Throws core::InputError naming --steps
/// (with the largest step count that fits) when two coincide: the halving schedule puts the last keys
/// (END − START)·2^−k apart, under a sample for many steps over a short close, and the crossfade needs them
/// strictly increasing. Call it before tracing.
std::vector<long> keyFrames(const std::vector<ClosingStep>& schedule, double sample_rate_hz, double width_m,
                            double start_s, double end_s);

/// The rate impulseResponseFor synthesizes at: `signal_hz` when the bands fit below its Nyquist frequency,
/// else `room_hz` (then resampled).
double synthesisRateHz(const core::Bands& bands, double room_hz, double signal_hz);

/// The impulse response of `response` to convolve with a signal at `signal_hz` (ir::synthesize, coherent
/// phasing). It has the gain, as a filter, of the response synthesized at the room's rate `room_hz`, whatever
/// `signal_hz` is: synthesized at `signal_hz` and scaled by √(room_hz / signal_hz) when the room's bands fit
/// below the signal's Nyquist frequency (Σh² is the band energy at any rate, so a filter's in-band gain² is
/// Σh²·rate/(2B): without the scale a 24 kHz signal came out 3 dB quieter than a 48 kHz one), else
/// synthesized at `room_hz` and resampled as a filter (dsp::resampleImpulseResponse).
std::vector<float> impulseResponseFor(const ir::EnergyResponse& response, double room_hz, double signal_hz,
                                      double length_s, double volume_m3, double speed_of_sound_m_s,
                                      std::uint64_t seed);

/// The same for both ears (ir::synthesizeBinaural, coherent phasing) of `listener` through `hrtf`, which
/// must be prepared at synthesisRateHz(bands, room_hz, signal_hz): left, right.
std::vector<std::vector<float>> binauralResponsesFor(const ir::EnergyResponse& response, double room_hz,
                                                     double signal_hz, double length_s, double volume_m3,
                                                     double speed_of_sound_m_s, std::uint64_t seed,
                                                     const spatial::Hrtf& hrtf, const room::Listener& listener);

}  // namespace diffray::door
