#pragma once
// How much a band's analysis filter alone biases the figures (EDT, T20, T30, C50, C80, D50, Ts) measured
// through it, and which measured figures it makes untrustworthy.
//
// Contract. A band filter smears an impulse response over its own ringing (BandFilter::ringSamples): a
// zero-phase filter both ahead of and after each sample. A short decay is read long and its early energy
// spread late (a Dirac reads EDT 0.35 s and C50 31 dB in the 63 Hz octave). The model: the energy envelope
// of an exponential decay that falls 60 dB in T (diffray's convention that Σ p² over a span is its
// energy), convolved with the band filter's squared impulse response h_b² (the expected band energy of
// diffuse, noise-like decay with that envelope), measured by metricsFromEnergy from the decay's start:
// modelReading(T). trueValue(T) is the same figure of the exponential itself (closed forms: T; C_te =
// 10·log10(10^(6·te/T) − 1); D50 = 1 − 10^(−0.3/T); Ts = T/(6·ln 10)). limited() asks which true decay
// would be read as the measured value m, and flags m when that decay's true figure lies more than one JND
// from m (ISO 3382-1:2009 Annex A, Table A.1: EDT 5 %, C80 1 dB, D50 0.05, Ts 10 ms; the same 5 % for T20
// and T30 and 1 dB for C50). Assuming modelReading moves with T the way trueValue does (T, EDT and Ts grow
// with T; C and D fall), that is decided by two model evaluations, at the decays whose true figures lie
// one JND either side of m. As T → 0 the readings level off near a Dirac's (ownFigure) instead of going
// on falling (a Dirac's T30 in the 2–8 kHz octaves reads what a 0.04 s decay does), so a Dirac's reading
// counts at the short end too: m is flagged when a decay too short to be within one JND, or a Dirac, reads
// at least as far as m. A decay time at most 5 % above a Dirac's reading is flagged outright: the readings
// are level there, and the model and a measurement of the same response differ by a few per cent.
// The inversion assumes the band's response is an exponential decay from time zero: with a strong direct
// sound the implied decay is not the room's, and the flag is a proxy for "not trustworthy to one JND".
// Units: seconds, dB, fractions; band indices as the BandFilter's. Immutable after construction;
// thread-safe.
#include <vector>

#include "diffray/ir/band_filter.h"
#include "diffray/ir/metrics.h"

namespace diffray::ir {

class FilterLimit {
 public:
  /// The relative JND used for EDT, T20 and T30 (5 %).
  static constexpr double kDecayTolerance = 0.05;

  /// Computes every band's h_b² (a unit impulse through filter.split) and a Dirac's reading.
  explicit FilterLimit(const BandFilter& filter);
  /// The model's metrics for an exponential decay of reverberation time t_s through band `band`. Throws
  /// core::InputError for t_s ≤ 0.
  BandMetrics modelReading(int band, double t_s) const;
  /// The figure of the exponential decay itself (no filter).
  static double trueValue(Figure figure, double t_s);
  /// EDT, T20, T30 only: modelReading's figure over t_s, minus 1 (NaN if not measurable).
  double relativeBias(int band, Figure figure, double t_s) const;
  /// The measured value comes from a decay whose true figure is more than one JND away (the rule above;
  /// false for a non-finite value).
  bool limited(int band, Figure figure, double measured) const;
  /// The figure a unit impulse reads through band `band` (the model as T → 0); NaN if not measurable.
  double ownFigure(int band, Figure figure) const;

 private:
  double fs_;
  std::vector<std::vector<double>> response_;  ///< per band: h_b², odd length, time 0 at the middle sample
  std::vector<BandMetrics> own_;               ///< per band: a Dirac's reading
};

}  // namespace diffray::ir
