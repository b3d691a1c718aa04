#pragma once
// The bytes of a 32-bit IEEE-float WAV header, written by diffray itself because libsndfile's plain float
// WAV has a 16-byte fmt chunk without the cbSize field that the WAVE spec requires of every non-PCM format
// (Microsoft, "WAVEFORMATEX structure": cbSize is ignored only for WAVE_FORMAT_PCM).
//   - 1 or 2 channels: WAVE_FORMAT_IEEE_FLOAT (3) in an 18-byte WAVEFORMATEX, cbSize = 0.
//   - more than 2 channels: WAVE_FORMAT_EXTENSIBLE (0xFFFE) in a 40-byte WAVEFORMATEXTENSIBLE, cbSize = 22,
//     32 valid bits, channel mask 0 (channels are listeners, not loudspeakers), sub-format
//     KSDATAFORMAT_SUBTYPE_IEEE_FLOAT (Microsoft, "Multiple channel audio data and WAVE files": the extensible
//     form is required above two channels).
// Both are followed by a fact chunk (sample frames per channel, required for non-PCM data) and the data
// chunk header; the samples follow as little-endian float32, interleaved. Pure functions, thread-safe.
#include <cstdint>
#include <string>

namespace diffray::audio {

/// The header (RIFF, fmt, fact, data chunk header) of a float32 WAV of `channels` channels at
/// `sample_rate_hz` holding `frames` frames. The caller keeps the sizes within a WAV's 32-bit fields
/// (kMaxWavDataBytes) and `channels` in 1..65535.
std::string floatWavHeader(int channels, int sample_rate_hz, std::uint64_t frames);

/// Appends `count` floats to `out` as little-endian IEEE-754 binary32, whatever the host's byte order.
void appendFloat32LE(std::string& out, const float* values, std::size_t count);

}  // namespace diffray::audio
