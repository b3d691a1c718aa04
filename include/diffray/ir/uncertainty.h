#pragma once
// How far to trust the metrics of a traced response: a standard error for every figure of every band, and
// a mark on a band whose energy sums negative (WBSDF diffraction scores signed energy) or whose figures
// are noisier than one just-noticeable difference.
//
// Contract. The tracer keeps its rays' scores in K independent batches (EnergyResponse::batches; the
// batches share no ray and no random stream). Replicate k is the histogram without batch k, its traced part
// scaled back to the whole's ray count: exact + (T − B_k)·N/(N − n_k) (T = Σ B_k, n_k batch k's rays, N
// theirs summed). The metrics are nonlinear functions of correlated bins, so the standard error is the
// delete-one jackknife of each figure over the replicates (Efron & Tibshirani, "An Introduction to the
// Bootstrap", 1993, eq. 11.5): SE² = (K − 1)/K · Σ_k (θ_(k) − θ̄)². With K = 16 the SE is itself
// uncertain by about 1/√(2(K − 1)) ≈ 18 %. A figure is "noisy" when its SE exceeds its ISO 3382-1
// (Annex A, Table A.1) just-noticeable difference (5 % for EDT, T20, T30; 1 dB for C50, C80; 0.05 for D50;
// 10 ms for Ts), or when some replicate cannot measure it at all while the whole can. A band is
// "negative_energy" when its energy sums to ≤ 0 with some of it negative (no figure can be given), and a
// figure is not available "because of negative energy" (not given, even if the metrics computed one) when
// the band's Schroeder curve (the backward sum of a signed histogram) goes below zero (it plunges into
// that zero by cancellation, which reads as a steep decay) before the figure has what it needs: the bottom
// of its fitting range (EDT 10, T20 25, T30 35 dB down, read on the decay of the positive energy alone,
// which cancellation does not steepen) or the end of its early interval (C50, D50: 50 ms after the onset,
// C80: 80 ms).
// The metrics of a synthesized WAV get the histogram's standard errors: the synthesis adds its own noise,
// which this does not count. Units: the figures' own (s, dB, fraction). Free functions: thread-safe.
#include <array>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "diffray/core/bands.h"
#include "diffray/ir/metrics.h"
#include "diffray/ir/response.h"

namespace diffray::ir {

/// One JND of `figure` at measured value `value` (ISO 3382-1 Table A.1; 5 % of it for EDT, T20, T30).
double figureJnd(Figure figure, double value);

struct BandUncertainty {
  static constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  enum class Flag { Ok, Noisy, NegativeEnergy };
  std::array<double, 7> se{kNaN, kNaN, kNaN, kNaN, kNaN, kNaN, kNaN};  ///< per Figure; NaN: none
  double decay_range_se = kNaN;      ///< dB
  /// How far (dB) the band's Schroeder curve falls before the jackknife standard error of its level
  /// exceeds 1 dB (a level's JND): the deepest decay the rays resolve. NaN without batches. markMetrics
  /// caps BandMetrics::decay_range_db at it.
  double monte_carlo_range_db = kNaN;
  std::array<int, 7> unmeasurable{};  ///< replicates without the figure while the whole has it
  int replicates = 0;                 ///< batches used (0 or 1: no standard errors)
  double energy = 0.0;                ///< Σ energy of the band (traced + exact), J/m²
  double abs_energy = 0.0;            ///< Σ |energy|
  double negative_fraction = 0.0;     ///< Σ negative / Σ |energy| over the traced bins
  double schroeder_zero_s = kNaN;     ///< first time (after emission) the Schroeder curve is < 0; NaN: never
  double depth_before_zero_db = kNaN;  ///< how far (dB) the decay of the positive energy alone has fallen then
  double onset_s = kNaN;              ///< the response's onset (metricsFromHistograms' time zero)
  bool negative_energy = false;       ///< the band sums to ≤ 0 with negative energy in it
  std::array<bool, 7> negative{};     ///< per Figure: not available because of negative energy
  std::array<bool, 7> noisy{};        ///< per Figure: SE above its JND, or unmeasurable in some replicate
  bool isNoisy(Figure f) const { return noisy[static_cast<std::size_t>(f)]; }
  bool isNegative(Figure f) const { return negative[static_cast<std::size_t>(f)]; }
  double standardError(Figure f) const { return se[static_cast<std::size_t>(f)]; }
  Flag flag() const;
  const char* flagName() const;  ///< "ok", "noisy", "negative_energy"
};

/// The jackknife of metricsFromHistograms over the response's batches, and the marks of `metrics` (the
/// response's own metrics from its histogram, or those of a WAV synthesized from it: the standard errors
/// are the histogram's either way, the marks follow the figures given). Without batches (fewer than two
/// used) there are no standard errors, and only the negative-energy marks.
std::vector<BandUncertainty> jackknifeMetrics(const EnergyResponse& response);
/// Marks of `metrics` from the standard errors of `u`, and their decay_range_db capped at
/// u.monte_carlo_range_db (then without decay_range_se) (a copy of u with noisy[] and negative[] set for
/// these figures, and no standard error for a figure they do not give); the figures that negative energy
/// makes unavailable (all of a band that sums negative) are set to NaN in `metrics` (never a plain number).
/// `histogram_marks`: for the metrics of a WAV synthesized from the histogram (which reads negative bins
/// as silence), markMetrics of the histogram's own metrics: a figure the histogram cannot give because of
/// negative energy is not given from the WAV either.
std::vector<BandUncertainty> markMetrics(std::vector<BandMetrics>& metrics, const std::vector<BandUncertainty>& u,
                                         const std::vector<BandUncertainty>* histogram_marks = nullptr);

/// One warning per marked band: "listener NAME, 4000 Hz: …", naming the figures and their standard errors
/// against their JNDs, or the negative energy.
std::vector<std::string> uncertaintyWarnings(const std::string& listener, const core::Bands& bands,
                                             const std::vector<BandMetrics>& metrics,
                                             const std::vector<BandUncertainty>& u);

/// Adds to each band of a metricsJson object "se" {figure: SE or null, "decay_range_db": …}, "flag",
/// "noisy" and "not_available_negative_energy" (lists of figures, where not empty) and
/// "negative_energy_fraction".
void addUncertaintyJson(nlohmann::ordered_json& bands_json, const core::Bands& bands,
                        const std::vector<BandUncertainty>& u);

}  // namespace diffray::ir
