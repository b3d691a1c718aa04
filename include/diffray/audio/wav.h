#pragma once
// Audio file I/O through libsndfile. An AudioBuffer holds interleaved samples in double, on the convention
// of design.md §2 that Σ p[n]² over a span is the energy (J/m²) of that span: no normalisation is applied,
// so a float WAV round-trips bit-exactly (float → double → float). Reading accepts anything libsndfile
// reads (WAV, AIFF, FLAC, …; integer formats are scaled to [−1, 1) as libsndfile does). Writing produces
// 32-bit float WAV, atomically (core::writeFileAtomically): a failed write leaves no file and leaves an
// existing file untouched. Plain data and free functions; calls on different files may run concurrently.
#include <string>
#include <vector>

namespace diffray::audio {

struct AudioBuffer {
  double sample_rate_hz = 48000.0;
  int channels = 1;
  std::vector<double> samples;  ///< interleaved: frame f, channel c at samples[f * channels + c]

  long frames() const { return channels > 0 ? static_cast<long>(samples.size()) / channels : 0; }
  /// One channel (0-based) as its own vector.
  std::vector<double> channel(int c) const;
};

/// Reads a whole audio file. Throws core::InputError naming `path` with libsndfile's reason for a missing
/// or unreadable file or an unknown format, and for an empty file (zero frames) or NaN/Inf samples.
AudioBuffer readAudio(const std::string& path);

/// Writes `audio` as a 32-bit float WAV, atomically. Throws core::InputError naming `path` for NaN/Inf
/// samples or samples beyond the float range (checked before anything is written), for a sample rate or
/// channel count libsndfile refuses, and when the file cannot be written.
void writeWavFloat(const std::string& path, const AudioBuffer& audio);

}  // namespace diffray::audio
