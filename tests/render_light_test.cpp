// The light tracer (render/light_tracer.h) against closed forms written here, sharing no code with it:
//  - a diffuse wall under a point light: mean radiance over each pixel = (1/Ω_pix) ∫ (ρ/π)·I cosθ/r² dω, the
//    irradiance E = I cosθ/r² of an isotropic point source, integrated over the pixel by Gauss–Legendre in
//    image-plane coordinates (dω = dX dY/(1 + X² + Y²)^{3/2});
//  - Young's double slit under a collimated laser: wall irradiance E(x) = I₀·|T(u)|²·cos³θ/(λL) with the
//    Fraunhofer transform |T(u)|² = 4a² cos²(πdu) sinc²(au), u = sinθ/λ, θ = atan(x/L) (Goodman, ch. 4; the
//    power per unit u mapped to wall length by du/dx = cos³θ/(λL)), times ρ/π, averaged over each pixel.
// Tolerances come from each pixel's standard error (chunk-to-chunk scatter, receiver/screen.h), fixed seeds.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "diffray/core/math.h"
#include "diffray/core/parallel.h"
#include "diffray/render/light_scene.h"
#include "diffray/render/light_setup.h"
#include "diffray/render/light_tracer.h"
#include "render_fixtures.h"

namespace {

namespace dr = diffray::render;
using diffray::core::Vec3;
constexpr double kPi = 3.14159265358979323846;

using render_fixtures::pixelMean;

struct Comparison {
  double chi2_per_dof = 0, max_abs_z = 0, mean_ratio = 0, mean_ratio_sigma = 0, max_err_over_peak = 0;
};

TEST(StatRenderEnergy, DiffuseWallUnderPointLightMatchesIrradiance) {
  // Wall z = 0 (1.6 × 1.2 m, ρ = 0.5) under an isotropic white point light of intensity I = 1 W/sr, seen by a
  // camera at z = 2 looking down −z. Every photon is aimed at the wall.
  dr::LightScene s;
  dr::DiffuseRect wall;
  wall.name = "wall";
  wall.frame = dr::rectFrame(Vec3(0, 0, 0), Vec3(0, 0, 1), Vec3(0, 1, 0), "wall");
  wall.half_x_m = 0.8, wall.half_y_m = 0.6;
  wall.albedo.values = {0.5};
  s.rects.push_back(wall);
  dr::Light light;
  light.kind = dr::Light::Kind::Point;
  light.spectrum.kind = dr::Spectrum::Kind::White;
  const Vec3 lp(0.3, 0.2, 1.0);
  light.position_m = lp;
  light.power_w = 4.0 * kPi;  // I = 1 W/sr
  light.aim = 0;
  s.lights.push_back(light);
  s.camera.position_m = Vec3(0, 0, 2);
  s.camera.look_at_m = Vec3(0, 0, 0);
  s.camera.up = Vec3(0, 1, 0);
  s.camera.fov_x_deg = 2.0 * std::atan(0.7 / 2.0) * 180.0 / kPi;  // the image spans x ∈ ±0.7 m on the wall
  s.camera.width = 14;
  s.camera.height = 10;
  const auto ps = dr::prepareScene(s);
  dr::RenderOptions o;
  o.photons = 600'000;
  o.seed = 7;
  const dr::RenderResult r = dr::renderLight(*ps, o);

  // Camera basis looking down −z with y up: right = f × up = (0,0,−1)×(0,1,0) = (1,0,0).
  const Vec3 fwd(0, 0, -1), up(0, 1, 0), right(1, 0, 0), cam(0, 0, 2);
  auto radiance = [&](const Vec3& d) {
    const Vec3 q = cam + (cam.z() / -d.z()) * d;  // the wall point seen along d
    const Vec3 to_light = lp - q;
    const double r2 = to_light.squaredNorm();
    return 0.5 / kPi * 1.0 * (to_light.z() / std::sqrt(r2)) / r2;  // ρ/π · I cosθ/r²
  };
  double chi2 = 0, max_z = 0, sum_ratio = 0, sum_var = 0;
  const int n = r.width * r.height;
  for (int iy = 0; iy < r.height; ++iy)
    for (int ix = 0; ix < r.width; ++ix) {
      const double expect = pixelMean(s.camera, right, up, fwd, ix, iy, radiance);
      const double got = r.pixelRadiance(ix, iy), se = r.pixelStdError(ix, iy);
      ASSERT_GT(se, 0.0);
      const double z = (got - expect) / se;
      chi2 += z * z;
      max_z = std::max(max_z, std::abs(z));
      sum_ratio += got / expect;
      sum_var += (se / expect) * (se / expect);
    }
  const double mean_ratio = sum_ratio / n, sigma = std::sqrt(sum_var) / n;
  std::printf("energy: chi2/dof %.3f, max |z| %.2f, mean ratio %.5f ± %.5f, photons %llu\n", chi2 / n, max_z,
              mean_ratio, sigma, static_cast<unsigned long long>(r.photons));
  // Each pixel within 4.5 σ (140 pixels); χ²/dof within 5 standard deviations of its mean 1 (sd √(2/n));
  // the mean ratio (normalisation of the whole chain: power, aiming weight, spectral weight, G-term, Ω_pix)
  // within 4 σ of 1.
  EXPECT_LT(max_z, 4.5);
  EXPECT_NEAR(chi2 / n, 1.0, 5.0 * std::sqrt(2.0 / n));
  EXPECT_NEAR(mean_ratio, 1.0, 4.0 * sigma);
  EXPECT_LT(sigma, 0.01);  // the test has the power to see a 4 % normalisation error
  // Every photon was aimed at the wall: none escapes.
  EXPECT_EQ(r.escaped, 0.0);
}

TEST(StatRenderDoubleSlit, CentralRowMatchesFraunhofer) {
  // Double slit a = 50 µm, d = 250 µm at z = 0 (uniform along y), a 633 nm laser beam 0.3 mm × 4 mm along
  // +z on it, a white wall (ρ = 1) at L = 2 m; the camera at z = 1 m looks at the wall, 96 × 6 pixels over
  // x ∈ ±30 mm on the wall.
  const double a = 50e-6, d = 250e-6, lambda = 633e-9, L = 2.0, beam_w = 0.3e-3, beam_h = 4e-3, power = 1.0;
  dr::LightScene s;
  dr::DiffuseRect wall;
  wall.frame = dr::rectFrame(Vec3(0, 0, L), Vec3(0, 0, -1), Vec3(0, 1, 0), "wall");
  wall.half_x_m = 0.04, wall.half_y_m = 0.01;
  wall.albedo.values = {1.0};
  s.rects.push_back(wall);
  dr::OccluderSpec slits;
  slits.kind = dr::OccluderSpec::Kind::DoubleSlit;
  slits.frame = dr::rectFrame(Vec3(0, 0, 0), Vec3(0, 0, 1), Vec3(0, 1, 0), "slits");
  slits.half_x_m = 1e-3, slits.half_y_m = 3e-3;
  slits.slit_width_m = a, slits.spacing_m = d;
  s.occluders.push_back(slits);
  dr::Light laser;
  laser.kind = dr::Light::Kind::Collimated;
  laser.spectrum.kind = dr::Spectrum::Kind::Laser;
  laser.spectrum.wavelength_nm = lambda * 1e9;
  laser.position_m = Vec3(0, 0, -0.01);
  laser.frame = dr::rectFrame(laser.position_m, Vec3(0, 0, 1), Vec3(0, 1, 0), "laser");
  laser.half_x_m = 0.5 * beam_w, laser.half_y_m = 0.5 * beam_h;
  laser.power_w = power;
  s.lights.push_back(laser);
  s.camera.position_m = Vec3(0, 0, 1.0);
  s.camera.look_at_m = Vec3(0, 0, 2.0);
  s.camera.up = Vec3(0, 1, 0);
  s.camera.fov_x_deg = 2.0 * std::atan(0.03 / 1.0) * 180.0 / kPi;
  s.camera.width = 96;
  s.camera.height = 6;
  const auto ps = dr::prepareScene(s);
  dr::RenderOptions o;
  o.photons = 1'500'000;
  o.seed = 3;
  const dr::RenderResult r = dr::renderLight(*ps, o);

  const double I0 = power / (beam_w * beam_h);
  auto irradiance = [&](double x) {  // the Fraunhofer oracle (see the file comment)
    const double theta = std::atan(x / L), u = std::sin(theta) / lambda;
    const double au = kPi * a * u;
    const double sinc = std::abs(au) < 1e-12 ? 1.0 : std::sin(au) / au;
    const double T2 = 4.0 * a * a * std::pow(std::cos(kPi * d * u), 2) * sinc * sinc;
    return I0 * T2 * std::pow(std::cos(theta), 3) / (lambda * L);
  };
  // Looking along +z with y up: right = (0,0,1)×(0,1,0) = (−1,0,0).
  const Vec3 fwd(0, 0, 1), up(0, 1, 0), right(-1, 0, 0), cam(0, 0, 1.0);
  auto radiance = [&](const Vec3& dir) {
    const Vec3 q = cam + ((L - cam.z()) / dir.z()) * dir;
    return 1.0 / kPi * irradiance(q.x());
  };
  // Each column: the mean over the image's rows (the pattern does not depend on y inside the beam).
  double chi2 = 0, max_z = 0, max_err = 0, peak = 0;
  std::vector<double> got(r.width), expect(r.width);
  for (int ix = 0; ix < r.width; ++ix) {
    double g = 0, var = 0, e = 0;
    for (int iy = 0; iy < r.height; ++iy) {
      g += r.pixelRadiance(ix, iy) / r.height;
      var += std::pow(r.pixelStdError(ix, iy) / r.height, 2);
      e += pixelMean(s.camera, right, up, fwd, ix, iy, radiance) / r.height;
    }
    const double z = (g - e) / std::sqrt(var);
    chi2 += z * z;
    max_z = std::max(max_z, std::abs(z));
    max_err = std::max(max_err, std::abs(g - e));
    peak = std::max(peak, e);
    got[ix] = g, expect[ix] = e;
  }
  std::printf("double slit: chi2/dof %.3f, max |z| %.2f, max error %.4f of peak, negative pixels %.4f, "
              "negative scores %.3f\n",
              chi2 / r.width, max_z, max_err / peak, r.negativePixelFraction(), r.negativeScoreFraction());
  EXPECT_LT(max_z, 4.5);
  EXPECT_NEAR(chi2 / r.width, 1.0, 5.0 * std::sqrt(2.0 / r.width));
  EXPECT_GT(r.negativeScoreFraction(), 0.05);  // the photons were signed; the pixels integrate them out
  // The dark fringes are dark: at the first minimum (x = λL/(2d)) the rendering is far below the peak.
  const int first_min = static_cast<int>((0.03 - 0.5 * lambda * L / d) / (0.06 / r.width));
  EXPECT_LT(got[first_min], 0.1 * peak);
}

TEST(RenderDeterminism, SameSeedSameImageForAnyThreadCount) {
  const dr::LightScene s = render_fixtures::wallUnderPointLight(8, 8);
  const auto ps = dr::prepareScene(s);
  dr::RenderOptions o;
  o.photons = 40'000;
  o.chunk_photons = 1000;
  render_fixtures::expectSameImageForAnyThreadCount(*ps, o);
}

}  // namespace
