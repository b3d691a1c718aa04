// FilterLimit (ir/filter_limit.h): which decay figures a band filter alone makes unreliable. Oracles that
// share no code with the model: a Dirac, whose true decay time is zero, so every figure it reads is the
// filter's; and exponentially decaying Gaussian noise of known T through the same filter, whose expected
// band energy is what the model computes by convolution.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>

#include "diffray/core/bands.h"
#include "diffray/core/error.h"
#include "diffray/ir/band_filter.h"
#include "diffray/ir/filter_limit.h"
#include "diffray/ir/metrics.h"

namespace diffray::ir {
namespace {

constexpr double kFs = 48000.0;

// Gaussian noise whose energy falls 60 dB in t_s, after `start` samples of silence, 2.5 t_s + 0.5 s long.
std::vector<double> decayingNoise(double t_s, std::uint64_t seed, long start = static_cast<long>(0.1 * kFs)) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::vector<double> p(static_cast<size_t>(static_cast<double>(start) + (2.5 * t_s + 0.5) * kFs), 0.0);
  const double step = std::pow(10.0, -3.0 / kFs / t_s);  // amplitude factor per sample
  double amplitude = 1.0;
  for (size_t n = static_cast<size_t>(start); n < p.size(); ++n, amplitude *= step) p[n] = normal(rng) * amplitude;
  return p;
}

// The standard error of the mean of independent estimates, from their spread.
double standardErrorOfMean(const std::vector<double>& v) {
  const double n = static_cast<double>(v.size());
  double mean = 0.0, sq = 0.0;
  for (double x : v) mean += x / n;
  for (double x : v) sq += (x - mean) * (x - mean);
  return std::sqrt(sq / (n - 1.0) / n);
}

// A Dirac's true figures are those of a decay of zero length: T = 0, C = +∞, D50 = 1, Ts = 0. Whatever
// it reads more than one JND from them is the filter's, and must be flagged; D50 and Ts read within a JND
// of the truth and must not be.
TEST(FilterLimit, ADiracIsFlaggedWhereItsReadingIsNotItsTruth) {
  const core::Bands bands = core::Bands::octave();
  std::vector<double> p(static_cast<size_t>(3 * kFs), 0.0);
  p[static_cast<size_t>(0.1 * kFs)] = 1.0;
  const auto m = metricsFromSignal(p, kFs, bands);
  int figures = 0;
  for (int b = 0; b < bands.size(); ++b) {
    SCOPED_TRACE(bands.label(b));
    for (Figure f : kAllFigures) {
      const double v = m[b].value(f);
      if (!std::isfinite(v)) continue;
      ++figures;
      const bool off = f == Figure::D50 ? std::abs(v - 1.0) > 0.05 : f == Figure::Ts ? v > 0.010 : true;
      EXPECT_EQ(m[b].limited(f), off) << figureName(f) << " " << v;
    }
  }
  EXPECT_GE(figures, 50);  // the Dirac's 81–123 dB ranges make nearly every figure measurable
  const std::string table = metricsTable(bands, m);
  const std::string row63 = table.substr(table.find("\n     63"), 70);
  EXPECT_EQ(std::count(row63.begin(), row63.end(), '*'), 5) << table;  // T20, T30, EDT, C50, C80
  EXPECT_EQ(metricsJson(bands, m)["63"]["filter_limited"].size(), 5u);
}

TEST(FilterLimit, ALongDecayIsNotFlagged) {
  // T = 3 s: the flag thresholds are 1.33 s (63 Hz EDT) and below, and these figures scatter by ~10 %.
  const core::Bands bands = core::Bands::octave();
  const auto m = metricsFromSignal(decayingNoise(3.0, 1), kFs, bands);
  for (int b = 0; b < bands.size(); ++b) {
    SCOPED_TRACE(bands.label(b));
    for (Figure f : kAllFigures) EXPECT_FALSE(m[b].limited(f)) << figureName(f);
    EXPECT_FALSE(metricsJson(bands, m)[bands.label(b)].contains("filter_limited"));
  }
}

TEST(FilterLimit, TheModelFallsWithTAndRejectsANonPositiveT) {
  const core::Bands bands = core::Bands::octave();
  const BandFilter filter(bands, kFs);
  const FilterLimit limit(filter);
  double previous = INFINITY;
  for (double t : {0.05, 0.1, 0.2, 0.4, 0.8, 1.6, 3.2}) {
    const double bias = limit.relativeBias(0, Figure::Edt, t);
    EXPECT_LT(bias, previous) << t;
    EXPECT_GT(bias, -0.01) << t;  // a filter lengthens decays
    previous = bias;
  }
  EXPECT_LT(previous, 0.02);  // 3.2 s at 63 Hz: within 2 %
  EXPECT_THROW(limit.relativeBias(0, Figure::T20, 0.0), core::InputError);
  EXPECT_FALSE(limit.limited(0, Figure::T20, NAN));
  // A Ts read from energy ahead of the onset can be negative; no decay has one, and the rule says so
  // instead of asking the model about a decay of zero length.
  EXPECT_TRUE(limit.limited(0, Figure::Ts, -0.02));
}

// The closed forms the flags compare with, against metricsFromEnergy (ISO 3382-1's definitions, summed
// numerically) of an unfiltered exponential 10^(−6t/T) in 0.1 ms bins, 3T long.
TEST(FilterLimit, TrueValuesAreTheMetricsOfAnExponential) {
  for (double t : {0.3, 1.0, 2.5}) {
    SCOPED_TRACE(t);
    const double bin = 1e-4;
    std::vector<double> e(static_cast<size_t>(3.0 * t / bin));
    for (size_t i = 0; i < e.size(); ++i) e[i] = std::pow(10.0, -6.0 * (static_cast<double>(i) + 0.5) * bin / t);
    const BandMetrics m = metricsFromEnergy(e, bin, 0);
    EXPECT_NEAR(m.c50, FilterLimit::trueValue(Figure::C50, t), 0.02);
    EXPECT_NEAR(m.c80, FilterLimit::trueValue(Figure::C80, t), 0.02);
    EXPECT_NEAR(m.d50, FilterLimit::trueValue(Figure::D50, t), 1e-3);
    EXPECT_NEAR(m.ts, FilterLimit::trueValue(Figure::Ts, t), 1e-3 * t);
    EXPECT_NEAR(m.t30, FilterLimit::trueValue(Figure::T30, t), 0.01 * t);
  }
}

// The model against measurement. The model is the expected band energy of decaying white noise (for
// x = w·a with white w, E[(x ∗ h)²] = a² ∗ h²), so the oracle is that expectation estimated directly:
// the squared band signals of 256 noise signals through the same filter, averaged, and measured once
// (metricsFromEnergy from the decay's start). Its statistical error comes from 16 groups of 16 seeds
// measured separately (standard error = their spread / 4); the tolerance is 4.07 of those (Student's t
// with 15 degrees of freedom, two-sided 0.1 %: the spread of 16 groups is itself uncertain). A first
// version, 96 decays in 8 groups within 3 s.e., failed on the 63 Hz C80: 8 groups had underestimated its
// scatter, which 512 decays confirmed (their mean converges to the model). A 63 Hz C80 from 80 ms
// of a 44 Hz wide band scatters by ~2 dB per signal, which is why so many. Cases: two decays the EDT flag
// marks (model bias +10–12 %) and two it passes (+1.5–2 %), in the two lowest octaves; EDT and C80.
TEST(StatFilterLimit, TheModelIsTheExpectedReadingOfDecayingNoise) {
  struct Case {
    double band_hz, t_s;
    bool flagged;
  };
  for (const Case c : {Case{125, 0.4, true}, Case{125, 1.2, false}, Case{63, 0.8, true}, Case{63, 2.4, false}}) {
    SCOPED_TRACE(std::to_string(c.band_hz) + " Hz, T " + std::to_string(c.t_s));
    const core::Bands bands = core::Bands::octave(c.band_hz, c.band_hz);  // one band: a fifth of the FFTs
    const BandFilter filter(bands, kFs);
    const FilterLimit limit(filter);
    // Silence ahead for the whole of the filter's ringing, so its response before the onset is kept (as
    // metricsFromSignal's lead does, and as the model's convolution has it).
    const long start = filter.ringSamples();
    const int groups = 16, per_group = 16;
    std::vector<double> all, group_edt, group_c80;
    for (int g = 0; g < groups; ++g) {
      std::vector<double> sum;
      for (int s = 0; s < per_group; ++s) {
        const std::vector<double> band = filter.split(decayingNoise(c.t_s, 1000 + g * per_group + s, start))[0];
        sum.resize(band.size(), 0.0);
        for (size_t n = 0; n < band.size(); ++n) sum[n] += band[n] * band[n];
      }
      all.resize(sum.size(), 0.0);
      for (size_t n = 0; n < sum.size(); ++n) all[n] += sum[n];
      const BandMetrics gm = metricsFromEnergy(sum, 1.0 / kFs, start);
      group_edt.push_back(gm.edt);
      group_c80.push_back(gm.c80);
    }
    const BandMetrics averaged = metricsFromEnergy(all, 1.0 / kFs, start);
    const double se = standardErrorOfMean(group_edt) / c.t_s;
    const double measured = averaged.edt / c.t_s - 1.0;
    const double model = limit.relativeBias(0, Figure::Edt, c.t_s);
    EXPECT_NEAR(measured, model, 4.07 * se) << "measured " << measured << ", model " << model << ", se " << se;
    EXPECT_EQ(limit.limited(0, Figure::Edt, c.t_s * (1.0 + model)), c.flagged) << model;
    // C80 the same way, in dB.
    const double c_se = standardErrorOfMean(group_c80);
    EXPECT_NEAR(averaged.c80, limit.modelReading(0, c.t_s).c80, 4.07 * c_se) << "C80 se " << c_se;
  }
}

}  // namespace
}  // namespace diffray::ir
