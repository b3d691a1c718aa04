#pragma once
// `diffray auralize --play`, `diffray door --play` and `--list-devices` (src/cli/auralize_play.cpp): real-time
// playback of a dry file convolved with an impulse response (or, for the door, with several crossfaded over
// time) through PortAudio (audio/portaudio_output.h). With no audio output device (CI, a headless server)
// both end with one line: --play exits 2 ("no audio output device …; write a file with -o instead"),
// --list-devices says none were found and exits 0.
#include <ostream>
#include <string>
#include <vector>

#include "diffray/audio/wav.h"

namespace diffray::cli {

struct PlayOptions {
  std::string ir;
  std::string in;
  std::string device;     ///< index or name substring; empty: the default output device
  int block_frames = 256; ///< the audio callback's buffer = the convolver's head block (the latency)
  double gain_db = 0.0;
  bool no_resample = false;  ///< refuse an IR at another rate than the dry signal's instead of resampling it
  std::string decode;  ///< empty: the IR as it is; "binaural" or "AZ:EL,…": an AmbiX IR decoded so
  std::string hrtf;    ///< the SOFA set of decode "binaural" (empty: the default set)
};

/// The IR's channels at the dry signal's rate `rate_hz`: as read when the rates agree, else resampled as a
/// filter (dsp::resampleImpulseResponse) with one info line on stdout, or refused (core::InputError naming
/// `ir_path`) when `no_resample`. Defined in src/cli/auralize.cpp.
std::vector<std::vector<float>> irAtRate(const audio::AudioBuffer& ir, double rate_hz, const std::string& ir_path,
                                         bool no_resample);

/// The IR's channels as `o.decode` asks (spatial/ambisonic_decoder.h): unchanged when it is empty, else an
/// AmbiX IR (4, 9 or 16 channels) decoded to the loudspeakers of the list or, for "binaural", to the two ears
/// through `o.hrtf` prepared at `rate_hz` (with one info line on stdout). Throws core::InputError naming
/// --decode, --hrtf or the IR. Defined in src/cli/auralize.cpp.
std::vector<std::vector<float>> decodedIr(std::vector<std::vector<float>> channels, const PlayOptions& o, double rate_hz);

/// The audio block (--block) playback accepts, in frames.
inline constexpr int kMinBlockFrames = 16, kMaxBlockFrames = 16384;
/// Throws core::InputError naming --block unless kMinBlockFrames ≤ block_frames ≤ kMaxBlockFrames: checked by
/// playAuralization() and, before any file is written, by `auralize --play -o`.
void requireBlockFrames(int block_frames);

/// Prints the output devices (index, name, host API, channels, default rate, default latency) on stdout;
/// returns the exit code (0).
int listAudioDevices();
/// Throws core::InputError unless `device` (as for --device) names an available output device.
void requireOutputDevice(const std::string& device);
/// Plays the convolution until it ends or Ctrl-C; returns the exit code (0, or 130 after Ctrl-C).
/// Throws core::InputError for bad files, options or no device.
int playAuralization(const PlayOptions& options);
/// `door --play`: plays the dry file `in` (its channels averaged) through `irs` crossfaded at `key_frames`
/// (audio::PlaybackRenderer's crossfading form; the IRs at the dry file's rate) on `device` (as for
/// --device), in blocks of `block_frames`, with `gain_db`; its status lines on `status` (stderr when stdout
/// holds JSON). Returns the exit code (0, or 130 after Ctrl-C); throws core::InputError for bad options or
/// no device.
int playCrossfade(const std::vector<std::vector<std::vector<float>>>& irs, const std::vector<long>& key_frames,
                  const std::string& in, const std::string& device, int block_frames, double gain_db,
                  std::ostream& status);

}  // namespace diffray::cli
