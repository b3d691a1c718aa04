#include "diffray/ir/filter_limit.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "diffray/core/error.h"
#include "diffray/ir/metrics.h"

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
    const BandMetrics own = metricsFromEnergy(h2, 1.0 / fs_, half);
    own_.insert(own_.end(), {own.edt, own.t20, own.t30});
    centre_.push_back(half);
    response_.push_back(std::move(h2));
  }
}

double FilterLimit::relativeBias(int band, DecayFigure figure, double t_s) const {
  core::requirePositive("filter limit: reverberation time", t_s);
  DIFFRAY_CHECK(band >= 0 && band < static_cast<int>(response_.size()));
  // Bins of T/400 (at least one sample): the energy envelope is smooth on that scale, and the
  // convolution stays small (2T of envelope against the filter's ringing).
  const long k = std::max(1L, std::lround(t_s * fs_ / 400.0));
  const double bin_s = static_cast<double>(k) / fs_;
  const std::vector<double>& h2 = response_[static_cast<size_t>(band)];
  const long centre = centre_[static_cast<size_t>(band)];
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
  std::vector<double> conv(static_cast<size_t>(e_bins + g_bins), 0.0);
  double level = 1.0;
  for (long i = 0; i < e_bins; ++i, level *= decay)
    for (long j = 0; j < g_bins; ++j) conv[static_cast<size_t>(i + j)] += level * g[static_cast<size_t>(j)];
  // Time zero where the envelope starts: bin lead_bins of the convolution.
  const BandMetrics m = metricsFromEnergy(conv, bin_s, lead_bins);
  const double value = figure == DecayFigure::Edt ? m.edt : figure == DecayFigure::T20 ? m.t20 : m.t30;
  return value / t_s - 1.0;
}

bool FilterLimit::limited(int band, DecayFigure figure, double measured_s) const {
  if (!(std::isfinite(measured_s) && measured_s > 0.0)) return false;
  // The decay kTolerance shorter than measured would read at least as long: the true one is shorter still.
  const double own = ownFigure(band, figure);
  if (std::isfinite(own) && measured_s <= (1.0 + kTolerance) * own) return true;
  const double bias = relativeBias(band, figure, measured_s / (1.0 + kTolerance));
  return !std::isfinite(bias) || bias > kTolerance;
}

double FilterLimit::ownFigure(int band, DecayFigure figure) const {
  DIFFRAY_CHECK(band >= 0 && 3 * band + 2 < static_cast<int>(own_.size()));
  return own_[static_cast<size_t>(3 * band + static_cast<int>(figure))];
}

}  // namespace diffray::ir
