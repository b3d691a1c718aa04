#pragma once
// Speech made locally with Debian's espeak-ng (dry signals never downloaded). espeak-ng runs
// as a subprocess (posix_spawnp, no shell: the text goes through a temporary file, never the command line)
// writing a temporary 22.05 kHz mono WAV, which is read back, resampled to the requested rate
// (dsp::resample) and scaled so its peak is `amplitude` of full scale. The temporaries live in a private
// folder from mkdtemp and are removed whatever happens. Calls may run concurrently (each has its own folder).
#include <string>
#include <vector>

namespace diffray::audio {

struct SpeechSpec {
  std::string text = "The quick brown fox jumps over the lazy dog. A door closes slowly in the next room.";
  std::string voice = "en";    ///< an espeak-ng voice name (`espeak-ng --voices` lists them)
  int words_per_minute = 160;  ///< espeak-ng's -s, 80 … 450
  double rate_hz = 48000.0;
  double amplitude = 0.5;  ///< peak, linear (0, 1]
};

/// True when an `espeak-ng` program is on the PATH.
bool espeakAvailable();

/// Mono speech samples at spec.rate_hz. Throws core::InputError for empty text, a speed outside 80 … 450,
/// an amplitude outside (0, 1], a missing espeak-ng (with the apt-get line), an unknown voice or any other
/// espeak-ng failure (its exit code named), and for silent output.
std::vector<float> synthesizeSpeech(const SpeechSpec& spec);

}  // namespace diffray::audio
