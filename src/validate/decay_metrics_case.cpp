// `diffray validate decay-metrics`: ISO 3382-1 metrics of synthetic exponential decays p² ∝ e^{−kt},
// k = 6·ln10/T, against their closed forms (T20 = T30 = EDT = T, C_te = 10·log10(e^{k·te} − 1),
// D50 = 1 − e^{−0.05k}, Ts = 1/k; T = 1 s gives C80 = 3.0534 dB, D50 = 0.49881), by two paths:
//  * hist: the metrics of the 1 ms energy histogram (ir/metrics.h). Target: within 0.5 %, except C50 at
//    T = 1 s (−0.0206 dB, near zero, where a relative error means nothing): there |error| ≤ 0.005 dB;
//    the rule used for C50/C80 is |error| ≤ max(0.5 % of |value|, 0.005 dB).
//  * wav: the metrics of impulse responses synthesized from the histogram (ir/synthesis.h, 48 kHz, rounded
//    to float32 as a WAV stores them), mean over 4 seeds, bands 1–8 kHz. A noise-based IR cannot meet
//    0.5 % (its metrics scatter like a measurement's), so its target is the synthesis agreement the tests hold:
//    T20/T30/EDT 2 %, C50/C80 0.5 dB, D50 0.02, Ts 3 %. Lower bands are reported in `extra`, not scored.
//    (Before the synthesis silenced the traced part ahead of its first bin, its band filters rang ahead
//    of this abrupt start, the onset was found ~1 ms early and Ts read 3.7 % long at T = 0.5 s: a miss
//    this case reported rather than relaxing the target.) `detail` says which path missed, if one does.
// Rows: x_m = T (s), y_m = band centre (Hz), label "T=… path band metric".
#include <chrono>
#include <cmath>
#include <string>

#include "diffray/core/error.h"
#include "diffray/ir/metrics.h"
#include "diffray/ir/synthesis.h"
#include "diffray/validate/case.h"

namespace diffray::validate {

namespace {

constexpr double kFs = 48000.0, kBin = 1e-3, kStart = 0.1;  // decay starts at 100 ms, after silence
constexpr int kSeeds = 4;
const char* const kNames[7] = {"t20", "t30", "edt", "c50", "c80", "d50", "ts"};

std::array<double, 7> asArray(const ir::BandMetrics& m) { return {m.t20, m.t30, m.edt, m.c50, m.c80, m.d50, m.ts}; }

std::array<double, 7> closedForm(double t60) {
  const double k = 6.0 * std::log(10.0) / t60;
  return {t60, t60, t60, 10.0 * std::log10(std::exp(0.05 * k) - 1.0), 10.0 * std::log10(std::exp(0.08 * k) - 1.0),
          1.0 - std::exp(-0.05 * k), 1.0 / k};
}

/// Error and tolerance of metric q: relative for times and D50 on the hist path, dB for C50/C80.
struct Score {
  double error = 0.0, tolerance = 0.0;
};

Score score(int q, double got, double want, bool wav) {
  if (!std::isfinite(got)) return {HUGE_VAL, 1.0};
  if (q == 3 || q == 4) return {std::abs(got - want), wav ? 0.5 : std::max(0.005 * std::abs(want), 0.005)};
  if (q == 5) return wav ? Score{std::abs(got - want), 0.02} : Score{std::abs(got / want - 1.0), 0.005};
  return {std::abs(got / want - 1.0), wav ? (q == 6 ? 0.03 : 0.02) : 0.005};
}

}  // namespace

CaseInfo decayMetricsCase() {
  CaseInfo c{"decay-metrics",
             "ISO 3382-1 metrics of exponential decays, from the histogram and from the synthesized IR, vs closed forms",
             {},
             0,
             {}};
  c.params = {{"reverb-time", {1.0, 0.5}, "reverberation times T of the decays (s)", 0.05, false, 20.0},
              {"volume", {200.0}, "room volume for the Dirac density of the synthesis (m³)", 1.0, true, 1e9}};
  c.param("reverb-time").list = true;
  c.run = [](const Params& p, const RunOptions& o) {
    const auto t0 = std::chrono::steady_clock::now();
    if (o.model != "wigner") throw core::InputError("--model", "decay-metrics takes no transport model");
    const double volume = p.at("volume")[0];
    core::requirePositive("--volume", volume);
    CaseResult r;
    r.name = "decay-metrics";
    r.target_rel_peak = 0.005;
    bool passed = true;
    double worst_hist = 0.0, sum_sq = 0.0, worst_wav_over_target = 0.0;
    int count = 0;
    for (double t60 : p.at("reverb-time")) {
      const double length_s = kStart + 2.0 * t60 + 0.5;  // down to −120 dB and beyond
      const double k = 6.0 * std::log(10.0) / t60;
      ir::EnergyResponse resp;
      resp.bands = core::Bands::octave();
      resp.bin_s = kBin;
      std::vector<double> h(static_cast<size_t>(std::lround(length_s / kBin)), 0.0);
      for (size_t i = static_cast<size_t>(std::lround(kStart / kBin)); i < h.size(); ++i) {
        const double a = static_cast<double>(i) * kBin - kStart;
        h[i] = (std::exp(-k * a) - std::exp(-k * (a + kBin))) / k;
      }
      resp.traced.assign(static_cast<size_t>(resp.bands.size()), h);
      const std::array<double, 7> want = closedForm(t60);
      const std::string tag = "T=" + std::to_string(t60).substr(0, 4) + "s ";

      const std::array<double, 7> hist = asArray(ir::metricsFromEnergy(h, kBin));
      for (int q = 0; q < 7; ++q) {
        const Score s = score(q, hist[q], want[q], false);
        Row row;
        row.x_m = t60;
        row.y_m = 1000.0;
        row.traced = hist[q];
        row.reference = want[q];
        row.label = tag + "hist " + kNames[q];
        r.rows.push_back(row);
        r.extra[tag + "hist " + kNames[q] + " error"] = s.error;
        passed = passed && s.error <= s.tolerance;
        if (q != 3) worst_hist = std::max(worst_hist, s.error), sum_sq += s.error * s.error, ++count;
      }

      std::vector<std::array<double, 7>> mean(static_cast<size_t>(resp.bands.size()), std::array<double, 7>{});
      for (int s = 0; s < kSeeds; ++s) {
        std::vector<double> pressure = ir::synthesize(resp, kFs, length_s, volume, 343.0, o.seed + static_cast<std::uint64_t>(s));
        for (double& v : pressure) v = static_cast<double>(static_cast<float>(v));  // what a float WAV holds
        const std::vector<ir::BandMetrics> m = ir::metricsFromSignal(pressure, kFs, resp.bands);
        for (int b = 0; b < resp.bands.size(); ++b)
          for (int q = 0; q < 7; ++q) mean[b][q] += asArray(m[b])[q] / kSeeds;
        if (o.on_progress) o.on_progress(1);
      }
      for (int b = 0; b < resp.bands.size(); ++b) {
        const bool scored = resp.bands.nominalHz(b) >= 1000.0;
        for (int q = 0; q < 7; ++q) {
          const Score s = score(q, mean[b][q], want[q], true);
          const std::string name = tag + "wav " + resp.bands.label(b) + " " + kNames[q];
          r.extra[name + (q == 3 || q == 4 || q == 5 ? " error" : " rel error")] = s.error;
          if (!scored) continue;
          Row row;
          row.x_m = t60;
          row.y_m = resp.bands.nominalHz(b);
          row.traced = mean[b][q];
          row.reference = want[q];
          row.label = name;
          r.rows.push_back(row);
          worst_wav_over_target = std::max(worst_wav_over_target, s.error / s.tolerance);
          passed = passed && s.error <= s.tolerance;
        }
      }
    }
    r.max_abs_error_rel_peak = worst_hist;  // hist path, relative (C50 excluded: scored in dB)
    r.rms_error_rel_peak = count ? std::sqrt(sum_sq / count) : 0.0;
    r.extra["wav_worst_error_over_target"] = worst_wav_over_target;
    r.rays = 0;
    r.passed = passed;
    r.detail = std::string("histogram path: worst ") + std::to_string(100 * worst_hist).substr(0, 6) +
               " % (0.5 % allowed); synthesized-WAV path: worst " +
               std::to_string(worst_wav_over_target).substr(0, 5) + " x its target" +
               (worst_wav_over_target > 1.0 ? " (MISSED)" : "");
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return r;
  };
  return c;
}

}  // namespace diffray::validate
