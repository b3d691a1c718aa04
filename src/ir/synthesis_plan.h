#pragma once
// Inside the IR synthesis (synthesis.cpp), for the syntheses that reuse what it drew and solved for the
// omnidirectional response (spatial_synthesis.cpp): the Dirac sequence, each band's final gain per bin,
// the traced part's turn per band and each arrival's complex coefficient per band. A channel built from the
// same plan with every direction weight 1 is the omnidirectional response itself. Plain data.
#include <complex>
#include <cstdint>
#include <vector>

#include "diffray/ir/synthesis.h"

namespace diffray::ir::detail {

struct SynthesisPlan {
  long samples = 0;
  long quiet = 0;     ///< the traced part is silent before this sample
  int fft_size = 0;   ///< the length of the FFT the band parts were filtered with
  std::vector<double> diracs;               ///< ±1 (or their sums) at each event's sample, the filled bins' included
  std::vector<long> bin_start;              ///< bin i covers samples bin_start[i] … bin_start[i+1] − 1
  std::vector<std::vector<double>> gains;   ///< [band][bin]: the final gain of the band's Diracs (empty: no traced part)
  /// [band][bin]: the energy of W's band part (the Diracs at their final gains, filtered, before the turn)
  /// in each bin, from sample `quiet` on
  std::vector<std::vector<double>> band_energy;
  std::vector<std::complex<double>> traced_turn;  ///< [band]: the traced part's rotation times its rescaling
  /// [arrival][band] (the response's arrival order): the coefficient of the band's unit pulse W_b·e^{−2πifτ};
  /// 0 for a band (or an arrival) not placed.
  std::vector<std::vector<std::complex<double>>> arrival_coefficients;
};

/// synthesize(), filling `plan` when it is not null.
std::vector<double> synthesizePlanned(const EnergyResponse& response, double sample_rate_hz, double length_s,
                                      double volume_m3, double speed_of_sound_m_s, std::uint64_t seed,
                                      Phasing phasing, SynthesisPlan* plan);

}  // namespace diffray::ir::detail
