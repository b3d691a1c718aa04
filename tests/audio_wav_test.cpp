// WAV I/O: float32 round trip bit-exact, atomic writes (nothing left behind on failure, an existing file
// untouched), and one-line errors naming the file for what libsndfile or our checks refuse.
#include <gtest/gtest.h>
#include <sndfile.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "temp_dir.h"
#include "diffray/audio/wav.h"
#include "diffray/core/error.h"

namespace diffray::audio {
namespace {

namespace fs = std::filesystem;

using diffray::test::TempDir;

std::string errorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const core::InputError& e) {
    return e.what();
  }
  return "";
}

TEST(AudioWav, Float32RoundTripIsBitExact) {
  const TempDir dir("wav_test");
  AudioBuffer a;
  a.sample_rate_hz = 44100;
  a.channels = 2;
  // Values that are exact floats, including tiny, huge and negative ones and > 1 (float WAV is not clipped).
  for (int i = 0; i < 1000; ++i)
    a.samples.push_back(static_cast<double>(static_cast<float>(std::sin(0.1 * i) * std::pow(10.0, i % 13 - 6))));
  a.samples[3] = 3.5;
  a.samples[4] = static_cast<double>(-1e-30f);
  writeWavFloat(dir.file("a.wav"), a);
  const AudioBuffer b = readAudio(dir.file("a.wav"));
  EXPECT_EQ(b.sample_rate_hz, 44100);
  EXPECT_EQ(b.channels, 2);
  ASSERT_EQ(b.samples.size(), a.samples.size());
  for (size_t i = 0; i < a.samples.size(); ++i) EXPECT_EQ(b.samples[i], a.samples[i]) << i;
  EXPECT_EQ(b.channel(1)[2], a.samples[5]);
  EXPECT_EQ(dir.entries(), 1);  // no temporary file left beside it
  // The file really is 32-bit float WAV.
  SF_INFO info;
  std::memset(&info, 0, sizeof info);
  SNDFILE* f = sf_open(dir.file("a.wav").c_str(), SFM_READ, &info);
  ASSERT_NE(f, nullptr);
  EXPECT_EQ(info.format, SF_FORMAT_WAV | SF_FORMAT_FLOAT);  // two channels: WAVE_FORMAT_IEEE_FLOAT
  sf_close(f);
}

// Channels held apart are written as the same file as their interleaved buffer, byte for byte; channels of
// different lengths and a non-finite sample are refused before anything is written.
TEST(AudioWav, PlanarChannelsWriteTheInterleavedFile) {
  const TempDir dir("wav_planar");
  AudioBuffer a;
  a.sample_rate_hz = 48000;
  a.channels = 3;
  std::vector<std::vector<double>> planar(3, std::vector<double>(9000));
  for (std::size_t f = 0; f < 9000; ++f)
    for (std::size_t c = 0; c < 3; ++c) {
      planar[c][f] = std::sin(0.01 * static_cast<double>(f) * static_cast<double>(c + 1)) / 3.0;  // rounds to float
      a.samples.push_back(planar[c][f]);
    }
  writeWavFloat(dir.file("i.wav"), a);
  writeWavFloat(dir.file("p.wav"), planar, 48000);
  std::ifstream i(dir.file("i.wav"), std::ios::binary), p(dir.file("p.wav"), std::ios::binary);
  const std::string ib{std::istreambuf_iterator<char>(i), {}}, pb{std::istreambuf_iterator<char>(p), {}};
  EXPECT_GT(ib.size(), 9000u * 3u * 4u);  // the samples and a header
  EXPECT_TRUE(ib == pb);
  planar[2].pop_back();
  EXPECT_NE(errorOf([&] { writeWavFloat(dir.file("q.wav"), planar, 48000); }).find("different lengths"), std::string::npos);
  planar[2].push_back(0.0);
  planar[1][4500] = NAN;
  EXPECT_NE(errorOf([&] { writeWavFloat(dir.file("q.wav"), planar, 48000); }).find("frame 4500, channel 2"), std::string::npos);
  EXPECT_EQ(dir.entries(), 2);
}

// The WAVE header per Microsoft's WAVEFORMATEX and WAVEFORMATEXTENSIBLE, read byte by byte here for both
// writers (whole buffer and streaming). Every non-PCM format carries cbSize; one or two channels of float are
// WAVE_FORMAT_IEEE_FLOAT (tag 3) in an 18-byte fmt chunk with cbSize 0; more than two channels require the
// extensible form: a 40-byte fmt chunk, tag 0xFFFE, cbSize 22, 32 valid bits, the IEEE-float sub-format GUID.
// A fact chunk (required for every format but PCM) holds the frames per channel; the RIFF and data sizes
// match the file.
void expectFloatHeader(const std::string& path, int channels, unsigned frames) {
  std::ifstream in(path, std::ios::binary);
  const std::string b((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto u16 = [&](std::size_t i) { return static_cast<unsigned>(static_cast<unsigned char>(b[i]) | static_cast<unsigned char>(b[i + 1]) << 8); };
  const auto u32 = [&](std::size_t i) { return u16(i) | u16(i + 2) << 16; };
  ASSERT_GE(b.size(), 12u);
  ASSERT_EQ(b.substr(0, 4), "RIFF");
  EXPECT_EQ(u32(4), b.size() - 8);
  ASSERT_EQ(b.substr(8, 4), "WAVE");
  std::size_t fmt = 0, fact = 0, data = 0;
  for (std::size_t i = 12; i + 8 <= b.size(); i += 8 + u32(i + 4) + (u32(i + 4) & 1u)) {
    if (b.substr(i, 4) == "fmt ") fmt = i;
    if (b.substr(i, 4) == "fact") fact = i;
    if (b.substr(i, 4) == "data") data = i;
  }
  ASSERT_NE(fmt, 0u) << path;
  ASSERT_NE(fact, 0u) << path;
  ASSERT_NE(data, 0u) << path;
  EXPECT_EQ(u32(fact + 8), frames);
  EXPECT_EQ(u32(data + 4), frames * 4u * static_cast<unsigned>(channels));
  EXPECT_EQ(data + 8 + u32(data + 4), b.size());
  EXPECT_EQ(u16(fmt + 10), static_cast<unsigned>(channels));
  EXPECT_EQ(u32(fmt + 12), 48000u);
  EXPECT_EQ(u32(fmt + 16), 48000u * 4u * static_cast<unsigned>(channels));  // bytes per second
  EXPECT_EQ(u16(fmt + 20), 4u * static_cast<unsigned>(channels));             // block align
  EXPECT_EQ(u16(fmt + 22), 32u);                                              // bits per sample
  if (channels <= 2) {
    EXPECT_EQ(u32(fmt + 4), 18u);
    EXPECT_EQ(u16(fmt + 8), 3u);   // WAVE_FORMAT_IEEE_FLOAT
    EXPECT_EQ(u16(fmt + 24), 0u);  // cbSize
    return;
  }
  EXPECT_EQ(u32(fmt + 4), 40u);
  EXPECT_EQ(u16(fmt + 8), 0xFFFEu);
  EXPECT_EQ(u16(fmt + 24), 22u);  // cbSize
  EXPECT_EQ(u16(fmt + 26), 32u);  // valid bits
  const unsigned char guid[16] = {0x03, 0x00, 0x00, 0x00, 0x00, 0x00, 0x10, 0x00,
                                  0x80, 0x00, 0x00, 0xAA, 0x00, 0x38, 0x9B, 0x71};
  EXPECT_EQ(std::memcmp(b.data() + fmt + 32, guid, 16), 0) << "KSDATAFORMAT_SUBTYPE_IEEE_FLOAT";
}

TEST(AudioWav, HeaderIsFloatPerTheWaveSpec) {
  const TempDir dir("wav_test");
  for (int channels : {1, 2, 3, 5}) {
    AudioBuffer a;
    a.sample_rate_hz = 48000;
    a.channels = channels;
    a.samples.assign(static_cast<std::size_t>(channels) * 64, 0.25);
    const std::string whole = dir.file("whole" + std::to_string(channels) + ".wav");
    writeWavFloat(whole, a);
    expectFloatHeader(whole, channels, 64);
    const std::string streamed = dir.file("streamed" + std::to_string(channels) + ".wav");
    WavWriter w(streamed, 48000, channels);
    const std::vector<float> frames(static_cast<std::size_t>(channels) * 40, 0.25f);
    w.write(frames.data(), 40);
    w.write(frames.data(), 24);
    w.commit();
    expectFloatHeader(streamed, channels, 64);
    // libsndfile reads both back, every sample.
    for (const std::string& f : {whole, streamed}) {
      const AudioBuffer r = readAudio(f);
      EXPECT_EQ(r.channels, channels);
      ASSERT_EQ(r.samples.size(), a.samples.size()) << f;
      for (double v : r.samples) EXPECT_EQ(v, 0.25);
    }
  }
}

TEST(AudioWav, NoTimestampedChunkSoSameSamplesGiveSameBytes) {
  // libsndfile's PEAK chunk (float WAV) holds the wall-clock time of writing: with it, two runs with the same
  // seed wrote different files. The header must hold nothing but the format and the samples.
  const TempDir dir("wav_test");
  AudioBuffer a;
  a.sample_rate_hz = 48000;
  a.channels = 1;
  a.samples = {0.25, -0.5, 0.125};
  writeWavFloat(dir.file("a.wav"), a);
  std::ifstream in(dir.file("a.wav"), std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(bytes.find("PEAK"), std::string::npos);
  EXPECT_NE(bytes.find("data"), std::string::npos);
}

TEST(AudioWav, FailedWriteLeavesNoFileAndKeepsTheOldOne) {
  const TempDir dir("wav_test");
  AudioBuffer good{48000, 1, {0.5, -0.25}};
  writeWavFloat(dir.file("ir.wav"), good);
  AudioBuffer bad = good;
  bad.samples[1] = std::nan("");
  EXPECT_NE(errorOf([&] { writeWavFloat(dir.file("ir.wav"), bad); }).find("NaN"), std::string::npos);
  bad.samples[1] = 1e39;  // beyond float
  EXPECT_NE(errorOf([&] { writeWavFloat(dir.file("ir.wav"), bad); }), "");
  EXPECT_EQ(readAudio(dir.file("ir.wav")).samples, good.samples);
  EXPECT_EQ(dir.entries(), 1);
  EXPECT_NE(errorOf([&] { writeWavFloat(dir.file("no/such/dir/x.wav"), good); }).find("x.wav"), std::string::npos);
  EXPECT_NE(errorOf([&] { writeWavFloat(dir.file("y.wav"), AudioBuffer{48000.5, 1, {0.1}}); }), "");
  EXPECT_NE(errorOf([&] { writeWavFloat(dir.file("y.wav"), AudioBuffer{48000, 2, {0.1}}); }), "");
  EXPECT_EQ(dir.entries(), 1);
}

TEST(AudioWav, SizeLimitIsTheRiff32BitField) {
  // 2^32 − 1 bytes is the largest a 32-bit size field holds: 10^9 mono float frames (4·10^9 bytes) fit,
  // 2^30 (exactly 4 GiB) do not, nor 2^29 stereo ones; 3600 s at 384 kHz mono (1.3824·10^9 frames) do not.
  EXPECT_NO_THROW(requireWavFits("-o", 1e9, 1, 48000.0));
  EXPECT_THROW(requireWavFits("-o", 1073741824.0, 1, 48000.0), core::InputError);
  EXPECT_THROW(requireWavFits("-o", 536870912.0, 2, 48000.0), core::InputError);
  EXPECT_NO_THROW(requireWavFits("-o", 536870912.0 - 1024.0, 2, 48000.0));
  EXPECT_THROW(requireWavFits("--duration", 3600.0 * 384000.0, 1, 384000.0), core::InputError);
}

TEST(AudioWav, ReadErrorsNameTheFileAndTheReason) {
  const TempDir dir("wav_test");
  const std::string missing = dir.file("missing.wav");
  const std::string m = errorOf([&] { readAudio(missing); });
  EXPECT_NE(m.find(missing), std::string::npos);
  EXPECT_NE(m.find("No such file"), std::string::npos) << m;
  std::ofstream(dir.file("text.wav")) << "this is not audio\n";
  EXPECT_NE(errorOf([&] { readAudio(dir.file("text.wav")); }).find("text.wav"), std::string::npos);
  // A float WAV holding NaN, written by libsndfile directly (writeWavFloat refuses to).
  SF_INFO info;
  std::memset(&info, 0, sizeof info);
  info.samplerate = 48000;
  info.channels = 1;
  info.format = SF_FORMAT_WAV | SF_FORMAT_FLOAT;
  SNDFILE* f = sf_open(dir.file("nan.wav").c_str(), SFM_WRITE, &info);
  ASSERT_NE(f, nullptr);
  const float data[3] = {0.5f, std::nanf(""), 0.25f};
  sf_writef_float(f, data, 3);
  sf_close(f);
  EXPECT_NE(errorOf([&] { readAudio(dir.file("nan.wav")); }).find("NaN"), std::string::npos);
  // Zero frames.
  f = sf_open(dir.file("empty.wav").c_str(), SFM_WRITE, &info);
  ASSERT_NE(f, nullptr);
  sf_close(f);
  EXPECT_NE(errorOf([&] { readAudio(dir.file("empty.wav")); }).find("no frames"), std::string::npos);
}

}  // namespace
}  // namespace diffray::audio
