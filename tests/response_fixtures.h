#pragma once
// Shared by the spatial synthesis and decoding tests: an energy response (octave bands, 1 ms bins) holding
// one arrival of energy 1 J/m² in every band, at `delay_s` from unit direction `direction`, and no traced
// part; the interaural lag of two ear signals by brute-force cross-correlation.
#include <vector>

#include "diffray/ir/response.h"

namespace diffray::test {

inline ir::EnergyResponse singleArrival(double delay_s, const core::Vec3& direction) {
  ir::EnergyResponse r;
  r.bands = core::Bands::octave();
  r.bin_s = 0.001;
  ir::Arrival a;
  a.delay_s = delay_s;
  a.energy = core::bandFill(1.0);
  a.direction = direction;
  r.arrivals.push_back(a);
  return r;
}

/// The lag (samples, left relative to right) of the largest cross-correlation of the ears within ±1 ms at
/// 48 kHz: negative when the left ear leads.
inline int interauralLagSamples(const std::vector<double>& l, const std::vector<double>& r) {
  int best = 0;
  double best_v = -1e300;
  for (int lag = -48; lag <= 48; ++lag) {
    double v = 0.0;
    for (int t = 0; t < static_cast<int>(l.size()); ++t) {
      const int u = t - lag;
      if (u >= 0 && u < static_cast<int>(r.size())) v += l[static_cast<std::size_t>(t)] * r[static_cast<std::size_t>(u)];
    }
    if (v > best_v) best_v = v, best = lag;
  }
  return best;
}

}  // namespace diffray::test
