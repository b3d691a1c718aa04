// The pinhole camera (render/camera.h) against constructions that share no code with it: world points built
// from a rotation matrix and the pixel grid's definition, and pixel solid angles against the closed form of a
// rectangular pyramid and direct quadrature of dω = dX dY/(1 + X² + Y²)^{3/2}. Also the light scene parser's
// one-line errors.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "diffray/core/error.h"
#include "diffray/render/camera.h"
#include "diffray/render/light_scene.h"

namespace {

namespace dr = diffray::render;
using diffray::core::Vec3;
constexpr double kPi = 3.14159265358979323846;

TEST(RenderCamera, KnownWorldPointLandsInPredictedPixel) {
  // A camera turned by an arbitrary rotation R: forward R·ẑ, up R·ŷ; looking along +z with y up, the image's
  // right is −x (right-handed world), so right = R·(−x̂).
  const Eigen::Matrix3d R = (Eigen::AngleAxisd(0.7, Vec3(0.3, 1, 0.2).normalized()) *
                             Eigen::AngleAxisd(-0.4, Vec3(1, 0, 0)))
                                .toRotationMatrix();
  dr::CameraSpec spec;
  spec.position_m = Vec3(1.0, -2.0, 0.5);
  spec.look_at_m = spec.position_m + 3.0 * (R * Vec3(0, 0, 1));
  spec.up = R * Vec3(0, 1, 0);
  spec.fov_x_deg = 50.0;
  spec.width = 64;
  spec.height = 48;
  const dr::Camera cam(spec);
  const double T = std::tan(25.0 * kPi / 180.0), s = 2.0 * T / 64, Ty = 24 * s;
  const int pixels[][2] = {{0, 0}, {63, 47}, {10, 30}, {32, 24}, {63, 0}};
  for (const auto& px : pixels)
    for (double fx : {0.1, 0.5, 0.9})
      for (double depth : {0.5, 7.0}) {
        const double X = -T + (px[0] + fx) * s, Y = Ty - (px[1] + 1.0 - fx) * s;
        const Vec3 p = spec.position_m + depth * (R * Vec3(-X, Y, 1.0));
        const dr::Camera::Projection pr = cam.project(p);
        EXPECT_EQ(pr.ix, px[0]) << "depth " << depth;
        EXPECT_EQ(pr.iy, px[1]) << "depth " << depth;
        EXPECT_NEAR(pr.distance_m, depth * std::sqrt(1 + X * X + Y * Y), 1e-12);
      }
  // Behind the camera and outside the field: no pixel.
  EXPECT_FALSE(cam.project(spec.position_m - R * Vec3(0, 0, 1)).inside());
  EXPECT_FALSE(cam.project(spec.position_m + R * Vec3(-1.2 * T, 0, 1)).inside());
}

TEST(RenderCamera, PixelSolidAnglesMatchPyramidAndQuadrature) {
  dr::CameraSpec spec;
  spec.fov_x_deg = 70.0;
  spec.width = 20;
  spec.height = 12;
  const dr::Camera cam(spec);
  // The whole image: a rectangular pyramid of half-angles α, β has Ω = 4·asin(sin α sin β).
  const double a = 35.0 * kPi / 180.0, b = std::atan(std::tan(a) * 12.0 / 20.0);
  double total = 0.0;
  for (int iy = 0; iy < 12; ++iy)
    for (int ix = 0; ix < 20; ++ix) total += cam.pixelSolidAngle(ix, iy);
  EXPECT_NEAR(total, 4.0 * std::asin(std::sin(a) * std::sin(b)), 1e-12);
  // One corner pixel by a 200 × 200 midpoint rule of dX dY/(1 + X² + Y²)^{3/2}.
  const double T = std::tan(a), s = 2.0 * T / 20;
  const double x0 = -T, y0 = 6 * s - s;  // pixel (0, 0): X ∈ [−T, −T + s], Y ∈ [Ty − s, Ty]
  double q = 0.0;
  const int n = 200;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const double X = x0 + (i + 0.5) * s / n, Y = y0 + (j + 0.5) * s / n;
      q += std::pow(1 + X * X + Y * Y, -1.5) * (s / n) * (s / n);
    }
  EXPECT_NEAR(cam.pixelSolidAngle(0, 0), q, 1e-6 * q);
}

TEST(RenderScene, ErrorsNameTheField) {
  const std::string camera = R"("camera": {"position": [0,0,1], "look_at": [0,0,0], "fov_deg": 40, "pixels": [4, 4]})";
  const std::string rect = R"("rectangles": [{"name": "wall", "centre": [0,0,0], "normal": [0,0,1], "width_m": 1, "height_m": 1}])";
  auto error = [&](const std::string& body) {
    try {
      dr::parseLightScene("{" + body + "}", "s.json");
    } catch (const diffray::core::InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(error(rect + R"(, "lights": [{"type": "point", "position": [0,0,1], "aim": "floor"}], )" + camera),
            "s.json: lights[0].aim: no rectangle or occluder is named \"floor\"");
  EXPECT_NE(error(rect + R"(, "lights": [{"type": "laser", "position": [0,0,1], "direction": [0,0,-1], "width_m": 0.01}], )" + camera)
                .find("s.json: lights[0].wavelength_nm: missing"),
            std::string::npos);
  EXPECT_NE(error(rect + R"(, "lights": [{"type": "point", "positon": [0,0,1]}], )" + camera).find("did you mean \"position\""),
            std::string::npos);
  EXPECT_NE(error(rect + R"(, "occluders": [{"type": "double-slit", "centre": [0,0,0.5], "normal": [0,0,1], "width_m": 0.01,
            "height_m": 0.01, "slit_width_m": 1e-4, "spacing_m": 5e-5}], "lights": [{"type": "point", "position": [0,0,1]}], )" + camera)
                .find("occluders[0].spacing_m: must exceed slit_width_m"),
            std::string::npos);
  EXPECT_NE(error(rect + R"(, "lights": [{"type": "point", "position": [0,0,1]}], "camera": {"position": [0,0,1],
            "look_at": [0,0,0], "up": [0,0,1], "fov_deg": 40, "pixels": [4, 4]})")
                .find("s.json: camera.up: must be non-zero and not parallel"),
            std::string::npos);
  EXPECT_EQ(error(rect + R"(, "lights": [{"type": "point", "position": [0,0,1]}], )" + camera), "no error");
}

}  // namespace
