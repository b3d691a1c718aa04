#pragma once
// What the tracer hands to IR synthesis and to the metrics (style.md: reconstruction kept apart from
// tracing): per band, the energy arriving at one listener, in J/m² (a 1 W omni source gives 1/r² at r in
// free field), as a histogram of the traced (diffuse, late) part with bin width bin_s and time 0 at
// emission, plus the exact arrivals (direct sound and image-source reflections) with their exact delays.
// The two never count the same path (transport/room_tracer.h). Plain data.
#include <vector>

#include "diffray/core/bands.h"
#include "diffray/core/math.h"

namespace diffray::ir {

struct Arrival {
  double delay_s = 0.0;
  core::BandArray energy = core::bandFill(0.0);  ///< per band, J/m²
  int order = 0;                                  ///< reflection order (0 = direct sound)
  /// Unit vector from the listener towards where the arrival comes from (its last image source or
  /// diffracting point), world frame; zero when not known.
  core::Vec3 direction{0, 0, 0};
};

struct EnergyResponse {
  core::Bands bands;
  double bin_s = 0.001;
  std::vector<std::vector<double>> traced;  ///< [band][bin], J/m² per bin, arrivals excluded
  std::vector<Arrival> arrivals;
  /// The traced part again, split into independent batches of rays: [batch][band][bin], Σ over batches =
  /// traced; batch_weights[k] is batch k's share (its rays). Empty when the tracer kept none. For the
  /// metrics' standard errors (ir/uncertainty.h).
  std::vector<std::vector<std::vector<double>>> batches;
  std::vector<double> batch_weights;
  /// Where the traced part comes from (receiver/direction_histogram.h), [band][bin]: the energy-weighted sum
  /// of unit vectors towards its arrivals, world frame, J/m²; empty when not recorded.
  std::vector<std::vector<core::Vec3>> directions;

  int bins() const { return traced.empty() ? 0 : static_cast<int>(traced[0].size()); }
  /// traced + arrivals binned: the band's whole energy histogram (what the metrics are computed from).
  std::vector<double> total(int band) const {
    std::vector<double> h = traced[band];
    for (const Arrival& a : arrivals) {
      const auto i = static_cast<long>(a.delay_s / bin_s);
      if (i >= 0 && i < static_cast<long>(h.size())) h[i] += a.energy[band];
    }
    return h;
  }
};

}  // namespace diffray::ir
