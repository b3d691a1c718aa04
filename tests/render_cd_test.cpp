// `diffray validate image-cd` at reduced photons: a rendered CD's first order at 550 nm against the
// grating equation sinθ_1 = sinθ_i + λ/Λ and straight-line geometry (the case's oracle; it shares no code
// with the tracer). The test also checks the case's oracle itself against the number (θ_1 = 20.1°
// at normal incidence) and that the centroid moves with the wavelength as the equation says.
#include <gtest/gtest.h>

#include <cmath>

#include "diffray/validate/case.h"
#include "validate_fixtures.h"

namespace {

using diffray::testing::runCase;

// The figure: 550 nm on Λ = 1.6 µm at normal incidence leaves at 20.1°, and lands within one
// pixel footprint of H·tan 20.1° on the ceiling 0.2 m above the CD.
TEST(RenderImageCd, FirstOrderLandsWhereTheGratingEquationSays) {
  const auto r = runCase("image-cd", 300'000);
  ASSERT_EQ(r.rows.size(), 1u);
  EXPECT_NEAR(r.extra.at("theta1_deg"), 20.1, 0.05);
  EXPECT_NEAR(r.extra.at("z_predicted_m"), 0.2 * std::tan(std::asin(550e-9 / 1.6e-6)), 1e-12);
  EXPECT_GE(r.extra.at("lobe_columns"), 2.0);  // the lobe is resolved, so the centroid is sub-pixel
  EXPECT_LE(r.max_abs_error_rel_peak, 1.0) << r.detail;
  EXPECT_TRUE(r.passed) << r.detail;
}

// Oblique incidence and another wavelength: sinθ_1 = sin 10° + 450 nm / 1.6 µm.
TEST(RenderImageCd, ObliqueIncidenceFollowsTheGratingEquation) {
  const auto r = runCase("image-cd", 300'000, {{"wavelength", {450e-9}}, {"incidence", {10.0}}});
  EXPECT_NEAR(std::sin(r.extra.at("theta1_deg") * M_PI / 180.0), std::sin(10.0 * M_PI / 180.0) + 450.0 / 1600.0,
              1e-9);
  EXPECT_TRUE(r.passed) << r.detail;
}

}  // namespace
