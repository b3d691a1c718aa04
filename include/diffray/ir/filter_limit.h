#pragma once
// How much a band's analysis filter alone biases a decay figure (EDT, T20, T30) measured through it.
//
// Contract. A band filter smears an impulse response over its own ringing (BandFilter::ringSamples): a
// zero-phase filter both ahead of and after each sample. A decay that is short against that ringing is
// read long (a Dirac reads EDT 0.35 s in the 63 Hz octave at any sample rate). The model: the band's
// energy envelope of an exponential decay that falls 60 dB in T (design.md §2's convention that Σ p² over
// a span is its energy), convolved with the band filter's squared impulse response h_b² (the expected
// band energy of diffuse, noise-like decay with that envelope), measured by metricsFromEnergy from the
// decay's start. relativeBias() is that measured figure over T, minus 1: filters lengthen decays, so it
// is positive (to within ~1 % of numerics) and falls as T grows. limited(T_m) asks which true decay would
// be read as the measured T_m and flags T_m when that decay is more than kTolerance shorter. Assuming the
// model's reading g(T) = T·(1 + bias) grows with T, that holds when g(T_m/(1 + kTolerance)) > T_m: one
// model evaluation. The assumption fails where g is flat: as T → 0, g levels off near the filter's own
// figure (ownFigure, what a Dirac reads), and every shorter decay reads about alike; a Dirac's T30 in the
// 2–8 kHz octaves passes the first test. So a figure at most kTolerance above ownFigure is flagged too. Units: seconds; band indices as the BandFilter's. Immutable after construction;
// thread-safe.
#include <vector>

#include "diffray/ir/band_filter.h"

namespace diffray::ir {

enum class DecayFigure { Edt, T20, T30 };

class FilterLimit {
 public:
  /// The just-noticeable difference of T and EDT (ISO 3382-1:2009 Annex A, Table A.1: 5 %): a filter bias
  /// beyond it is flagged.
  static constexpr double kTolerance = 0.05;

  /// Computes every band's h_b² (a unit impulse through filter.split).
  explicit FilterLimit(const BandFilter& filter);
  /// The model's measured figure for a decay of reverberation time t_s through band `band`, over t_s,
  /// minus 1; NaN if the model's figure cannot be measured. Throws core::InputError for t_s ≤ 0.
  double relativeBias(int band, DecayFigure figure, double t_s) const;
  /// A figure measured as t_s comes from a true decay more than kTolerance shorter: relativeBias at
  /// t_s/(1 + kTolerance) exceeds kTolerance, or cannot be measured (false for a non-finite t_s).
  bool limited(int band, DecayFigure figure, double measured_s) const;
  /// The figure a unit impulse reads through band `band` (the model as T → 0); NaN if not measurable.
  double ownFigure(int band, DecayFigure figure) const;

 private:
  double fs_;
  std::vector<long> centre_;                   ///< per band: the sample of h_b² at time 0
  std::vector<std::vector<double>> response_;  ///< per band: h_b², the impulse at sample centre_[b]
  std::vector<double> own_;                    ///< per band: ownFigure for Edt, T20, T30
};

}  // namespace diffray::ir
