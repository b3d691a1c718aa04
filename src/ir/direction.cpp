#include "diffray/ir/direction.h"

#include <cmath>

#include "diffray/core/error.h"
#include "diffray/ir/metrics.h"

namespace diffray::ir {

EarlyDirection earlyDirection(const EnergyResponse& response, int band, const core::Vec3& forward,
                              const core::Vec3& left, const core::Vec3& up, double window_s) {
  DIFFRAY_CHECK(band >= 0 && band < response.bands.size() && window_s > 0.0);
  EarlyDirection d;
  const std::vector<double> total = response.total(band);
  const long onset = onsetBin(total);
  if (onset < 0) return d;
  const double t0 = static_cast<double>(onset) * response.bin_s, t1 = t0 + window_s;
  core::Vec3 sum(0, 0, 0);
  for (const Arrival& a : response.arrivals) {
    if (a.delay_s < t0 || a.delay_s >= t1) continue;
    d.energy += a.energy[band];
    sum += a.energy[band] * a.direction;
  }
  const bool recorded = static_cast<int>(response.directions.size()) > band;
  for (long i = onset; i < static_cast<long>(total.size()); ++i) {
    const double start = static_cast<double>(i) * response.bin_s;
    if (start >= t1) break;
    // The last bin may stick out of the window: its share by time.
    const double share = std::min(1.0, (t1 - start) / response.bin_s);
    d.energy += share * response.traced[band][static_cast<std::size_t>(i)];
    if (recorded) sum += share * response.directions[band][static_cast<std::size_t>(i)];
  }
  const double n = sum.norm();
  if (!(d.energy > 0.0) || !(n > 0.0)) return d;
  d.world = sum / n;
  d.r_e = n / d.energy;
  const double x = d.world.dot(forward), y = d.world.dot(left), z = d.world.dot(up);
  d.azimuth_deg = std::atan2(y, x) * 180.0 / core::kPi;
  d.elevation_deg = std::asin(std::max(-1.0, std::min(1.0, z))) * 180.0 / core::kPi;
  return d;
}

}  // namespace diffray::ir
