#pragma once
// Audio file I/O: reading through libsndfile, writing 32-bit float WAV (audio/wav_float_format.h). An AudioBuffer holds interleaved samples in double, on diffray's convention
// that Σ p[n]² over a span is the energy (J/m²) of that span: no normalisation is applied,
// so a float WAV round-trips bit-exactly (float → double → float). Reading accepts anything libsndfile
// reads (WAV, AIFF, FLAC, …; integer formats are scaled to [−1, 1) as libsndfile does). Writing produces
// 32-bit float WAV, atomically (core::writeFileAtomically): a failed write leaves no file and leaves an
// existing file untouched. Plain data and free functions; calls on different files may run concurrently.
// AudioReader and WavWriter stream a file in blocks (memory independent of its length): the writer fills a
// temporary file beside the target and renames it over the target in commit(); destroyed uncommitted (an
// error on the way), it removes the temporary, so no half-written file is ever left. Each object is used
// by one thread at a time.
#include <string>
#include <vector>

#include "diffray/core/temp_files.h"

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
/// `warning`, when given, receives why the file may not be what its header claims (cut short: fewer sample
/// bytes than declared; the frames that are there are read), or "".
AudioBuffer readAudio(const std::string& path, std::string* warning = nullptr);

/// Writes `audio` as a 32-bit float WAV, atomically. Throws core::InputError naming `path` for NaN/Inf
/// samples or samples beyond the float range (checked before anything is written), for a sample rate or
/// channel count a WAV cannot hold (1..1024 channels, a 32-bit byte rate), and when the file cannot be written.
void writeWavFloat(const std::string& path, const AudioBuffer& audio);
/// The same for channels held apart (channels[c][frame], all of one length), written without an
/// interleaved copy of the samples; also refuses channels of different lengths.
void writeWavFloat(const std::string& path, const std::vector<std::vector<double>>& channels, double sample_rate_hz);

/// The largest float32 payload a WAV file holds: its RIFF and data chunk sizes are unsigned 32-bit fields,
/// so frames·channels·4 bytes plus the header (a few dozen bytes; 1 KiB reserved) must stay below 4 GiB.
/// (no RF64 is written; a larger plain WAV would carry wrapped sizes that readers refuse.)
inline constexpr double kMaxWavDataBytes = 4294967295.0 - 1024.0;
/// Throws core::InputError naming `field` when `frames` × `channels` float32 samples would not fit in one
/// WAV file (kMaxWavDataBytes), with the length that would fit at `sample_rate_hz`. For a check before any
/// work: `frames` is a double so that a product of options cannot overflow.
void requireWavFits(const std::string& field, double frames, int channels, double sample_rate_hz);

/// Reads an audio file (anything libsndfile reads) block by block, as float in [−1, 1) for integer formats.
class AudioReader {
 public:
  /// Opens `path`. Throws core::InputError naming `path` for a missing or unreadable file, an unknown
  /// format, or a file with no frames.
  explicit AudioReader(const std::string& path);
  ~AudioReader();
  AudioReader(const AudioReader&) = delete;
  AudioReader& operator=(const AudioReader&) = delete;

  double sampleRateHz() const { return sample_rate_hz_; }
  int channels() const { return channels_; }
  long frames() const { return frames_; }  ///< as the header says: a claim, not a size to allocate
  const std::string& path() const { return path_; }
  /// Reads up to `frames` interleaved frames into `out` (room for frames·channels() floats); returns the
  /// number read, 0 at the end. Throws core::InputError naming the file for a read error or a NaN/Inf
  /// sample (the frame and channel named).
  long read(float* out, long frames);
  /// Why the file may not be what its header claims (a file cut short: fewer sample bytes than declared), or
  /// empty. The frames that are there are read; the caller decides whether to warn.
  const std::string& warning() const { return warning_; }

 private:
  std::string path_;
  void* file_ = nullptr;  ///< SNDFILE*
  double sample_rate_hz_ = 0.0;
  int channels_ = 0;
  long frames_ = 0;
  long position_ = 0;  ///< frames read so far
  std::string warning_;
};

/// The most samples (frames × channels) a reader keeps in memory: 2^30, 8 GiB as double. Reading stops
/// with core::InputError past it, whatever the header claims (a header's length is never trusted: buffers
/// grow with the data actually decoded).
inline constexpr long kMaxReadSamples = 1L << 30;

/// The rest of `reader`'s file as one channel: channel `channel` (0-based), or the mean of all channels for
/// channel < 0. Memory grows with the frames actually read; more than `max_frames` frames is refused with
/// core::InputError naming the file and the cap.
std::vector<float> readChannel(AudioReader& reader, int channel, long max_frames = kMaxReadSamples);

/// Writes a 32-bit float WAV block by block into a temporary file beside `path`, renamed to `path` by
/// commit(). Without commit() (an exception on the way) the temporary is removed in the destructor.
class WavWriter {
 public:
  /// Throws core::InputError naming `path` for a layout a WAV cannot hold or a file it cannot create.
  WavWriter(const std::string& path, int sample_rate_hz, int channels);
  ~WavWriter();
  WavWriter(const WavWriter&) = delete;
  WavWriter& operator=(const WavWriter&) = delete;

  /// Appends `frames` interleaved frames. Throws core::InputError naming `path` for a NaN/Inf sample (the
  /// frame named) or a failed write.
  void write(const float* samples, long frames);
  /// Closes the file (final header sizes) and renames it to `path`. Throws core::InputError on failure.
  void commit();
  long framesWritten() const { return written_; }

 private:
  std::string path_;
  std::string tmp_;
  core::TempRegistration registered_;  ///< tmp_, deleted if the program is interrupted before commit()
  void* file_ = nullptr;  ///< std::FILE*
  int channels_ = 0;
  int rate_hz_ = 0;
  long written_ = 0;
  std::string block_;  ///< one block's little-endian bytes, reused
};

}  // namespace diffray::audio
