// The crossfading convolver (both engines: uniformly and non-uniformly partitioned) against a brute-force
// oracle written here (no code shared with dsp/): direct
// time-domain convolution of the input with every IR, weighted by hat-function gains computed from
// "where does n lie between the key frames" (linear interpolation of the IR index), summed. Random block
// sizes, call sizes, key frames and IR lengths; the lazy start and stop of the convolvers checked where a
// convolver starts mid-signal; continuity of the output against an analytic bound on the sample-to-sample
// jump, which a hard switch between the same IRs breaks; K = 1 is plain convolution.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <random>
#include <vector>

#include "diffray/core/error.h"
#include "diffray/dsp/crossfade_convolver.h"
#include "diffray/dsp/multichannel_convolver.h"

namespace {

using diffray::dsp::CrossfadeConvolver;
using diffray::dsp::NonUniformCrossfadeConvolver;
using Irs = std::vector<std::vector<std::vector<float>>>;  // [k][channel][sample]

std::vector<float> noise(std::mt19937& rng, size_t n, float amplitude = 1.0f) {
  std::uniform_real_distribution<float> u(-amplitude, amplitude);
  std::vector<float> v(n);
  for (float& s : v) s = u(rng);
  return v;
}

/// The oracle's gains at frame n: find the key-frame interval [t_j, t_{j+1}) holding n, the fraction
/// u = (n − t_j)/(t_{j+1} − t_j) of the way through it, and give IR j weight 1 − u and IR j+1 weight u;
/// before t_0 all weight to IR 0, from t_{K−1} on all to IR K−1.
std::vector<double> oracleGains(const std::vector<long>& t, long n) {
  const size_t K = t.size();
  std::vector<double> g(K, 0.0);
  if (n <= t.front()) {
    g.front() = 1.0;
  } else if (n >= t.back()) {
    g.back() = 1.0;
  } else {
    size_t j = 0;
    while (!(t[j] <= n && n < t[j + 1])) ++j;
    const double u = static_cast<double>(n - t[j]) / static_cast<double>(t[j + 1] - t[j]);
    g[j] = 1.0 - u;
    g[j + 1] = u;
  }
  return g;
}

/// z[n] = Σ_j h[j]·x[n − j] for n in [0, frames), in double; x is one channel of length ≤ frames.
std::vector<double> direct(const std::vector<double>& x, const std::vector<float>& h, long frames) {
  std::vector<double> z(static_cast<size_t>(frames), 0.0);
  for (size_t i = 0; i < x.size(); ++i) {
    if (x[i] == 0.0) continue;
    for (size_t j = 0; j < h.size() && static_cast<long>(i + j) < frames; ++j) z[i + j] += x[i] * h[j];
  }
  return z;
}

/// The oracle output, interleaved, `frames` frames: for output channel o, input channel (C = 1 ? 0 : o)
/// through IR channel (M = 1 ? 0 : o) (the pairing of multichannel_convolver.h).
std::vector<double> oracle(const std::vector<float>& in, int in_channels, const Irs& irs, const std::vector<long>& t,
                           long frames) {
  const int M = static_cast<int>(irs[0].size());
  const int outs = in_channels == 1 ? M : in_channels;
  const long n_in = static_cast<long>(in.size()) / in_channels;
  std::vector<double> y(static_cast<size_t>(frames * outs), 0.0);
  for (int o = 0; o < outs; ++o) {
    std::vector<double> x(static_cast<size_t>(n_in));
    for (long n = 0; n < n_in; ++n) x[static_cast<size_t>(n)] = in[static_cast<size_t>(n * in_channels + (in_channels == 1 ? 0 : o))];
    for (size_t k = 0; k < irs.size(); ++k) {
      const std::vector<double> z = direct(x, irs[k][static_cast<size_t>(M == 1 ? 0 : o)], frames);
      for (long n = 0; n < frames; ++n) y[static_cast<size_t>(n * outs + o)] += oracleGains(t, n)[k] * z[static_cast<size_t>(n)];
    }
  }
  return y;
}

/// Feeds `in` through `conv` in calls of random size (0 … 3 blocks), then flushes tailFrames(); returns
/// all output. Records the largest activeConvolvers() seen between calls in `max_active` if given.
template <class Conv>
std::vector<float> runInRandomCalls(Conv& conv, const std::vector<float>& in, std::mt19937& rng,
                                    int* max_active = nullptr) {
  const long cin = conv.inputChannels(), cout = conv.outputChannels();
  const long frames = static_cast<long>(in.size()) / cin;
  std::vector<float> out(static_cast<size_t>(frames * cout), 0.0f);
  std::uniform_int_distribution<long> call(0, 3L * conv.blockSize());
  for (long pos = 0; pos < frames;) {
    if (max_active != nullptr) *max_active = std::max(*max_active, conv.activeConvolvers());
    const long n = std::min(call(rng), frames - pos);
    conv.process(in.data() + pos * cin, out.data() + pos * cout, n);
    pos += n;
  }
  const long tail = conv.tailFrames();
  out.resize(static_cast<size_t>((frames + tail) * cout), 0.0f);
  for (long pos = frames; pos < frames + tail;) {
    const long n = std::min(std::max(call(rng), 1L), frames + tail - pos);
    conv.flush(out.data() + pos * cout, n);
    pos += n;
  }
  return out;
}

double maxAbs(const std::vector<double>& v) {
  double m = 0.0;
  for (double s : v) m = std::max(m, std::abs(s));
  return m;
}

/// max |got − ref| / max |ref| over the frames of `got`; `ref` (longer) must be 0 past them.
double relativeError(const std::vector<float>& got, const std::vector<double>& ref) {
  double err = 0.0;
  for (size_t i = 0; i < ref.size(); ++i) err = std::max(err, std::abs((i < got.size() ? got[i] : 0.0) - ref[i]));
  return err / maxAbs(ref);
}

TEST(Crossfade, MatchesOracleWithRandomBlocksCallsAndKeyFrames) {
  std::mt19937 rng(20240611);
  std::uniform_int_distribution<int> pow2(0, 9), any_block(1, 500), ir_count(1, 5), ir_len(1, 1200),
      x_len(1, 5000), spacing(1, 2500), first(-1500, 2000);
  struct Pairing {
    int ir_channels, in_channels;
  };
  const Pairing pairings[] = {{1, 1}, {2, 2}, {2, 1}, {1, 2}};
  double worst = 0.0;
  for (int trial = 0; trial < 24; ++trial) {
    const int block = trial % 2 == 0 ? 1 << pow2(rng) : any_block(rng);
    const Pairing p = pairings[trial % 4];
    const int K = ir_count(rng);
    Irs irs(static_cast<size_t>(K));
    for (auto& ir : irs) {
      const size_t len = static_cast<size_t>(ir_len(rng));
      for (int m = 0; m < p.ir_channels; ++m) ir.push_back(noise(rng, len));
    }
    std::vector<long> t{first(rng)};
    while (static_cast<int>(t.size()) < K) t.push_back(t.back() + spacing(rng));
    const long frames = x_len(rng);
    const std::vector<float> in = noise(rng, static_cast<size_t>(frames * p.in_channels));
    long longest = 0;
    for (const auto& ir : irs) longest = std::max(longest, static_cast<long>(ir[0].size()));
    // The oracle over the whole linear convolution: past input + longest IR − 1 every term is zero.
    const std::vector<double> ref = oracle(in, p.in_channels, irs, t, frames + longest - 1);
    // Both engines: uniformly partitioned (the offline door) and non-uniform (the real-time door).
    CrossfadeConvolver conv;
    conv.init(block, irs, p.in_channels, t);
    NonUniformCrossfadeConvolver non_uniform;
    non_uniform.init(block, irs, p.in_channels, t);
    for (const std::vector<float>& y : {runInRandomCalls(conv, in, rng), runInRandomCalls(non_uniform, in, rng)}) {
      ASSERT_LE(y.size(), ref.size());
      const double rel = relativeError(y, ref);
      worst = std::max(worst, rel);
      EXPECT_LE(rel, 1e-5) << "trial " << trial << ": block " << block << ", K " << K << ", input " << frames;
    }
  }
  std::cout << "[ measured ] worst error / output peak over 24 trials: " << worst << "\n";
}

TEST(Crossfade, LazyStartAndStopIsExact) {
  // Key frames 3000 apart, IRs 1000 long: each convolver starts from silence 1000 samples (rounded down to
  // the block grid) before its fade-in at t_{k−1}, in the middle of the signal, and stops at t_{k+1}.
  std::mt19937 rng(99);
  const std::vector<long> t{2000, 5000, 8000, 11000, 14000};
  Irs irs;
  for (size_t k = 0; k < t.size(); ++k) irs.push_back({noise(rng, 1000, 1.0f / static_cast<float>(k + 1))});
  const long frames = 16000;
  const std::vector<float> in = noise(rng, static_cast<size_t>(frames));
  CrossfadeConvolver conv;
  conv.init(128, irs, 1, t);
  int max_active = 0;
  const std::vector<float> y = runInRandomCalls(conv, in, rng, &max_active);
  const std::vector<double> ref = oracle(in, 1, irs, t, frames + 999);
  EXPECT_LE(relativeError(y, ref), 1e-5);
  // Where convolver k has just started (its first L_k outputs after t_{k−1}), the history it was given is
  // what makes the output right: compare sample by sample there.
  const double peak = maxAbs(ref);
  for (size_t k = 1; k < t.size(); ++k)
    for (long n = t[k - 1]; n < t[k - 1] + 1000; ++n)
      ASSERT_NEAR(y[static_cast<size_t>(n)], ref[static_cast<size_t>(n)], 1e-5 * peak) << "IR " << k << ", frame " << n;
  // That window has teeth: a convolver started from silence at t_{k−1} (no history) would be off there by
  // far more than the tolerance.
  for (size_t k = 1; k < t.size(); ++k) {
    std::vector<double> late(in.begin(), in.end()), full(in.begin(), in.end());
    std::fill(late.begin(), late.begin() + t[k - 1], 0.0);
    const std::vector<double> z_late = direct(late, irs[k][0], t[k - 1] + 1000);
    const std::vector<double> z_full = direct(full, irs[k][0], t[k - 1] + 1000);
    double off = 0.0;
    for (long n = t[k - 1]; n < t[k - 1] + 1000; ++n)
      off = std::max(off, oracleGains(t, n)[k] * std::abs(z_late[static_cast<size_t>(n)] - z_full[static_cast<size_t>(n)]));
    EXPECT_GT(off, 1e-3 * peak) << "IR " << k;
  }
  // Lazy: besides the one fading out and the one fading in, only a convolver warming up for the next
  // fade (from L_k before t_k) runs, so never more than three; midway between key frames exactly two, and
  // before t_0 − L_1 only IR 0's.
  EXPECT_LE(max_active, 3);
  EXPECT_EQ(conv.activeConvolvers(), 1);  // only the last IR is left at the end
  conv.reset();
  std::vector<float> out(128);
  for (long pos = 0; pos < frames; pos += 128) {
    for (size_t k = 0; k + 1 < t.size(); ++k)
      if (pos == (t[k] + t[k + 1]) / 2 / 128 * 128) {
        EXPECT_EQ(conv.activeConvolvers(), 2) << "frame " << pos;
      }
    if (pos == 512) {
      EXPECT_EQ(conv.activeConvolvers(), 1);
    }
    conv.process(in.data() + pos, out.data(), 128);
  }
}

TEST(Crossfade, GainsAreHatFunctionsSummingToOne) {
  CrossfadeConvolver conv;
  const std::vector<long> t{-10, 5, 100, 101};
  conv.init(16, Irs(4, {{1.0f}}), 1, t);
  for (long n = -50; n < 200; ++n) {
    const std::vector<double> g = oracleGains(t, n);
    double sum = 0.0;
    for (int k = 0; k < 4; ++k) {
      EXPECT_NEAR(conv.gain(k, n), g[static_cast<size_t>(k)], 1e-15) << "k " << k << ", n " << n;
      sum += conv.gain(k, n);
    }
    EXPECT_NEAR(sum, 1.0, 1e-15);
  }
  EXPECT_EQ(conv.gain(1, 5), 1.0);
  EXPECT_EQ(conv.gain(0, -10), 1.0);
  EXPECT_EQ(conv.gain(3, 101), 1.0);
}

TEST(Crossfade, ContinuousAtEveryKeyFrameWithinTheAnalyticBound) {
  // Input x[n] = A·sin(ω n), n ≥ 0 (x[n] = 0 before: the sine starts at a zero, so no step at n = 0),
  // ω = 2π f/fs. With z_k = h_k ∗ x and y = Σ_k g_k z_k, the jump Δy(n) = y[n+1] − y[n] splits as
  //     Δy(n) = Σ_k g_k(n+1)·Δz_k(n) + Σ_k Δg_k(n)·z_k(n).
  // First term: g_k ≥ 0 and Σ_k g_k = 1, so |·| ≤ max_k |Δz_k(n)|. Each Δz_k(n) = Σ_j h_k[j]·Δx(n − j) and
  // |Δx| = |A·(sin(ω(m+1)) − sin(ωm))| = 2A·|cos(ω(m + ½))|·sin(ω/2) ≤ 2A·sin(ω/2) (also 0 for m < 0), so
  // |Δz_k| ≤ 2A·sin(ω/2)·Σ|h_k|. Second term: |z_k| ≤ A·Σ|h_k|, and Σ_k |Δg_k(n)| is 2/(t_{j+1} − t_j) on
  // key-frame interval j (one hat falls by 1/D_j, the next rises by as much) and 0 outside, so
  // |·| ≤ (2/D_min)·A·max_k Σ|h_k|. Hence, with S = max_k Σ|h_k|,
  //     |Δy| ≤ A·S·(2 sin(ω/2) + 2/D_min) + 2ε,
  // where ε = 1e-5·A·S covers the convolver's rounding on each of the two samples (the accuracy the oracle
  // test above establishes, relative to a peak that is at most A·S).
  const double fs = 48000.0, f = 440.0, A = 0.8;
  const double w = 2.0 * M_PI * f / fs;
  std::mt19937 rng(4);
  // IRs of very different gains, polarities and delays: a dry path, a weak inverted echo with a noisy
  // tail, a strong late one.
  std::vector<float> h0(1, 1.0f), h1(400, 0.0f), h2(1300, 0.0f);
  h1[250] = -0.3f;
  const std::vector<float> tail = noise(rng, 100, 0.02f);
  std::copy(tail.begin(), tail.end(), h1.begin() + 300);
  h2[1200] = 2.0f;
  h2[1299] = 0.5f;
  const Irs irs{{h0}, {h1}, {h2}, {h0}};
  const std::vector<long> t{3000, 7000, 9000, 12000};  // D_min = 2000
  const long frames = 15000;
  std::vector<float> in(static_cast<size_t>(frames));
  for (long n = 0; n < frames; ++n) in[static_cast<size_t>(n)] = static_cast<float>(A * std::sin(w * static_cast<double>(n)));
  CrossfadeConvolver conv;
  conv.init(256, irs, 1, t);
  const std::vector<float> y = runInRandomCalls(conv, in, rng);

  double S = 0.0;
  for (const auto& ir : irs) {
    double s = 0.0;
    for (float v : ir[0]) s += std::abs(v);
    S = std::max(S, s);
  }
  const double d_min = 2000.0;
  const double bound = A * S * (2.0 * std::sin(w / 2.0) + 2.0 / d_min) + 2.0 * 1e-5 * A * S;
  // Only while the input lasts (it stops mid-wave at `frames`, a step the bound does not cover).
  double worst = 0.0, worst_at_keys = 0.0;
  for (long n = 0; n + 1 < frames; ++n) {
    const double jump = std::abs(static_cast<double>(y[static_cast<size_t>(n + 1)]) - y[static_cast<size_t>(n)]);
    worst = std::max(worst, jump);
    for (long key : t)
      if (std::abs(n - key) <= 1) worst_at_keys = std::max(worst_at_keys, jump);
  }
  EXPECT_LE(worst, bound);
  EXPECT_LE(worst_at_keys, bound);

  // Teeth: the same IRs switched hard (IR k from the midpoint before t_k to the midpoint after) break it.
  std::vector<double> x(in.begin(), in.end());
  std::vector<std::vector<double>> z;
  for (const auto& ir : irs) z.push_back(direct(x, ir[0], frames));
  double hard_worst = 0.0;
  auto hardIr = [&](long n) {
    size_t k = 0;
    while (k + 1 < t.size() && n >= (t[k] + t[k + 1]) / 2) ++k;
    return k;
  };
  for (long n = 0; n + 1 < frames; ++n) {
    const double a = z[hardIr(n)][static_cast<size_t>(n)], b = z[hardIr(n + 1)][static_cast<size_t>(n + 1)];
    hard_worst = std::max(hard_worst, std::abs(b - a));
  }
  EXPECT_GT(hard_worst, 2.0 * bound);
  std::cout << "[ measured ] largest jump: crossfade " << worst << " (at key frames " << worst_at_keys
            << "), bound " << bound << ", hard switch " << hard_worst << "\n";
}

TEST(Crossfade, OneImpulseResponseIsPlainConvolution) {
  std::mt19937 rng(8);
  const std::vector<std::vector<float>> ir{noise(rng, 777), noise(rng, 777)};
  const long frames = 4096 + 300;
  const std::vector<float> in = noise(rng, static_cast<size_t>(frames * 2));
  CrossfadeConvolver xfade;
  xfade.init(256, {ir}, 2, {1234});
  diffray::dsp::MultichannelConvolver plain;
  plain.init(256, ir, 2);
  // Same calls (whole blocks, then the rest): the same numbers, bit for bit.
  std::vector<float> a(in.size()), b(in.size());
  for (long pos = 0; pos < frames; pos += 256) {
    const long n = std::min(256L, frames - pos);
    xfade.process(in.data() + pos * 2, a.data() + pos * 2, n);
    plain.process(in.data() + pos * 2, b.data() + pos * 2, n);
  }
  EXPECT_EQ(a, b);
  EXPECT_EQ(xfade.tailFrames(), 776);
  // And against the oracle with random calls.
  xfade.reset();
  const std::vector<float> y = runInRandomCalls(xfade, in, rng);
  EXPECT_EQ(static_cast<long>(y.size()), 2 * (frames + 776));
  EXPECT_LE(relativeError(y, oracle(in, 2, {ir}, {1234}, frames + 776)), 1e-5);
}

TEST(Crossfade, RefusesBadArguments) {
  CrossfadeConvolver conv;
  const std::vector<std::vector<float>> mono{{1.0f, 0.5f}}, stereo{{1.0f}, {0.5f}};
  using diffray::core::InputError;
  EXPECT_THROW(conv.init(64, {}, 1, {}), InputError);                           // K = 0
  EXPECT_THROW(conv.init(64, {mono, mono}, 1, {0}), InputError);                // K key frames needed
  EXPECT_THROW(conv.init(64, {mono, mono}, 1, {10, 10}), InputError);           // not strictly increasing
  EXPECT_THROW(conv.init(64, {mono, mono, mono}, 1, {0, 20, 10}), InputError);  // decreasing
  EXPECT_THROW(conv.init(64, {mono, stereo}, 1, {0, 10}), InputError);          // channel counts differ
  EXPECT_THROW(conv.init(64, {stereo, stereo}, 3, {0, 10}), InputError);        // stereo IR, 3-ch input
  EXPECT_THROW(conv.init(0, {mono}, 1, {0}), InputError);                       // block size
  EXPECT_THROW(conv.init(64, {{{}}}, 1, {0}), InputError);                      // empty IR
  EXPECT_THROW(conv.init(64, {{{1.0f, NAN}}}, 1, {0}), InputError);             // NaN
  EXPECT_NO_THROW(conv.init(64, {mono, mono}, 1, {-5, 10}));  // key frames may be negative
}

}  // namespace
