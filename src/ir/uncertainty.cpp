#include "diffray/ir/uncertainty.h"

#include <cmath>
#include <cstdio>

#include "diffray/core/error.h"
#include "diffray/ir/filter_limit.h"

namespace diffray::ir {

namespace {

constexpr double kNaN = BandUncertainty::kNaN;

/// "C80", "EDT", … as the table's headings name them.
std::string displayName(Figure f) {
  static constexpr const char* kNames[] = {"EDT", "T20", "T30", "C50", "C80", "D50", "Ts"};
  return kNames[static_cast<int>(f)];
}

/// A figure's value or SE with its unit, as a warning shows it ("2.4 dB", "0.031 s", "12 ms", "0.07").
std::string withUnit(Figure f, double v) {
  char text[48];
  switch (f) {
    case Figure::C50:
    case Figure::C80: std::snprintf(text, sizeof text, "%.2g dB", v); break;
    case Figure::D50: std::snprintf(text, sizeof text, "%.2g", v); break;
    case Figure::Ts: std::snprintf(text, sizeof text, "%.2g ms", 1e3 * v); break;
    default: std::snprintf(text, sizeof text, "%.2g s", v); break;
  }
  return text;
}

/// The Monte-Carlo limit of a decay: the level's standard error at which the curve stops being read, one
/// JND of a level (1 dB, as for G and the clarities in ISO 3382-1 Table A.1).
constexpr double kLevelSeLimitDb = 1.0;

/// The Schroeder curve of a histogram at each bin's start, dB re its total; -inf once nothing positive
/// is left (and all -inf when the total is not positive).
std::vector<double> schroederLevels(const std::vector<double>& e) {
  std::vector<double> tail(e.size(), 0.0);
  double acc = 0.0;
  for (std::size_t i = e.size(); i-- > 0;) tail[i] = acc += e[i];
  std::vector<double> level(e.size(), -HUGE_VAL);
  if (e.empty() || !(tail[0] > 0.0)) return level;
  for (std::size_t i = 0; i < e.size() && tail[i] > 0.0; ++i) level[i] = 10.0 * std::log10(tail[i] / tail[0]);
  return level;
}

/// The jackknife standard error of the replicates' finite values (NaN with fewer than two).
double jackknifeSe(const std::vector<double>& theta) {
  double mean = 0.0;
  int n = 0;
  for (double t : theta)
    if (std::isfinite(t)) mean += t, ++n;
  if (n < 2) return kNaN;
  mean /= n;
  double ss = 0.0;
  for (double t : theta)
    if (std::isfinite(t)) ss += (t - mean) * (t - mean);
  return std::sqrt(ss * (n - 1.0) / n);
}

void setValue(BandMetrics& m, Figure f, double v) {
  switch (f) {
    case Figure::Edt: m.edt = v; break;
    case Figure::T20: m.t20 = v; break;
    case Figure::T30: m.t30 = v; break;
    case Figure::C50: m.c50 = v; break;
    case Figure::C80: m.c80 = v; break;
    case Figure::D50: m.d50 = v; break;
    case Figure::Ts: m.ts = v; break;
  }
}

/// Whether the Schroeder curve's fall to zero (negative energy) keeps figure f from being measured: it
/// comes before the curve reaches the bottom of the figure's fitting range (EDT 10, T20 25, T30 35 dB:
/// metrics.h), or before the end of its early interval (C50, D50 50 ms, C80 80 ms after the onset).
/// Ts can always be computed from a signed histogram.
bool blockedByZero(const BandUncertainty& u, Figure f) {
  if (!std::isfinite(u.schroeder_zero_s)) return false;
  const double early = std::isfinite(u.onset_s) ? u.schroeder_zero_s - u.onset_s : 0.0;
  switch (f) {
    case Figure::Edt: return u.depth_before_zero_db < 10.0;
    case Figure::T20: return u.depth_before_zero_db < 25.0;
    case Figure::T30: return u.depth_before_zero_db < 35.0;
    case Figure::C50:
    case Figure::D50: return early <= 0.050;
    case Figure::C80: return early <= 0.080;
    case Figure::Ts: return false;
  }
  return false;
}

}  // namespace

double figureJnd(Figure figure, double value) {
  switch (figure) {
    case Figure::Edt:
    case Figure::T20:
    case Figure::T30: return FilterLimit::kDecayTolerance * std::abs(value);
    case Figure::C50:
    case Figure::C80: return 1.0;
    case Figure::D50: return 0.05;
    case Figure::Ts: return 0.010;
  }
  return kNaN;
}

BandUncertainty::Flag BandUncertainty::flag() const {
  if (negative_energy) return Flag::NegativeEnergy;
  for (std::size_t i = 0; i < negative.size(); ++i)
    if (negative[i]) return Flag::NegativeEnergy;
  for (bool n : noisy)
    if (n) return Flag::Noisy;
  return Flag::Ok;
}

const char* BandUncertainty::flagName() const {
  switch (flag()) {
    case Flag::Ok: return "ok";
    case Flag::Noisy: return "noisy";
    case Flag::NegativeEnergy: return "negative_energy";
  }
  return "ok";
}

std::vector<BandUncertainty> jackknifeMetrics(const EnergyResponse& response) {
  const int nb = response.bands.size();
  DIFFRAY_CHECK(static_cast<int>(response.traced.size()) == nb);
  DIFFRAY_CHECK(response.batches.size() == response.batch_weights.size());
  std::vector<std::vector<double>> total;
  for (int b = 0; b < nb; ++b) total.push_back(response.total(b));
  std::vector<BandUncertainty> out(static_cast<std::size_t>(nb));
  for (int b = 0; b < nb; ++b) {
    BandUncertainty& u = out[static_cast<std::size_t>(b)];
    double neg = 0.0, all = 0.0;
    for (double e : response.traced[static_cast<std::size_t>(b)]) {
      all += std::abs(e);
      if (e < 0.0) neg -= e;
    }
    u.negative_fraction = all > 0.0 ? neg / all : 0.0;
    const std::vector<double>& e = total[static_cast<std::size_t>(b)];
    bool any_negative = false;
    for (double v : e) {
      u.energy += v;
      u.abs_energy += std::abs(v);
      any_negative |= v < 0.0;
    }
    u.negative_energy = any_negative && !(u.energy > 0.0);
    // The Schroeder curve (backward sum) at each bin's start: the first time it is below zero, and how far
    // the decay has fallen by then. That depth is read on the backward sum of the positive energy alone:
    // the signed curve falls steeply into its zero by cancellation, however shallow the decay there.
    std::vector<double> tail(e.size() + 1, 0.0), positive(e.size() + 1, 0.0);
    for (std::size_t i = e.size(); i-- > 0;) {
      tail[i] = tail[i + 1] + e[i];
      positive[i] = positive[i + 1] + std::max(0.0, e[i]);
    }
    for (std::size_t i = 0; i < e.size() && tail[0] > 0.0; ++i)
      if (tail[i] < 0.0) {
        u.schroeder_zero_s = static_cast<double>(i) * response.bin_s;
        u.depth_before_zero_db = 10.0 * std::log10(positive[0] / positive[i]);
        break;
      }
  }
  {
    std::vector<double> broadband(total.empty() ? 0 : total[0].size(), 0.0);
    for (const auto& band : total)
      for (std::size_t i = 0; i < band.size(); ++i) broadband[i] += band[i];
    const long onset = onsetBin(broadband);
    for (auto& u : out) u.onset_s = onset >= 0 ? static_cast<double>(onset) * response.bin_s : kNaN;
  }
  // Replicates: the whole without batch k, its traced part scaled back to all the rays.
  const std::size_t nk = response.batches.size();
  if (nk < 2) return out;
  double weight_sum = 0.0;
  for (double w : response.batch_weights) weight_sum += w;
  std::vector<std::vector<double>> traced_sum(static_cast<std::size_t>(nb),
                                              std::vector<double>(total.empty() ? 0 : total[0].size(), 0.0));
  for (const auto& batch : response.batches)
    for (int b = 0; b < nb; ++b)
      for (std::size_t i = 0; i < traced_sum[b].size(); ++i) traced_sum[b][i] += batch[b][i];
  // theta[b][figure][k]; the decay range as an eighth figure.
  std::vector<std::array<std::vector<double>, 8>> theta(static_cast<std::size_t>(nb));
  // Per band and bin edge, the replicates' Schroeder levels: their sum, sum of squares and count (finite ones).
  std::vector<std::vector<double>> level_sum(static_cast<std::size_t>(nb)), level_sq(static_cast<std::size_t>(nb));
  std::vector<std::vector<int>> level_n(static_cast<std::size_t>(nb));
  const std::vector<BandMetrics> whole = metricsFromHistograms(total, response.bin_s);
  for (std::size_t k = 0; k < nk; ++k) {
    const double n_k = response.batch_weights[k];
    if (!(n_k > 0.0 && n_k < weight_sum)) continue;
    const double up = n_k / (weight_sum - n_k);
    std::vector<std::vector<double>> rep = total;
    for (int b = 0; b < nb; ++b)
      for (std::size_t i = 0; i < rep[b].size(); ++i) {
        const double bk = response.batches[k][b][i];
        rep[b][i] += -bk + (traced_sum[b][i] - bk) * up;
      }
    const std::vector<BandMetrics> m = metricsFromHistograms(rep, response.bin_s);
    for (int b = 0; b < nb; ++b) {
      for (Figure f : kAllFigures) {
        const double v = m[b].value(f);
        theta[b][static_cast<std::size_t>(f)].push_back(v);
        if (!std::isfinite(v) && std::isfinite(whole[b].value(f))) ++out[b].unmeasurable[static_cast<std::size_t>(f)];
      }
      theta[b][7].push_back(m[b].decay_range_db);
      const std::vector<double> level = schroederLevels(rep[b]);
      level_sum[b].resize(level.size(), 0.0);
      level_sq[b].resize(level.size(), 0.0);
      level_n[b].resize(level.size(), 0);
      for (std::size_t i = 0; i < level.size() && std::isfinite(level[i]); ++i) {
        level_sum[b][i] += level[i];
        level_sq[b][i] += level[i] * level[i];
        ++level_n[b][i];
      }
    }
  }
  for (int b = 0; b < nb; ++b) {
    BandUncertainty& u = out[static_cast<std::size_t>(b)];
    u.replicates = static_cast<int>(theta[b][0].size());
    for (Figure f : kAllFigures) {
      const std::size_t i = static_cast<std::size_t>(f);
      // A figure that some replicate cannot measure has no standard error: it is flagged instead.
      u.se[i] = u.unmeasurable[i] ? kNaN : jackknifeSe(theta[b][i]);
    }
    u.decay_range_se = jackknifeSe(theta[b][7]);
    // How deep the Schroeder curve reaches before the jackknife SE of its level exceeds kLevelSeLimitDb:
    // below that depth the decay is carried by too few rays to be read.
    const std::vector<double> level = schroederLevels(total[static_cast<std::size_t>(b)]);
    double depth = 0.0;
    for (std::size_t i = 0; i < level.size() && i < level_n[b].size() && std::isfinite(level[i]); ++i) {
      const double n = level_n[b][i];
      if (n < u.replicates) break;  // some replicate has no energy left here
      const double mean = level_sum[b][i] / n;
      const double var = std::max(0.0, level_sq[b][i] / n - mean * mean) * (n - 1.0);  // jackknife: (n−1)/n·Σ(θ−θ̄)²
      if (std::sqrt(var) > kLevelSeLimitDb) break;
      depth = std::max(depth, -level[i]);
    }
    if (u.replicates >= 2) u.monte_carlo_range_db = depth;
  }
  return out;
}

std::vector<BandUncertainty> markMetrics(std::vector<BandMetrics>& metrics, const std::vector<BandUncertainty>& u,
                                         const std::vector<BandUncertainty>* histogram_marks) {
  DIFFRAY_CHECK(metrics.size() == u.size() && (!histogram_marks || histogram_marks->size() == u.size()));
  std::vector<BandUncertainty> out = u;
  for (std::size_t b = 0; b < u.size(); ++b) {
    BandUncertainty& m = out[b];
    BandMetrics& bm = metrics[b];
    // The decay range reaches no deeper than the Monte-Carlo noise lets the curve be read; the standard
    // error of the curve's own depth says nothing about that limit, so the capped range has none.
    if (std::isfinite(m.monte_carlo_range_db) && bm.decay_range_db > m.monte_carlo_range_db) {
      bm.decay_range_db = m.monte_carlo_range_db;
      m.decay_range_se = kNaN;
    }
    if (m.negative_energy) {
      BandMetrics none;
      none.shorter_than_filter = bm.shorter_than_filter;
      bm = none;
    }
    for (Figure f : kAllFigures) {
      const std::size_t i = static_cast<std::size_t>(f);
      // A figure the negative energy cuts is not given even when the metrics computed one: a curve that
      // falls into its zero by cancellation reads as a steep decay.
      if ((histogram_marks && (*histogram_marks)[b].isNegative(f)) ||
          (!bm.shorter_than_filter && (m.negative_energy || blockedByZero(m, f)))) {
        setValue(bm, f, kNaN);
        m.negative[i] = true;
        m.se[i] = kNaN;
        continue;
      }
      const double v = bm.value(f);
      m.noisy[i] = std::isfinite(v) && (m.unmeasurable[i] > 0 || m.se[i] > figureJnd(f, v));
      if (!std::isfinite(v)) m.se[i] = kNaN;  // no standard error for a figure not given
    }
  }
  return out;
}

std::vector<std::string> uncertaintyWarnings(const std::string& listener, const core::Bands& bands,
                                             const std::vector<BandMetrics>& metrics,
                                             const std::vector<BandUncertainty>& u) {
  DIFFRAY_CHECK(metrics.size() == u.size() && static_cast<int>(u.size()) == bands.size());
  std::vector<std::string> out;
  for (int b = 0; b < bands.size(); ++b) {
    const BandUncertainty& m = u[static_cast<std::size_t>(b)];
    if (m.flag() == BandUncertainty::Flag::Ok) continue;
    std::string w = "listener " + listener + ", " + bands.label(b) + " Hz: ";
    char text[200];
    if (m.negative_energy) {
      std::snprintf(text, sizeof text, "energy sums negative (%.3g of %.3g in absolute value): metrics not available",
                    m.energy, m.abs_energy);
      w += text;
    } else {
      std::string parts, missing;
      for (Figure f : kAllFigures) {
        const std::size_t i = static_cast<std::size_t>(f);
        if (m.negative[i]) missing += (missing.empty() ? "" : ", ") + displayName(f);
        if (!m.noisy[i]) continue;
        const double v = metrics[static_cast<std::size_t>(b)].value(f);
        if (!parts.empty()) parts += "; ";
        if (m.unmeasurable[i] > 0) {
          std::snprintf(text, sizeof text, "%s not measurable in %d of %d jackknife replicates", displayName(f).c_str(),
                        m.unmeasurable[i], m.replicates);
          parts += text;
        } else {
          parts += displayName(f) + " standard error " + withUnit(f, m.se[i]) + " exceeds its JND (" +
                   withUnit(f, figureJnd(f, v)) + ")";
        }
      }
      if (!missing.empty()) {
        std::snprintf(text, sizeof text, "the energy decay curve falls to zero or below at %.3f s (negative energy): ",
                      m.schroeder_zero_s);
        w += text + missing + " not available" + (parts.empty() ? "" : "; ");
      }
      w += parts;
    }
    out.push_back(w + "; trace more rays");
  }
  return out;
}

void addUncertaintyJson(nlohmann::ordered_json& bands_json, const core::Bands& bands,
                        const std::vector<BandUncertainty>& u) {
  DIFFRAY_CHECK(static_cast<int>(u.size()) == bands.size());
  const auto value = [](double v) {
    return std::isfinite(v) ? nlohmann::ordered_json(v) : nlohmann::ordered_json(nullptr);
  };
  for (int b = 0; b < bands.size(); ++b) {
    const BandUncertainty& m = u[static_cast<std::size_t>(b)];
    nlohmann::ordered_json& j = bands_json[bands.label(b)];
    nlohmann::ordered_json se = nlohmann::ordered_json::object();
    for (Figure f : kAllFigures) se[figureName(f)] = value(m.standardError(f));
    se["decay_range_db"] = value(m.decay_range_se);
    j["se"] = se;
    j["flag"] = m.flagName();
    nlohmann::ordered_json noisy = nlohmann::ordered_json::array(), negative = nlohmann::ordered_json::array();
    for (Figure f : kAllFigures) {
      if (m.isNoisy(f)) noisy.push_back(figureName(f));
      if (m.isNegative(f)) negative.push_back(figureName(f));
    }
    if (!noisy.empty()) j["noisy"] = noisy;
    if (!negative.empty()) j["not_available_negative_energy"] = negative;
    j["negative_energy_fraction"] = m.negative_fraction;
  }
}

}  // namespace diffray::ir
