// Sound strength G (ir/strength.h): a free-field arrival at r reads 20·log10(10/r) (ISO 3382-1's reference
// is the same source at 10 m), traced energy and arrivals add, and the standard error from the batches
// against the variance of a sum of independent batch estimates worked out here.
#include <gtest/gtest.h>

#include <cmath>

#include "diffray/core/error.h"
#include "diffray/ir/strength.h"

namespace {

namespace ir = diffray::ir;

ir::EnergyResponse emptyResponse(int bins) {
  ir::EnergyResponse r;
  r.bands = diffray::core::Bands::octave();
  r.traced.assign(static_cast<std::size_t>(r.bands.size()), std::vector<double>(static_cast<std::size_t>(bins), 0.0));
  return r;
}

TEST(IrStrength, AFreeFieldArrivalReadsItsDistanceFromTenMetres) {
  for (double r_m : {1.0, 2.5, 10.0, 40.0}) {
    ir::EnergyResponse resp = emptyResponse(100);
    ir::Arrival direct;
    direct.energy = diffray::core::bandFill(2.0 / (r_m * r_m));  // a 2 W source
    resp.arrivals.push_back(direct);
    for (const ir::Strength& s : ir::strengthPerBand(resp, 2.0)) {
      EXPECT_NEAR(s.g_db, 20.0 * std::log10(10.0 / r_m), 1e-12) << r_m;
      EXPECT_TRUE(std::isnan(s.se_db));  // no batches: no standard error
    }
  }
}

TEST(IrStrength, TracedEnergyAddsAndItsBatchesGiveTheStandardError) {
  // Traced energy 0.03 J/m² in four equal batches 0.006, 0.008, 0.007, 0.009; arrivals 0.01. Each batch
  // alone estimates the traced total as 4·B_k: 0.024, 0.032, 0.028, 0.036 (mean 0.03, sample variance
  // 2.667e-5); the total's variance is that over 4, se = 2.582e-3, and se(G) = 4.3429·se/E with E = 0.04.
  ir::EnergyResponse resp = emptyResponse(10);
  const double batch[4] = {0.006, 0.008, 0.007, 0.009};
  for (int k = 0; k < 4; ++k) {
    resp.batches.push_back(std::vector<std::vector<double>>(resp.traced.size(), std::vector<double>(10, 0.0)));
    resp.batch_weights.push_back(25000.0);  // rays per batch: only their shares matter
    for (std::size_t b = 0; b < resp.traced.size(); ++b) {
      resp.batches.back()[b][3] = batch[k];
      resp.traced[b][3] += batch[k];
    }
  }
  ir::Arrival a;
  a.energy = diffray::core::bandFill(0.01);
  resp.arrivals.push_back(a);
  const double sample_var = (0.006 * 0.006 + 0.002 * 0.002 + 0.002 * 0.002 + 0.006 * 0.006) / 3.0;
  const double se_e = std::sqrt(sample_var / 4.0);
  for (const ir::Strength& s : ir::strengthPerBand(resp, 1.0)) {
    EXPECT_NEAR(s.g_db, 10.0 * std::log10(0.04 * 100.0), 1e-12);
    EXPECT_NEAR(s.se_db, 10.0 / std::log(10.0) * se_e / 0.04, 1e-12);
  }
}

TEST(IrStrength, NegativeEnergyHasNoStrengthAndPowerMustBePositive) {
  ir::EnergyResponse resp = emptyResponse(4);
  resp.traced[0][1] = -1e-3;
  EXPECT_TRUE(std::isnan(ir::strengthPerBand(resp, 1.0)[0].g_db));
  EXPECT_THROW(ir::strengthPerBand(resp, 0.0), diffray::core::InputError);
}

}  // namespace
