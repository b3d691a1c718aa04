// Audio readers trust no header's length: a FLAC whose STREAMINFO claims far more frames than the file
// holds is read as the frames it holds, memory growing only with the data actually decoded (a 242-byte
// file claiming 2^30 frames once took 8.4 GB). The files are written with libsndfile in the test's own
// folder, then their header is patched by hand (FLAC format specification, STREAMINFO block: the total
// sample count is the low 36 bits of the 8 bytes at offset 18).
#include <gtest/gtest.h>
#include <sndfile.h>

#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

#include "diffray/audio/wav.h"
#include "diffray/core/error.h"
#include "temp_dir.h"

namespace diffray::audio {
namespace {

using diffray::test::TempDir;

constexpr long kFrames = 1000;

/// Sample f of channel c: multiples of 2^-15, exact in 16-bit PCM.
double sampleAt(long f, int c) { return static_cast<double>((f * 37 + c * 1001) % 2000 - 1000) / 32768.0; }

/// Writes a 16-bit FLAC of kFrames frames, then makes its header claim `claimed` frames.
void writeFlacClaiming(const std::string& path, int channels, std::uint64_t claimed) {
  SF_INFO info{};
  info.samplerate = 48000;
  info.channels = channels;
  info.format = SF_FORMAT_FLAC | SF_FORMAT_PCM_16;
  SNDFILE* file = sf_open(path.c_str(), SFM_WRITE, &info);
  ASSERT_NE(file, nullptr) << sf_strerror(nullptr);
  std::vector<double> samples;
  for (long f = 0; f < kFrames; ++f)
    for (int c = 0; c < channels; ++c) samples.push_back(sampleAt(f, c));
  ASSERT_EQ(sf_writef_double(file, samples.data(), kFrames), kFrames);
  sf_close(file);

  std::fstream bytes(path, std::ios::in | std::ios::out | std::ios::binary);
  char head[26];
  ASSERT_TRUE(bytes.read(head, sizeof head));
  ASSERT_EQ(std::string(head, 4), "fLaC");
  ASSERT_EQ(head[4] & 0x7f, 0) << "the first metadata block is STREAMINFO";
  std::uint64_t field = 0;
  for (int i = 18; i < 26; ++i) field = field << 8 | static_cast<unsigned char>(head[i]);
  ASSERT_EQ(field & ((std::uint64_t{1} << 36) - 1), static_cast<std::uint64_t>(kFrames));
  field = (field & ~((std::uint64_t{1} << 36) - 1)) | claimed;
  for (int i = 25; i >= 18; --i, field >>= 8) head[i] = static_cast<char>(field & 0xff);
  bytes.seekp(0);
  ASSERT_TRUE(bytes.write(head, sizeof head));
}

TEST(AudioClaimedLength, ReaderSeesTheClaimedLength) {
  // The patch works: libsndfile reports the claimed length.
  const TempDir dir("claimed_length");
  writeFlacClaiming(dir.file("a.flac"), 1, std::uint64_t{1} << 35);
  const AudioReader reader(dir.file("a.flac"));
  EXPECT_EQ(reader.frames(), 1L << 35);
}

TEST(AudioClaimedLength, ReadAudioReadsTheFramesTheFileHolds) {
  const TempDir dir("claimed_length");
  writeFlacClaiming(dir.file("a.flac"), 2, std::uint64_t{1} << 35);
  const AudioBuffer audio = readAudio(dir.file("a.flac"));
  ASSERT_EQ(audio.channels, 2);
  ASSERT_EQ(audio.frames(), kFrames);
  for (long f = 0; f < kFrames; ++f)
    for (int c = 0; c < 2; ++c) ASSERT_EQ(audio.samples[static_cast<size_t>(f * 2 + c)], sampleAt(f, c));
}

TEST(AudioClaimedLength, ReadChannelReadsTheFramesTheFileHolds) {
  const TempDir dir("claimed_length");
  writeFlacClaiming(dir.file("a.flac"), 2, (std::uint64_t{1} << 36) - 1);
  AudioReader reader(dir.file("a.flac"));
  const std::vector<float> mean = readChannel(reader, -1);
  ASSERT_EQ(static_cast<long>(mean.size()), kFrames);
  for (long f = 0; f < kFrames; ++f)
    ASSERT_EQ(mean[static_cast<size_t>(f)], static_cast<float>(0.5 * (sampleAt(f, 0) + sampleAt(f, 1))));
  AudioReader again(dir.file("a.flac"));
  const std::vector<float> second = readChannel(again, 1);
  ASSERT_EQ(static_cast<long>(second.size()), kFrames);
  EXPECT_EQ(second[7], static_cast<float>(sampleAt(7, 1)));
}

TEST(AudioClaimedLength, ReadingBeyondTheCapIsRefusedNamingIt) {
  const TempDir dir("claimed_length");
  writeFlacClaiming(dir.file("a.flac"), 1, kFrames);
  AudioReader reader(dir.file("a.flac"));
  try {
    readChannel(reader, 0, 999);
    FAIL() << "no error";
  } catch (const core::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("999"), std::string::npos) << e.what();
  }
  AudioReader exact(dir.file("a.flac"));
  EXPECT_EQ(static_cast<long>(readChannel(exact, 0, kFrames).size()), kFrames);
}

}  // namespace
}  // namespace diffray::audio
