// Real-time playback without hardware: the test backend drives audio::playbackCallback (the function
// PortAudio calls) on its own thread. Checked: the wet output equals direct convolution of the dry file
// (tests/dsp_oracle.h; Diracs in the dry signal give the IR back) at two callback sizes; an underrun gives
// silence in place of the missing dry frames and is counted; the SPSC ring delivers a sequence in order
// across threads; the closing door's crossfading renderer equals Σ_k g_k(n)·(h_k ∗ x)[n] by direct
// convolution with hat gains written here; and no operator new/delete runs inside a callback (plain and
// crossfading) over hundreds of callbacks that cross every tail stage's block boundary (a counting global operator new, active only on the callback thread
// between the backend's hooks). Locks: none by construction (code review: render() uses std::atomic and
// the convolver, which uses no mutex outside init()); not checked at run time.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <new>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "diffray/audio/playback.h"
#include "diffray/audio/spsc_ring.h"
#include "diffray/audio/test_backend.h"
#include "diffray/audio/wav.h"
#include "diffray/dsp/crossfade_convolver.h"
#include "dsp_oracle.h"
#include "temp_dir.h"

// ---- Counting global allocation functions: count only while the calling thread has set the flag. ----
namespace {
thread_local bool t_counting = false;
std::atomic<long> g_news{0};
std::atomic<long> g_deletes{0};

void* countedAllocOrNull(std::size_t n) noexcept {
  if (t_counting) g_news.fetch_add(1);
  return std::malloc(n == 0 ? 1 : n);
}
void* countedAlignedAllocOrNull(std::size_t n, std::align_val_t a) noexcept {
  if (t_counting) g_news.fetch_add(1);
  const auto align = static_cast<std::size_t>(a);
  return std::aligned_alloc(align, (std::max<std::size_t>(n, 1) + align - 1) / align * align);
}
void* countedAlloc(std::size_t n) {
  if (void* p = countedAllocOrNull(n)) return p;
  throw std::bad_alloc();
}
void* countedAlignedAlloc(std::size_t n, std::align_val_t a) {
  if (void* p = countedAlignedAllocOrNull(n, a)) return p;
  throw std::bad_alloc();
}
void countedFree(void* p) {
  if (t_counting && p != nullptr) g_deletes.fetch_add(1);
  std::free(p);
}
}  // namespace

void* operator new(std::size_t n) { return countedAlloc(n); }
void* operator new[](std::size_t n) { return countedAlloc(n); }
void* operator new(std::size_t n, std::align_val_t a) { return countedAlignedAlloc(n, a); }
void* operator new[](std::size_t n, std::align_val_t a) { return countedAlignedAlloc(n, a); }
// The nothrow forms too: every allocation and deallocation of the test binary goes through the same malloc
// and free, whichever form allocated it (AddressSanitizer reports a mismatch otherwise).
void* operator new(std::size_t n, const std::nothrow_t&) noexcept { return countedAllocOrNull(n); }
void* operator new[](std::size_t n, const std::nothrow_t&) noexcept { return countedAllocOrNull(n); }
void* operator new(std::size_t n, std::align_val_t a, const std::nothrow_t&) noexcept {
  return countedAlignedAllocOrNull(n, a);
}
void* operator new[](std::size_t n, std::align_val_t a, const std::nothrow_t&) noexcept {
  return countedAlignedAllocOrNull(n, a);
}
void operator delete(void* p) noexcept { countedFree(p); }
void operator delete[](void* p) noexcept { countedFree(p); }
void operator delete(void* p, std::size_t) noexcept { countedFree(p); }
void operator delete[](void* p, std::size_t) noexcept { countedFree(p); }
void operator delete(void* p, std::align_val_t) noexcept { countedFree(p); }
void operator delete[](void* p, std::align_val_t) noexcept { countedFree(p); }
void operator delete(void* p, std::size_t, std::align_val_t) noexcept { countedFree(p); }
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept { countedFree(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { countedFree(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { countedFree(p); }
void operator delete(void* p, std::align_val_t, const std::nothrow_t&) noexcept { countedFree(p); }
void operator delete[](void* p, std::align_val_t, const std::nothrow_t&) noexcept { countedFree(p); }

namespace {

using namespace diffray;
using diffray::test::directConvolution;
using diffray::test::relativeError;
using diffray::test::uniformNoise;

void startCounting(void*) { t_counting = true; }
void stopCounting(void*) { t_counting = false; }

using diffray::test::TempDir;

/// Interleaves two equally long channels.
std::vector<float> interleave(const std::vector<float>& a, const std::vector<float>& b) {
  std::vector<float> v(2 * a.size());
  for (size_t i = 0; i < a.size(); ++i) {
    v[2 * i] = a[i];
    v[2 * i + 1] = b[i];
  }
  return v;
}

std::vector<float> channelOf(const std::vector<float>& interleaved, int c, size_t frames) {
  std::vector<float> v(frames);
  for (size_t i = 0; i < frames; ++i) v[i] = interleaved[2 * i + static_cast<size_t>(c)];
  return v;
}

/// Dry stereo: Diracs (left at 37, right at 500) then noise from frame 3000 on, in a float WAV.
struct DryFixture {
  std::vector<float> left, right;
  std::string path;
  DryFixture(const std::filesystem::path& dir, std::mt19937& rng) {
    left.assign(6000, 0.0f);
    right.assign(6000, 0.0f);
    left[37] = 1.0f;
    right[500] = 1.0f;
    const auto nl = uniformNoise(rng, 3000), nr = uniformNoise(rng, 3000);
    std::copy(nl.begin(), nl.end(), left.begin() + 3000);
    std::copy(nr.begin(), nr.end(), right.begin() + 3000);
    path = (dir / "dry.wav").string();
    audio::WavWriter writer(path, 48000, 2);
    const auto frames = interleave(left, right);
    writer.write(frames.data(), static_cast<long>(left.size()));
    writer.commit();
  }
};

/// Streams the dry file at `path` through `renderer` on the test backend; the reader thread joined.
audio::TestBackendRun playThrough(audio::PlaybackRenderer& renderer, const std::string& path,
                                  const audio::TestBackendOptions& options) {
  audio::AudioReader reader(path);
  audio::DryFileStreamer streamer(reader, renderer);
  const audio::TestBackendRun run = audio::runTestBackend(renderer, options);
  streamer.wait();
  return run;
}

TEST(RealtimePlayback, TestBackendOutputEqualsDirectConvolution) {
  const TempDir dir("rt_convolution");
  std::mt19937 rng(424242);
  const DryFixture dry(dir.path, rng);
  // A stereo IR long enough for three stages at block 64: 64, 512, 4096.
  const std::vector<std::vector<float>> ir{uniformNoise(rng, 20000), uniformNoise(rng, 20000)};
  const size_t wet_frames = dry.left.size() + ir[0].size() - 1;
  const std::vector<double> want_l = directConvolution(dry.left, ir[0]), want_r = directConvolution(dry.right, ir[1]);
  for (long callback_frames : {64L, 96L}) {
    audio::PlaybackConfig config;
    config.block_frames = 64;
    config.ring_frames = 1024;  // smaller than the file: the reader thread must stream
    audio::PlaybackRenderer renderer(ir, 2, config);
    ASSERT_EQ(renderer.convolver().outputChannels(), 2);
    audio::TestBackendOptions options;
    options.frames_per_callback = callback_frames;
    const audio::TestBackendRun run = playThrough(renderer, dry.path, options);
    EXPECT_EQ(renderer.underruns(), 0);
    EXPECT_TRUE(renderer.finished());
    const size_t frames = run.output.size() / 2;
    ASSERT_GE(frames, wet_frames);
    ASSERT_LT(frames, wet_frames + static_cast<size_t>(callback_frames));  // ends within a callback of the tail
    EXPECT_LE(relativeError(channelOf(run.output, 0, wet_frames), want_l), 1e-5) << callback_frames;
    EXPECT_LE(relativeError(channelOf(run.output, 1, wet_frames), want_r), 1e-5) << callback_frames;
    // The Diracs: the IR itself, in the gap before the noise starts.
    for (size_t k = 0; k + 500 < 3000; ++k) ASSERT_NEAR(run.output[2 * (500 + k) + 1], ir[1][k], 1e-5) << k;
    for (size_t f = wet_frames; f < frames; ++f) ASSERT_NEAR(run.output[2 * f], 0.0f, 1e-5);
  }
}

/// The hat gain of IR k at frame n for key frames t (1 at t_k, linear to 0 at its neighbours; the first
/// and last IR 1 beyond the ends), written out here.
double hatGain(const std::vector<long>& t, size_t k, long n) {
  if (n <= t[k]) return k == 0 ? 1.0 : (n <= t[k - 1] ? 0.0 : double(n - t[k - 1]) / double(t[k] - t[k - 1]));
  return k + 1 == t.size() ? 1.0 : (n >= t[k + 1] ? 0.0 : double(t[k + 1] - n) / double(t[k + 1] - t[k]));
}

TEST(RealtimePlayback, CrossfadingRendererEqualsCrossfadedDirectConvolutions) {
  // The closing door's real-time renderer: the stereo dry file averaged to one channel, convolved with three
  // two-channel IRs (long enough for the non-uniform engine's tail stages at block 64) and crossfaded at
  // key frames 1000, 2500 and 4000; against Σ_k g_k(n)·(h_k ∗ x)[n] by direct convolution.
  const TempDir dir("rt_crossfade");
  std::mt19937 rng(515151);
  const DryFixture dry(dir.path, rng);
  const std::vector<long> keys{1000, 2500, 4000};
  std::vector<std::vector<std::vector<float>>> irs;
  for (long length : {9000L, 12000L, 7000L}) irs.push_back({uniformNoise(rng, length), uniformNoise(rng, length)});
  std::vector<float> mono(dry.left.size());
  for (size_t i = 0; i < mono.size(); ++i) mono[i] = 0.5f * (dry.left[i] + dry.right[i]);
  const size_t wet_frames = mono.size() + 12000 - 1;
  std::vector<std::vector<double>> want(2, std::vector<double>(wet_frames, 0.0));
  for (size_t k = 0; k < irs.size(); ++k)
    for (int c = 0; c < 2; ++c) {
      const std::vector<double> z = directConvolution(mono, irs[k][static_cast<size_t>(c)]);
      for (size_t n = 0; n < z.size(); ++n) want[static_cast<size_t>(c)][n] += hatGain(keys, k, static_cast<long>(n)) * z[n];
    }
  for (long callback_frames : {64L, 100L}) {
    audio::PlaybackConfig config;
    config.block_frames = 64;
    config.ring_frames = 1024;
    audio::PlaybackRenderer renderer(irs, keys, 2, config);
    ASSERT_TRUE(renderer.crossfading());
    ASSERT_EQ(renderer.outputChannels(), 2);
    EXPECT_EQ(renderer.irFrames(), 12000);
    audio::TestBackendOptions options;
    options.frames_per_callback = callback_frames;
    const audio::TestBackendRun run = playThrough(renderer, dry.path, options);
    EXPECT_EQ(renderer.underruns(), 0);
    EXPECT_TRUE(renderer.finished());
    const size_t frames = run.output.size() / 2;
    ASSERT_GE(frames, wet_frames);
    EXPECT_LE(relativeError(channelOf(run.output, 0, wet_frames), want[0]), 1e-5) << callback_frames;
    EXPECT_LE(relativeError(channelOf(run.output, 1, wet_frames), want[1]), 1e-5) << callback_frames;
    for (size_t f = wet_frames; f < frames; ++f) ASSERT_NEAR(run.output[2 * f], 0.0f, 1e-5);
  }
}

TEST(RealtimePlayback, GainScalesTheOutput) {
  std::mt19937 rng(3);
  const std::vector<std::vector<float>> ir{uniformNoise(rng, 300)};
  audio::PlaybackConfig config;
  config.block_frames = 32;
  config.gain_db = -6.0;
  audio::PlaybackRenderer renderer(ir, 1, config);
  const float one = 1.0f;
  ASSERT_EQ(renderer.pushDry(&one, 1), 1);
  renderer.endInput();
  const audio::TestBackendRun run = audio::runTestBackend(renderer, {});
  ASSERT_GE(run.output.size(), ir[0].size());
  const double g = std::pow(10.0, -6.0 / 20.0);
  for (size_t k = 0; k < ir[0].size(); ++k) ASSERT_NEAR(run.output[k], g * ir[0][k], 1e-6) << k;
}

TEST(RealtimePlayback, UnderrunGivesSilenceAndIsCounted) {
  std::mt19937 rng(9);
  const std::vector<std::vector<float>> ir{uniformNoise(rng, 700)};
  audio::PlaybackConfig config;
  config.block_frames = 64;
  audio::PlaybackRenderer renderer(ir, 1, config);
  const auto x = uniformNoise(rng, 100);
  ASSERT_EQ(renderer.pushDry(x.data(), 100), 100);
  audio::TestBackendOptions options;
  options.frames_per_callback = 64;
  options.wait_for_input = false;  // a reader that has fallen behind
  options.max_callbacks = 20;
  const audio::TestBackendRun run = audio::runTestBackend(renderer, options);
  EXPECT_EQ(renderer.underruns(), 19);  // the 2nd callback got 36 of 64 frames, the rest none
  EXPECT_EQ(renderer.underrunFrames(), 28 + 18 * 64);
  EXPECT_FALSE(renderer.finished());  // the input has not ended
  // The missing frames were silence: the output is x convolved with the IR, its tail included.
  std::vector<double> want = directConvolution(x, ir[0]);
  want.resize(run.output.size(), 0.0);
  EXPECT_LE(relativeError(run.output, want), 1e-5);
}

TEST(RealtimeRing, DeliversASequenceInOrderAcrossThreads) {
  audio::SpscFrameRing ring(100, 2);  // 128 frames
  EXPECT_EQ(ring.capacity(), 128);
  constexpr long kFrames = 20000;
  std::thread producer([&] {
    std::vector<float> chunk(2 * 37);
    for (long next = 0; next < kFrames;) {
      const long n = std::min<long>(37, kFrames - next);
      for (long i = 0; i < n; ++i) chunk[2 * i] = chunk[2 * i + 1] = static_cast<float>(next + i);
      for (long done = 0; done < n;) {
        const long pushed = ring.push(chunk.data() + 2 * done, n - done);
        if (pushed == 0) std::this_thread::yield();
        done += pushed;
      }
      next += n;
    }
  });
  std::vector<float> got(2 * 53);
  long expected = 0;
  bool in_order = true;
  while (expected < kFrames) {
    const long n = ring.pop(got.data(), 53);
    if (n == 0) std::this_thread::yield();
    for (long i = 0; i < n; ++i, ++expected)
      in_order = in_order && got[2 * i] == static_cast<float>(expected) && got[2 * i + 1] == static_cast<float>(expected);
  }
  producer.join();
  EXPECT_TRUE(in_order);
  EXPECT_EQ(ring.available(), 0);
}

TEST(RealtimeAllocation, CallbackAllocatesNothingAcrossTailStageBoundaries) {
  // The counter works: an allocation between the hooks is seen, in the plain and the nothrow forms.
  startCounting(nullptr);
  auto* probe = new int(1);
  delete probe;
  auto* nothrow_probe = new (std::nothrow) int(2);
  delete nothrow_probe;
  stopCounting(nullptr);
  ASSERT_EQ(g_news.load(), 2);
  ASSERT_EQ(g_deletes.load(), 2);
  g_news = 0;
  g_deletes = 0;

  const TempDir dir("rt_allocation");
  std::mt19937 rng(77);
  const DryFixture dry(dir.path, rng);
  const std::vector<std::vector<float>> ir{uniformNoise(rng, 20000), uniformNoise(rng, 20000)};
  audio::PlaybackConfig config;
  config.block_frames = 64;
  config.ring_frames = 512;
  config.max_callback_frames = 80;  // callbacks of 100 frames are processed in two pieces
  audio::PlaybackRenderer renderer(ir, 2, config);
  ASSERT_EQ(renderer.convolver().outputChannels(), 2);
  audio::TestBackendOptions options;
  options.frames_per_callback = 100;
  options.keep_output = false;
  options.before_callback = startCounting;
  options.after_callback = stopCounting;
  const audio::TestBackendRun run = playThrough(renderer, dry.path, options);
  // 26000 frames: stage 1 (block 512) fires ~50 times, stage 2 (block 4096) ~6 times.
  EXPECT_GE(run.callbacks, 259);
  EXPECT_TRUE(renderer.finished());
  EXPECT_EQ(g_news.load(), 0) << "operator new inside the audio callback";
  EXPECT_EQ(g_deletes.load(), 0) << "operator delete inside the audio callback";
}

TEST(RealtimeAllocation, CrossfadingCallbackAllocatesNothing) {
  // The closing door's renderer, over callbacks that cross every key frame and tail-stage boundary.
  const TempDir dir("rt_crossfade_allocation");
  std::mt19937 rng(79);
  const DryFixture dry(dir.path, rng);
  std::vector<std::vector<std::vector<float>>> irs;
  for (long length : {20000L, 15000L, 18000L}) irs.push_back({uniformNoise(rng, length)});
  audio::PlaybackConfig config;
  config.block_frames = 64;
  config.ring_frames = 512;
  config.max_callback_frames = 80;
  audio::PlaybackRenderer renderer(irs, {500, 2500, 4500}, 2, config);
  audio::TestBackendOptions options;
  options.frames_per_callback = 100;
  options.keep_output = false;
  options.before_callback = startCounting;
  options.after_callback = stopCounting;
  g_news = 0;
  g_deletes = 0;
  const audio::TestBackendRun run = playThrough(renderer, dry.path, options);
  EXPECT_GE(run.callbacks, 259);  // 26000 frames
  EXPECT_TRUE(renderer.finished());
  EXPECT_EQ(g_news.load(), 0) << "operator new inside the crossfading callback";
  EXPECT_EQ(g_deletes.load(), 0) << "operator delete inside the crossfading callback";
}

// The closing door's time-varying convolver (dsp/crossfade_convolver.h) promises the same: process() and
// flush() allocate nothing, over calls that start and stop convolvers at every key frame.
TEST(RealtimeAllocation, CrossfadeConvolverAllocatesNothingAcrossKeyFrames) {
  std::mt19937 rng(78);
  std::vector<std::vector<std::vector<float>>> irs;
  for (long length : {3000L, 5000L, 4000L}) irs.push_back({uniformNoise(rng, length), uniformNoise(rng, length)});
  dsp::CrossfadeConvolver conv;
  conv.init(256, irs, 1, {2000, 6000, 9000});
  const std::vector<float> in = uniformNoise(rng, 100);
  std::vector<float> out(200);
  g_news = 0;
  g_deletes = 0;
  int most_active = 0;
  startCounting(nullptr);
  for (int call = 0; call < 200; ++call) {  // 20000 frames: past the last key frame and every IR's span
    conv.process(in.data(), out.data(), 100);
    most_active = std::max(most_active, conv.activeConvolvers());
  }
  for (long left = conv.tailFrames(); left > 0; left -= 100) conv.flush(out.data(), std::min<long>(left, 100));
  stopCounting(nullptr);
  EXPECT_GE(most_active, 2);
  EXPECT_EQ(g_news.load(), 0) << "operator new in CrossfadeConvolver::process/flush";
  EXPECT_EQ(g_deletes.load(), 0) << "operator delete in CrossfadeConvolver::process/flush";
}

}  // namespace
