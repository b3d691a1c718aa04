// Real-time bench: audio::PlaybackRenderer driven by the test backend (the same callback PortAudio runs),
// 3 s stereo IR (exponentially decaying white noise, 60 dB over 3 s), stereo white-noise input fed by a
// producer thread, block 256 frames at 48 kHz; each callback timed. Beside it, the uniformly partitioned
// dsp::MultichannelConvolver on the same blocks: what the non-uniform head/tail split buys.
#include "realtime_bench.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <nlohmann/json.hpp>
#include <random>
#include <thread>
#include <vector>

#include "diffray/audio/playback.h"
#include "diffray/audio/test_backend.h"
#include "diffray/dsp/multichannel_convolver.h"

namespace diffray::bench {

namespace {

constexpr int kBlock = 256;
constexpr double kRateHz = 48000.0;

struct Summary {
  double median_ms, p90_ms, p99_ms, max_ms;
};

Summary summarise(std::vector<double> seconds) {
  std::sort(seconds.begin(), seconds.end());
  const auto at = [&](double q) { return 1e3 * seconds[static_cast<size_t>(q * static_cast<double>(seconds.size() - 1))]; };
  return {at(0.5), at(0.9), at(0.99), 1e3 * seconds.back()};
}

std::vector<float> noise(std::mt19937& rng, size_t n) {
  std::uniform_real_distribution<float> u(-0.5f, 0.5f);
  std::vector<float> v(n);
  for (float& s : v) s = u(rng);
  return v;
}

}  // namespace

void benchRealtime(double seconds) {
  std::mt19937 rng(2024);
  const auto ir_frames = static_cast<size_t>(3.0 * kRateHz);
  std::vector<std::vector<float>> ir(2);
  for (auto& channel : ir) {
    channel = noise(rng, ir_frames);
    for (size_t i = 0; i < ir_frames; ++i)  // −60 dB over the IR's length
      channel[i] *= static_cast<float>(std::pow(10.0, -3.0 * static_cast<double>(i) / static_cast<double>(ir_frames)));
  }
  const auto frames = static_cast<long>(seconds * kRateHz);
  const std::vector<float> dry = noise(rng, 2 * static_cast<size_t>(frames));

  audio::PlaybackConfig config;
  config.block_frames = kBlock;
  audio::PlaybackRenderer renderer(ir, 2, config);
  std::thread producer([&] {
    for (long done = 0; done < frames;) {
      const long n = renderer.pushDry(dry.data() + 2 * done, std::min<long>(4096, frames - done));
      if (n == 0) std::this_thread::sleep_for(std::chrono::milliseconds(1));
      done += n;
    }
    renderer.endInput();
  });
  audio::TestBackendOptions options;
  options.frames_per_callback = kBlock;
  options.keep_output = false;
  options.time_callbacks = true;
  const audio::TestBackendRun run = audio::runTestBackend(renderer, options);
  producer.join();
  const Summary nonuniform = summarise(run.callback_seconds);

  dsp::MultichannelConvolver uniform;
  uniform.init(kBlock, ir, 2);
  std::vector<float> out(2 * kBlock);
  std::vector<double> uniform_seconds;
  for (long start = 0; start + kBlock <= frames; start += kBlock) {
    const auto t0 = std::chrono::steady_clock::now();
    uniform.process(dry.data() + 2 * start, out.data(), kBlock);
    uniform_seconds.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  const Summary plain = summarise(uniform_seconds);

  nlohmann::json j{{"bench", "realtime"},
                   {"block_frames", kBlock},
                   {"sample_rate_hz", kRateHz},
                   {"ir_s", 3},
                   {"channels", 2},
                   {"callbacks", run.callbacks},
                   {"underruns", renderer.underruns()},
                   {"callback_median_ms", nonuniform.median_ms},
                   {"callback_p90_ms", nonuniform.p90_ms},
                   {"callback_p99_ms", nonuniform.p99_ms},
                   {"callback_max_ms", nonuniform.max_ms},
                   {"uniform_median_ms", plain.median_ms},
                   {"uniform_max_ms", plain.max_ms},
                   {"anchor_block_duration_ms", 1e3 * kBlock / kRateHz}};
  std::cout << j.dump() << std::endl;
}

}  // namespace diffray::bench
