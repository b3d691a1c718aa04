// render/film.h's CSV of pixels: every pixel once, in image order, with the values the RenderResult holds
// (radiance, standard error, XYZ) and the linear sRGB that linearSrgb() gives, to the 9 digits written.
// And every shipped light scene (rooms/light/*.json) loads: the gallery's commands keep working.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "diffray/render/film.h"
#include "diffray/render/light_scene.h"
#include "diffray/render/light_setup.h"
#include "diffray/render/light_tracer.h"
#include "render_fixtures.h"

namespace {

namespace dr = diffray::render;

std::vector<double> splitRow(const std::string& line) {
  std::vector<double> v;
  std::stringstream ss(line);
  std::string cell;
  while (std::getline(ss, cell, ',')) v.push_back(std::stod(cell));
  return v;
}

void expectClose(double got, double want) { EXPECT_NEAR(got, want, 1e-8 * std::abs(want) + 1e-300); }

TEST(RenderFilm, PixelCsvHoldsEveryPixelInImageOrder) {
  const dr::LightScene s = render_fixtures::wallUnderPointLight(6, 4);  // the wall fills the view
  const auto ps = dr::prepareScene(s);
  dr::RenderOptions o;
  o.photons = 20'000;
  o.chunk_photons = 2000;
  const dr::RenderResult r = dr::renderLight(*ps, o);
  const diffray::image::Image rgb = dr::linearSrgb(r);

  std::ostringstream out;
  dr::writePixelCsv(out, r, rgb);
  std::istringstream in(out.str());
  std::string line;
  ASSERT_TRUE(std::getline(in, line));
  EXPECT_EQ(line, "ix,iy,radiance_w_m2_sr,std_error_w_m2_sr,X,Y,Z,r,g,b");
  int rows = 0, lit = 0;
  while (std::getline(in, line)) {
    const std::vector<double> v = splitRow(line);
    ASSERT_EQ(v.size(), 10u) << line;
    const int ix = rows % r.width, iy = rows / r.width;
    EXPECT_EQ(v[0], ix);
    EXPECT_EQ(v[1], iy);
    expectClose(v[2], r.pixelRadiance(ix, iy));
    expectClose(v[3], r.pixelStdError(ix, iy));
    const std::size_t i = static_cast<std::size_t>(iy) * r.width + ix;
    for (int c = 0; c < 3; ++c) expectClose(v[4 + c], r.xyz[3 * i + c]);
    for (int c = 0; c < 3; ++c) expectClose(v[7 + c], rgb.rgb[3 * i + c]);
    if (v[2] > 0) ++lit;
    ++rows;
  }
  EXPECT_EQ(rows, r.width * r.height);
  EXPECT_GT(lit, rows / 2);  // the wall fills the view: most values compared are not zeros
}

TEST(RenderShippedScenes, EveryLightSceneLoads) {
  int scenes = 0;
  for (const auto& entry : std::filesystem::directory_iterator(std::string(DIFFRAY_SOURCE_DIR) + "/rooms/light")) {
    if (entry.path().extension() != ".json") continue;
    SCOPED_TRACE(entry.path().string());
    dr::LightScene s;
    EXPECT_NO_THROW(s = dr::loadLightScene(entry.path().string()));
    EXPECT_FALSE(s.lights.empty());
    EXPECT_FALSE(s.rects.empty());
    ++scenes;
  }
  EXPECT_GE(scenes, 10);  // the gallery's scenes (README, rooms/light/README.md)
}

}  // namespace
