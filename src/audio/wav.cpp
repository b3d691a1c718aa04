#include "diffray/audio/wav.h"

#include <sndfile.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cfloat>
#include <cstdint>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <cstdio>
#include <memory>
#include <sstream>

#include "diffray/audio/wav_float_format.h"
#include "diffray/core/atomic_file.h"
#include "diffray/core/error.h"

namespace diffray::audio {

namespace {

/// The refusal of a file holding more than `cap` frames or samples, with the cap stated.
core::InputError tooLong(const std::string& path, long cap, const char* what) {
  return core::InputError(path, std::string("the audio file is too long: diffray reads at most ") + std::to_string(cap) +
                                    " " + what + " of it into memory");
}
// The highest sample rate read (768 kHz, the top of the PCM rates in use): a header claiming more is
// refused before any buffer is sized by it (a 4 kB file saying 1 GHz once took 3 GB in metrics' FFTs).
constexpr int kMaxReadRateHz = 768000;
void checkSampleRate(const std::string& path, int rate_hz) {
  if (rate_hz > kMaxReadRateHz)
    throw core::InputError(path, "sample rate " + std::to_string(rate_hz) + " Hz is above the highest diffray reads (" +
                                     std::to_string(kMaxReadRateHz) + " Hz)");
}

struct SndfileCloser {
  void operator()(SNDFILE* f) const { sf_close(f); }
};
using SndfilePtr = std::unique_ptr<SNDFILE, SndfileCloser>;

std::string sampleWhere(long index, int channels) {
  std::ostringstream s;
  s << "frame " << index / channels << ", channel " << index % channels + 1;
  return s.str();
}

}  // namespace

std::vector<double> AudioBuffer::channel(int c) const {
  DIFFRAY_CHECK(c >= 0 && c < channels);
  std::vector<double> out(static_cast<size_t>(frames()));
  for (size_t f = 0; f < out.size(); ++f) out[f] = samples[f * static_cast<size_t>(channels) + static_cast<size_t>(c)];
  return out;
}

namespace {
/// libsndfile reads a file cut short (a copy or download interrupted) without an error: it notes in its log
/// "data : DECLARED (should be HELD)" and reads the frames that are there. This turns that note into one line.
std::string truncationWarning(SNDFILE* file, const std::string& path) {
  char log[8192] = {};
  sf_command(file, SFC_GET_LOG_INFO, log, sizeof(log) - 1);
  const std::string text(log);
  std::size_t at = text.find("\ndata");
  if (at == std::string::npos) return "";
  const std::size_t end = text.find('\n', at + 1);
  const std::string line = text.substr(at + 1, end == std::string::npos ? std::string::npos : end - at - 1);
  const std::size_t colon = line.find(':'), should = line.find("(should be ");
  if (colon == std::string::npos || should == std::string::npos) return "";
  const long long declared = std::atoll(line.c_str() + colon + 1);
  const long long held = std::atoll(line.c_str() + should + 11);
  if (!(held < declared)) return "";
  return path + ": the file is cut short: its header declares " + std::to_string(declared) +
         " bytes of samples, it holds " + std::to_string(held) + " (only those are read)";
}
}  // namespace

AudioBuffer readAudio(const std::string& path, std::string* warning) {
  SF_INFO info;
  std::memset(&info, 0, sizeof(info));
  SndfilePtr file(sf_open(path.c_str(), SFM_READ, &info));
  if (!file) throw core::InputError(path, std::string("cannot read audio: ") + sf_strerror(nullptr));
  if (info.frames <= 0) throw core::InputError(path, "the audio file holds no frames");
  if (info.channels <= 0 || info.samplerate <= 0)
    throw core::InputError(path, "the audio file has no channels or no sample rate");
  checkSampleRate(path, info.samplerate);
  AudioBuffer out;
  out.sample_rate_hz = info.samplerate;
  out.channels = info.channels;
  if (warning != nullptr) *warning = truncationWarning(file.get(), path);
  // In blocks, the buffer growing with the frames actually decoded: the header's length is not trusted
  // (a FLAC's STREAMINFO may claim 2^36 frames in a 242-byte file).
  const auto channels = static_cast<size_t>(info.channels);
  constexpr sf_count_t kBlock = 1 << 16;
  size_t held = 0;  // samples read
  for (;;) {
    if (held + static_cast<size_t>(kBlock) * channels > static_cast<size_t>(kMaxReadSamples)) {
      // Room for the last block only up to the cap, and one frame more to see whether the file goes on.
      const auto room = static_cast<sf_count_t>((static_cast<size_t>(kMaxReadSamples) - held) / channels);
      out.samples.resize(held + static_cast<size_t>(room + 1) * channels);
      const sf_count_t got = sf_readf_double(file.get(), out.samples.data() + held, room + 1);
      if (got > room) throw tooLong(path, kMaxReadSamples, "samples");
      held += static_cast<size_t>(std::max<sf_count_t>(got, 0)) * channels;
      break;
    }
    out.samples.resize(held + static_cast<size_t>(kBlock) * channels);
    const sf_count_t got = sf_readf_double(file.get(), out.samples.data() + held, kBlock);
    if (got > 0) held += static_cast<size_t>(got) * channels;
    if (got < kBlock) break;
  }
  if (sf_error(file.get()) != SF_ERR_NO_ERROR)
    throw core::InputError(path, std::string("cannot read audio: ") + sf_strerror(file.get()));
  if (held == 0) throw core::InputError(path, "the audio file holds no frames");
  out.samples.resize(held);
  out.samples.shrink_to_fit();
  for (size_t i = 0; i < out.samples.size(); ++i)
    if (!std::isfinite(out.samples[i]))
      throw core::InputError(path, "sample at " + sampleWhere(static_cast<long>(i), out.channels) + " is " +
                                       (std::isnan(out.samples[i]) ? "NaN" : "infinite"));
  return out;
}

void requireWavFits(const std::string& field, double frames, int channels, double sample_rate_hz) {
  const double bytes = frames * channels * sizeof(float);
  if (!(bytes <= kMaxWavDataBytes)) {
    const double max_s = std::floor(kMaxWavDataBytes / (channels * sizeof(float))) / sample_rate_hz;
    std::ostringstream what;
    what << "the output would hold " << frames << " frames x " << channels << " channel(s) = " << bytes / 1e9
         << " GB of float32, beyond a WAV file's 4 GiB limit (at most " << max_s << " s at " << sample_rate_hz
         << " Hz)";
    throw core::InputError(field, what.str());
  }
}

namespace {

/// writeWavFloat of `channels` channels of `frames` frames at fs, sample_at(f, c) giving frame f of channel c.
template <class SampleAt>
void writeFloatSamples(const std::string& path, int channels, std::size_t frames, double fs, SampleAt sample_at) {
  // Everything is checked before a byte is written.
  if (channels < 1 || channels > 1024)
    throw core::InputError(path, "cannot write " + std::to_string(channels) + " channels");
  if (frames == 0) throw core::InputError(path, "cannot write: the sample count is zero or not a whole number of frames");
  if (!(fs >= 1.0 && fs <= 1e7 && std::floor(fs) == fs))
    throw core::InputError(path, "cannot write a WAV at a sample rate of " + std::to_string(fs) +
                                     " Hz (a whole number of Hz is needed)");
  for (std::size_t f = 0; f < frames; ++f)
    for (int c = 0; c < channels; ++c) {
      const double v = sample_at(f, c);
      if (!std::isfinite(v) || std::abs(v) > FLT_MAX)
        throw core::InputError(path, "refusing to write sample at " +
                                         sampleWhere(static_cast<long>(f) * channels + c, channels) + ": " +
                                         (std::isnan(v) ? "NaN" : "not a finite 32-bit float"));
    }
  if (fs * 4.0 * channels > 4294967295.0)
    throw core::InputError(path, "cannot write a WAV of " + std::to_string(channels) + " channels at " +
                                     std::to_string(fs) + " Hz (its byte rate field is 32-bit)");
  requireWavFits(path, static_cast<double>(frames), channels, fs);
  std::string bytes = floatWavHeader(channels, static_cast<int>(fs), frames);
  bytes.reserve(bytes.size() + frames * static_cast<std::size_t>(channels) * sizeof(float));
  std::vector<float> block;  // interleaved, a few thousand frames at a time
  constexpr std::size_t kBlockFrames = 4096;
  for (std::size_t f0 = 0; f0 < frames; f0 += kBlockFrames) {
    const std::size_t f1 = std::min(frames, f0 + kBlockFrames);
    block.clear();
    for (std::size_t f = f0; f < f1; ++f)
      for (int c = 0; c < channels; ++c) block.push_back(static_cast<float>(sample_at(f, c)));
    appendFloat32LE(bytes, block.data(), block.size());
  }
  core::writeFileAtomically(path, [&bytes](std::ostream& out) {
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  });
}

}  // namespace

void writeWavFloat(const std::string& path, const AudioBuffer& audio) {
  if (audio.channels < 1 || audio.channels > 1024)
    throw core::InputError(path, "cannot write " + std::to_string(audio.channels) + " channels");
  if (audio.samples.size() % static_cast<size_t>(audio.channels) != 0)
    throw core::InputError(path, "cannot write: the sample count is zero or not a whole number of frames");
  const auto channels = static_cast<std::size_t>(audio.channels);
  writeFloatSamples(path, audio.channels, audio.samples.size() / channels, audio.sample_rate_hz,
                    [&](std::size_t f, int c) { return audio.samples[f * channels + static_cast<std::size_t>(c)]; });
}

void writeWavFloat(const std::string& path, const std::vector<std::vector<double>>& channels, double sample_rate_hz) {
  for (const std::vector<double>& c : channels)
    if (c.size() != channels.front().size()) throw core::InputError(path, "cannot write channels of different lengths");
  writeFloatSamples(path, static_cast<int>(std::min<std::size_t>(channels.size(), 1025)),
                    channels.empty() ? 0 : channels.front().size(), sample_rate_hz,
                    [&](std::size_t f, int c) { return channels[static_cast<std::size_t>(c)][f]; });
}

AudioReader::AudioReader(const std::string& path) : path_(path) {
  SF_INFO info;
  std::memset(&info, 0, sizeof(info));
  SNDFILE* file = sf_open(path.c_str(), SFM_READ, &info);
  if (file == nullptr) throw core::InputError(path, std::string("cannot read audio: ") + sf_strerror(nullptr));
  if (info.frames <= 0 || info.channels <= 0 || info.samplerate <= 0) {
    sf_close(file);  // the destructor does not run when the constructor throws
    throw core::InputError(path, info.frames <= 0 ? "the audio file holds no frames"
                                                  : "the audio file has no channels or no sample rate");
  }
  if (info.samplerate > kMaxReadRateHz) {
    sf_close(file);
    checkSampleRate(path, info.samplerate);
  }
  file_ = file;
  warning_ = truncationWarning(file, path);
  sample_rate_hz_ = info.samplerate;
  channels_ = info.channels;
  frames_ = static_cast<long>(info.frames);
}

AudioReader::~AudioReader() {
  if (file_ != nullptr) sf_close(static_cast<SNDFILE*>(file_));
}

long AudioReader::read(float* out, long frames) {
  auto* file = static_cast<SNDFILE*>(file_);
  const sf_count_t got = sf_readf_float(file, out, static_cast<sf_count_t>(frames));
  if (sf_error(file) != SF_ERR_NO_ERROR)
    throw core::InputError(path_, std::string("cannot read audio: ") + sf_strerror(file));
  const long samples = static_cast<long>(got) * channels_;
  for (long i = 0; i < samples; ++i)
    if (!std::isfinite(out[i]))
      throw core::InputError(path_, "sample at " + sampleWhere(position_ * channels_ + i, channels_) + " is " +
                                        (std::isnan(out[i]) ? "NaN" : "infinite"));
  position_ += static_cast<long>(got);
  return static_cast<long>(got);
}

std::vector<float> readChannel(AudioReader& reader, int channel, long max_frames) {
  constexpr long kBlock = 8192;
  const int cin = reader.channels();
  DIFFRAY_CHECK(channel < cin);
  std::vector<float> block(static_cast<size_t>(kBlock * cin)), x;
  for (long frames; (frames = reader.read(block.data(), kBlock)) > 0;) {
    if (static_cast<long>(x.size()) + frames > max_frames) throw tooLong(reader.path(), max_frames, "frames");
    for (long f = 0; f < frames; ++f) {
      if (channel >= 0) {
        x.push_back(block[static_cast<size_t>(f * cin + channel)]);
        continue;
      }
      double sum = 0.0;
      for (int c = 0; c < cin; ++c) sum += block[static_cast<size_t>(f * cin + c)];
      x.push_back(static_cast<float>(sum / cin));
    }
  }
  return x;
}

WavWriter::WavWriter(const std::string& path, int sample_rate_hz, int channels)
    : path_(path), tmp_(path + ".tmp." + std::to_string(::getpid())), registered_(tmp_), channels_(channels) {
  if (channels < 1 || channels > 1024 || sample_rate_hz < 1 ||
      static_cast<double>(sample_rate_hz) * 4.0 * channels > 4294967295.0)
    throw core::InputError(path, "cannot write a float WAV of " + std::to_string(channels) + " channels at " +
                                     std::to_string(sample_rate_hz) + " Hz");
  rate_hz_ = sample_rate_hz;
  std::FILE* file = std::fopen(tmp_.c_str(), "wb");
  if (file == nullptr) throw core::InputError(path, std::string("cannot open for writing: ") + std::strerror(errno));
  file_ = file;
  const std::string header = floatWavHeader(channels_, rate_hz_, 0);  // sizes filled in by commit()
  if (std::fwrite(header.data(), 1, header.size(), file) != header.size())
    throw core::InputError(path, std::string("write failed: ") + std::strerror(errno));
}

WavWriter::~WavWriter() {
  if (file_ == nullptr) return;  // committed
  std::fclose(static_cast<std::FILE*>(file_));
  std::remove(tmp_.c_str());
}

void WavWriter::write(const float* samples, long frames) {
  const long count = frames * channels_;
  for (long i = 0; i < count; ++i)
    if (!std::isfinite(samples[i]))
      throw core::InputError(path_, "refusing to write sample at " + sampleWhere(written_ * channels_ + i, channels_) +
                                        ": " + (std::isnan(samples[i]) ? "NaN" : "infinite"));
  if ((static_cast<double>(written_) + static_cast<double>(frames)) * 4.0 * channels_ > kMaxWavDataBytes)
    throw core::InputError(path_, "write failed: the audio outgrows a WAV file's 4 GiB limit");
  block_.clear();
  appendFloat32LE(block_, samples, static_cast<std::size_t>(count));
  if (std::fwrite(block_.data(), 1, block_.size(), static_cast<std::FILE*>(file_)) != block_.size())
    throw core::InputError(path_, std::string("write failed: ") + std::strerror(errno));
  written_ += frames;
}

void WavWriter::commit() {
  DIFFRAY_CHECK(file_ != nullptr);
  auto* file = static_cast<std::FILE*>(file_);
  const std::string header = floatWavHeader(channels_, rate_hz_, static_cast<std::uint64_t>(written_));
  const bool header_ok = std::fseek(file, 0, SEEK_SET) == 0 &&
                         std::fwrite(header.data(), 1, header.size(), file) == header.size();
  const int closed = std::fclose(file);
  file_ = nullptr;
  if (!header_ok || closed != 0 || std::rename(tmp_.c_str(), path_.c_str()) != 0) {
    std::remove(tmp_.c_str());
    throw core::InputError(path_, "cannot finish writing (header, close or rename failed)");
  }
}

}  // namespace diffray::audio
