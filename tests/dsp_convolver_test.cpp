// The partitioned FFT convolver against direct time-domain convolution (tests/dsp_oracle.h, no code shared
// with the FFT path): random block sizes, IR lengths, input lengths and call sizes; a Dirac gives the IR back;
// reset() forgets the past; the multichannel pairings.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <random>
#include <vector>

#include "diffray/core/error.h"
#include "diffray/dsp/multichannel_convolver.h"
#include "diffray/dsp/partitioned_convolver.h"
#include "dsp_oracle.h"

namespace {

using diffray::dsp::MultichannelConvolver;
using diffray::dsp::PartitionedConvolver;

using diffray::test::directConvolution;
using diffray::test::runInRandomCalls;

std::vector<float> noise(std::mt19937& rng, size_t n) { return diffray::test::uniformNoise(rng, n); }

double maxAbs(const std::vector<double>& v) {
  double m = 0.0;
  for (double s : v) m = std::max(m, std::abs(s));
  return m;
}

TEST(DspConvolver, MatchesDirectConvolutionWithRandomSizes) {
  std::mt19937 rng(20240605);
  std::uniform_int_distribution<int> pow2(0, 11), any_block(1, 700), ir_len(1, 3000), x_len(1, 6000);
  double worst = 0.0;
  for (int trial = 0; trial < 40; ++trial) {
    const int block = trial % 2 == 0 ? 1 << pow2(rng) : any_block(rng);
    const std::vector<float> h = noise(rng, static_cast<size_t>(ir_len(rng)));
    const std::vector<float> x = noise(rng, static_cast<size_t>(x_len(rng)));
    PartitionedConvolver conv;
    conv.init(block, h);
    const std::vector<float> y = runInRandomCalls(conv, x, static_cast<long>(h.size()), rng);
    const std::vector<double> ref = directConvolution(x, h);
    ASSERT_EQ(y.size(), ref.size());
    double err = 0.0;
    for (size_t t = 0; t < y.size(); ++t) err = std::max(err, std::abs(y[t] - ref[t]));
    const double rel = err / maxAbs(ref);
    worst = std::max(worst, rel);
    EXPECT_LE(rel, 1e-5) << "block " << block << ", IR " << h.size() << ", input " << x.size();
  }
  std::cout << "[ measured ] worst error / output peak over 40 trials: " << worst << "\n";
}

TEST(DspConvolver, DiracGivesTheImpulseResponse) {
  std::mt19937 rng(7);
  for (int block : {1, 64, 100, 4096}) {
    const std::vector<float> h = noise(rng, 1500);
    PartitionedConvolver conv;
    conv.init(block, h);
    // A Dirac delayed by 3 samples, then silence: the IR delayed by 3 and nothing after it.
    std::vector<float> in(h.size() + 300, 0.0f), out(in.size(), 1.0f);
    in[3] = 1.0f;
    conv.process(in.data(), out.data(), static_cast<long>(in.size()));
    for (size_t t = 0; t < out.size(); ++t) {
      const double expected = t >= 3 && t < h.size() + 3 ? h[t - 3] : 0.0;
      ASSERT_NEAR(out[t], expected, 1e-6) << "block " << block << ", sample " << t;
    }
  }
}

TEST(DspConvolver, InPlaceProcessingMatchesSeparateBuffers) {
  std::mt19937 rng(11);
  const std::vector<float> h = noise(rng, 700), x = noise(rng, 2000);
  PartitionedConvolver a, b;
  a.init(128, h);
  b.init(128, h);
  std::vector<float> separate(x.size()), in_place(x);
  a.process(x.data(), separate.data(), static_cast<long>(x.size()));
  b.process(in_place.data(), in_place.data(), static_cast<long>(in_place.size()));
  EXPECT_EQ(separate, in_place);
}

TEST(DspConvolver, ResetForgetsThePast) {
  std::mt19937 rng(3);
  const std::vector<float> h = noise(rng, 900);
  const std::vector<float> probe = noise(rng, 2500);
  PartitionedConvolver fresh;
  fresh.init(256, h);
  std::vector<float> expected(probe.size());
  fresh.process(probe.data(), expected.data(), static_cast<long>(probe.size()));

  PartitionedConvolver used;
  used.init(256, h);
  const std::vector<float> before = noise(rng, 1000 + 37);  // ends mid-block, leaving a tail pending
  std::vector<float> scratch(before.size());
  used.process(before.data(), scratch.data(), static_cast<long>(before.size()));
  used.reset();
  std::vector<float> got(probe.size());
  used.process(probe.data(), got.data(), static_cast<long>(probe.size()));
  EXPECT_EQ(got, expected);
}

TEST(DspConvolver, RefusesBadArguments) {
  PartitionedConvolver conv;
  const std::vector<float> h{1.0f, 0.5f};
  EXPECT_THROW(conv.init(0, h), diffray::core::InputError);
  EXPECT_THROW(conv.init(64, std::vector<float>{}), diffray::core::InputError);
  EXPECT_THROW(conv.init(64, std::vector<float>{1.0f, NAN}), diffray::core::InputError);
  // Before init the output is silence.
  std::vector<float> in(10, 1.0f), out(10, 5.0f);
  conv.process(in.data(), out.data(), 10);
  EXPECT_EQ(out, std::vector<float>(10, 0.0f));
}

/// Channel `c` of an interleaved buffer with `channels` channels.
std::vector<float> channelOf(const std::vector<float>& v, int channels, int c) {
  std::vector<float> out;
  for (size_t i = static_cast<size_t>(c); i < v.size(); i += static_cast<size_t>(channels)) out.push_back(v[i]);
  return out;
}

/// Runs `ir` on an interleaved input of `in_channels` and checks each output channel against direct
/// convolution of (input channel `in_of(o)`, IR channel `ir_of(o)`).
template <class InOf, class IrOf>
void checkPairing(const std::vector<std::vector<float>>& ir, int in_channels, int expected_outputs, InOf in_of,
                  IrOf ir_of) {
  std::mt19937 rng(static_cast<unsigned>(ir.size() * 10 + static_cast<size_t>(in_channels)));
  const long frames = 1200;
  const long total = frames + static_cast<long>(ir[0].size()) - 1;
  std::vector<float> in = noise(rng, static_cast<size_t>(frames * in_channels));
  in.resize(static_cast<size_t>(total * in_channels), 0.0f);
  MultichannelConvolver conv;
  conv.init(64, ir, in_channels);
  ASSERT_EQ(conv.outputChannels(), expected_outputs);
  std::vector<float> out(static_cast<size_t>(total * expected_outputs));
  conv.process(in.data(), out.data(), total);
  for (int o = 0; o < expected_outputs; ++o) {
    std::vector<float> x = channelOf(in, in_channels, in_of(o));
    x.resize(static_cast<size_t>(frames));
    const std::vector<double> ref = directConvolution(x, ir[static_cast<size_t>(ir_of(o))]);
    const std::vector<float> y = channelOf(out, expected_outputs, o);
    ASSERT_EQ(y.size(), ref.size());
    double err = 0.0;
    for (size_t t = 0; t < y.size(); ++t) err = std::max(err, std::abs(y[t] - ref[t]));
    EXPECT_LE(err, 1e-5 * maxAbs(ref)) << "output channel " << o;
  }
}

TEST(DspConvolver, MultichannelPairings) {
  std::mt19937 rng(5);
  const std::vector<std::vector<float>> mono{noise(rng, 300)};
  const std::vector<std::vector<float>> stereo{noise(rng, 300), noise(rng, 300)};
  const std::vector<std::vector<float>> four{noise(rng, 200), noise(rng, 200), noise(rng, 200), noise(rng, 200)};
  checkPairing(mono, 2, 2, [](int o) { return o; }, [](int) { return 0; });    // mono IR on every channel
  checkPairing(stereo, 2, 2, [](int o) { return o; }, [](int o) { return o; });  // channel-wise
  checkPairing(four, 1, 4, [](int) { return 0; }, [](int o) { return o; });    // mono input, 4 IR channels
  checkPairing(mono, 1, 1, [](int) { return 0; }, [](int) { return 0; });
  EXPECT_THROW(MultichannelConvolver::outputChannels(2, 3), diffray::core::InputError);
  MultichannelConvolver conv;
  EXPECT_THROW(conv.init(64, stereo, 3), diffray::core::InputError);
  EXPECT_THROW(conv.init(64, {noise(rng, 10), noise(rng, 11)}, 2), diffray::core::InputError);
}

TEST(DspConvolver, LongImpulseResponseInLargeBlocksStaysAccurate) {
  // auralize's offline configuration (a 3 s IR at 48 kHz in blocks of 32768: 5 partitions, FFTs of 65536 in
  // single precision) against direct convolution in double, over a short input and the whole tail.
  std::mt19937 rng(17);
  std::vector<float> h = noise(rng, 144000);
  for (size_t i = 0; i < h.size(); ++i) h[i] *= static_cast<float>(std::exp(-6.9 * static_cast<double>(i) / 144000.0));
  const std::vector<float> x = noise(rng, 2000);
  PartitionedConvolver conv;
  conv.init(32768, h);
  std::vector<float> in(x);
  in.resize(x.size() + h.size() - 1, 0.0f);
  std::vector<float> y(in.size());
  conv.process(in.data(), y.data(), static_cast<long>(in.size()));
  const std::vector<double> ref = directConvolution(x, h);
  double err = 0.0;
  for (size_t t = 0; t < y.size(); ++t) err = std::max(err, std::abs(y[t] - ref[t]));
  std::cout << "[ measured ] 3 s IR, blocks of 32768: error / output peak " << err / maxAbs(ref) << "\n";
  EXPECT_LE(err, 1e-5 * maxAbs(ref));
}

TEST(DspConvolver, ParallelProcessingMatchesSerialBitForBit) {
  // processParallel() runs the output channels on TBB's threads; each channel's arithmetic is unchanged, so
  // the result equals process() exactly (and process() is checked against direct convolution above).
  std::mt19937 rng(13);
  const std::vector<std::vector<float>> four{noise(rng, 900), noise(rng, 900), noise(rng, 900), noise(rng, 900)};
  const long frames = 5000;
  const std::vector<float> in = noise(rng, static_cast<size_t>(frames));
  MultichannelConvolver serial, parallel;
  serial.init(128, four, 1);
  parallel.init(128, four, 1);
  std::vector<float> a(static_cast<size_t>(frames * 4)), b(a.size());
  for (long start = 0; start < frames; start += 1234) {  // calls ending mid-block too
    const long n = std::min<long>(1234, frames - start);
    serial.process(in.data() + start, a.data() + start * 4, n);
    parallel.processParallel(in.data() + start, b.data() + start * 4, n);
  }
  EXPECT_EQ(a, b);
}

}  // namespace
