// Spatial figures (ir/spatial_metrics.h) against closed forms:
// - J_LF and J_LFC of a direct sound from the front and one reflection of amplitude a from azimuth φ in the
//   horizontal plane, 40 ms later: the AmbiX channels are W = δ(t) + a·δ(t − 40 ms), Y = a·sin φ·δ(t − 40 ms)
//   (SN3D: Y = sin φ·cos θ), so J_LF = a²sin²φ/(1 + a²) and J_LFC = a²|sin φ|/(1 + a²) in every band;
// - IACC of identical ears = 1; of one ear delayed by 0.5 ms (inside the ±1 ms lags) near 1; of independent
//   noises near 0, within a bound from the number of independent samples in the window;
// - one window's IACC (windowIacc) against the definition summed lag by lag, with windows that touch either
//   end of the record, so that lags reach past it.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <vector>

#include "diffray/core/bands.h"
#include "diffray/core/error.h"
#include "diffray/ir/spatial_metrics.h"

namespace {

namespace ir = diffray::ir;
using diffray::core::Bands;
constexpr double kPi = 3.14159265358979323846;
constexpr double kFs = 48000.0;

TEST(IrSpatialMetrics, LateralFractionOfOneReflectionMatchesItsClosedForm) {
  // 250 Hz – 4 kHz octaves: the band filters' 40 Hz crossovers spread an arrival over about ±25 ms, and the
  // reflection lies 35 ms from the 5 ms and 40 ms from the 80 ms window edges, so the closed form holds to
  // a small fraction of the figure; 0.01 is a fifth of J_LF's JND (0.05, ISO 3382-1 Table A.1).
  const Bands bands = Bands::octave(250.0, 4000.0);
  const double a = 0.5;
  for (double phi_deg : {90.0, 30.0, -60.0}) {
    const double s = std::sin(phi_deg * kPi / 180.0);
    std::vector<double> w(48000, 0.0), y(48000, 0.0);
    const std::size_t t0 = 4800, t1 = t0 + 1920;  // 100 ms of silence, then 40 ms
    w[t0] = 1.0;
    w[t1] = a;
    y[t1] = a * s;
    const auto m = ir::lateralFractions(w, y, kFs, bands);
    for (int b = 0; b < bands.size(); ++b) {
      EXPECT_NEAR(m[static_cast<std::size_t>(b)].jlf, a * a * s * s / (1.0 + a * a), 0.01) << phi_deg << " " << bands.label(b);
      EXPECT_NEAR(m[static_cast<std::size_t>(b)].jlfc, a * a * std::abs(s) / (1.0 + a * a), 0.01) << phi_deg << " " << bands.label(b);
    }
  }
}

TEST(IrSpatialMetrics, LateLateralLevelOfAToneBurstMatchesItsEnergy) {
  // Y holds, 200 ms after the onset (well past 80 ms), a 1 kHz tone burst of amplitude A and 0.4 s with
  // raised-cosine edges of 20 ms: its energy Σy² = A²/2·(0.38 s)·fs within the 1 kHz octave (its spectrum is
  // ~10 Hz wide), so L_J(1 kHz) = 10·lg(Σy² / E_10). The other octaves hold none of it: no L_J there
  // (−∞ dB is not a figure) or one far below. Tolerance 0.05 dB: the burst's edges and its sidelobes outside
  // the octave, both below 1e-3 of its energy.
  const Bands bands = Bands::octave(250.0, 4000.0);
  std::vector<double> w(96000, 0.0), y(96000, 0.0);
  const std::size_t t0 = 4800;
  w[t0] = 1.0;
  const double amp = 0.1, edge = 0.02, len = 0.4;
  double energy = 0.0;
  for (std::size_t i = 0; i < static_cast<std::size_t>(len * kFs); ++i) {
    const double t = static_cast<double>(i) / kFs;
    double g = 1.0;
    if (t < edge) g = 0.5 * (1.0 - std::cos(kPi * t / edge));
    if (t > len - edge) g = 0.5 * (1.0 - std::cos(kPi * (len - t) / edge));
    y[t0 + 9600 + i] = amp * g * std::sin(2.0 * kPi * 1000.0 * t);
    energy += y[t0 + 9600 + i] * y[t0 + 9600 + i];
  }
  const double ref = 1e-4;  // a 1 W source's free field at 10 m: 1/100 m² per band, here scaled
  const auto m = ir::lateralFractions(w, y, kFs, bands, ref);
  EXPECT_NEAR(m[2].lj_db, 10.0 * std::log10(energy / ref), 0.05);
  EXPECT_LT(m[0].lj_db, m[2].lj_db - 30.0);
  // Without a reference there is no L_J.
  EXPECT_TRUE(std::isnan(ir::lateralFractions(w, y, kFs, bands)[2].lj_db));
}

TEST(IrSpatialMetrics, NoLateralEnergyWithoutLateralSound) {
  // A reflection from straight behind (φ = 180°) reaches Y with gain sin 180° = 0.
  const Bands bands = Bands::octave(250.0, 4000.0);
  std::vector<double> w(48000, 0.0), y(48000, 0.0);
  w[4800] = 1.0;
  w[6720] = 0.7;
  const auto m = ir::lateralFractions(w, y, kFs, bands);
  for (const auto& band : m) EXPECT_EQ(band.jlf, 0.0);
}

// A decaying noise response (reverberation time t60_s) starting at 100 ms.
std::vector<double> decayingNoise(unsigned seed, double t60_s = 0.6) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> g;
  std::vector<double> x(48000, 0.0);
  const double k = 6.9 / t60_s;
  for (std::size_t n = 4800; n < x.size(); ++n) x[n] = g(rng) * std::exp(-k * (static_cast<double>(n) - 4800.0) / kFs);
  return x;
}

TEST(IrSpatialMetrics, IaccOfIdenticalEarsIsOne) {
  const Bands bands = Bands::octave(125.0, 4000.0);
  const std::vector<double> x = decayingNoise(7);
  const auto m = ir::interauralCrossCorrelation(x, x, kFs, bands);
  for (const auto& band : m) {
    EXPECT_NEAR(band.iacc_e, 1.0, 1e-9);
    EXPECT_NEAR(band.iacc_l, 1.0, 1e-9);
  }
}

TEST(IrSpatialMetrics, IaccOfADelayedEarAndOfIndependentEars) {
  const Bands bands = Bands::octave(1000.0, 4000.0);
  const std::vector<double> l = decayingNoise(11);
  // Delayed by 24 samples (0.5 ms): the lag τ = 0.5 ms lines the ears up; only the windows' edges differ
  // (the energy within 0.5 ms of them, a fraction ~1e-2 of the early window's at most).
  std::vector<double> r(l.size(), 0.0);
  for (std::size_t n = 24; n < l.size(); ++n) r[n] = l[n - 24];
  for (const auto& band : ir::interauralCrossCorrelation(l, r, kFs, bands)) {
    EXPECT_GT(band.iacc_e, 0.97);
    EXPECT_GT(band.iacc_l, 0.97);
  }
  // Independent ears: at one lag the normalised correlation of two independent noises of bandwidth B over
  // T seconds has a standard deviation about 1/√(2BT); the maximum over the ±1 ms lags (about 4B·1 ms
  // independent ones, 3 to 11 here) stays within 4σ. Nearly stationary noises (T60 = 20 s) so that the
  // late window's 0.67 s all count (a decay at rate k leaves an effective T of 1/k): B = 707, 1414,
  // 2828 Hz gives 4σ = 0.13, 0.092, 0.065.
  const std::vector<double> steady = decayingNoise(11, 20.0), other = decayingNoise(12, 20.0);
  const auto m = ir::interauralCrossCorrelation(steady, other, kFs, bands);
  for (int b = 0; b < bands.size(); ++b) {
    const double bw = bands.nominalHz(b) / std::sqrt(2.0);
    const double sigma = 1.0 / std::sqrt(2.0 * bw * 0.67);
    EXPECT_LT(m[static_cast<std::size_t>(b)].iacc_l, 4.0 * sigma) << bands.label(b);
  }
}

TEST(IrSpatialMetrics, WindowIaccIsTheLargestNormalisedCorrelationOverTheLags) {
  std::mt19937_64 rng(5);
  std::normal_distribution<double> g;
  std::vector<double> l(300), r(300);
  for (std::size_t i = 0; i < l.size(); ++i) l[i] = g(rng), r[i] = 0.5 * l[(i + 290) % 300] + g(rng);
  const long n = static_cast<long>(l.size());
  // Windows at the start, inside and at the end; lag ranges shorter, longer and not a multiple of eight.
  for (const auto& [from, to, max_lag] : {std::array<long, 3>{0, 120, 48}, {30, 250, 13}, {200, 300, 48}, {0, 300, 7},
                                          {290, 300, 20}, {5, 300, 0}}) {
    double el = 0.0, er = 0.0, best = 0.0;
    for (long i = from; i < to; ++i) el += l[i] * l[i], er += r[i] * r[i];
    for (long tau = -max_lag; tau <= max_lag; ++tau) {
      double c = 0.0;
      for (long i = from; i < to; ++i)
        if (i + tau >= 0 && i + tau < n) c += l[i] * r[i + tau];
      best = std::max(best, std::abs(c));
    }
    EXPECT_NEAR(ir::windowIacc(l, r, from, to, max_lag), best / std::sqrt(el * er), 1e-14) << from << " " << to << " " << max_lag;
  }
  EXPECT_TRUE(std::isnan(ir::windowIacc(std::vector<double>(10, 0.0), std::vector<double>(10, 1.0), 0, 10, 3)));
}

TEST(IrSpatialMetrics, RefusesMismatchedOrSilentInput) {
  const Bands bands = Bands::octave(250.0, 4000.0);
  std::vector<double> a(1000, 0.0), b(999, 0.0);
  EXPECT_THROW(ir::lateralFractions(a, b, kFs, bands), diffray::core::InputError);
  b.resize(1000);
  EXPECT_THROW(ir::interauralCrossCorrelation(a, b, kFs, bands), diffray::core::InputError);
  a[10] = NAN;
  EXPECT_THROW(ir::lateralFractions(a, b, kFs, bands), diffray::core::InputError);
}

}  // namespace
