// Uniform WBSDF shift sampling (WbsdfTable::sampleUniform, RenderOptions::uniform_shifts: the render-is
// bench's alternative to importance sampling) and the image-double-slit validation case.
// Oracles: the table's own cell masses summed exactly (the expectation both samplers must reach: they share
// no code with the sums), and the Fraunhofer pattern of validate/image_setup.h (reference/fraunhofer.h,
// independent of the renderer). Tolerances from each estimator's sample variance; fixed seeds.
#include <gtest/gtest.h>

#include <cmath>

#include "diffray/core/rng.h"
#include "diffray/render/light_tracer.h"
#include "diffray/validate/image_setup.h"
#include "diffray/wbsdf/microstructure.h"
#include "diffray/wbsdf/table.h"
#include "validate_fixtures.h"

namespace {

using namespace diffray;

TEST(StatWbsdfUniform, UniformAndImportanceSamplingAgreeInExpectation) {
  // A double-slit table; at x inside the right slit, the expectation of weight·[u' in a band of cells] is the
  // band's summed signed mass for either sampler.
  wbsdf::TableOptions o;
  o.wavelength_m = 600e-9;
  o.u_half_range_per_m = 0.02 / o.wavelength_m;
  const auto table = wbsdf::WbsdfTable::build(*wbsdf::Openings::slits(2, 50e-6, 250e-6), o);
  const auto& lay = table->layout();
  const double x = 125e-6 + 10e-6;
  const int row = static_cast<int>(std::floor((x - lay.x0_m) / lay.dx_m));
  // Bands: all cells, and cells [nu/2 + 3, nu/2 + 40) (covering fringes where W changes sign).
  for (auto [k0, k1] : {std::pair<int, int>{0, lay.nu}, std::pair<int, int>{lay.nu / 2 + 3, lay.nu / 2 + 40}}) {
    double exact = 0.0;
    for (int k = k0; k < k1; ++k) exact += table->mass(row, k);
    const double u_lo = lay.u0_per_m + k0 * lay.du_per_m, u_hi = lay.u0_per_m + k1 * lay.du_per_m;
    for (bool uniform : {false, true}) {
      core::Rng rng(11, uniform ? 2 : 1);
      const int n = 400'000;
      double sum = 0.0, sum_sq = 0.0;
      for (int i = 0; i < n; ++i) {
        const auto s = uniform ? table->sampleUniform(x, rng.uniform()) : table->sample(x, rng.uniform());
        const double f = s.u_shift >= u_lo && s.u_shift < u_hi ? s.weight : 0.0;
        sum += f;
        sum_sq += f * f;
      }
      const double mean = sum / n, se = std::sqrt(std::max(0.0, sum_sq / n - mean * mean) / n);
      ASSERT_GT(se, 0.0);
      EXPECT_NEAR(mean, exact, 4.5 * se) << (uniform ? "uniform" : "importance") << " band " << k0 << "–" << k1;
    }
  }
}

using diffray::testing::expectRowsMatch;

TEST(StatValidateImage, DoubleSlitCaseAtReducedPhotonsMatchesFraunhofer) {
  validate::DoubleSlitImageSetup s;  // rooms/light/double-slit.json, 480 × 160 pixels
  validate::ImageRunOptions o;
  o.photons = 2'000'000;
  o.seed = 5;
  const validate::CaseResult r = validate::runImageDoubleSlit(s, o);
  EXPECT_EQ(r.rows.size(), 480u);
  EXPECT_GE(r.extra.at("rows_averaged"), 30.0);  // the rows inside the 6 mm beam (0.166 mm per pixel)
  expectRowsMatch(r);
}

TEST(StatValidateImage, UniformShiftSamplingIsUnbiasedToo) {
  validate::DoubleSlitImageSetup s;
  s.width = 160;  // coarser pixels: the noisier estimator still resolves the pattern at few photons
  s.height = 54;
  validate::ImageRunOptions o;
  o.photons = 2'000'000;
  o.seed = 6;
  o.uniform_shifts = true;
  expectRowsMatch(validate::runImageDoubleSlit(s, o));
}

}  // namespace
