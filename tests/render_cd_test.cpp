// `diffray validate image-cd` at reduced photons: a rendered CD's first order at 550 nm against the
// grating equation sinθ_1 = sinθ_i + λ/Λ and straight-line geometry (the case's oracle; it shares no code
// with the tracer). The test also checks the case's oracle itself against the textbook number (θ_1 = 20.1°
// at normal incidence) and that the centroid moves with the wavelength as the equation says.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "diffray/core/error.h"

#include "diffray/render/light_scene.h"
#include "diffray/render/light_setup.h"
#include "diffray/render/light_tracer.h"
#include "diffray/validate/case.h"
#include "validate_fixtures.h"

namespace {

using diffray::testing::runCase;

// The grating equation: 550 nm on Λ = 1.6 µm at normal incidence leaves at 20.1°, and lands within one
// pixel footprint of H·tan 20.1° on the ceiling 0.2 m above the CD.
TEST(RenderImageCd, FirstOrderLandsWhereTheGratingEquationSays) {
  const auto r = runCase("image-cd", 300'000);
  ASSERT_EQ(r.rows.size(), 1u);
  EXPECT_NEAR(r.extra.at("theta1_deg"), 20.1, 0.05);
  EXPECT_NEAR(r.extra.at("z_predicted_m"), 0.2 * std::tan(std::asin(550e-9 / 1.6e-6)), 1e-12);
  EXPECT_GE(r.extra.at("lobe_columns"), 2.0);  // the lobe is resolved, so the centroid is sub-pixel
  EXPECT_LE(r.max_abs_error_rel_peak, 1.0) << r.detail;
  EXPECT_TRUE(r.passed) << r.detail;
  // The check discriminates: a tracer sending 540 or 560 nm where 550 nm should go (a 10 nm error: the
  // order moves by ~1.6 mm, 2.5 footprints) would fail it. The rendered lobe lies more than two footprints
  // from both of those predictions (computed here, not by the case).
  const double footprint = r.extra.at("pixel_footprint_m"), z = r.extra.at("z_measured_m");
  for (const double wrong_nm : {540.0, 560.0}) {
    const double z_wrong = 0.2 * std::tan(std::asin(wrong_nm / 1600.0));
    EXPECT_GT(std::abs(z - z_wrong), 2.0 * footprint) << wrong_nm << " nm";
  }
}

// Oblique incidence and another wavelength: sinθ_1 = sin 10° + 450 nm / 1.6 µm.
TEST(RenderImageCd, ObliqueIncidenceFollowsTheGratingEquation) {
  const auto r = runCase("image-cd", 300'000, {{"wavelength", {450e-9}}, {"incidence", {10.0}}});
  EXPECT_NEAR(std::sin(r.extra.at("theta1_deg") * M_PI / 180.0), std::sin(10.0 * M_PI / 180.0) + 450.0 / 1600.0,
              1e-9);
  EXPECT_TRUE(r.passed) << r.detail;
}

// A grating's reflectance scales every reflected photon's energy and nothing else: with the same seed the
// random streams are identical, so the energy on the wall scales by exactly R and the rest is counted as
// absorbed by the occluder (the balance on_diffuse + absorbed_occluders + … is unchanged).
TEST(RenderGratingReflectance, ScalesReflectedEnergyExactly) {
  auto sceneText = [](double r) {
    return std::string(R"({"rectangles": [{"name": "wall", "centre": [0, 0.3, 0.2], "normal": [0, 0, -1],
      "width_m": 0.6, "height_m": 0.6}],
      "occluders": [{"type": "grating", "name": "cd", "centre": [0, 0, 0], "normal": [0, 1, 0], "up": [1, 0, 0],
      "width_m": 0.02, "height_m": 0.02, "period_m": 1.6e-6, "modulation": 3, "reflectance": )") +
           std::to_string(r) + R"(}],
      "lights": [{"type": "point", "position": [0, 1, -0.5], "aim": "cd"}],
      "camera": {"position": [0, 0.3, -0.5], "look_at": [0, 0.3, 0.2], "fov_deg": 40, "pixels": [16, 16]}})";
  };
  diffray::render::RenderOptions ro;
  ro.photons = 20000;
  ro.seed = 7;
  const auto full_scene = diffray::render::parseLightScene(sceneText(1.0), "full.json");
  const auto half_scene = diffray::render::parseLightScene(sceneText(0.5), "half.json");
  const auto full = diffray::render::renderLight(*diffray::render::prepareScene(full_scene, true), ro);
  const auto half = diffray::render::renderLight(*diffray::render::prepareScene(half_scene, true), ro);
  ASSERT_GT(std::abs(full.on_diffuse), 0.0);
  EXPECT_NEAR(half.on_diffuse, 0.5 * full.on_diffuse, 1e-12 * std::abs(full.on_diffuse));
  EXPECT_NEAR(half.escaped, 0.5 * full.escaped, 1e-12 * std::abs(full.escaped) + 1e-300);
  const double reflected = full.on_diffuse + full.escaped + full.evanescent + full.bounce_limit;
  EXPECT_NEAR(half.absorbed_occluders - full.absorbed_occluders, 0.5 * (reflected - full.evanescent),
              1e-9 * std::abs(reflected));
  EXPECT_THROW(diffray::render::parseLightScene(sceneText(1.5), "bad.json"), diffray::core::InputError);
}

}  // namespace
