// The shift range of a light scene's occluder tables (render/direction_bounds.h, render/light_setup.cpp).
// Oracles: a closed form (a square seen from a point: the largest x/|v| is at an edge's middle, 1/√2, not at
// a corner, 1/√3), brute force over a dense grid of the vector set, and the direction to a wall's nearest
// edge point computed by hand.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "diffray/render/direction_bounds.h"
#include "diffray/render/light_scene.h"
#include "diffray/render/light_setup.h"

namespace {

using diffray::core::Vec3;
using diffray::render::cosineRange;

TEST(RenderDirectionBounds, SquareSeenFromAPointPeaksAtAnEdgeMiddle) {
  const auto r = cosineRange(Vec3(0, 0, 1), {Vec3(1, 0, 0), Vec3(0, 1, 0)}, Vec3(1, 0, 0));
  EXPECT_NEAR(r.hi, 1.0 / std::sqrt(2.0), 1e-15);
  EXPECT_NEAR(r.lo, -1.0 / std::sqrt(2.0), 1e-15);
  // Along the normal: the square's centre, straight ahead (inside the set, not on an edge).
  EXPECT_EQ(cosineRange(Vec3(0, 0, 1), {Vec3(1, 0, 0), Vec3(0, 1, 0)}, Vec3(0, 0, 1)).hi, 1.0);
  // A box of vectors around 0 (an object around the point) holds every direction.
  const auto touching = cosineRange(Vec3(0.5, 0, 0), {Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 0.5)}, Vec3(0, 0, 1));
  EXPECT_EQ(touching.lo, -1.0);
  EXPECT_EQ(touching.hi, 1.0);
}

// Random sets of 2–4 generators away from 0, and random axes: the range holds every value of a dense grid
// over the set (it is a bound) and exceeds the grid's extremes by no more than the grid's resolution (it is
// tight). Grid: 33 points per generator (17 for four), error of its maximum ≤ ½·|f''|·(Δs/2)², |f''| ≲ 10 here.
TEST(RenderDirectionBounds, RangeHoldsAndHugsABruteForceGrid) {
  std::mt19937_64 gen(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int cases = 0;
  while (cases < 60) {
    const int m = 2 + cases % 3;
    std::vector<Vec3> g;
    for (int j = 0; j < m; ++j) g.emplace_back(0.6 * u(gen), 0.6 * u(gen), 0.6 * u(gen));
    const Vec3 c(u(gen), u(gen), u(gen));
    const Vec3 e = Vec3(u(gen), u(gen), u(gen)).normalized();
    const int n = m == 4 ? 17 : 33;
    double lo = 2.0, hi = -2.0, nearest = 1e300;
    std::vector<int> idx(static_cast<size_t>(m), 0);
    for (;;) {
      Vec3 v = c;
      for (int j = 0; j < m; ++j) v += (-1.0 + 2.0 * idx[j] / (n - 1)) * g[j];
      nearest = std::min(nearest, v.norm());
      lo = std::min(lo, v.dot(e) / v.norm());
      hi = std::max(hi, v.dot(e) / v.norm());
      int j = 0;
      while (j < m && ++idx[j] == n) idx[j++] = 0;
      if (j == m) break;
    }
    if (nearest < 0.2) continue;  // keep away from 0, where the cosine turns fast
    ++cases;
    const auto r = cosineRange(c, g, e);
    const double step = 2.0 / (n - 1), slack = 0.5 * 10.0 * (0.5 * step) * (0.5 * step);
    EXPECT_LE(r.lo, lo + 1e-12) << "case " << cases;
    EXPECT_GE(r.hi, hi - 1e-12) << "case " << cases;
    EXPECT_GE(r.lo, lo - slack) << "case " << cases;
    EXPECT_LE(r.hi, hi + slack) << "case " << cases;
  }
}

// A slit 0.1 m in front of a wall 0.4 m wide: light diffracted to the wall's side edge leaves at
// α = 0.2/√(0.2² + 0.1²) = 0.894 (at the edge's middle). The slit's table must hold that shift however tall
// the wall is; with corners alone a 2 m tall wall gave 0.197, and the lit row of the image shrank to a fifth.
TEST(RenderDirectionBounds, SlitTableReachesTheWallsSideEdgeForAnyWallHeight) {
  for (const char* height : {"0.4", "2.0"}) {
    const std::string text = std::string(R"({"name": "edge",
      "rectangles": [{"name": "wall", "centre": [0, 0, 0.1], "normal": [0, 0, -1], "width_m": 0.4, "height_m": )") +
                             height + R"(, "albedo": 1.0}],
      "occluders": [{"type": "slit", "name": "s", "centre": [0, 0, 0], "normal": [0, 0, 1], "width_m": 0.002,
                     "height_m": 0.01, "slit_width_m": 0.6e-6}],
      "lights": [{"type": "laser", "position": [0, 0, -0.01], "direction": [0, 0, 1], "width_m": 0.0001,
                  "height_m": 0.004, "power_w": 1, "wavelength_nm": 550}],
      "camera": {"position": [0, 0, 0.02], "look_at": [0, 0, 0.1], "fov_deg": 140, "pixels": [20, 4]}})";
    const auto scene = diffray::render::parseLightScene(text, "edge.json");
    const auto prepared = diffray::render::prepareScene(scene, true);
    const auto& layout = prepared->scene.occluders()[0].table_x->layout();
    const double lambda = 550e-9, reach = 0.2 / std::sqrt(0.2 * 0.2 + 0.1 * 0.1);
    // The plate's corners (±1 mm) and the margin 1.02 move it a little: at least the centre's figure, at
    // most the margin over the plate's own extremes.
    EXPECT_GE(-layout.u0_per_m * lambda, reach) << "wall height " << height;
    EXPECT_LE(-layout.u0_per_m * lambda, 1.03 * 0.201 / std::sqrt(0.201 * 0.201 + 0.1 * 0.1)) << "wall height " << height;
  }
}

}  // namespace
