// Dry signals and resampling against closed forms written here, sharing no code with dsp/:
//  * the sweep's zero crossings lie where the phase 2π·f1·T/L·(e^{tL/T} − 1) is a multiple of π, solved
//    for t in closed form (t_k = T/L·ln(1 + k·L/(2·f1·T))); the crossing spacing gives the instantaneous
//    frequency f1·(f2/f1)^{t/T};
//  * clicks at round(k·interval·rate) with the exact amplitude, zero elsewhere; a Hann click's samples and its
//    peak at the amplitude for even widths too;
//  * a sine resampled 44.1 → 48 kHz is the same sine (amplitude, phase, no delay) sampled at 48 kHz, and the
//    length is round(n·ratio); an impulse response keeps its DC gain Σh;
//  * speech from espeak-ng: plausible length and peak, not silent (skipped when espeak-ng is missing).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <numeric>
#include <vector>

#include "diffray/audio/speech.h"
#include "diffray/core/error.h"
#include "diffray/dsp/dry_signals.h"
#include "diffray/dsp/resample.h"

namespace {

using namespace diffray;
constexpr double kPi = 3.14159265358979323846;

/// Sign changes of x, located by linear interpolation, in samples (exact zeros skipped).
std::vector<double> zeroCrossings(const std::vector<float>& x) {
  std::vector<double> t;
  for (size_t i = 0; i + 1 < x.size(); ++i)
    if ((x[i] < 0.0f && x[i + 1] > 0.0f) || (x[i] > 0.0f && x[i + 1] < 0.0f))
      t.push_back(static_cast<double>(i) + x[i] / (static_cast<double>(x[i]) - x[i + 1]));
  return t;
}

TEST(DspSignals, SweepZeroCrossingsFollowTheExponentialPhase) {
  dsp::SweepSpec spec;
  spec.rate_hz = 48000.0;
  spec.duration_s = 2.0;
  spec.from_hz = 50.0;
  spec.to_hz = 2000.0;
  spec.amplitude = 0.5;
  spec.fade_s = 0.01;
  const std::vector<float> x = dsp::exponentialSweep(spec);
  ASSERT_EQ(x.size(), 96000u);
  const double T = spec.duration_s, L = std::log(spec.to_hz / spec.from_hz);
  // φ(0) = 0 and the fade starts at 0: x[0] is exactly 0, the first sign change is crossing k = 1.
  EXPECT_EQ(x[0], 0.0f);
  const std::vector<double> crossings = zeroCrossings(x);
  // Number of half periods in the sweep: φ(T)/π = 2·f1·T·(f2/f1 − 1)/L.
  const double half_periods = 2.0 * spec.from_hz * T * (spec.to_hz / spec.from_hz - 1.0) / L;
  EXPECT_NEAR(static_cast<double>(crossings.size()), std::floor(half_periods), 1.0);
  // Between the fades (where the envelope is 1 and linear interpolation sees a pure sine).
  const double fade_samples = spec.fade_s * spec.rate_hz, last = static_cast<double>(x.size()) - fade_samples;
  double worst = 0.0;
  for (size_t i = 0; i < crossings.size(); ++i) {
    const double k = static_cast<double>(i + 1);
    const double t_k = T / L * std::log1p(k * L / (2.0 * spec.from_hz * T));
    if (crossings[i] > fade_samples && crossings[i] < last)
      worst = std::max(worst, std::abs(crossings[i] - t_k * spec.rate_hz));
  }
  std::cout << "[ measured ] worst zero-crossing offset: " << worst << " samples over " << crossings.size() << "\n";
  EXPECT_LT(worst, 0.02);  // linear interpolation of a ≤ 2 kHz sine at 48 kHz

  // Instantaneous frequency from the spacing of crossings 20 apart (10 periods), against f1·(f2/f1)^{t/T}.
  double worst_rel = 0.0;
  for (size_t i = 0; i + 20 < crossings.size(); i += 20) {
    const double f_est = 10.0 * spec.rate_hz / (crossings[i + 20] - crossings[i]);
    // The law f(t) = f1·e^{tL/T} averaged over the span [t1, t2]: f1·(e^{t2·L/T} − e^{t1·L/T})/((t2 − t1)·L/T).
    const double t1 = crossings[i] / spec.rate_hz, t2 = crossings[i + 20] / spec.rate_hz;
    const double f_law = spec.from_hz * (std::exp(t2 * L / T) - std::exp(t1 * L / T)) / ((t2 - t1) * L / T);
    worst_rel = std::max(worst_rel, std::abs(f_est / f_law - 1.0));
  }
  std::cout << "[ measured ] worst instantaneous-frequency error: " << worst_rel << "\n";
  EXPECT_LT(worst_rel, 1e-4);

  // Peak: the amplitude, reached between the fades. The last sample, 1/48000 s before T, lies under the
  // fade's envelope A·sin²(π·(1/48000)/(2·fade)) = A·sin²(π/960).
  const float peak = *std::max_element(x.begin(), x.end(), [](float a, float b) { return std::abs(a) < std::abs(b); });
  EXPECT_NEAR(std::abs(peak), 0.5, 1e-4);
  EXPECT_LE(std::abs(x.back()), 0.5 * std::pow(std::sin(kPi / 960.0), 2) * (1.0 + 1e-6));
}

TEST(DspSignals, SweepRefusesBadInput) {
  dsp::SweepSpec spec;
  spec.from_hz = 1000.0;
  spec.to_hz = 1000.0;
  EXPECT_THROW(dsp::exponentialSweep(spec), core::InputError);
  spec.from_hz = 20.0;
  spec.to_hz = 30000.0;  // above 24 kHz
  EXPECT_THROW(dsp::exponentialSweep(spec), core::InputError);
  spec.to_hz = 20000.0;
  spec.duration_s = -1.0;
  EXPECT_THROW(dsp::exponentialSweep(spec), core::InputError);
}

TEST(DspSignals, ClickTrainPositionsAndAmplitudesAreExact) {
  dsp::ClickSpec spec;
  spec.rate_hz = 48000.0;
  spec.duration_s = 1.0;
  spec.interval_s = 0.1234;  // 5923.2 samples: positions round(k·5923.2)
  spec.amplitude = 0.25;
  const std::vector<float> x = dsp::clickTrain(spec);
  ASSERT_EQ(x.size(), 48000u);
  const std::vector<long> expected = {0, 5923, 11846, 17770, 23693, 29616, 35539, 41462, 47386};
  std::vector<long> found;
  for (size_t i = 0; i < x.size(); ++i)
    if (x[i] != 0.0f) {
      found.push_back(static_cast<long>(i));
      EXPECT_EQ(x[i], 0.25f) << "at " << i;
    }
  EXPECT_EQ(found, expected);

  // A Hann click of 5 samples: sin²(π·j/6), j = 1 … 5 = ¼, ¾, 1, ¾, ¼ of the amplitude.
  spec.width_samples = 5;
  const std::vector<float> y = dsp::clickTrain(spec);
  const double hann[5] = {0.25, 0.75, 1.0, 0.75, 0.25};
  for (long start : expected)
    for (int j = 0; j < 5; ++j) EXPECT_NEAR(y[static_cast<size_t>(start + j)], 0.25 * hann[j], 1e-7);
  EXPECT_EQ(std::count_if(y.begin(), y.end(), [](float s) { return s != 0.0f; }), 45);

  spec.interval_s = 2.0 / 48000.0;  // shorter than a 5-sample click
  EXPECT_THROW(dsp::clickTrain(spec), core::InputError);
}

TEST(DspSignals, ClickPeakIsTheAmplitudeForEveryWidth) {
  // The requested peak (--level) whatever the width: even widths have no middle sample, so the Hann window
  // sin²(π(j+1)/(w+1)) tops out at sin²(π·(w/2)/(w+1)) < 1 (¾ for w = 2) unless scaled by it.
  dsp::ClickSpec spec;
  spec.rate_hz = 48000.0;
  spec.duration_s = 0.01;
  spec.interval_s = 0.005;
  spec.amplitude = 0.5;
  for (int w = 1; w <= 9; ++w) {
    spec.width_samples = w;
    const std::vector<float> x = dsp::clickTrain(spec);
    EXPECT_FLOAT_EQ(*std::max_element(x.begin(), x.end()), 0.5f) << "width " << w;
  }
  // w = 2: both samples sin²(π/3) = ¾ before scaling, so both at the peak; w = 4: sin²(π/5)/sin²(2π/5) at
  // the ends.
  spec.width_samples = 2;
  const std::vector<float> two = dsp::clickTrain(spec);
  EXPECT_FLOAT_EQ(two[0], 0.5f);
  EXPECT_FLOAT_EQ(two[1], 0.5f);
  spec.width_samples = 4;
  const std::vector<float> four = dsp::clickTrain(spec);
  const double end = 0.5 * std::pow(std::sin(kPi / 5.0) / std::sin(2.0 * kPi / 5.0), 2);
  EXPECT_NEAR(four[0], end, 1e-7);
  EXPECT_FLOAT_EQ(four[1], 0.5f);
  EXPECT_FLOAT_EQ(four[2], 0.5f);
  EXPECT_NEAR(four[3], end, 1e-7);
}

TEST(DspResample, SineStaysTheSameSineAt48k) {
  const double from = 44100.0, to = 48000.0, f = 1000.0, a = 0.5, phase = 0.3;
  const long n = 44100;
  std::vector<float> x(static_cast<size_t>(n));
  for (long i = 0; i < n; ++i) x[static_cast<size_t>(i)] = static_cast<float>(a * std::sin(2 * kPi * f * static_cast<double>(i) / from + phase));
  const std::vector<float> y = dsp::resample(x, 1, from, to);
  ASSERT_EQ(y.size(), 48000u);
  // Least-squares fit of c·cos + s·sin at f over the interior (the ends see the filter's edge), then the
  // residual against the ideal samples a·sin(2πf·j/48000 + phase): no delay, same amplitude and phase.
  double cc = 0, cs = 0, ss = 0, yc = 0, ys = 0;
  const long lo = 2000, hi = 46000;
  for (long j = lo; j < hi; ++j) {
    const double w = 2 * kPi * f * static_cast<double>(j) / to, c = std::cos(w), s = std::sin(w), v = y[static_cast<size_t>(j)];
    cc += c * c, cs += c * s, ss += s * s, yc += v * c, ys += v * s;
  }
  const double det = cc * ss - cs * cs;
  const double coef_c = (yc * ss - ys * cs) / det, coef_s = (ys * cc - yc * cs) / det;
  EXPECT_NEAR(std::hypot(coef_c, coef_s), a, 1e-4 * a);
  EXPECT_NEAR(std::atan2(coef_c, coef_s), phase, 1e-4);
  double worst = 0.0;
  for (long j = lo; j < hi; ++j)
    worst = std::max(worst, std::abs(y[static_cast<size_t>(j)] - a * std::sin(2 * kPi * f * static_cast<double>(j) / to + phase)));
  std::cout << "[ measured ] worst deviation from the ideal 48 kHz sine: " << worst / a << " of the amplitude\n";
  EXPECT_LT(worst, 1e-4 * a);
}

TEST(DspResample, LengthIsRoundedRatioAndChannelsStayApart) {
  for (const auto& [from, to, n] : std::vector<std::tuple<double, double, long>>{
           {44100, 48000, 1001}, {48000, 44100, 1001}, {48000, 22050, 7}, {8000, 96000, 333}, {44100, 44100, 10}}) {
    const std::vector<float> y = dsp::resample(std::vector<float>(static_cast<size_t>(2 * n), 0.1f), 2, from, to);
    EXPECT_EQ(static_cast<long>(y.size()), 2 * std::lround(static_cast<double>(n) * to / from)) << from << " -> " << to << ", " << n;
  }
  // Stereo: a sine on the left, silence on the right; the right stays silent.
  std::vector<float> x(2 * 4410, 0.0f);
  for (size_t i = 0; i < 4410; ++i) x[2 * i] = static_cast<float>(std::sin(2 * kPi * 440.0 * static_cast<double>(i) / 44100.0));
  const std::vector<float> y = dsp::resample(x, 2, 44100.0, 48000.0);
  double right = 0.0, left = 0.0;
  for (size_t i = 0; i < y.size() / 2; ++i) left = std::max(left, double(std::abs(y[2 * i]))), right = std::max(right, double(std::abs(y[2 * i + 1])));
  EXPECT_GT(left, 0.9);
  EXPECT_EQ(right, 0.0);
  EXPECT_THROW(dsp::resample(x, 11, 44100.0, 48000.0), core::InputError);  // 8820 samples, not 11·k
  EXPECT_THROW(dsp::resample(x, 2, 44100.0, 0.0), core::InputError);
  EXPECT_THROW(dsp::resample(x, 2, 1000.0, 300000.0), core::InputError);  // ratio 300
}

TEST(DspResample, ImpulseResponseKeepsItsDcGain) {
  // A Dirac (a pass-through filter, Σh = 1) and a short decaying IR (Σh known) moved 44.1 → 48 kHz and
  // 48 → 44.1 kHz: the DC gain Σh' equals Σh (the band-limited sinc sums to fs2/fs1 samples, times fs1/fs2).
  std::vector<float> dirac(400, 0.0f);
  dirac[200] = 1.0f;
  std::vector<float> decay(400, 0.0f);
  for (size_t i = 100; i < 300; ++i) decay[i] = static_cast<float>(std::exp(-0.02 * (static_cast<double>(i) - 100.0)));
  for (const auto& h : {dirac, decay})
    for (const auto& [from, to] : std::vector<std::pair<double, double>>{{44100, 48000}, {48000, 44100}}) {
      const std::vector<float> g = dsp::resampleImpulseResponse(h, 1, from, to);
      const double sum_h = std::accumulate(h.begin(), h.end(), 0.0), sum_g = std::accumulate(g.begin(), g.end(), 0.0);
      EXPECT_NEAR(sum_g, sum_h, 1e-3 * sum_h) << from << " -> " << to;
    }
}

TEST(AudioSpeech, EspeakGivesPlausibleSpeech) {
  if (!audio::espeakAvailable()) GTEST_SKIP() << "espeak-ng is not installed (tools/deps.sh installs it)";
  audio::SpeechSpec spec;
  spec.text = "The quick brown fox jumps over the lazy dog.";  // 9 words
  spec.rate_hz = 48000.0;
  spec.amplitude = 0.5;
  const std::vector<float> x = audio::synthesizeSpeech(spec);
  const double seconds = static_cast<double>(x.size()) / spec.rate_hz;
  // 9 words at 160 words per minute are 3.4 s; espeak-ng adds pauses and trailing silence: 1.5 … 8 s.
  EXPECT_GT(seconds, 1.5);
  EXPECT_LT(seconds, 8.0);
  double peak = 0.0, energy = 0.0;
  for (float s : x) peak = std::max(peak, double(std::abs(s))), energy += double(s) * s;
  EXPECT_NEAR(peak, 0.5, 1e-6);
  // Speech has a crest factor of ~4–10: an RMS far above silence.
  EXPECT_GT(std::sqrt(energy / static_cast<double>(x.size())), 0.5 / 30.0);
  spec.voice = "nosuchvoice";
  EXPECT_THROW(audio::synthesizeSpeech(spec), core::InputError);
}

}  // namespace
