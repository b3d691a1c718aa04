// The zero-phase band filter (perfect reconstruction, zero phase, selectivity) and IR synthesis (energy
// per bin, arrivals at exact fractional delays, Poisson rate, agreement of the synthesized IR's metrics
// with the histogram's). Oracles: Parseval, symmetry, closed-form rates, the histogram metrics.
#include <gtest/gtest.h>

#include <cmath>
#include <numeric>

#include "diffray/core/error.h"
#include "diffray/core/math.h"
#include "diffray/ir/band_filter.h"
#include "diffray/ir/metrics.h"
#include "diffray/ir/synthesis.h"

namespace diffray::ir {
namespace {

constexpr double kFs = 48000.0;

double energy(const std::vector<double>& x, size_t from, size_t to) {
  double s = 0.0;
  for (size_t n = from; n < to; ++n) s += x.at(n) * x.at(n);
  return s;
}
double energy(const std::vector<double>& x) { return energy(x, 0, x.size()); }
double energy(const std::vector<double>& x, size_t from) { return energy(x, from, x.size()); }

TEST(IrBandFilter, BandsSumBackToTheInputInsideTheCoveredRange) {
  const BandFilter filter(core::Bands::octave(), kFs);
  // Gaussian tone bursts (σ = 50 ms: spectral width ~3 Hz) well inside [coveredLow, coveredHigh].
  ASSERT_LT(filter.coveredLowHz(), 150.0);
  ASSERT_GT(filter.coveredHighHz(), 6000.0);
  std::vector<double> x(48000);
  for (size_t n = 0; n < x.size(); ++n) {
    const double t = static_cast<double>(n) / kFs - 0.5;
    const double envelope = std::exp(-0.5 * t * t / (0.05 * 0.05));
    x[n] = envelope * (std::sin(core::kTwoPi * 200 * t) + 0.5 * std::cos(core::kTwoPi * 1414 * t) +
                       0.25 * std::sin(core::kTwoPi * 5000 * t));
  }
  const auto bands = filter.split(x);
  double worst = 0.0;
  for (size_t n = 0; n < x.size(); ++n) {
    double sum = 0.0;
    for (const auto& b : bands) sum += b[n];
    worst = std::max(worst, std::abs(sum - x[n]));
  }
  EXPECT_LT(worst, 1e-9);
}

// The scene loader refuses a sample rate whose Nyquist frequency the top band's filter would reach, with its
// own copy of the crossover (room/scene_file.cpp, kTopCrossoverHalfWidthHz): for both default band sets it
// asks for more than 22480 Hz. The filter itself must agree, or a scene would load and then fail after
// tracing (or be refused while it would have worked).
TEST(IrBandFilter, TopBandNeedsTheRateTheSceneLoaderAsksFor) {
  for (const core::Bands& bands : {core::Bands::octave(), core::Bands::thirdOctave()}) {
    EXPECT_THROW(BandFilter(bands, 22480.0), core::InputError);
    EXPECT_NO_THROW(BandFilter(bands, 22481.0));
  }
}

TEST(IrBandFilter, ZeroPhaseAndSelective) {
  const BandFilter filter(core::Bands::octave(), kFs);
  // An impulse at n0: every band's response is symmetric about n0 and peaks there (no group delay).
  std::vector<double> x(24000, 0.0);
  const size_t n0 = 12000;
  x[n0] = 1.0;
  for (const auto& band : filter.split(x)) {
    double peak = 0.0;
    for (double v : band) peak = std::max(peak, std::abs(v));
    EXPECT_DOUBLE_EQ(std::abs(band[n0]), peak);
    for (size_t j = 1; j < 3000; ++j) EXPECT_NEAR(band[n0 + j], band[n0 - j], 1e-12 * peak);
  }
  // A 1 kHz tone (the band's flat middle) lands in the 1 kHz band whole: steady-state energy there equals
  // the input's, the other bands hold nothing (crossovers only span the outer quarters of each band).
  std::vector<double> tone(48000);
  for (size_t n = 0; n < tone.size(); ++n) tone[n] = std::sin(core::kTwoPi * 1000.0 * static_cast<double>(n) / kFs);
  const auto bands = filter.split(tone);
  const int k = core::Bands::octave().find(1000);
  EXPECT_NEAR(energy(bands[k], 12000, 36000) / energy(tone, 12000, 36000), 1.0, 1e-6);
  for (int b = 0; b < static_cast<int>(bands.size()); ++b) {
    if (b == k) continue;
    EXPECT_LT(energy(bands[b], 12000, 36000), 1e-9 * energy(tone, 12000, 36000));
  }
}

EnergyResponse exponentialResponse(double t60_s, double start_s, double scale, double length_s) {
  EnergyResponse r;
  r.bands = core::Bands::octave();
  r.bin_s = 1e-3;
  const double k = 6.0 * std::log(10.0) / t60_s;
  std::vector<double> h(static_cast<size_t>(std::lround(length_s / r.bin_s)), 0.0);
  for (size_t i = 0; i < h.size(); ++i) {
    const double a = std::max(static_cast<double>(i) * r.bin_s, start_s), b = static_cast<double>(i + 1) * r.bin_s;
    if (b > start_s) h[i] = scale * (std::exp(-k * (a - start_s)) - std::exp(-k * (b - start_s))) / k;
  }
  r.traced.assign(static_cast<size_t>(r.bands.size()), h);
  return r;
}

// Only the 4 kHz band holds energy (wider than 2 / bin_s, so it is matched bin by bin). The band part
// follows the histogram and stays inside the band's filter. Tolerances: 10 ms windows within 5 % (0.2 dB),
// well inside what T20/T30 tolerate (a 5 % JND is 0.9 dB over a 0.3 s fit of this 75 dB/s decay), and the
// total within 1 %. Out-of-band energy below 1e-4 (−40 dB): the gains act on the Diracs before the filter,
// so only the truncation of the filter's ringing at the signal's start and end can put energy outside
// (both ends lie far down: −60 dB of the ringing's ~1/(πBt) amplitude); gains applied after the filter
// (this code's first version) spread ±30 % steps per 1 ms bin into sidebands of ~−20 dB.
TEST(IrSynthesis, TracedEnergyFollowsTheHistogramAndStaysInItsBand) {
  EnergyResponse r = exponentialResponse(0.8, 0.02, 1.0, 1.0);
  const int k = r.bands.find(4000);
  for (int b = 0; b < r.bands.size(); ++b)
    if (b != k) std::fill(r.traced[b].begin(), r.traced[b].end(), 0.0);
  const std::vector<double> p = synthesize(r, kFs, 1.0, 200.0, 343.0, 7);
  const std::vector<double>& e = r.traced[k];
  for (int w = 2; w < 90; ++w) {  // 10 ms windows, 20 ms … 900 ms
    double want = 0.0;
    for (int i = 10 * w; i < 10 * (w + 1); ++i) want += e[i];
    EXPECT_NEAR(energy(p, static_cast<size_t>(480 * w), static_cast<size_t>(480 * (w + 1))) / want, 1.0, 0.05)
        << "window at " << 10 * w << " ms";
  }
  EXPECT_NEAR(energy(p) / std::accumulate(e.begin(), e.end(), 0.0), 1.0, 0.01);
  const BandFilter filter(r.bands, kFs);
  RealFft fft(fastFftLength(static_cast<long>(p.size())));
  std::vector<std::complex<double>> spectrum;
  fft.forward(p, spectrum);
  double outside = 0.0, all = 0.0;
  for (int j = 0; j < fft.bins(); ++j) {
    const double power = std::norm(spectrum[j]);
    all += power;
    if (filter.gain(k, j * kFs / fft.size()) == 0.0) outside += power;
  }
  EXPECT_LT(outside / all, 1e-4);
}

// A lone arrival (100 ms, well clear of time 0, where a band's zero-phase pulse would lose its first
// half) holds its energy in every band as an octave analysis of the response sees it (BandFilter::split,
// W_b of the sum of all bands' parts), for a flat, an alternating and a falling spectrum, within 0.5 %.
// Matching each band part's own energy left the 63 Hz band 7 % short (its lower crossover holds its part
// filtered twice) and bands beside a much weaker or stronger neighbour up to 16 % off.
TEST(IrSynthesis, ALoneArrivalHoldsItsEnergyInEveryOctave) {
  EnergyResponse r;
  r.bands = core::Bands::octave();
  r.traced.assign(static_cast<size_t>(r.bands.size()), std::vector<double>(300, 0.0));
  const double profiles[3][8] = {{1, 1, 1, 1, 1, 1, 1, 1}, {1, 0.1, 1, 0.1, 1, 0.1, 1, 0.1},
                                 {2, 1.5, 1, 0.7, 0.5, 0.3, 0.1, 0.02}};
  for (const auto& profile : profiles) {
    Arrival a;
    a.delay_s = 0.1;
    for (int b = 0; b < r.bands.size(); ++b) a.energy[b] = 1e-3 * profile[b];
    r.arrivals = {a};
    const std::vector<std::vector<double>> bands = BandFilter(r.bands, kFs).split(synthesize(r, kFs, 0.4, 210.0, 343.0, 1));
    for (int b = 0; b < r.bands.size(); ++b) EXPECT_NEAR(energy(bands[b]) / a.energy[b], 1.0, 0.005) << r.bands.label(b);
  }
}

// A decay that starts at once (at 100 ms, 1–8 kHz: bands wide enough to hold a 10 ms envelope) and an
// arrival before it (50 ms, in the 1 and 4 kHz bands, which do not overlap). The traced part is silent
// before its first bin: the zero-phase band filters would ring ahead of it otherwise (synthesis.h); what
// is left after the start still follows the histogram (10 ms within 5 %, as in the test above). The
// arrival's pulse is kept whole: its energy exactly, and half of it before its delay (a zero-phase pulse
// is symmetric about it).
TEST(IrSynthesis, TracedPartIsSilentBeforeItsFirstBinAndArrivalsStayWhole) {
  EnergyResponse r = exponentialResponse(0.5, 0.1, 1.0, 0.8);
  const int k1 = r.bands.find(1000), k4 = r.bands.find(4000);
  for (int b = 0; b < k1; ++b) std::fill(r.traced[b].begin(), r.traced[b].end(), 0.0);
  const std::vector<double> traced_only = synthesize(r, kFs, 0.8, 200.0, 343.0, 3);
  for (size_t n = 0; n < 4800; ++n) ASSERT_EQ(traced_only[n], 0.0) << "sample " << n;
  double want = 0.0;
  for (const auto& band : r.traced) want += std::accumulate(band.begin() + 100, band.begin() + 110, 0.0);
  EXPECT_NEAR(energy(traced_only, 4800, 5280) / want, 1.0, 0.05);
  Arrival a;
  a.delay_s = 0.05;
  a.energy[k1] = a.energy[k4] = 1e-3;
  r.arrivals.push_back(a);
  const std::vector<double> p = synthesize(r, kFs, 0.8, 200.0, 343.0, 3);
  EnergyResponse alone = r;  // the arrival without the decay
  for (auto& band : alone.traced) std::fill(band.begin(), band.end(), 0.0);
  const double pulse = energy(synthesize(alone, kFs, 0.8, 200.0, 343.0, 3));
  EXPECT_NEAR(pulse, 2e-3, 0.02 * 2e-3);  // its bands' energies (as analysed: see the next tests) and ~1 %
  EXPECT_NEAR(energy(p, 0, 4800), pulse, 1e-9);  // whole: the pulses' tails past 100 ms are far below this
  EXPECT_NEAR(energy(p, 0, 2400) + 0.5 * p[2400] * p[2400], 0.5 * pulse, 1e-9);
}

TEST(IrSynthesis, ArrivalAtAFractionalDelayKeepsItsEnergyAndTime) {
  EnergyResponse r;
  r.bands = core::Bands::octave();
  r.bin_s = 1e-3;
  Arrival a;
  a.delay_s = 0.2123456;  // 10192.5888 samples; far from both ends, so no filter tail is cut off
  // Bands 2, 4, 6 (250 Hz, 1 kHz, 4 kHz) do not overlap: an octave analysis finds each band's energy
  // (within 0.5 %, the amplitudes' Jacobi rounds and the FFT grids), and in the bands between only what
  // the crossovers leak: below 1 % of the two neighbours' energy (∫W_b²W_k² is ~0.3 % of ∫W_k² here).
  for (int b = 2; b < r.bands.size(); b += 2) a.energy[b] = 0.1 * (b + 1);
  r.arrivals.push_back(a);
  const std::vector<double> p = synthesize(r, kFs, 0.5, 200.0, 343.0, 1);
  const std::vector<std::vector<double>> analysed = BandFilter(r.bands, kFs).split(p);
  for (int b = 0; b < r.bands.size(); ++b) {
    if (a.energy[b] > 0.0) {
      EXPECT_NEAR(energy(analysed[b]) / a.energy[b], 1.0, 0.005) << r.bands.label(b);
    } else {
      const double beside = (b > 0 ? a.energy[b - 1] : 0.0) + (b + 1 < r.bands.size() ? a.energy[b + 1] : 0.0);
      EXPECT_LE(energy(analysed[b]), 0.01 * beside + 1e-12) << r.bands.label(b);  // 1e-12: FFT rounding
    }
  }
  // Energy centroid: p is band-limited below fs/4, so p² is band-limited below fs/2 and the sampled
  // centroid Σ n·p²/Σ p² equals the continuous one, τ·fs, for a zero-phase pulse symmetric about τ.
  double moment = 0.0;
  for (size_t n = 0; n < p.size(); ++n) moment += static_cast<double>(n) * p[n] * p[n];
  EXPECT_NEAR(moment / energy(p), a.delay_s * kFs, 1e-3);
  const auto peak = std::max_element(p.begin(), p.end(), [](double x, double y) { return std::abs(x) < std::abs(y); });
  EXPECT_NEAR(static_cast<double>(peak - p.begin()), a.delay_s * kFs, 0.5);
  // One band alone: its energy as analysed, whatever the delay.
  r.arrivals[0].energy = core::bandFill(0.0);
  r.arrivals[0].energy[5] = 0.25;
  r.arrivals[0].delay_s = 0.3000001;
  EXPECT_NEAR(energy(BandFilter(r.bands, kFs).split(synthesize(r, kFs, 0.5, 200.0, 343.0, 1))[5]), 0.25, 0.005 * 0.25);
}

TEST(IrSynthesis, ReproducibleForASeed) {
  const EnergyResponse r = exponentialResponse(0.5, 0.01, 1.0, 0.6);
  EXPECT_EQ(synthesize(r, kFs, 0.6, 200.0, 343.0, 5), synthesize(r, kFs, 0.6, 200.0, 343.0, 5));
  EXPECT_NE(synthesize(r, kFs, 0.6, 200.0, 343.0, 5), synthesize(r, kFs, 0.6, 200.0, 343.0, 6));
}

// The Dirac count against Λ(t) = ∫μ: 4πc³t³/(3V) below the cap, 10⁴ s⁻¹ above. Random signs make
// E[Σ d²] = the event count even when two events share a sample; Var(Σ d²) ≤ 3N. 5σ bounds.
TEST(StatIrSynthesis, PoissonRateFollowsTheImageSourceDensity) {
  const double c = 343.0, v = 200.0;
  const std::vector<double> d = poissonDiracs(static_cast<long>(1.5 * kFs), kFs, v, c, 11);
  const double a = 4.0 * core::kPi * c * c * c / v;
  const double early = a * std::pow(0.06, 3) / 3.0;  // [0, 60 ms], below the cap (reached at 62.8 ms)
  EXPECT_NEAR(energy(d, 0, static_cast<size_t>(0.06 * kFs)), early, 5.0 * std::sqrt(3.0 * early));
  const double late = 1e4 * 1.0;  // [0.5, 1.5 s]
  EXPECT_NEAR(energy(d, static_cast<size_t>(0.5 * kFs)), late, 5.0 * std::sqrt(3.0 * late));
}

// The metrics of the synthesized IR against those of the histogram it came from (metricsFromHistograms:
// the same onset rule), for an exponential decay (T = 1 s) behind a direct sound, 1 ms bins, 48 kHz,
// V = 200 m³, mean over 16 seeds. Targets: T20/T30/EDT 2 %, C50/C80 0.5 dB, D50 0.02, Ts 3 %.
// They hold for the mean from 1 kHz up (asserted); single realisations scatter about it (rms printed: at
// 1–8 kHz T20/T30 ≤ 0.9 %, EDT ≤ 1.8 %, C50/C80 0.2–0.45 dB, D50 ≤ 0.024, but Ts 3–6 %: a diffuse Dirac
// that falls within the direct sound's pulse interferes with it, which energy histograms cannot show;
// that is the price of a coherent signal). Below 1 kHz a band
// cannot hold the envelope's detail (bandwidth < 1/bin) and the direct sound interferes with the early
// diffuse field within the filter's ~1/B time resolution: there the figures are printed, not asserted
// (measured: tests/README.md, "Metrics from the histograms and from the WAV").
TEST(StatIrSynthesis, MetricsOfTheSynthesizedIrAgreeWithTheHistogram) {
  EnergyResponse r = exponentialResponse(1.0, 0.01, 6.0, 2.5);
  Arrival direct;
  direct.delay_s = 0.01;
  direct.energy = core::bandFill(1.0 / 9.0);  // 1 W at 3 m
  r.arrivals.push_back(direct);
  std::vector<std::vector<double>> total;
  for (int b = 0; b < r.bands.size(); ++b) total.push_back(r.total(b));
  const std::vector<BandMetrics> ref = metricsFromHistograms(total, r.bin_s);
  const int seeds = 16, nb = r.bands.size();
  std::vector<std::array<double, 7>> mean(static_cast<size_t>(nb), std::array<double, 7>{}), rms = mean;
  const std::array<double, 7> target{0.02, 0.02, 0.02, 0.5, 0.5, 0.02, 0.03};
  for (int s = 0; s < seeds; ++s) {
    const std::vector<BandMetrics> m = metricsFromSignal(synthesize(r, kFs, 2.5, 200.0, 343.0, 100 + s), kFs, r.bands);
    for (int b = 0; b < nb; ++b) {
      const std::array<double, 7> err{m[b].t20 / ref[b].t20 - 1, m[b].t30 / ref[b].t30 - 1, m[b].edt / ref[b].edt - 1,
                                      m[b].c50 - ref[b].c50,     m[b].c80 - ref[b].c80,     m[b].d50 - ref[b].d50,
                                      m[b].ts / ref[b].ts - 1};
      for (int q = 0; q < 7; ++q) {
        mean[b][q] += err[q] / seeds;
        rms[b][q] += err[q] * err[q] / seeds;
      }
    }
  }
  for (int b = 0; b < nb; ++b) {
    std::printf("  %5s Hz mean error: T20 %+.2f%% T30 %+.2f%% EDT %+.2f%% C50 %+.2f dB C80 %+.2f dB D50 %+.3f Ts %+.1f%%\n",
                r.bands.label(b).c_str(), 100 * mean[b][0], 100 * mean[b][1], 100 * mean[b][2], mean[b][3], mean[b][4],
                mean[b][5], 100 * mean[b][6]);
    std::printf("           rms error:  T20 %.2f%%  T30 %.2f%%  EDT %.2f%%  C50 %.2f dB  C80 %.2f dB  D50 %.3f  Ts %.1f%%\n",
                100 * std::sqrt(rms[b][0]), 100 * std::sqrt(rms[b][1]), 100 * std::sqrt(rms[b][2]), std::sqrt(rms[b][3]),
                std::sqrt(rms[b][4]), std::sqrt(rms[b][5]), 100 * std::sqrt(rms[b][6]));
    if (r.bands.nominalHz(b) < 1000) continue;
    for (int q = 0; q < 7; ++q) EXPECT_LE(std::abs(mean[b][q]), target[q]) << r.bands.label(b) << " #" << q;
  }
}

// A shoebox-like response: decay times falling from 2.5 s (63, 125 Hz) to 0.7 s (8 kHz), so that each
// band decays at its own rate beside neighbours decaying up to twice as slowly; a direct sound at 10 ms
// (1 W at 3 m), a floor reflection 2 ms behind it (within the low bands' time resolution), a mirror-
// symmetric pair of wall reflections at exactly the same delay, and later ones; the diffuse part starts
// 3 ms after the direct sound. Criterion: ISO 3382-1:2009 Annex A, Table A.1 just-noticeable differences
// (EDT, T20, T30 5 % relative; C50, C80 1 dB; D50 0.05; Ts 10 ms), between the metrics of the histogram
// (metricsFromHistograms) and of the synthesized IR (metricsFromSignal).
//  * The mean over 8 seeds, every band 125 Hz – 8 kHz: the synthesis must not be biased by a JND.
//  * Each single realisation, bands ≥ 1 kHz: there a noise decay's own scatter (ISO 3382-2:2008 A.2,
//    σ(T30)/T30 = 0.55·√((1 + 1.52/n)/(B·T30)) with n = 10 for an impulse response: 1.4 % at 1 kHz,
//    T = 1.8 s; σ(T20) = 0.88·√((1 + 1.90/n)/(B·T20)): 2.3 %) is under a third of the JND. Below, one
//    realisation scatters by a large part of a JND (T20 at 63 Hz: 8 %, at 250 Hz: 4 %), so a single IR
//    cannot promise it there; its bias (the mean) is asserted from 125 Hz. 63 Hz: not asserted (a 45 Hz
//    band rings for ~1/B = 22 ms, half the C50 window; printed).
//  * EDT is printed, not asserted: here the direct sound and the first reflections take ~5 of its 10 dB,
//    so its line is fitted to ~5 dB of diffuse decay (0.1 s at 2 kHz), and a slope fitted over a span D
//    scatters as D^(−3/2): (20/5)^(3/2) = 8 times the T20's, well beyond the 5 % JND.
EnergyResponse roomLikeResponse() {
  EnergyResponse r;
  r.bands = core::Bands::octave();
  r.bin_s = 1e-3;
  const double t60[8] = {2.5, 2.5, 2.4, 2.0, 1.8, 1.5, 1.1, 0.7};
  const double direct_s = 0.010, diffuse_s = 0.013, length_s = 3.0;
  const auto bins = static_cast<size_t>(std::lround(length_s / r.bin_s));
  for (int b = 0; b < r.bands.size(); ++b) {
    // Diffuse power at its start: that of a 210 m³ room's reverberant field, 4·W·T/(13.8·V)·c ≈ 0.5 J/m²/s·T.
    const double k = 6.0 * std::log(10.0) / t60[b], level = 0.5 * t60[b];
    std::vector<double> h(bins, 0.0);
    for (size_t i = 0; i < bins; ++i) {
      const double a = std::max(static_cast<double>(i) * r.bin_s, diffuse_s), e = static_cast<double>(i + 1) * r.bin_s;
      if (e > diffuse_s) h[i] = level * (std::exp(-k * (a - diffuse_s)) - std::exp(-k * (e - diffuse_s))) / k;
    }
    r.traced.push_back(h);
  }
  const auto arrival = [&](double delay_s, double energy, int order) {
    Arrival a;
    a.delay_s = delay_s;
    a.order = order;
    for (int b = 0; b < r.bands.size(); ++b) a.energy[b] = energy * (order == 0 ? 1.0 : 1.0 - 0.05 * b);
    r.arrivals.push_back(a);
  };
  arrival(direct_s, 1.0 / 9.0, 0);
  arrival(direct_s + 0.002, 0.07, 1);   // floor
  arrival(0.0191, 0.03, 1);             // the two side walls, same delay
  arrival(0.0191, 0.03, 1);
  arrival(0.0236, 0.025, 1);
  arrival(0.0311, 0.012, 2);
  arrival(0.0447, 0.008, 2);
  return r;
}

TEST(StatIrSynthesis, RoomLikeResponseAgreesWithinOneJnd) {
  const EnergyResponse r = roomLikeResponse();
  std::vector<std::vector<double>> total;
  for (int b = 0; b < r.bands.size(); ++b) total.push_back(r.total(b));
  const std::vector<BandMetrics> ref = metricsFromHistograms(total, r.bin_s);
  const std::array<double, 7> jnd{0.05, 0.05, 0.05, 1.0, 1.0, 0.05, 0.010};  // EDT T20 T30 C50 C80 D50 Ts
  const char* names[7] = {"EDT", "T20", "T30", "C50", "C80", "D50", "Ts"};
  const int seeds = 8, nb = r.bands.size();
  std::vector<std::array<double, 7>> mean(static_cast<size_t>(nb), std::array<double, 7>{});
  for (int s = 0; s < seeds; ++s) {
    const std::vector<BandMetrics> m = metricsFromSignal(synthesize(r, kFs, 3.0, 210.0, 343.0, 300 + s), kFs, r.bands);
    for (int b = 0; b < nb; ++b) {
      // Errors in JNDs: relative for the decay times, absolute for the rest.
      const std::array<double, 7> err{(m[b].edt / ref[b].edt - 1) / jnd[0], (m[b].t20 / ref[b].t20 - 1) / jnd[1],
                                      (m[b].t30 / ref[b].t30 - 1) / jnd[2], (m[b].c50 - ref[b].c50) / jnd[3],
                                      (m[b].c80 - ref[b].c80) / jnd[4],     (m[b].d50 - ref[b].d50) / jnd[5],
                                      (m[b].ts - ref[b].ts) / jnd[6]};
      for (int q = 0; q < 7; ++q) {
        mean[b][q] += err[q] / seeds;
        if (q > 0 && r.bands.nominalHz(b) >= 1000) {
          EXPECT_LE(std::abs(err[q]), 1.0) << r.bands.label(b) << " Hz " << names[q] << ", seed " << 300 + s;
        }
      }
    }
  }
  for (int b = 0; b < nb; ++b) {
    std::printf("  %5s Hz mean error / JND:", r.bands.label(b).c_str());
    for (int q = 0; q < 7; ++q) std::printf(" %s %+.2f", names[q], mean[b][q]);
    std::printf("\n");
    if (r.bands.nominalHz(b) < 125) continue;
    for (int q = 1; q < 7; ++q) EXPECT_LE(std::abs(mean[b][q]), 1.0) << r.bands.label(b) << " Hz " << names[q];
  }
}

}  // namespace
}  // namespace diffray::ir
