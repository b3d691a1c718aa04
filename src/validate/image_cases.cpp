// `diffray validate image-double-slit`: the rendered double slit against Fraunhofer.
// Set-up, oracle and comparison: validate/image_setup.h.
#include <chrono>
#include <cmath>
#include <vector>

#include "diffray/core/error.h"
#include "diffray/core/math.h"
#include "diffray/reference/fraunhofer.h"
#include "diffray/render/light_setup.h"
#include "diffray/render/light_tracer.h"
#include "diffray/validate/image_setup.h"

namespace diffray::validate {

namespace {
constexpr double kPi = 3.14159265358979323846;
}

DoubleSlitImageSetup doubleSlitImageSetup(const Params& p) {
  DoubleSlitImageSetup s;
  s.wavelength_m = p.at("wavelength")[0];
  s.slit_width_m = p.at("width")[0];
  s.spacing_m = p.at("spacing")[0];
  s.distance_m = p.at("distance")[0];
  if (!(s.spacing_m > s.slit_width_m)) throw core::InputError("--spacing", "must exceed --width");
  if (!(s.wavelength_m >= 380e-9 && s.wavelength_m <= 780e-9))
    throw core::InputError("--wavelength", "must lie in [380e-9, 780e-9] m (the visible range)");
  // The beam spans the slits' outer edges exactly, so every opening is fully and evenly lit.
  s.beam_half_x_m = 0.5 * (s.spacing_m + s.slit_width_m);
  return s;
}

double WallView::tanHalf() const { return std::tan(0.5 * fov_deg * kPi / 180.0); }
double WallView::pitch() const { return 2.0 * tanHalf() / width; }
double WallView::topY() const { return 0.5 * pitch() * height; }
double WallView::columnX(int ix) const { return -(-tanHalf() + (ix + 0.5) * pitch()) * distance_m; }
double WallView::rowY(int iy) const { return (topY() - (iy + 0.5) * pitch()) * distance_m; }

double WallView::pixelMean(int ix, int iy, const std::function<double(double, double)>& radiance) const {
  const auto& gl = core::gaussLegendre(8);
  const double T = tanHalf(), p = pitch(), Ty = topY(), D = distance_m;
  double num = 0.0, den = 0.0;
  for (std::size_t i = 0; i < gl.nodes.size(); ++i)
    for (std::size_t j = 0; j < gl.nodes.size(); ++j) {
      const double X = -T + (ix + 0.5 + 0.5 * gl.nodes[i]) * p;
      const double Y = Ty - (iy + 0.5 + 0.5 * gl.nodes[j]) * p;
      const double w = gl.weights[i] * gl.weights[j] * std::pow(1.0 + X * X + Y * Y, -1.5);
      num += w * radiance(-X * D, Y * D);
      den += w;
    }
  return num / den;
}

render::LightScene doubleSlitImageScene(const DoubleSlitImageSetup& s) {
  using core::Vec3;
  const double L = s.distance_m;
  render::LightScene sc;
  sc.name = "image-double-slit";
  render::DiffuseRect wall;
  wall.name = "wall";
  wall.frame = render::rectFrame(Vec3(0, 0, L), Vec3(0, 0, -1), Vec3(0, 1, 0), "wall");
  wall.half_x_m = 0.03 * L, wall.half_y_m = 0.015 * L;
  wall.albedo.values = {s.albedo};
  sc.rects.push_back(wall);
  render::OccluderSpec slits;
  slits.name = "slits";
  slits.kind = render::OccluderSpec::Kind::DoubleSlit;
  slits.frame = render::rectFrame(Vec3(0, 0, 0), Vec3(0, 0, 1), Vec3(0, 1, 0), "slits");
  slits.half_x_m = std::max(2e-3, 2.0 * s.beam_half_x_m), slits.half_y_m = std::max(5e-3, 2.0 * s.beam_half_y_m);
  slits.slit_width_m = s.slit_width_m, slits.spacing_m = s.spacing_m;
  sc.occluders.push_back(slits);
  render::Light laser;
  laser.name = "laser";
  laser.kind = render::Light::Kind::Collimated;
  laser.spectrum.kind = render::Spectrum::Kind::Laser;
  laser.spectrum.wavelength_nm = s.wavelength_m * 1e9;
  laser.position_m = Vec3(0, 0, -0.05);
  laser.frame = render::rectFrame(laser.position_m, Vec3(0, 0, 1), Vec3(0, 1, 0), "laser");
  laser.half_x_m = s.beam_half_x_m, laser.half_y_m = s.beam_half_y_m;
  laser.power_w = s.power_w;
  sc.lights.push_back(laser);
  sc.camera.position_m = Vec3(0, 0, 0.6 * L);
  sc.camera.look_at_m = Vec3(0, 0, L);
  sc.camera.up = Vec3(0, 1, 0);
  sc.camera.fov_x_deg = s.fov_deg;
  sc.camera.width = s.width, sc.camera.height = s.height;
  return sc;
}

ImageRunOptions imageRunOptions(const RunOptions& o, const std::string& case_name) {
  if (o.model != "wigner") throw core::InputError("--model", case_name + " takes the wigner model only");
  ImageRunOptions io;
  io.photons = o.rays;
  io.seed = o.seed;
  io.on_progress = o.on_progress;
  return io;
}

render::RenderResult renderImageScene(const render::LightScene& scene, const ImageRunOptions& o,
                                      std::uint64_t default_photons, double& seconds_render) {
  const auto ps = render::prepareScene(scene);
  render::RenderOptions ro;
  ro.photons = o.photons ? o.photons : default_photons;
  ro.seed = o.seed;
  ro.uniform_shifts = o.uniform_shifts;
  ro.chunk_photons = o.chunk_photons;
  ro.on_progress = o.on_progress;
  const auto t0 = std::chrono::steady_clock::now();
  render::RenderResult img = render::renderLight(*ps, ro);
  seconds_render = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return img;
}

CaseResult runImageDoubleSlit(const DoubleSlitImageSetup& s, const ImageRunOptions& o) {
  const auto t0 = std::chrono::steady_clock::now();
  double seconds_render = 0.0;
  const render::RenderResult img = renderImageScene(doubleSlitImageScene(s), o, 80'000'000, seconds_render);

  // The oracle's camera (WallView): D = 0.4·L the camera-to-wall distance.
  const double L = s.distance_m, D = 0.4 * L, lambda = s.wavelength_m;
  const WallView view{D, s.fov_deg, s.width, s.height};
  const double pitch = view.pitch(), Ty = view.topY();
  const double I0 = s.power_w / (4.0 * s.beam_half_x_m * s.beam_half_y_m);
  auto radiance = [&](double x_wall) {  // ρ/π · I₀ |T(u)|² cos²θ/(λ r)
    const double u = reference::screenU(x_wall, L, lambda);
    const double t2 = reference::doubleSlitFraunhofer(u, s.slit_width_m, s.spacing_m);
    return s.albedo / kPi * I0 * reference::farFieldScreenIntensity2D(x_wall, L, lambda, t2);
  };
  // Rows wholly inside the lit band |y| < beam half-height.
  std::vector<int> rows;
  for (int iy = 0; iy < s.height; ++iy) {
    const double y_top = (Ty - iy * pitch) * D, y_bottom = (Ty - (iy + 1) * pitch) * D;
    if (std::max(std::abs(y_top), std::abs(y_bottom)) < s.beam_half_y_m * (1.0 - 1e-9)) rows.push_back(iy);
  }
  if (rows.empty()) throw core::InputError("image-double-slit", "no image row lies inside the beam");
  const double nrows = static_cast<double>(rows.size());
  CaseResult r;
  r.name = "image-double-slit";
  r.rays = img.photons;
  for (int ix = 0; ix < s.width; ++ix) {
    Row row;
    double var = 0.0;
    for (int iy : rows) {
      row.reference += view.pixelMean(ix, iy, [&](double x, double) { return radiance(x); }) / nrows;
      row.traced += img.pixelRadiance(ix, iy) / nrows;
      var += std::pow(img.pixelStdError(ix, iy) / nrows, 2);
    }
    row.std_error = std::sqrt(var);
    row.x_m = view.columnX(ix);
    r.rows.push_back(row);
  }
  r.negative_energy_fraction = img.negativePixelFraction();
  r.target_rel_peak = 0.01;
  r.extra["rows_averaged"] = static_cast<double>(rows.size());
  r.extra["seconds_render"] = seconds_render;
  r.extra["negative_score_fraction"] = img.negativeScoreFraction();
  r.detail = "central band of " + std::to_string(rows.size()) +
             " rows (inside the beam) vs Fraunhofer averaged over each pixel, absolute radiance, no fitted scale";
  scoreRows(r);
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

CaseInfo imageDoubleSlitCase() {
  CaseInfo c{"image-double-slit",
             "rendered double slit (diffray render): the image's central rows vs Fraunhofer, absolute radiance",
             {},
             80'000'000,
             {}};
  c.params = {{"wavelength", {632.8e-9}, "laser wavelength (m), visible"},
              {"width", {50e-6}, "slit width a (m)"},
              {"spacing", {250e-6}, "slit spacing d, centre to centre (m)"},
              {"distance", {2.0}, "slits to wall (m); the camera stands at 0.6 of it"}};
  c.run = [](const Params& p, const RunOptions& o) {
    return runImageDoubleSlit(doubleSlitImageSetup(p), imageRunOptions(o, "image-double-slit"));
  };
  return c;
}

}  // namespace diffray::validate
