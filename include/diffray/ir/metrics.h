#pragma once
// Room-acoustic metrics per band after ISO 3382-1, from an energy histogram or from a
// sampled impulse response, by one rule for both so that the two can be compared.
//
// Contract. Energies are in J/m² per bin (for a signal, p[n]² per sample: diffray's convention that
// Σ p² over a span is its energy). Inside a bin energy is taken as uniform in time. Time zero is the
// onset: the start of the first bin whose energy exceeds max·10^(−20/10) (ISO 3382-1 A.3.4). The noise
// floor of measured responses is found by Lundeby et al.'s iterative method (1995; ISO 3382-1 §5.3.3,
// method described in metrics.cpp): the Schroeder integral E(t) = ∫_t^∞ p² stops at the point where the
// late decay meets the noise and the energy of the decay's exponential continuation beyond it is added.
// T20, T30 and EDT are −60 dB over the slope of the least-squares line through the Schroeder curve (dB,
// sampled at bin edges) from the first time it reaches −5 (EDT: 0) dB to the first time it reaches −25,
// −35 (EDT: −10) dB; C50, C80 = 10·log10(E(0)/E(t_e) − 1); D50 = 1 − E(50 ms)/E(0); Ts = ∫t p²/∫p² with t
// from the onset. A figure is NaN when it cannot be measured: the usable decay (decay_range_db, above the
// noise floor) does not reach the bottom of its fitting range plus, when the decay meets a noise floor,
// 10 dB (ISO 3382-1 §5.3.3), or nothing arrives after t_e; C50, C80, D50 and Ts also when the band clears
// its noise floor by less than 10 dB (they would measure the noise). metricsFromSignal filters the signal with its
// mean removed and the filters' ringing time of zeros in front (BandFilter::ringSamples), and measures no
// band whose filter rings for longer than the file lasts after the onset, and flags each figure within its
// band filter's reach (FilterLimit::limited: the exponential decay that reads this way through the
// filter has a true figure more than one JND away, or cannot be told from a Dirac).
// Free functions, no state: thread-safe.
#include <array>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "diffray/core/bands.h"

namespace diffray::ir {

/// The seven figures of a band, in the order of the table and the JSON.
enum class Figure { Edt, T20, T30, C50, C80, D50, Ts };
inline constexpr std::array<Figure, 7> kAllFigures{Figure::Edt, Figure::T20, Figure::T30, Figure::C50,
                                                   Figure::C80, Figure::D50, Figure::Ts};
/// "edt", "t20", … (the JSON keys).
const char* figureName(Figure figure);

struct BandMetrics {
  static constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  double t20 = kNaN, t30 = kNaN, edt = kNaN;  ///< s
  double c50 = kNaN, c80 = kNaN;              ///< dB
  double d50 = kNaN;                          ///< fraction, 0 … 1
  double ts = kNaN;                           ///< centre time, s after the onset
  /// How far (dB) the Schroeder curve falls before it ends or meets the noise floor: T20, T30 and EDT need
  /// 25, 35 and 10 dB, and 10 dB more when it meets a noise floor. For a traced response markMetrics
  /// (uncertainty.h) caps it where the Monte-Carlo noise stops the curve from being read.
  double decay_range_db = kNaN;
  /// Where the noise truncation stopped the integral, s after the onset (NaN: not truncated).
  double truncation_s = kNaN;
  /// metricsFromSignal: the file ends sooner after the onset than the band's filter rings
  /// (BandFilter::ringSamples(band)), so the band signal is cut off while it still holds much of the
  /// filter's own response; every figure is then NaN (metricsJson adds "shorter_than_filter": true).
  bool shorter_than_filter = false;
  /// metricsFromSignal: per figure (index: Figure), whether it is within its band filter's reach
  /// (FilterLimit::limited, filter_limit.h): the exponential decay that reads this way through the filter
  /// has a true figure more than one JND away, or cannot be told from a Dirac. The figure is still given;
  /// metricsJson lists it under "filter_limited", metricsTable marks it with '*'.
  std::array<bool, 7> filter_limited{};
  bool limited(Figure f) const { return filter_limited[static_cast<size_t>(f)]; }
  double value(Figure f) const;  ///< the figure's value
};

/// Metrics of one band's energy histogram (J/m² per bin of width bin_s seconds, first bin at time 0).
/// Throws core::InputError for bin_s ≤ 0 or non-finite energies. All NaN if no energy is positive.
BandMetrics metricsFromEnergy(const std::vector<double>& energy_per_bin, double bin_s);
/// The same with time zero at bin `onset` given (e.g. the broadband onset); all NaN if it is out of range.
BandMetrics metricsFromEnergy(const std::vector<double>& energy_per_bin, double bin_s, long onset);
/// The onset rule: the first bin whose energy exceeds max·10^(−20/10); −1 if no energy is positive.
long onsetBin(const std::vector<double>& energy_per_bin);

/// Every band of a response (energy_per_band[b][bin]) with one time zero for all: the onset of the
/// band-summed histogram, as metricsFromSignal does with the band-summed signal. This is what the
/// histogram side of a comparison with a synthesized IR should call.
std::vector<BandMetrics> metricsFromHistograms(const std::vector<std::vector<double>>& energy_per_band,
                                               double bin_s);

/// Metrics of each band of a sampled impulse response p (Pa-like units, sample 0 at time 0): zero-phase
/// band filtering (BandFilter), squared, then metricsFromEnergy with one bin per sample, with time zero
/// at the onset of the band-summed signal (one time zero for every band: see metricsFromHistograms).
/// Throws core::InputError for non-finite samples, a sample rate ≤ 0, or bands above the Nyquist frequency.
std::vector<BandMetrics> metricsFromSignal(const std::vector<double>& p, double sample_rate_hz,
                                           const core::Bands& bands);

/// {"125": {"t20": …, "t30": …, "edt": …, "c50": …, "c80": …, "d50": …, "ts": …, "decay_range_db": …}, …}
/// plus "filter_limited": ["edt", …] and "shorter_than_filter": true where they apply;
/// keyed by nominal centre in band order (an ordered_json: a plain json object would sort "1000" before
/// "125"); NaN as null. Embed it in ordered_json objects too, or the keys are sorted again.
nlohmann::ordered_json metricsJson(const core::Bands& bands, const std::vector<BandMetrics>& metrics);

struct BandUncertainty;  // ir/uncertainty.h

/// A text table, one row per band (T20 T30 EDT in s, C50 C80 in dB, D50, Ts in ms, decay range in dB),
/// "-" where a figure is NaN and '*' after a filter-limited one, followed by a note on each mark used.
/// With `uncertainty` (markMetrics' marks, one per band): '?' after a figure whose standard error exceeds
/// its JND, '!' for one not available because of negative energy, and a last column "flag" (ok, noisy,
/// neg).
std::string metricsTable(const core::Bands& bands, const std::vector<BandMetrics>& metrics,
                         const std::vector<BandUncertainty>* uncertainty = nullptr);

}  // namespace diffray::ir
