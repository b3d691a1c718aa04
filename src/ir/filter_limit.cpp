#include "diffray/ir/filter_limit.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "diffray/core/error.h"

namespace diffray::ir {

FilterLimit::FilterLimit(const BandFilter& filter) : fs_(filter.sampleRateHz()) {
  // One impulse in the middle of twice the longest ringing: every band's whole response fits.
  const long ring = filter.ringSamples();
  std::vector<double> impulse(static_cast<size_t>(2 * ring + 1), 0.0);
  impulse[static_cast<size_t>(ring)] = 1.0;
  std::vector<std::vector<double>> bands = filter.split(impulse);
  for (int b = 0; b < static_cast<int>(bands.size()); ++b) {
    // Keep the band's own ringing only (ringSamples(b) ≤ ring either side): beyond it the response is
    // negligible.
    const long half = filter.ringSamples(b);
    std::vector<double> h2(static_cast<size_t>(2 * half + 1));
    for (long n = -half; n <= half; ++n) {
      const double v = bands[static_cast<size_t>(b)][static_cast<size_t>(ring + n)];
      h2[static_cast<size_t>(n + half)] = v * v;
    }
    own_.push_back(metricsFromEnergy(h2, 1.0 / fs_, half));
    response_.push_back(std::move(h2));
  }
}

BandMetrics FilterLimit::modelReading(int band, double t_s) const {
  core::requirePositive("filter limit: reverberation time", t_s);
  DIFFRAY_CHECK(band >= 0 && band < static_cast<int>(response_.size()));
  // Bins of T/400 (at least one sample): the energy envelope is smooth on that scale, and the
  // convolution stays small (2T of envelope against the filter's ringing).
  const long k = std::max(1L, std::lround(t_s * fs_ / 400.0));
  const double bin_s = static_cast<double>(k) / fs_;
  const std::vector<double>& h2 = response_[static_cast<size_t>(band)];
  const long centre = static_cast<long>(h2.size() / 2);  // h2 spans ±ringSamples(band) about time 0
  // h_b² summed into bins aligned so that bin c0 starts at time 0.
  const long lead_bins = (centre + k - 1) / k;
  const long first = centre - lead_bins * k;  // sample of h2 at the start of bin 0 (may be negative)
  const long g_bins = lead_bins + (static_cast<long>(h2.size()) - centre + k - 1) / k;
  std::vector<double> g(static_cast<size_t>(g_bins), 0.0);
  for (long n = std::max(0L, first); n < static_cast<long>(h2.size()); ++n)
    g[static_cast<size_t>((n - first) / k)] += h2[static_cast<size_t>(n)];
  // The envelope: energy 10^(−6t/T) per second over 2T (120 dB), per bin its value at the bin's start
  // (proportional to its integral over the bin, and the metrics do not depend on scale).
  const long e_bins = static_cast<long>(std::ceil(2.0 * t_s / bin_s));
  const double decay = std::pow(10.0, -6.0 * bin_s / t_s);  // per bin
  // conv[m] = Σ_{i < e_bins} decay^i · g[m − i], by the recursion conv[m] = decay·conv[m − 1] + g[m] −
  // decay^e_bins · g[m − e_bins]: O(e_bins + g_bins) instead of their product (a decay of a few ms in a
  // low band has bins of one sample against the filter's tens of thousands).
  std::vector<double> conv(static_cast<size_t>(e_bins + g_bins), 0.0);
  const double decay_all = std::pow(decay, static_cast<double>(e_bins));
  double run = 0.0;
  for (long m = 0; m < e_bins + g_bins; ++m) {
    run *= decay;
    if (m < g_bins) run += g[static_cast<size_t>(m)];
    if (m >= e_bins && m - e_bins < g_bins) run -= decay_all * g[static_cast<size_t>(m - e_bins)];
    conv[static_cast<size_t>(m)] = std::max(run, 0.0);  // rounding may leave −ε where it should be 0
  }
  // Time zero where the envelope starts: bin lead_bins of the convolution.
  return metricsFromEnergy(conv, bin_s, lead_bins);
}

double FilterLimit::trueValue(Figure figure, double t_s) {
  switch (figure) {
    case Figure::Edt:
    case Figure::T20:
    case Figure::T30:
      return t_s;
    case Figure::C50:
      return 10.0 * std::log10(std::pow(10.0, 0.3 / t_s) - 1.0);
    case Figure::C80:
      return 10.0 * std::log10(std::pow(10.0, 0.48 / t_s) - 1.0);
    case Figure::D50:
      return 1.0 - std::pow(10.0, -0.3 / t_s);
    case Figure::Ts:
      return t_s / (6.0 * std::log(10.0));
  }
  return std::numeric_limits<double>::quiet_NaN();
}

double FilterLimit::relativeBias(int band, Figure figure, double t_s) const {
  DIFFRAY_CHECK(figure == Figure::Edt || figure == Figure::T20 || figure == Figure::T30);
  return modelReading(band, t_s).value(figure) / t_s - 1.0;
}

namespace {

// The decay time whose exponential has the true figure v (trueValue inverted); 0 when v is beyond what
// any decay reaches on the short side, infinity on the long side.
double decayTimeOf(Figure figure, double v) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  switch (figure) {
    case Figure::Edt:
    case Figure::T20:
    case Figure::T30:
      return std::max(v, 0.0);
    case Figure::C50:
    case Figure::C80: {
      const double te = figure == Figure::C50 ? 0.05 : 0.08;
      // log10(10^(C/10) + 1) by log1p, which keeps very negative C; C → +∞: T → 0; C → −∞: T → ∞.
      return 6.0 * te * std::log(10.0) / std::log1p(std::pow(10.0, v / 10.0));
    }
    case Figure::D50:
      if (v >= 1.0) return 0.0;
      if (v <= 0.0) return kInf;
      return -0.3 / std::log10(1.0 - v);
    case Figure::Ts:
      return std::max(v, 0.0) * 6.0 * std::log(10.0);
  }
  return kInf;
}

}  // namespace

bool FilterLimit::limited(int band, Figure figure, double measured) const {
  if (!std::isfinite(measured)) return false;
  // The band of true values within one JND of the measured one.
  double lo = measured, hi = measured;
  switch (figure) {
    case Figure::Edt:
    case Figure::T20:
    case Figure::T30:
      lo = measured / (1.0 + kDecayTolerance), hi = measured * (1.0 + kDecayTolerance);
      break;
    case Figure::C50:
    case Figure::C80:
      lo = measured - 1.0, hi = measured + 1.0;
      break;
    case Figure::D50:
      lo = measured - 0.05, hi = measured + 0.05;
      break;
    case Figure::Ts:
      lo = measured - 0.010, hi = measured + 0.010;
      break;
  }
  // The decays whose true figures are lo and hi. Figures that fall with T (C, D) swap the ends. A decay of
  // zero length has the instant's true figure (0 s, +∞ dB, D50 = 1, Ts = 0): when that lies within the
  // JND, so do all shorter decays, and the short end needs no test (t_short = 0).
  const bool rising = !(figure == Figure::C50 || figure == Figure::C80 || figure == Figure::D50);
  // A decay time within 5 % of a Dirac's reading is where the readings level off: the model and a
  // measurement of the same thing differ there by a few per cent, so no comparison can place it.
  const double own = ownFigure(band, figure);
  const bool decay_time = figure == Figure::Edt || figure == Figure::T20 || figure == Figure::T30;
  if (decay_time && std::isfinite(own) && measured <= (1.0 + kDecayTolerance) * own) return true;
  const double t_short = decayTimeOf(figure, rising ? lo : hi), t_long = decayTimeOf(figure, rising ? hi : lo);
  // The true decay reads as `measured`. It is shorter than t_short if some decay shorter than t_short reads
  // at least that far: the model at t_short, or a Dirac (as T → 0 the readings level off near ownFigure and
  // need not keep falling: a Dirac's T30 in the 2–8 kHz octaves reads what a 0.04 s decay does).
  if (t_short > 0.0 && std::isfinite(t_short)) {
    double reading = modelReading(band, t_short).value(figure);
    if (!std::isfinite(reading)) return true;  // the model cannot tell
    if (std::isfinite(own)) reading = rising ? std::max(reading, own) : std::min(reading, own);
    if (rising ? reading >= measured : reading <= measured) return true;
  }
  // It is longer than t_long if t_long reads short of it (an infinitely long decay reads as itself). No
  // decay at all has a true figure as low as hi (a Ts 10 ms below zero, read from energy ahead of the onset):
  // then nothing within one JND reads this way.
  if (!(t_long > 0.0)) return true;
  if (std::isfinite(t_long)) {
    const double reading = modelReading(band, t_long).value(figure);
    if (!std::isfinite(reading)) return true;
    if (rising ? reading < measured : reading > measured) return true;
  }
  return false;
}

double FilterLimit::ownFigure(int band, Figure figure) const {
  DIFFRAY_CHECK(band >= 0 && band < static_cast<int>(own_.size()));
  return own_[static_cast<size_t>(band)].value(figure);
}

}  // namespace diffray::ir
