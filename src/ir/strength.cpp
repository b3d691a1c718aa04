// Sound strength G per band and its standard error over the ray batches (see the header).
#include "diffray/ir/strength.h"

#include <cmath>
#include <limits>

#include "diffray/core/error.h"

namespace diffray::ir {

std::vector<Strength> strengthPerBand(const EnergyResponse& response, double total_power_w) {
  core::requirePositive("source power", total_power_w);
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  const double e10 = total_power_w / 100.0;
  const int nb = static_cast<int>(response.traced.size());
  std::vector<Strength> out(static_cast<std::size_t>(nb));
  const std::size_t nk = response.batches.size();
  for (int b = 0; b < nb; ++b) {
    double traced = 0.0, arrivals = 0.0;
    for (double v : response.traced[static_cast<std::size_t>(b)]) traced += v;
    for (const Arrival& a : response.arrivals) arrivals += a.energy[b];
    const double e = traced + arrivals;
    Strength& s = out[static_cast<std::size_t>(b)];
    s.g_db = e > 0.0 ? 10.0 * std::log10(e / e10) : kNaN;
    s.se_db = kNaN;
    if (!(e > 0.0) || nk < 2 || response.batch_weights.size() != nk) continue;
    double weight_sum = 0.0;  // the weights are the batches' rays: their shares are w_k/Σw
    for (double w : response.batch_weights) weight_sum += w;
    if (!(weight_sum > 0.0)) continue;
    double var = 0.0;
    for (std::size_t k = 0; k < nk; ++k) {
      double bk = 0.0;
      for (double v : response.batches[k][static_cast<std::size_t>(b)]) bk += v;
      const double w = response.batch_weights[k] / weight_sum;
      if (!(w > 0.0)) continue;
      var += w * w * (bk / w - traced) * (bk / w - traced);
    }
    var *= static_cast<double>(nk) / static_cast<double>(nk - 1);
    s.se_db = 10.0 / std::log(10.0) * std::sqrt(var) / e;
  }
  return out;
}

void addStrengthJson(nlohmann::ordered_json& bands_json, const core::Bands& bands, const std::vector<Strength>& g) {
  const auto value = [](double v) { return std::isfinite(v) ? nlohmann::ordered_json(v) : nlohmann::ordered_json(); };
  for (int b = 0; b < bands.size() && b < static_cast<int>(g.size()); ++b) {
    auto& entry = bands_json[bands.label(b)];
    entry["g_db"] = value(g[static_cast<std::size_t>(b)].g_db);
    if (entry.contains("se") && entry["se"].is_object()) entry["se"]["g_db"] = value(g[static_cast<std::size_t>(b)].se_db);
  }
}

}  // namespace diffray::ir
