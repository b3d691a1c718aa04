#pragma once
// Playback on a sound card through PortAudio. A PortAudioHost holds PortAudio initialised for its
// lifetime (Pa_Initialize / Pa_Terminate). PortAudio's host APIs (ALSA, JACK, OSS) print diagnostics on
// stderr while they probe devices, which on a machine without sound hardware is a screenful of noise: the
// host object sends fd 2 to /dev/null while PortAudio initialises, opens and closes streams and terminates,
// unless DIFFRAY_AUDIO_VERBOSE=1 is set. Errors still reach the user as one line (core::InputError carrying
// Pa_GetErrorText).
// Playback opens a paFloat32 output stream with the renderer's channel count and block size and hands it
// audio::playbackCallback (audio/playback.h); play() polls from the calling thread until the renderer
// finishes or `stop` is set (Ctrl-C).
// Thread-safety: one PortAudioHost at a time per process, used from one thread.
#include <atomic>
#include <string>
#include <vector>

#include "diffray/audio/playback.h"

namespace diffray::audio {

struct OutputDevice {
  int index = -1;  ///< PortAudio device index
  std::string name;
  std::string host_api;
  int max_output_channels = 0;
  double default_sample_rate_hz = 0.0;
  double default_low_latency_s = 0.0;
  bool is_default = false;
};

struct PlaybackReport {
  std::string device;
  double output_latency_s = 0.0;  ///< as PortAudio reports it for the open stream
  bool interrupted = false;       ///< stopped by `stop` before the end
};

class PortAudioHost {
 public:
  /// Initialises PortAudio; throws core::InputError when it cannot start.
  PortAudioHost();
  ~PortAudioHost();
  PortAudioHost(const PortAudioHost&) = delete;
  PortAudioHost& operator=(const PortAudioHost&) = delete;

  /// The devices with at least one output channel.
  std::vector<OutputDevice> outputDevices() const;
  /// `spec` empty: the default output device; all digits: that device index; anything else: the one output
  /// device whose name contains it (case-insensitive). Throws core::InputError when there is no output
  /// device at all, or none (or several) match.
  OutputDevice chooseOutputDevice(const std::string& spec) const;
  /// Plays `renderer` on `device` at `sample_rate_hz` until it finishes or `stop` becomes true. Throws
  /// core::InputError when the stream cannot be opened (rate or channel count refused, device busy).
  PlaybackReport play(PlaybackRenderer& renderer, const OutputDevice& device, double sample_rate_hz,
                      const std::atomic<bool>& stop);
};

}  // namespace diffray::audio
