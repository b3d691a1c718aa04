// ISO 3382-1 metrics against closed forms of an exponential decay p² ∝ e^{−kt}, k = 6·ln10/T:
// E(t) = e^{−kt}/k, so C_te = 10·log10(e^{k·te} − 1), D50 = 1 − e^{−0.05k}, Ts = 1/k, T20 = T30 = EDT = T;
// and those closed forms evaluated by hand to 4–5 digits. Plus the noise-floor truncation on a decay in white noise.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "diffray/core/bands.h"
#include "diffray/core/error.h"
#include "diffray/ir/band_filter.h"
#include "diffray/ir/metrics.h"

namespace diffray::ir {
namespace {

double rate(double t60_s) { return 6.0 * std::log(10.0) / t60_s; }

/// Exact bin integrals of e^{−k(t − t0)} for t ≥ t0 (zero before), bins of width bin_s.
std::vector<double> exponentialHistogram(double t60_s, double bin_s, double length_s, double t0_s = 0.0) {
  const double k = rate(t60_s);
  std::vector<double> e(static_cast<size_t>(std::lround(length_s / bin_s)), 0.0);
  for (size_t i = 0; i < e.size(); ++i) {
    const double a = std::max(static_cast<double>(i) * bin_s, t0_s), b = static_cast<double>(i + 1) * bin_s;
    if (b > t0_s) e[i] = (std::exp(-k * (a - t0_s)) - std::exp(-k * (b - t0_s))) / k;
  }
  return e;
}

double clarityDb(double t60_s, double te_s) { return 10.0 * std::log10(std::exp(rate(t60_s) * te_s) - 1.0); }

TEST(IrMetrics, ExponentialDecayMatchesClosedFormsAndHandValues) {
  for (double t60 : {1.0, 0.5}) {
    SCOPED_TRACE(t60);
    // 1 ms bins: 50 and 80 ms fall on bin edges, where the uniform-in-bin model is exact. Length 2T + 0.5 s
    // (−120 dB and more): the truncated tail is below double precision of the sums.
    const BandMetrics m = metricsFromEnergy(exponentialHistogram(t60, 1e-3, 2 * t60 + 0.5), 1e-3);
    EXPECT_NEAR(m.t20, t60, 1e-6 * t60);
    EXPECT_NEAR(m.t30, t60, 1e-6 * t60);
    EXPECT_NEAR(m.edt, t60, 1e-6 * t60);
    EXPECT_NEAR(m.c50, clarityDb(t60, 0.05), 1e-6);
    EXPECT_NEAR(m.c80, clarityDb(t60, 0.08), 1e-6);
    EXPECT_NEAR(m.d50, 1.0 - std::exp(-0.05 * rate(t60)), 1e-9);
    // Ts with energy uniform inside each bin: the centroid of e^{−kt} over a bin lies k·Δ²/12 before the
    // bin's middle, a relative error of (kΔ)²/12 (1.6e-5 for T = 1 s, 6.4e-5 for 0.5 s) to leading order.
    const double k_bin = rate(t60) * 1e-3;
    EXPECT_NEAR(m.ts, 1.0 / rate(t60), 1.2 * k_bin * k_bin / 12.0 / rate(t60));
    // The record ends while it decays, and Lundeby's first noise estimate is the mean power of its last 10 %
    // (Δ): the decay line e^{−kt} meets it at t_c = t_end − Δ + ln(kΔ/(1 − e^{−kΔ}))/k, where the integral
    // stops. The range is the exact curve's depth there, 60·t_c/T dB, to within the bin t_c falls in.
    const double t_end = 2 * t60 + 0.5, delta = 0.1 * t_end, k = rate(t60);
    const double t_c = t_end - delta + std::log(k * delta / (1.0 - std::exp(-k * delta))) / k;
    EXPECT_NEAR(m.decay_range_db, 60.0 * t_c / t60, 60.0 * 1e-3 / t60);
  }
  // The closed forms evaluated by hand, to the digits quoted (±half a unit in the last place).
  const BandMetrics one = metricsFromEnergy(exponentialHistogram(1.0, 1e-3, 2.5), 1e-3);
  EXPECT_NEAR(one.c80, 3.0534, 0.5e-4);
  EXPECT_NEAR(one.c50, -0.0206, 0.5e-4);
  EXPECT_NEAR(one.d50, 0.49881, 0.5e-5);
  EXPECT_NEAR(one.ts, 0.07238, 0.5e-5);
  const BandMetrics half = metricsFromEnergy(exponentialHistogram(0.5, 1e-3, 1.5), 1e-3);
  EXPECT_NEAR(half.c80, 9.0956, 0.5e-4);
  EXPECT_NEAR(half.d50, 0.74881, 0.5e-5);
}

TEST(IrMetrics, OnsetIgnoresLeadingSilenceAndLowPreArrivalEnergy) {
  // The decay starts at 37 ms; a −30 dB blip at 5 ms lies below the −20 dB onset threshold.
  std::vector<double> e = exponentialHistogram(1.0, 1e-3, 2.5, 0.037);
  const double peak = e[37];
  e[5] = peak * 1e-3;
  const BandMetrics m = metricsFromEnergy(e, 1e-3);
  EXPECT_NEAR(m.c80, clarityDb(1.0, 0.08), 1e-6);
  EXPECT_NEAR(m.ts, 1.0 / rate(1.0), 3e-5 / rate(1.0));
  EXPECT_NEAR(m.t30, 1.0, 1e-6);
  EXPECT_EQ(onsetBin(e), 37);
}

TEST(IrMetrics, ShortDecayLeavesT30Unmeasured) {
  // A histogram that stops 30 dB down: the decay line meets the end before −35 dB, so T30 is NaN, while
  // T20 and EDT are still measured (the cut is compensated by the decay's exponential continuation).
  const BandMetrics m = metricsFromEnergy(exponentialHistogram(1.0, 1e-3, 0.5), 1e-3);
  EXPECT_TRUE(std::isnan(m.t30));
  EXPECT_LT(m.decay_range_db, 35.0);
  EXPECT_NEAR(m.t20, 1.0, 0.01);
  EXPECT_NEAR(m.edt, 1.0, 0.01);
}

TEST(IrMetrics, ARecordEndingWithinFiftyMillisecondsGivesNoEnergyRatios) {
  // 10 ms of a 1 s decay (`ir --length 0.01`): nothing after 50 ms to compare with, so D50, C50, C80 and Ts
  // are not given (D50 read 1 and Ts the record's own centre, 0.5 ms). 300 ms of it: D50 and Ts are.
  const BandMetrics short_record = metricsFromEnergy(exponentialHistogram(1.0, 1e-3, 0.010), 1e-3);
  EXPECT_TRUE(std::isnan(short_record.d50));
  EXPECT_TRUE(std::isnan(short_record.ts));
  EXPECT_TRUE(std::isnan(short_record.c50));
  EXPECT_TRUE(std::isnan(short_record.c80));
  const BandMetrics longer = metricsFromEnergy(exponentialHistogram(1.0, 1e-3, 0.300), 1e-3);
  EXPECT_TRUE(std::isfinite(longer.d50));
  EXPECT_TRUE(std::isfinite(longer.ts));
}

// Noise decays (T = 2 s) cut after 1 s, 30 dB down, with no noise floor: in some bands the decay line
// meets the last 10 %'s level only past the end, and the Schroeder curve used to plunge at the cut, so that
// the decay range read 69–99 dB and T30 was reported 11–18 % short. Now the integral is continued past the
// end (Lundeby's continuation): no band claims more range than the 30 dB it holds (+5 dB for the noise's
// fluctuation), T30 is not measurable, and T20 is unbiased: over 8 seeds its mean lies within 4 standard
// errors (from the seeds' own scatter) of T in every band from 500 Hz up.
TEST(StatIrMetrics, NoiseDecayCutShortClaimsNoMoreRangeThanItHolds) {
  const double fs = 48000.0, t60 = 2.0;
  const core::Bands bands = core::Bands::octave();
  const int seeds = 8;
  std::vector<double> sum(static_cast<std::size_t>(bands.size()), 0.0), sum_sq(sum.size(), 0.0);
  for (int seed = 1; seed <= seeds; ++seed) {
    std::mt19937_64 gen(static_cast<std::uint64_t>(seed));
    std::normal_distribution<double> g(0.0, 1.0);
    std::vector<double> p(48000);
    for (std::size_t n = 0; n < p.size(); ++n)
      p[n] = 0.1 * g(gen) * std::pow(10.0, -3.0 * (static_cast<double>(n) / fs) / t60);
    const std::vector<BandMetrics> m = metricsFromSignal(p, fs, bands);
    for (int b = 0; b < bands.size(); ++b) {
      SCOPED_TRACE(bands.label(b));
      EXPECT_LE(m[b].decay_range_db, 35.0);
      EXPECT_TRUE(std::isnan(m[b].t30));
      sum[b] += m[b].t20;
      sum_sq[b] += m[b].t20 * m[b].t20;
    }
  }
  for (int b = bands.find(500); b < bands.size(); ++b) {
    const double mean = sum[b] / seeds, sd = std::sqrt((sum_sq[b] - seeds * mean * mean) / (seeds - 1));
    EXPECT_NEAR(mean, t60, 4.0 * sd / std::sqrt(static_cast<double>(seeds))) << bands.label(b);
  }
}

TEST(IrMetrics, NothingMeasurableInSilenceOrFlatNoise) {
  const BandMetrics zero = metricsFromEnergy(std::vector<double>(100, 0.0), 1e-3);
  EXPECT_TRUE(std::isnan(zero.t30) && std::isnan(zero.c80) && std::isnan(zero.ts));
  std::mt19937_64 rng(3);
  std::normal_distribution<double> normal;
  std::vector<double> noise(8000);
  for (double& v : noise) v = std::pow(normal(rng), 2);
  const BandMetrics flat = metricsFromEnergy(noise, 1.0 / 8000);
  EXPECT_TRUE(std::isnan(flat.t20));
  EXPECT_TRUE(std::isnan(flat.t30));
}

TEST(IrMetrics, BadInputIsRefused) {
  EXPECT_THROW(metricsFromEnergy({1.0, 0.5}, 0.0), core::InputError);
  EXPECT_THROW(metricsFromEnergy({1.0, NAN}, 1e-3), core::InputError);
  EXPECT_THROW(metricsFromSignal({1.0, INFINITY}, 48000, core::Bands::octave()), core::InputError);
}

// A measured-looking response: white noise under an exponential envelope (T = 1 s) plus a white noise
// floor 60 dB below the start, sampled at 8 kHz. Without truncation the floor's energy (2 s at −60 dB,
// i.e. −44 dB of the decay's total) lifts the Schroeder curve by ~1 dB at −35 dB and T30 by ~10 %.
// Lundeby's truncation must bring T30 and T20 back to T within 3 % (a missing truncation is ~10 % off).
// Honest note: the three fixed seeds give T20 = 0.989, 1.008, 1.015 and T30 = 0.997, 1.025, 1.000 s, so
// the scatter (~1.5 %, more than white noise alone would give: the truncation point and the
// compensation move with the noise) uses much of the 3 %.
TEST(StatIrMetrics, NoiseFloorIsTruncated) {
  const double fs = 8000.0, t60 = 1.0, floor_power = 1e-6;
  for (std::uint64_t seed : {1u, 2u, 3u}) {
    SCOPED_TRACE(seed);
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> normal;
    std::vector<double> e(static_cast<size_t>(3.0 * fs));
    for (size_t n = 0; n < e.size(); ++n) {
      const double t = static_cast<double>(n) / fs;
      const double p = std::exp(-0.5 * rate(t60) * t) * normal(rng) + std::sqrt(floor_power) * normal(rng);
      e[n] = p * p;
    }
    const BandMetrics m = metricsFromEnergy(e, 1.0 / fs);
    EXPECT_NEAR(m.t30, t60, 0.03 * t60);
    EXPECT_NEAR(m.t20, t60, 0.03 * t60);
    // The decay meets the floor at 60 dB / (60 dB/s) = 1 s.
    EXPECT_NEAR(m.truncation_s, 1.0, 0.15);
    EXPECT_GT(m.decay_range_db, 45.0);
    EXPECT_LT(m.decay_range_db, 70.0);
  }
}

/// White noise under an exponential envelope (T = t60_s) from sample `delay`, fixed seed.
std::vector<double> noiseDecay(double fs, double t60_s, double length_s, long delay, std::uint64_t seed) {
  std::mt19937_64 gen(seed);
  std::normal_distribution<double> g(0.0, 1.0);
  std::vector<double> p(static_cast<size_t>(delay) + static_cast<size_t>(length_s * fs), 0.0);
  for (size_t n = static_cast<size_t>(delay); n < p.size(); ++n)
    p[n] = g(gen) * std::exp(-0.5 * rate(t60_s) * static_cast<double>(n - static_cast<size_t>(delay)) / fs);
  return p;
}

// Every metric is measured from the onset, so a pre-delay must not change it: the same samples starting
// at sample 0 and after 100 ms of silence give the same figures in every band, within a twentieth of
// ISO 3382-1's JNDs (C 0.05 dB, D50 0.0025, Ts 0.5 ms, EDT/T20 0.25 %; the two lengths get different FFT
// grids, so not to rounding). Before the signal was padded in front, the bands' zero-phase filters lost
// the half of their response before sample 0: C50 at 63 Hz read 0.3–1.4 dB low.
TEST(IrMetrics, APreDelayChangesNothing) {
  const double fs = 48000.0;
  const core::Bands bands = core::Bands::octave();
  const std::vector<double> now = noiseDecay(fs, 0.5, 1.5, 0, 11), later = noiseDecay(fs, 0.5, 1.5, 4800, 11);
  const std::vector<BandMetrics> a = metricsFromSignal(now, fs, bands), b = metricsFromSignal(later, fs, bands);
  for (int k = 0; k < bands.size(); ++k) {
    SCOPED_TRACE(bands.label(k));
    std::printf("  %5s Hz: C50 %+.5f dB, C80 %+.5f dB, D50 %+.6f, Ts %+.4f ms, EDT %+.4f %%, T20 %+.4f %%\n",
                bands.label(k).c_str(), a[k].c50 - b[k].c50, a[k].c80 - b[k].c80, a[k].d50 - b[k].d50,
                1e3 * (a[k].ts - b[k].ts), 100 * (a[k].edt / b[k].edt - 1), 100 * (a[k].t20 / b[k].t20 - 1));
    EXPECT_NEAR(a[k].c50, b[k].c50, 0.05);
    EXPECT_NEAR(a[k].c80, b[k].c80, 0.05);
    EXPECT_NEAR(a[k].d50, b[k].d50, 0.0025);
    EXPECT_NEAR(a[k].ts, b[k].ts, 0.0005);
    EXPECT_NEAR(a[k].edt, b[k].edt, 0.0025 * b[k].edt);
    EXPECT_NEAR(a[k].t20, b[k].t20, 0.0025 * b[k].t20);
  }
}

// ISO 3382-1 §5.3.3: an evaluation range ends at least 10 dB above the noise. A decay (T = 1 s) into a
// white noise floor 30 dB below its start gives ~30 dB of decay: EDT (needs 20 dB) is measured and near T,
// T20 (35 dB) and T30 (45 dB) are not. Without the margin T20 was fitted down into the noise.
TEST(IrMetrics, EvaluationRangesStopTenDecibelsAboveTheNoise) {
  const double fs = 8000.0, t60 = 1.0;
  std::mt19937_64 rng(5);
  std::normal_distribution<double> normal;
  std::vector<double> e(static_cast<size_t>(3.0 * fs));
  for (size_t n = 0; n < e.size(); ++n) {
    const double p = std::exp(-0.5 * rate(t60) * static_cast<double>(n) / fs) * normal(rng) + 0.0316 * normal(rng);
    e[n] = p * p;
  }
  const BandMetrics m = metricsFromEnergy(e, 1.0 / fs);
  EXPECT_GT(m.decay_range_db, 25.0);
  EXPECT_LT(m.decay_range_db, 35.0);
  EXPECT_NEAR(m.edt, t60, 0.15 * t60);
  EXPECT_TRUE(std::isnan(m.t20)) << m.t20;
  EXPECT_TRUE(std::isnan(m.t30)) << m.t30;
  EXPECT_FALSE(std::isnan(m.c50));
  // A floor only 6 dB below the start: C50, C80, D50 and Ts would measure the noise, and are not given.
  std::mt19937_64 rng2(6);
  for (size_t n = 0; n < e.size(); ++n) {
    const double p = std::exp(-0.5 * rate(t60) * static_cast<double>(n) / fs) * normal(rng2) + 0.5 * normal(rng2);
    e[n] = p * p;
  }
  const BandMetrics noisy = metricsFromEnergy(e, 1.0 / fs);
  EXPECT_LT(noisy.decay_range_db, 10.0);
  EXPECT_TRUE(std::isnan(noisy.c50) && std::isnan(noisy.c80) && std::isnan(noisy.d50) && std::isnan(noisy.ts))
      << noisy.c50 << " " << noisy.d50 << " " << noisy.ts;
}

// A DC offset (0.5 % of the first sample's level, −46 dB) is removed before filtering: the decay range and
// T30 of every band from 125 Hz up are those of the response without it (within 0.5 dB and 1 %). Without
// the removal the zero padding turned it into steps whose low-frequency energy read as a noise floor (the
// 63 Hz range fell from 88 to 56 dB).
TEST(IrMetrics, ADcOffsetIsRemoved) {
  const double fs = 48000.0;
  const core::Bands bands = core::Bands::octave();
  const std::vector<double> clean = noiseDecay(fs, 0.5, 1.5, 2400, 12);
  std::vector<double> offset = clean;
  for (double& v : offset) v += 0.005;
  const std::vector<BandMetrics> a = metricsFromSignal(clean, fs, bands), b = metricsFromSignal(offset, fs, bands);
  for (int k = 0; k < bands.size(); ++k) {
    SCOPED_TRACE(bands.label(k));
    EXPECT_NEAR(b[k].decay_range_db, a[k].decay_range_db, 0.5);
    if (bands.nominalHz(k) >= 125) {
      EXPECT_NEAR(b[k].t30, a[k].t30, 0.01 * a[k].t30);
    }
  }
}

TEST(IrMetrics, JsonAndTableShowMissingFiguresAsNullAndDash) {
  const core::Bands bands = core::Bands::octave(1000, 2000);
  BandMetrics a = metricsFromEnergy(exponentialHistogram(1.0, 1e-3, 2.5), 1e-3);
  BandMetrics b;  // all NaN
  const nlohmann::ordered_json j = metricsJson(bands, {a, b});
  // Keys in band order, not sorted as strings (where "1000" < "125" would show).
  const core::Bands octaves = core::Bands::octave();
  const nlohmann::ordered_json all = metricsJson(octaves, std::vector<BandMetrics>(static_cast<size_t>(octaves.size())));
  std::vector<std::string> keys;
  for (const auto& item : all.items()) keys.push_back(item.key());
  EXPECT_EQ(keys, (std::vector<std::string>{"63", "125", "250", "500", "1000", "2000", "4000", "8000"}));
  EXPECT_NEAR(j["1000"]["c80"].get<double>(), clarityDb(1.0, 0.08), 1e-6);
  EXPECT_TRUE(j["2000"]["t30"].is_null());
  for (const char* key : {"t20", "t30", "edt", "c50", "c80", "d50", "ts"}) EXPECT_TRUE(j["1000"].contains(key));
  const std::string table = metricsTable(bands, {a, b});
  EXPECT_NE(table.find("   3.05"), std::string::npos);
  EXPECT_NE(table.find("      -"), std::string::npos);
  EXPECT_NE(table.find("not measurable"), std::string::npos);
}

// A band whose analysis filter rings longer than the response lasts after its onset is not measured: its
// band signal is the filter's own response cut off at the file's end. A 21-sample click read a negative
// decay range at 63 Hz, a negative Ts at 125 Hz and an EDT of 0.25 s before. A decay 0.25 s long is
// measured in the bands whose filters ring for less (BandFilter::ringSamples(b): 0.19 s at 125 Hz, 0.15 s
// above) and not at 63 Hz (0.39 s).
TEST(IrMetrics, NoBandIsMeasuredFromLessThanItsFilterRings) {
  const double fs = 48000.0;
  const core::Bands bands = core::Bands::octave();
  std::vector<double> click(21, 0.0);
  click[3] = 1.0;
  for (const BandMetrics& m : metricsFromSignal(click, fs, bands)) {
    EXPECT_TRUE(m.shorter_than_filter);
    EXPECT_TRUE(std::isnan(m.decay_range_db) && std::isnan(m.ts) && std::isnan(m.edt) && std::isnan(m.d50));
  }
  const std::vector<double> decay = noiseDecay(fs, 0.1, 0.25, 0, 3);
  const std::vector<BandMetrics> m = metricsFromSignal(decay, fs, bands);
  const BandFilter filter(bands, fs);
  for (int b = 0; b < bands.size(); ++b) {
    SCOPED_TRACE(bands.label(b));
    const bool long_enough = filter.ringSamples(b) <= static_cast<long>(decay.size());
    EXPECT_EQ(m[b].shorter_than_filter, !long_enough);
    EXPECT_EQ(std::isfinite(m[b].decay_range_db), long_enough);
  }
  EXPECT_FALSE(m[bands.size() - 1].shorter_than_filter);  // the top band is measured
  EXPECT_TRUE(m[0].shorter_than_filter);                   // the 63 Hz band (0.39 s) is not
  EXPECT_EQ(filter.ringSamples(), filter.ringSamples(0));  // the longest ringing is the lowest band's
  EXPECT_NE(metricsTable(bands, m).find("short: the file ends"), std::string::npos);
  EXPECT_EQ(metricsJson(bands, m)["63"]["shorter_than_filter"], true);
  EXPECT_FALSE(metricsJson(bands, m)["1000"].contains("shorter_than_filter"));
}

}  // namespace
}  // namespace diffray::ir
