// Area lights (render::Light::Kind::Area, render/light_tracer.h) against oracles written here, sharing no
// code with the tracer:
//  - the power a one-sided Lambertian rectangle sends onto a parallel, directly opposed equal rectangle is
//    P·F₁₂, F₁₂ the closed-form view factor of Howell's catalogue, configuration C-11 (J. R. Howell, "A
//    Catalog of Radiation Heat Transfer Configuration Factors", also Siegel & Howell, Thermal Radiation Heat
//    Transfer, appendix): X = a/c, Y = b/c,
//      F₁₂ = 2/(πXY)·{ ln[(1+X²)(1+Y²)/(1+X²+Y²)]^{1/2} + X√(1+Y²)·atan(X/√(1+Y²))
//                      + Y√(1+X²)·atan(Y/√(1+X²)) − X·atan X − Y·atan Y };
//    two-sided lights send half of that (P/2 from each face).
//  - partial spatial coherence (van Cittert–Zernike): a double slit (width a, spacing d) lit by an incoherent
//    strip of width s at distance D gives on a wall at L the source-averaged Fraunhofer pattern
//      E(X) = P/(πD²)·D/(D+L)·(1/s)∫ |T(u)|² cos³θ/(λL) dx_s,   u = (sinθ_out + x_s/√(x_s² + D²))/λ,
//    (P/(πD²): the irradiance of the Lambertian lamp on the slits; D/(D+L): the spreading along the slits,
//    which do not diffract along y; |T(u)|² = 4a² sinc²(πau) cos²(πdu)), whose fringe term is multiplied by
//    sinc(πds/(λD)) (small angles). The rendered row is compared with E(X) by quadrature, and the fitted
//    visibility with the closed-form sinc.
// Tolerances from the estimators' variances (binomial, run-to-run scatter, pixel standard errors); fixed seeds.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "diffray/core/error.h"
#include "diffray/core/math.h"
#include "diffray/core/parallel.h"
#include "diffray/reference/fraunhofer.h"
#include "diffray/render/light_scene.h"
#include "diffray/render/light_setup.h"
#include "diffray/render/light_tracer.h"
#include "render_fixtures.h"

namespace {

namespace dr = diffray::render;
using diffray::core::Vec3;
constexpr double kPi = 3.14159265358979323846;

// Howell C-11 (file comment): two parallel, directly opposed a × b rectangles a distance c apart.
double viewFactorOpposedRects(double a, double b, double c) {
  const double X = a / c, Y = b / c, X2 = X * X, Y2 = Y * Y;
  const double sx = std::sqrt(1 + X2), sy = std::sqrt(1 + Y2);
  // ln[(1+X²)(1+Y²)/(1+X²+Y²)] written as log1p(X²Y²/(1+X²+Y²)), the same number without the cancellation.
  return 2.0 / (kPi * X * Y) *
         (0.5 * std::log1p(X2 * Y2 / (1 + X2 + Y2)) + X * sy * std::atan(X / sy) +
          Y * sx * std::atan(Y / sx) - X * std::atan(X) - Y * std::atan(Y));
}

std::string vec(const Vec3& v) {
  std::ostringstream o;
  o.precision(17);
  o << "[" << v.x() << ", " << v.y() << ", " << v.z() << "]";
  return o.str();
}

// A tilted lamp a × b (laser line: every photon carries the same energy) facing a receiver c away along its
// normal, with the same up: the two rectangles coincide in projection.
struct Opposed {
  double a = 0.6, b = 0.4, c = 0.5, power_w = 2.0;
  Vec3 centre{0.1, -0.2, 0.3}, n = Vec3(1, 2, 2) / 3.0, up{0, 0, 1};
  dr::LightScene scene(bool aim, bool two_sided, double side = 1.0) const {
    const Vec3 rc = centre + side * c * n;
    std::ostringstream j;
    j << R"({"rectangles": [{"name": "receiver", "centre": )" << vec(rc) << R"(, "normal": )" << vec(-n)
      << R"(, "up": )" << vec(up) << R"(, "width_m": )" << a << R"(, "height_m": )" << b << R"(, "albedo": 0.5}],
      "lights": [{"type": "area", "name": "lamp", "centre": )" << vec(centre) << R"(, "normal": )" << vec(n)
      << R"(, "up": )" << vec(up) << R"(, "width_m": )" << a << R"(, "height_m": )" << b << R"(, "power_w": )"
      << power_w << R"(, "spectrum": "laser", "wavelength_nm": 550)"
      << (two_sided ? R"(, "two_sided": true)" : "") << (aim ? R"(, "aim": "receiver")" : "") << R"(}],
      "camera": {"position": )" << vec(rc + side * 2.0 * n) << R"(, "look_at": )" << vec(rc) << R"(,
                 "fov_deg": 30, "pixels": [2, 2]}})";
    return dr::parseLightScene(j.str(), "opposed.json");
  }
};

double onDiffuse(const dr::LightScene& s, std::uint64_t photons, std::uint64_t seed) {
  const auto ps = dr::prepareScene(s);
  dr::RenderOptions o;
  o.photons = photons;
  o.seed = seed;
  return dr::renderLight(*ps, o).on_diffuse;
}

TEST(RenderAreaLight, ViewFactorFormulaMatchesHowellsTable) {
  // The transcription of C-11 against Howell's tabulated values: a = b = c gives 0.1998; the limit of large
  // plates tends to 1, and of small ones to (ab/(πc²))·(1 − (a² + b²)/(3c²)) (cosθ₁cosθ₂/(πr²) expanded to
  // second order in the offsets, whose mean square across two plates is a²/6 and b²/6).
  EXPECT_NEAR(viewFactorOpposedRects(1, 1, 1), 0.1998, 1e-4);
  EXPECT_NEAR(viewFactorOpposedRects(1e3, 1e3, 1), 1.0, 3e-3);
  EXPECT_NEAR(viewFactorOpposedRects(0.01, 0.02, 1) / (2e-4 / kPi * (1 - 5e-4 / 3)), 1.0, 1e-6);
}

TEST(StatRenderAreaLight, PowerOnOpposedRectangleIsTheViewFactor) {
  const Opposed g;
  const double F = viewFactorOpposedRects(g.a, g.b, g.c);
  for (bool two_sided : {false, true}) {
    // Unaimed: each photon (energy P/N) lands with probability p = F (one-sided) or F/2 (two-sided), so the
    // received power is (P/N)·Binomial(N, p): σ = P·√(p(1 − p)/N).
    const double p = two_sided ? 0.5 * F : F;
    const std::uint64_t n = 400'000;
    const double got = onDiffuse(g.scene(false, two_sided), n, 11) / g.power_w;
    const double sigma = std::sqrt(p * (1 - p) / static_cast<double>(n));
    std::printf("view factor, %s, unaimed: expected %.5f, got %.5f (%.2f sigma, sigma %.5f)\n",
                two_sided ? "two-sided" : "one-sided", p, got, (got - p) / sigma, sigma);
    EXPECT_NEAR(got, p, 4.0 * sigma);
  }
  for (bool two_sided : {false, true}) {
    // Aimed: every photon lands, weight P·cosθ_x·cosθ_y·A/(π r²) (·1/2 two-sided); σ from the scatter of
    // K independent runs (different seeds).
    const double p = two_sided ? 0.5 * F : F;
    const int K = 16;
    double sum = 0, sum2 = 0;
    const dr::LightScene s = g.scene(true, two_sided);
    for (int k = 0; k < K; ++k) {
      const double v = onDiffuse(s, 25'000, 100 + k) / g.power_w;
      sum += v, sum2 += v * v;
    }
    const double mean = sum / K, sd = std::sqrt((sum2 - K * mean * mean) / (K - 1)), sigma = sd / std::sqrt(K);
    std::printf("view factor, %s, aimed: expected %.5f, got %.5f (%.2f sigma, sigma %.6f)\n",
                two_sided ? "two-sided" : "one-sided", p, mean, (mean - p) / sigma, sigma);
    EXPECT_NEAR(mean, p, 4.0 * sigma);
    EXPECT_LT(sigma, 0.01 * p);  // the check has the power to see a 4 % error
  }
}

TEST(RenderAreaLight, OneSidedLightSendsNothingBackward) {
  // The receiver behind the lamp's emitting face: nothing arrives, aimed (weight max(cosθ_x, 0) = 0) or not.
  const Opposed g;
  EXPECT_EQ(onDiffuse(g.scene(true, false, -1.0), 20'000, 5), 0.0);
  EXPECT_EQ(onDiffuse(g.scene(false, false, -1.0), 20'000, 5), 0.0);
  EXPECT_GT(onDiffuse(g.scene(true, true, -1.0), 20'000, 5), 0.0);
}

TEST(RenderAreaLight, ParsesEveryKey) {
  const Opposed g;
  const dr::LightScene s = g.scene(true, true);
  ASSERT_EQ(s.lights.size(), 1u);
  const dr::Light& l = s.lights[0];
  EXPECT_EQ(l.kind, dr::Light::Kind::Area);
  EXPECT_EQ(l.name, "lamp");
  EXPECT_TRUE(l.two_sided);
  EXPECT_EQ(l.aim, 0);
  EXPECT_EQ(l.spectrum.kind, dr::Spectrum::Kind::Laser);
  EXPECT_DOUBLE_EQ(l.spectrum.wavelength_nm, 550.0);
  EXPECT_DOUBLE_EQ(l.power_w, 2.0);
  EXPECT_DOUBLE_EQ(l.half_x_m, 0.3);
  EXPECT_DOUBLE_EQ(l.half_y_m, 0.2);
  EXPECT_LT((l.position_m - g.centre).norm(), 1e-15);
  EXPECT_LT((l.frame.n - g.n).norm(), 1e-15);
  EXPECT_NEAR(l.frame.ey.dot(g.n), 0.0, 1e-15);   // up projected on the plane
  EXPECT_GT(l.frame.ey.dot(g.up), 0.0);
  // Defaults: one-sided, white, no aim.
  const dr::LightScene d = dr::parseLightScene(
      R"({"rectangles": [{"centre": [0,0,0], "normal": [0,0,1], "width_m": 1, "height_m": 1}],
          "lights": [{"type": "area", "centre": [0,0,1], "normal": [0,0,-1], "width_m": 0.1, "height_m": 0.2}],
          "camera": {"position": [0,0,2], "look_at": [0,0,0], "fov_deg": 30, "pixels": [2, 2]}})",
      "d.json");
  EXPECT_FALSE(d.lights[0].two_sided);
  EXPECT_EQ(d.lights[0].spectrum.kind, dr::Spectrum::Kind::White);
  EXPECT_EQ(d.lights[0].aim, -1);
  EXPECT_EQ(d.lights[0].name, "area1");
}

TEST(RenderAreaLight, BadKeysAreOneLineErrorsNamingTheField) {
  auto error = [](const std::string& light) {
    try {
      dr::parseLightScene(
          R"({"rectangles": [{"name": "wall", "centre": [0,0,0], "normal": [0,0,1], "width_m": 1, "height_m": 1}],
              "lights": [{"type": "area", "centre": [0,0,1], )" + light + R"(}],
              "camera": {"position": [0,0,2], "look_at": [0,0,0], "fov_deg": 30, "pixels": [2, 2]}})",
          "bad.json");
    } catch (const diffray::core::InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const std::string ok = R"("normal": [0,0,-1], "width_m": 0.1, "height_m": 0.1)";
  EXPECT_NE(error(R"("normal": [0,0,-1], "width_m": 0, "height_m": 0.1)").find("lights[0].width_m"),
            std::string::npos);
  EXPECT_NE(error(R"("normal": [0,0,-1], "width_m": 0.1, "height_m": -1)").find("lights[0].height_m"),
            std::string::npos);
  EXPECT_NE(error(R"("normal": [0,0,0], "width_m": 0.1, "height_m": 0.1)").find("normal"), std::string::npos);
  EXPECT_NE(error(R"("normal": [0,1,0], "up": [0,2,0], "width_m": 0.1, "height_m": 0.1)").find("up"),
            std::string::npos);
  EXPECT_NE(error(ok + R"(, "colour": 1)").find("lights[0]"), std::string::npos);
  EXPECT_NE(error(ok + R"(, "two_sided": 1)").find("lights[0].two_sided"), std::string::npos);
  EXPECT_NE(error(ok + R"(, "aim": "nothing")").find("lights[0].aim"), std::string::npos);
  EXPECT_NE(error(ok + R"(, "spectrum": "laser")").find("wavelength_nm"), std::string::npos);
  EXPECT_NE(error(R"("width_m": 0.1, "height_m": 0.1)").find("normal"), std::string::npos);
  EXPECT_NE(error(ok + R"(, "power_w": 0)").find("lights[0].power_w"), std::string::npos);
  EXPECT_EQ(error(ok + R"(, "two_sided": true, "aim": "wall")"), "no error");
}

TEST(RenderAreaLight, LampSceneFileHasTheContrastsItDocuments) {
  // rooms/light/double-slit-lamp.json (and its README rows) state contrasts 0.99, 0.51, 0.00 for its three
  // lamps, from top to bottom of the image: sinc(πds/(λD)) from the file's own numbers.
  const dr::LightScene s = dr::loadLightScene(std::string(DIFFRAY_SOURCE_DIR) + "/rooms/light/double-slit-lamp.json");
  ASSERT_EQ(s.lights.size(), 3u);
  ASSERT_EQ(s.occluders.size(), 1u);
  const dr::OccluderSpec& o = s.occluders[0];
  const double contrast[] = {0.99, 0.51, 0.00};
  for (int i = 0; i < 3; ++i) {
    const dr::Light& l = s.lights[i];
    EXPECT_EQ(l.kind, dr::Light::Kind::Area);
    EXPECT_EQ(l.aim, static_cast<int>(s.rects.size()));  // the slits
    const double D = o.frame.origin.z() - l.position_m.z(), lambda = l.spectrum.wavelength_nm * 1e-9;
    const double arg = kPi * o.spacing_m * (2.0 * l.half_x_m) / (lambda * D);
    EXPECT_NEAR(std::sin(arg) / arg, contrast[i], 0.005) << l.name;
    // Its band Y = y(1 + L/D) − y_s·L/D: the first lamp (lowest) lights the top of the wall.
    if (i > 0) {
      EXPECT_GT(l.position_m.y(), s.lights[i - 1].position_m.y());
    }
  }
}

TEST(RenderAreaLightDeterminism, SameSeedSameImageForAnyThreadCount) {
  const Opposed g;
  for (bool aim : {false, true}) {
    const dr::LightScene s = g.scene(aim, true);
    const auto ps = dr::prepareScene(s);
    dr::RenderOptions o;
    o.photons = 20'000;
    o.chunk_photons = 1000;
    render_fixtures::expectSameImageForAnyThreadCount(*ps, o);
  }
}

// The double slit under an incoherent strip lamp (file comment). Slits at z = 0, the lamp at z = −D facing
// +z, aimed at the slit screen (exactly the slits' extent across x), a white wall (ρ = 1) at z = L, the
// camera at z = 1 m looking at it: 96 × 4 pixels over x ∈ ±30 mm, the rows inside the lit band.
struct LampSlits {
  double a = 50e-6, d = 250e-6, lambda = 632.8e-9, D = 1.0, L = 2.0, s = 1.5e-3, lamp_h = 1e-3, power = 1.0;
  dr::LightScene scene() const {
    dr::LightScene sc;
    dr::DiffuseRect wall;
    wall.name = "wall";
    wall.frame = dr::rectFrame(Vec3(0, 0, L), Vec3(0, 0, -1), Vec3(0, 1, 0), "wall");
    wall.half_x_m = 0.04, wall.half_y_m = 0.01;
    wall.albedo.values = {1.0};
    sc.rects.push_back(wall);
    dr::OccluderSpec slits;
    slits.name = "slits";
    slits.kind = dr::OccluderSpec::Kind::DoubleSlit;
    slits.frame = dr::rectFrame(Vec3(0, 0, 0), Vec3(0, 0, 1), Vec3(0, 1, 0), "slits");
    slits.half_x_m = 0.5 * (a + d), slits.half_y_m = 2e-3;
    slits.slit_width_m = a, slits.spacing_m = d;
    sc.occluders.push_back(slits);
    dr::Light lamp;
    lamp.name = "lamp";
    lamp.kind = dr::Light::Kind::Area;
    lamp.spectrum.kind = dr::Spectrum::Kind::Laser;
    lamp.spectrum.wavelength_nm = lambda * 1e9;
    lamp.position_m = Vec3(0, 0, -D);
    lamp.frame = dr::rectFrame(lamp.position_m, Vec3(0, 0, 1), Vec3(0, 1, 0), "lamp");
    lamp.half_x_m = 0.5 * s, lamp.half_y_m = 0.5 * lamp_h;
    lamp.power_w = power;
    lamp.aim = 1;  // the slit screen: targets are rects, then occluders
    sc.lights.push_back(lamp);
    sc.camera.position_m = Vec3(0, 0, 1.0);
    sc.camera.look_at_m = Vec3(0, 0, L);
    sc.camera.up = Vec3(0, 1, 0);
    sc.camera.fov_x_deg = 2.0 * std::atan(0.03 / 1.0) * 180.0 / kPi;
    sc.camera.width = 96;
    sc.camera.height = 4;
    return sc;
  }
};

TEST(StatRenderAreaLight, DoubleSlitUnderStripLampLosesVisibilityByVanCittertZernike) {
  const LampSlits g;
  const dr::LightScene sc = g.scene();
  const auto ps = dr::prepareScene(sc);
  dr::RenderOptions o;
  o.photons = 2'500'000;
  o.seed = 5;
  const dr::RenderResult r = dr::renderLight(*ps, o);

  // The oracle (file comment): E(X) by Gauss–Legendre over the lamp's width, split into the fringe-free part
  // (|T|² = 2a² sinc²(πau)) and the fringe term (2a² sinc²(πau)·cos(2πdu)); B1 is the fringe term of a point
  // lamp (x_s = 0), so the row is α·B0 + β·B1 with α = 1 and β = V = sinc(πds/(λD)) up to the envelope's
  // change over the lamp (below).
  const auto& gl = diffray::core::gaussLegendre(16);
  const double scale = g.power / (kPi * g.D * g.D) * g.D / (g.D + g.L) / kPi;  // ·ρ/π, ρ = 1
  auto sinc2 = [&](double u) {
    const double x = kPi * g.a * u;
    return std::abs(x) < 1e-12 ? 1.0 : std::pow(std::sin(x) / x, 2);
  };
  struct Parts {
    double full, flat, fringe_point;
  };
  auto parts = [&](double X) {
    const double rw = std::hypot(X, g.L), cos3 = std::pow(g.L / rw, 3), sin_out = X / rw;
    Parts p{0, 0, 0};
    for (std::size_t i = 0; i < gl.nodes.size(); ++i) {
      const double xs = 0.5 * g.s * gl.nodes[i], w = 0.5 * gl.weights[i];  // (1/s)∫ dx_s
      const double u = (sin_out + xs / std::hypot(xs, g.D)) / g.lambda;
      p.full += w * diffray::reference::doubleSlitFraunhofer(u, g.a, g.d);
      p.flat += w * 2.0 * g.a * g.a * sinc2(u);
    }
    const double u0 = sin_out / g.lambda;
    p.fringe_point = 2.0 * g.a * g.a * sinc2(u0) * std::cos(2 * kPi * g.d * u0);
    const double k = scale * cos3 / (g.lambda * g.L);
    return Parts{k * p.full, k * p.flat, k * p.fringe_point};
  };
  // Looking along +z with y up: right = (0,0,1)×(0,1,0) = (−1,0,0).
  const Vec3 fwd(0, 0, 1), up(0, 1, 0), right(-1, 0, 0), cam(0, 0, 1.0);
  auto wallX = [&](const Vec3& dir) { return (cam + ((g.L - cam.z()) / dir.z()) * dir).x(); };
  double chi2 = 0, max_z = 0, peak = 0, max_err = 0;
  double m00 = 0, m01 = 0, m11 = 0, v0 = 0, v1 = 0;  // weighted least squares for (α, β)
  double f00 = 0, f01 = 0, f11 = 0, w0 = 0, w1 = 0;  // the same fit on the oracle row itself
  for (int ix = 0; ix < r.width; ++ix) {
    double got = 0, var = 0, expect = 0, b0 = 0, b1 = 0;
    for (int iy = 0; iy < r.height; ++iy) {
      got += r.pixelRadiance(ix, iy) / r.height;
      var += std::pow(r.pixelStdError(ix, iy) / r.height, 2);
      using render_fixtures::pixelMean;
      expect += pixelMean(sc.camera, right, up, fwd, ix, iy, [&](const Vec3& v) { return parts(wallX(v)).full; }) /
                r.height;
      b0 += pixelMean(sc.camera, right, up, fwd, ix, iy, [&](const Vec3& v) { return parts(wallX(v)).flat; }) /
            r.height;
      b1 += pixelMean(sc.camera, right, up, fwd, ix, iy,
                      [&](const Vec3& v) { return parts(wallX(v)).fringe_point; }) / r.height;
    }
    const double z = (got - expect) / std::sqrt(var);
    chi2 += z * z;
    max_z = std::max(max_z, std::abs(z));
    max_err = std::max(max_err, std::abs(got - expect));
    peak = std::max(peak, expect);
    m00 += b0 * b0 / var, m01 += b0 * b1 / var, m11 += b1 * b1 / var, v0 += b0 * got / var, v1 += b1 * got / var;
    f00 += b0 * b0, f01 += b0 * b1, f11 += b1 * b1, w0 += b0 * expect, w1 += b1 * expect;
  }
  const double det = m00 * m11 - m01 * m01;
  const double alpha = (m11 * v0 - m01 * v1) / det, beta = (m00 * v1 - m01 * v0) / det;
  const double sigma_alpha = std::sqrt(m11 / det), sigma_beta = std::sqrt(m00 / det);
  const double fdet = f00 * f11 - f01 * f01, beta_oracle = (f00 * w1 - f01 * w0) / fdet;
  const double arg = kPi * g.d * g.s / (g.lambda * g.D), vcz = std::sin(arg) / arg;
  std::printf("lamp double slit: chi2/dof %.3f, max |z| %.2f, max error %.4f of peak; alpha %.4f +- %.4f, "
              "visibility %.4f +- %.4f (oracle row %.4f, van Cittert-Zernike %.4f)\n",
              chi2 / r.width, max_z, max_err / peak, alpha, sigma_alpha, beta, sigma_beta, beta_oracle, vcz);
  EXPECT_LT(max_z, 4.5);
  EXPECT_NEAR(chi2 / r.width, 1.0, 5.0 * std::sqrt(2.0 / r.width));
  // The source-averaged oracle carries the closed form: the envelope sinc²(πau) changes by ≲ (πa·s/(2λD))²/3
  // ≈ 0.3 % over the lamp, so its fitted visibility is the sinc within 0.005.
  EXPECT_NEAR(beta_oracle, vcz, 0.005);
  EXPECT_NEAR(alpha, 1.0, 4.0 * sigma_alpha);
  EXPECT_NEAR(beta, vcz, 4.0 * sigma_beta + std::abs(beta_oracle - vcz));
  EXPECT_LT(sigma_beta, 0.05);  // enough power to tell 0.51 from a coherent 1 or an incoherent 0
  EXPECT_LT(beta, 0.7);
}

}  // namespace
