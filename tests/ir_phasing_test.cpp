// ir::synthesize's Phasing::Coherent (ir/synthesis.h), which the closing door's crossfades rely on.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "diffray/ir/synthesis.h"

namespace di = diffray::ir;

namespace {

// A direct arrival at 10 ms, a reflection at 17 ms, and an exponential tail (T = 0.4 s), scaled band by band.
di::EnergyResponse response(double tail_scale, double arrival_scale) {
  di::EnergyResponse r;
  r.bands = diffray::core::Bands::octave();
  r.bin_s = 0.001;
  r.traced.assign(r.bands.size(), std::vector<double>(500, 0.0));
  for (int b = 0; b < r.bands.size(); ++b)
    for (int i = 12; i < 500; ++i) r.traced[b][i] = tail_scale * 1e-3 * std::exp(-13.8 * i * 1e-3 / 0.4) * (1.0 + 0.05 * b);
  di::Arrival direct, reflection;
  direct.delay_s = 0.010;
  direct.energy = diffray::core::bandFill(arrival_scale * 0.01);
  reflection.delay_s = 0.017;
  reflection.energy = diffray::core::bandFill(arrival_scale * 0.004);
  reflection.order = 1;
  r.arrivals = {direct, reflection};
  return r;
}

}  // namespace

// With coherent phasing the synthesis is linear in the square roots of the energies, band by band: scaling the
// traced part's energy by s and the arrivals' by 1/s gives √s·h_traced + h_arrivals/√s exactly, h_traced and
// h_arrivals synthesized alone with the same seed. So neighbouring door steps differ only by such gains, and a
// crossfade between them mixes like signals. Orthogonal phasing turns the traced part to suit the arrivals of
// each response and is not linear: the same identity fails (the check has teeth).
TEST(SynthesisPhasing, CoherentIsLinearInAmplitudesOrthogonalIsNot) {
  using P = di::Phasing;
  di::EnergyResponse traced_only = response(1.0, 1.0), arrivals_only = response(1.0, 1.0);
  traced_only.arrivals.clear();
  for (auto& band : arrivals_only.traced) std::fill(band.begin(), band.end(), 0.0);
  const auto ht = di::synthesize(traced_only, 48000, 0.5, 100.0, 343.0, 5, P::Coherent);
  const auto ha = di::synthesize(arrivals_only, 48000, 0.5, 100.0, 343.0, 5, P::Coherent);
  for (double scale : {1.0, 0.7, 0.3}) {
    for (P phasing : {P::Coherent, P::Orthogonal}) {
      const auto h = di::synthesize(response(scale, 1.0 / scale), 48000, 0.5, 100.0, 343.0, 5, phasing);
      ASSERT_EQ(h.size(), ht.size());
      double peak = 0.0, worst = 0.0;
      for (std::size_t i = 0; i < h.size(); ++i) {
        peak = std::max(peak, std::abs(h[i]));
        worst = std::max(worst, std::abs(h[i] - (std::sqrt(scale) * ht[i] + ha[i] / std::sqrt(scale))));
      }
      if (phasing == P::Coherent) {
        EXPECT_LT(worst, 1e-9 * peak) << scale;
      } else {
        EXPECT_GT(worst, 1e-3 * peak) << scale;
      }
    }
  }
}
