// FilterLimit (ir/filter_limit.h): which decay figures a band filter alone makes unreliable. Oracles that
// share no code with the model: a Dirac, whose true decay time is zero, so every figure it reads is the
// filter's; and exponentially decaying Gaussian noise of known T measured through metricsFromSignal, whose
// mean error over many seeds is the bias the model predicts.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "diffray/core/bands.h"
#include "diffray/core/error.h"
#include "diffray/ir/band_filter.h"
#include "diffray/ir/filter_limit.h"
#include "diffray/ir/metrics.h"

namespace diffray::ir {
namespace {

constexpr double kFs = 48000.0;

// Gaussian noise whose energy falls 60 dB in t_s, after 0.1 s of silence, 2.5 t_s + 0.5 s long.
std::vector<double> decayingNoise(double t_s, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  const long start = static_cast<long>(0.1 * kFs);
  std::vector<double> p(static_cast<size_t>(start + (2.5 * t_s + 0.5) * kFs), 0.0);
  for (size_t n = static_cast<size_t>(start); n < p.size(); ++n)
    p[n] = normal(rng) * std::pow(10.0, -3.0 * static_cast<double>(n - start) / kFs / t_s);
  return p;
}

TEST(FilterLimit, EveryDecayFigureOfADiracIsFlagged) {
  const core::Bands bands = core::Bands::octave();
  std::vector<double> p(static_cast<size_t>(3 * kFs), 0.0);
  p[static_cast<size_t>(0.1 * kFs)] = 1.0;
  const auto m = metricsFromSignal(p, kFs, bands);
  int figures = 0;
  for (int b = 0; b < bands.size(); ++b) {
    SCOPED_TRACE(bands.label(b));
    for (auto [value, flag] : {std::pair{m[b].edt, m[b].edt_filter_limited}, std::pair{m[b].t20, m[b].t20_filter_limited},
                               std::pair{m[b].t30, m[b].t30_filter_limited}}) {
      if (!std::isfinite(value)) continue;
      ++figures;
      EXPECT_TRUE(flag) << value;
    }
  }
  EXPECT_GE(figures, 20);  // the Dirac's 81–123 dB ranges make nearly every figure measurable
  const std::string table = metricsTable(bands, m);
  const std::string row63 = table.substr(table.find("\n     63"), 60);
  EXPECT_EQ(std::count(row63.begin(), row63.end(), '*'), 3) << table;  // T20, T30 and EDT marked
  EXPECT_TRUE(metricsJson(bands, m)["63"].contains("filter_limited"));
}

TEST(FilterLimit, ALongDecayIsNotFlagged) {
  // T = 3 s: the flag thresholds are 1.33 s (63 Hz EDT) and below, and these figures scatter by ~10 %.
  const core::Bands bands = core::Bands::octave();
  const auto m = metricsFromSignal(decayingNoise(3.0, 1), kFs, bands);
  for (int b = 0; b < bands.size(); ++b) {
    SCOPED_TRACE(bands.label(b));
    EXPECT_FALSE(m[b].edt_filter_limited || m[b].t20_filter_limited || m[b].t30_filter_limited);
    EXPECT_FALSE(metricsJson(bands, m)[bands.label(b)].contains("filter_limited"));
  }
}

TEST(FilterLimit, TheModelFallsWithTAndRejectsANonPositiveT) {
  const core::Bands bands = core::Bands::octave();
  const BandFilter filter(bands, kFs);
  const FilterLimit limit(filter);
  double previous = INFINITY;
  for (double t : {0.05, 0.1, 0.2, 0.4, 0.8, 1.6, 3.2}) {
    const double bias = limit.relativeBias(0, DecayFigure::Edt, t);
    EXPECT_LT(bias, previous) << t;
    EXPECT_GT(bias, -0.01) << t;  // a filter lengthens decays
    previous = bias;
  }
  EXPECT_LT(previous, 0.02);  // 3.2 s at 63 Hz: within 2 %
  EXPECT_THROW(limit.relativeBias(0, DecayFigure::T20, 0.0), core::InputError);
  EXPECT_FALSE(limit.limited(0, DecayFigure::T20, NAN));
}

// The model against measurement: the mean EDT error of decaying noise over 24 seeds, for decays short
// enough that the filter matters (125 Hz at 0.2 s, 250 Hz at 0.1 s) and one where it does not (1 kHz at
// 0.5 s). Tolerance: 3 standard errors of that mean (the seeds' own scatter, 25–40 % at low bands).
TEST(StatFilterLimit, TheModelPredictsTheMeasuredBiasOfShortDecays) {
  const core::Bands bands = core::Bands::octave();
  const BandFilter filter(bands, kFs);
  const FilterLimit limit(filter);
  struct Case {
    int band;
    double t_s;
  };
  for (const Case c : {Case{1, 0.2}, Case{2, 0.1}, Case{4, 0.5}}) {
    SCOPED_TRACE(bands.label(c.band));
    const int seeds = 24;
    double sum = 0.0, sum_sq = 0.0;
    for (int s = 0; s < seeds; ++s) {
      const double e = metricsFromSignal(decayingNoise(c.t_s, 100 + s), kFs, bands)[c.band].edt / c.t_s - 1.0;
      sum += e;
      sum_sq += e * e;
    }
    const double mean = sum / seeds;
    const double se = std::sqrt((sum_sq / seeds - mean * mean) / (seeds - 1));
    const double model = limit.relativeBias(c.band, DecayFigure::Edt, c.t_s);
    EXPECT_NEAR(mean, model, 3.0 * se) << "model " << model;
    // Where the model flags, the measured bias is beyond the tolerance too, by more than its noise.
    if (model > FilterLimit::kTolerance) {
      EXPECT_GT(mean - 3.0 * se, FilterLimit::kTolerance);
    }
  }
}

}  // namespace
}  // namespace diffray::ir
