#pragma once
// Spatial room-acoustic figures per band (ISO 3382-1:2009 Annex A.3.2 and A.3.5) from a directional
// impulse response: the early lateral energy fractions J_LF and J_LFC from a first-order Ambisonic (AmbiX)
// response, and the interaural cross-correlation coefficients IACC_E and IACC_L from a binaural one.
//
// Contract. Signals are sampled impulse responses (p[n], any unit), all of one length and rate.
// - AmbiX: ACN channel order and SN3D normalisation (W = channel 0, Y = channel 1), the recording's front
//   (+x) toward the source. Y is then the lateral figure-of-eight whose gain at ±90° equals W's, the pair
//   ISO 3382-1 A.3.2 asks for:
//     J_LF  = ∫_{5 ms}^{80 ms} p_Y² dt / ∫_{0}^{80 ms} p_W² dt,
//     J_LFC = ∫_{5 ms}^{80 ms} |p_Y·p_W| dt / ∫_{0}^{80 ms} p_W² dt,
//   and, when the free-field energy of the same source at 10 m is known (a simulation: P/(100 m²) per band
//   for a source of power P), the late lateral sound level of A.3.3,
//     L_J = 10·lg(∫_{80 ms}^{∞} p_Y² dt / ∫_0^∞ p_10² dt) dB.
// - Binaural (left, right; ISO 3382-1 A.3.5):
//     IACF(τ) = ∫_{t1}^{t2} p_L(t)·p_R(t + τ) dt / √(∫_{t1}^{t2} p_L² dt · ∫_{t1}^{t2} p_R² dt),
//     IACC = max |IACF(τ)| over |τ| ≤ 1 ms;   IACC_E: t1 = 0, t2 = 80 ms;   IACC_L: t1 = 80 ms,
//     t2 = 750 ms (or the record's end if it ends before; the late window of Hidaka, Beranek & Okano,
//     J. Acoust. Soc. Am. 98(2), 1995).
// Time zero is the onset of the broadband response (W, or the two ears' energies summed): the first sample
// whose energy reaches 20 dB below the peak (ISO 3382-1 A.3.4), as in metrics.h. Each channel is split
// into bands by the zero-phase BandFilter, with its ringing time of zeros in front and its mean removed, as
// metricsFromSignal does; a window that starts at time zero starts where the band's own filtered energy
// begins (its filter's ringing before the onset belongs to the direct sound). A figure is NaN when its
// windows hold no energy, or the record ends before the early window does; a band whose filter rings for
// longer than the record lasts after the onset gives NaN throughout. The band averages follow common
// practice: J_LF over the 125 Hz – 1 kHz octaves, IACC_E3 and IACC_L3 over 500 Hz – 2 kHz.
// Free functions, no state: thread-safe.
#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "diffray/core/bands.h"

namespace diffray::ir {

struct SpatialBandMetrics {
  static constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  double jlf = kNaN, jlfc = kNaN;       ///< fractions (AmbiX)
  double lj_db = kNaN;                  ///< late lateral sound level, dB (AmbiX with a known reference)
  double iacc_e = kNaN, iacc_l = kNaN;  ///< 0 … 1 (binaural)
};

/// J_LF and J_LFC per band from the W and Y channels of an AmbiX response. Throws core::InputError for
/// signals of different lengths, non-finite samples or a silent W.
/// With `reference_10m` > 0 (the energy per band of the source's free-field response at 10 m, in the
/// signals' units: Σp²), L_J too.
std::vector<SpatialBandMetrics> lateralFractions(const std::vector<double>& w, const std::vector<double>& y,
                                                 double sample_rate_hz, const core::Bands& bands,
                                                 double reference_10m = 0.0);

/// IACC_E and IACC_L per band from a binaural response. Throws core::InputError as lateralFractions.
std::vector<SpatialBandMetrics> interauralCrossCorrelation(const std::vector<double>& left,
                                                           const std::vector<double>& right,
                                                           double sample_rate_hz, const core::Bands& bands);

/// The interaural cross-correlation coefficient of one window: the largest |Σ_{i∈[from,to)} l[i]·r[i+τ]| over
/// |τ| ≤ max_lag, r taken as 0 outside its samples, over √(Σ l²·Σ r²) (both over the window); NaN when either
/// ear is silent there. What interauralCrossCorrelation applies to each band and window. Needs
/// 0 ≤ from ≤ to ≤ the length of l and r.
double windowIacc(const std::vector<double>& l, const std::vector<double>& r, long from, long to, long max_lag);

/// The mean of `figure` over the bands whose nominal centre lies in [lo_hz, hi_hz] (NaN if one is NaN or
/// none lies there).
double bandAverage(const core::Bands& bands, const std::vector<SpatialBandMetrics>& metrics,
                   double SpatialBandMetrics::*figure, double lo_hz, double hi_hz);

/// {"<centre Hz>": {"jlf": …, "jlfc": …} or {"iacc_e": …, "iacc_l": …}} (null for NaN), and the averages.
nlohmann::ordered_json spatialJson(const core::Bands& bands, const std::vector<SpatialBandMetrics>& metrics,
                                   bool ambix);
/// A table: band, then J_LF and J_LFC (ambix) or IACC_E and IACC_L, '-' for NaN, and the averages.
std::string spatialTable(const core::Bands& bands, const std::vector<SpatialBandMetrics>& metrics, bool ambix);

}  // namespace diffray::ir
