#pragma once
// Shared oracle functions of the render tests (tests/render_*_test.cpp). They use only the camera's spec (its
// field of view and pixel counts), never render::Camera, so they share no code with the renderer.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "diffray/core/math.h"
#include "diffray/core/parallel.h"
#include "diffray/render/camera.h"
#include "diffray/render/light_scene.h"
#include "diffray/render/light_tracer.h"

namespace render_fixtures {

/// Mean over pixel (ix, iy) of f(direction), weighted by solid angle, for a camera with basis (right, up,
/// forward) and the spec's horizontal field of view: Gauss–Legendre n × n in image-plane coordinates (X, Y)
/// at distance 1, dω = dX dY / (1 + X² + Y²)^{3/2}; rows top first.
template <class F>
double pixelMean(const diffray::render::CameraSpec& c, const diffray::core::Vec3& right,
                 const diffray::core::Vec3& up, const diffray::core::Vec3& fwd, int ix, int iy, F f, int n = 6) {
  constexpr double kPi = 3.14159265358979323846;
  const auto& gl = diffray::core::gaussLegendre(n);
  const double T = std::tan(0.5 * c.fov_x_deg * kPi / 180.0), s = 2.0 * T / c.width, Ty = 0.5 * s * c.height;
  double num = 0.0, den = 0.0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const double X = -T + (ix + 0.5 + 0.5 * gl.nodes[i]) * s, Y = Ty - (iy + 0.5 + 0.5 * gl.nodes[j]) * s;
      const double w = gl.weights[i] * gl.weights[j] * std::pow(1 + X * X + Y * Y, -1.5);
      num += w * f((fwd + X * right + Y * up).normalized());
      den += w;
    }
  return num / den;
}

/// Renders the scene with 1 and then 2 threads and expects bit-identical images (render/light_tracer.h:
/// chunks with their own random streams).
inline void expectSameImageForAnyThreadCount(const diffray::render::PreparedScene& ps,
                                             const diffray::render::RenderOptions& o) {
  std::vector<double> first;
  for (int threads : {1, 2}) {
    diffray::core::ThreadLimit limit(threads);
    const diffray::render::RenderResult r = diffray::render::renderLight(ps, o);
    if (first.empty()) first = r.xyz;
    else EXPECT_EQ(first, r.xyz);
  }
}

/// A 1 m white wall (albedo 0.8) at z = 0 facing +z under a 1 W white point light at (0.1, 0, 1), seen
/// from (0, 0, 2) in width × height pixels over a 40° field: the wall fills the view.
inline diffray::render::LightScene wallUnderPointLight(int width, int height) {
  using diffray::core::Vec3;
  diffray::render::LightScene s;
  diffray::render::DiffuseRect wall;
  wall.frame = diffray::render::rectFrame(Vec3(0, 0, 0), Vec3(0, 0, 1), Vec3(0, 1, 0), "wall");
  s.rects.push_back(wall);
  diffray::render::Light light;
  light.position_m = Vec3(0.1, 0, 1);
  s.lights.push_back(light);
  s.camera.position_m = Vec3(0, 0, 2);
  s.camera.look_at_m = Vec3(0, 0, 0);
  s.camera.width = width;
  s.camera.height = height;
  return s;
}

}  // namespace render_fixtures
