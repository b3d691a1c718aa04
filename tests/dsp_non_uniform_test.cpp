// NonUniformConvolver (head + tail stages of growing block size) against direct time-domain convolution
// (tests/dsp_oracle.h, no shared code with the FFT path): random block sizes, IR lengths spanning one to
// four stages, random call sizes; a Dirac gives the IR back; reset(); the in-place call; the multichannel
// wrapper built on it.
#include <gtest/gtest.h>

#include <algorithm>
#include <iostream>
#include <random>
#include <vector>

#include "diffray/dsp/multichannel_convolver.h"
#include "diffray/dsp/non_uniform_convolver.h"
#include "dsp_oracle.h"

namespace {

using diffray::dsp::NonUniformConvolver;
using diffray::dsp::NonUniformMultichannelConvolver;
using diffray::test::directConvolution;
using diffray::test::relativeError;
using diffray::test::uniformNoise;

/// x then |h|−1 zeros through `conv` in calls of random size (0 … 3 head blocks): the whole convolution.
std::vector<float> runInRandomCalls(NonUniformConvolver& conv, const std::vector<float>& x, std::mt19937& rng) {
  return diffray::test::runInRandomCalls(conv, x, conv.irLength(), rng);
}

TEST(NonUniformConvolver, StagesGrowByEightFromTheBlock) {
  NonUniformConvolver conv;
  conv.init(256, std::vector<float>(3 * 48000, 0.5f));
  ASSERT_EQ(conv.stages(), 2);  // 256, 2048; 16384 exceeds kMaxTailBlock
  EXPECT_EQ(conv.stageBlockSize(0), 256);
  EXPECT_EQ(conv.stageBlockSize(1), 2048);
  conv.init(16, std::vector<float>(9000, 0.5f));
  ASSERT_EQ(conv.stages(), 4);  // 16, 128, 1024, 8192
  EXPECT_EQ(conv.stageBlockSize(3), 8192);
  conv.init(256, std::vector<float>(2048, 0.5f));  // fits the head: no tail
  EXPECT_EQ(conv.stages(), 1);
  conv.init(2048, std::vector<float>(100000, 0.5f));  // 8·2048 > kMaxTailBlock: uniform
  EXPECT_EQ(conv.stages(), 1);
}

TEST(NonUniformConvolver, MatchesDirectConvolutionWithRandomSizes) {
  std::mt19937 rng(20240611);
  std::uniform_int_distribution<int> block(1, 20);
  double worst = 0.0;
  int max_stages = 0;
  for (int trial = 0; trial < 24; ++trial) {
    const int b = trial % 3 == 0 ? 1 << (trial % 5) : block(rng);
    // IR lengths reaching the 2nd, 3rd or 4th stage (starts at 8b, 64b, 512b).
    std::uniform_int_distribution<long> ir_len(1, 600L * b);
    const auto h = uniformNoise(rng, static_cast<size_t>(std::min<long>(ir_len(rng), 12000)));
    const auto x = uniformNoise(rng, static_cast<size_t>(std::uniform_int_distribution<long>(1, 3000)(rng)));
    NonUniformConvolver conv;
    conv.init(b, h);
    max_stages = std::max(max_stages, conv.stages());
    const auto got = runInRandomCalls(conv, x, rng);
    const double err = relativeError(got, directConvolution(x, h));
    worst = std::max(worst, err);
    EXPECT_LE(err, 1e-5) << "trial " << trial << " block " << b << " ir " << h.size() << " x " << x.size();
  }
  EXPECT_GE(max_stages, 4);  // the trials did reach three tail stages
  std::cout << "worst relative error " << worst << "\n";
}

TEST(NonUniformConvolver, DiracGivesTheImpulseResponse) {
  std::mt19937 rng(7);
  const auto h = uniformNoise(rng, 5000);
  for (int b : {16, 64, 100}) {
    NonUniformConvolver conv;
    conv.init(b, h);
    ASSERT_GE(conv.stages(), 2);
    std::vector<float> x(h.size(), 0.0f);
    x[0] = 1.0f;
    std::vector<float> y(x.size());
    for (size_t pos = 0; pos < x.size(); pos += static_cast<size_t>(b)) {
      const long n = std::min<long>(b, static_cast<long>(x.size() - pos));
      conv.process(x.data() + pos, y.data() + pos, n);
    }
    for (size_t i = 0; i < h.size(); ++i) ASSERT_NEAR(y[i], h[i], 1e-5) << "block " << b << " sample " << i;
  }
}

TEST(NonUniformConvolver, ResetForgetsThePastAndInPlaceWorks) {
  std::mt19937 rng(11);
  const auto h = uniformNoise(rng, 3000);
  const auto x = uniformNoise(rng, 2500);
  NonUniformConvolver conv;
  conv.init(32, h);
  runInRandomCalls(conv, uniformNoise(rng, 1234), rng);  // some history to forget
  conv.reset();
  std::vector<float> buffer(x);
  buffer.resize(x.size() + h.size() - 1, 0.0f);
  for (size_t pos = 0; pos < buffer.size(); pos += 32) {  // in place: in == out
    const long n = std::min<long>(32, static_cast<long>(buffer.size() - pos));
    conv.process(buffer.data() + pos, buffer.data() + pos, n);
  }
  EXPECT_LE(relativeError(buffer, directConvolution(x, h)), 1e-5);
}

TEST(NonUniformConvolver, MultichannelStereoIrOnStereoInput) {
  std::mt19937 rng(5);
  const std::vector<std::vector<float>> ir{uniformNoise(rng, 4000), uniformNoise(rng, 4000)};
  const auto left = uniformNoise(rng, 3000), right = uniformNoise(rng, 3000);
  const size_t frames = left.size() + 4000 - 1;
  std::vector<float> in(2 * frames, 0.0f), out(2 * frames, 0.0f);
  for (size_t f = 0; f < left.size(); ++f) {
    in[2 * f] = left[f];
    in[2 * f + 1] = right[f];
  }
  NonUniformMultichannelConvolver conv;
  conv.init(64, ir, 2);
  ASSERT_EQ(conv.outputChannels(), 2);
  std::uniform_int_distribution<long> call(0, 200);
  for (size_t pos = 0; pos < frames;) {
    const long n = std::min<long>(call(rng), static_cast<long>(frames - pos));
    conv.process(in.data() + 2 * pos, out.data() + 2 * pos, n);
    pos += static_cast<size_t>(n);
  }
  for (int c = 0; c < 2; ++c) {
    std::vector<float> got(frames);
    for (size_t f = 0; f < frames; ++f) got[f] = out[2 * f + static_cast<size_t>(c)];
    EXPECT_LE(relativeError(got, directConvolution(c == 0 ? left : right, ir[static_cast<size_t>(c)])), 1e-5)
        << "channel " << c;
  }
}

}  // namespace
