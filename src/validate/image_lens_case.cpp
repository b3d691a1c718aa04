// `diffray validate image-lens-psf`: a thin lens's point-spread function, rendered, against
// the focal-plane Fraunhofer pattern of its rectangular opening. Set-up, oracle and comparison:
// validate/image_setup.h (LensPsfImageSetup).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>

#include "diffray/core/error.h"
#include "diffray/render/light_setup.h"
#include "diffray/render/light_tracer.h"
#include "diffray/validate/image_setup.h"

namespace diffray::validate {

namespace {

constexpr double kPi = 3.14159265358979323846;

double sincSquared(double z) {  // (sin πz / πz)²
  if (std::abs(z) < 1e-12) return 1.0;
  const double s = std::sin(kPi * z) / (kPi * z);
  return s * s;
}

}  // namespace

double LensPsfImageSetup::imageDistance() const {
  return source_distance_m > 0.0 ? 1.0 / (1.0 / focal_length_m - 1.0 / source_distance_m) : focal_length_m;
}

double LensPsfImageSetup::fovDeg() const {
  const double half_width_m = lobes * wavelength_m * imageDistance() / std::min(aperture_width_m, aperture_height_m);
  return 2.0 * std::atan(half_width_m / camera_distance_m) * 180.0 / kPi;
}

LensPsfImageSetup lensPsfImageSetup(const Params& p) {
  LensPsfImageSetup s;
  s.wavelength_m = p.at("wavelength")[0];
  s.aperture_width_m = p.at("width")[0];
  s.aperture_height_m = p.at("height")[0];
  s.focal_length_m = p.at("focal")[0];
  s.source_distance_m = p.at("source")[0];
  s.lobes = p.at("lobes")[0];
  s.width = s.height = static_cast<int>(p.at("pixels")[0]);
  if (s.width % 2 == 0) throw core::InputError("--pixels", "must be odd (a central row and column of pixels)");
  if (!(s.wavelength_m >= 380e-9 && s.wavelength_m <= 780e-9))
    throw core::InputError("--wavelength", "must lie in [380e-9, 780e-9] m (the visible range)");
  if (!(std::max(s.aperture_width_m, s.aperture_height_m) < 0.2 * s.focal_length_m))
    throw core::InputError("--focal", "must exceed 5 times the opening (the lens is paraxial)");
  if (s.source_distance_m > 0.0 && !(s.source_distance_m > 1.05 * s.focal_length_m))
    throw core::InputError("--source", "must be 0 (a collimated beam) or beyond 1.05 times --focal (a real image)");
  if (!(s.fovDeg() < 60.0)) throw core::InputError("--lobes", "too many for the camera's field (60 degrees)");
  return s;
}

render::LightScene lensPsfImageScene(const LensPsfImageSetup& s) {
  using core::Vec3;
  const double f = s.focal_length_m, L = s.imageDistance(), a = s.aperture_width_m, b = s.aperture_height_m;
  const double view_half_m = std::tan(0.5 * s.fovDeg() * kPi / 180.0) * s.camera_distance_m;
  render::LightScene sc;
  sc.name = "image-lens-psf";
  render::DiffuseRect wall;
  wall.name = "wall";
  wall.frame = render::rectFrame(Vec3(0, 0, L), Vec3(0, 0, -1), Vec3(0, 1, 0), "wall");
  wall.half_x_m = wall.half_y_m = 2.0 * view_half_m;  // beyond the field: the table need not reach further
  wall.albedo.values = {s.albedo};
  sc.rects.push_back(wall);
  render::OccluderSpec lens;
  lens.name = "lens";
  lens.kind = render::OccluderSpec::Kind::Lens;
  lens.frame = render::rectFrame(Vec3(0, 0, 0), Vec3(0, 0, 1), Vec3(0, 1, 0), "lens");
  // A point light is aimed at the plate, so the plate is the opening there: every photon drawn passes.
  const double plate = s.source_distance_m > 0.0 ? 0.5 : 1.0;
  lens.half_x_m = plate * a, lens.half_y_m = plate * b;
  lens.aperture_width_m = a, lens.aperture_height_m = b;
  lens.focal_length_m = f;
  sc.occluders.push_back(lens);
  render::Light light;
  light.name = "light";
  light.spectrum.kind = render::Spectrum::Kind::Laser;
  light.spectrum.wavelength_nm = s.wavelength_m * 1e9;
  light.power_w = s.power_w;
  if (s.source_distance_m > 0.0) {
    light.kind = render::Light::Kind::Point;
    light.position_m = Vec3(0, 0, -s.source_distance_m);
    light.aim = static_cast<int>(sc.rects.size());  // the lens: every photon drawn toward its plate
  } else {
    light.kind = render::Light::Kind::Collimated;
    light.position_m = Vec3(0, 0, -0.05);
    light.frame = render::rectFrame(light.position_m, Vec3(0, 0, 1), Vec3(0, 1, 0), "laser");
    light.half_x_m = 0.5 * a, light.half_y_m = 0.5 * b;  // exactly the opening: every point of it evenly lit
  }
  sc.lights.push_back(light);
  sc.camera.position_m = Vec3(0, 0, L - s.camera_distance_m);
  sc.camera.look_at_m = Vec3(0, 0, L);
  sc.camera.up = Vec3(0, 1, 0);
  sc.camera.fov_x_deg = s.fovDeg();
  sc.camera.width = s.width, sc.camera.height = s.height;
  return sc;
}

CaseResult runImageLensPsf(const LensPsfImageSetup& s, const ImageRunOptions& o) {
  const auto t0 = std::chrono::steady_clock::now();
  double seconds_render = 0.0;
  const render::RenderResult img = renderImageScene(lensPsfImageScene(s), o, 80'000'000, seconds_render);
  CaseResult r = scoreImageLensPsf(s, img);
  r.extra["seconds_render"] = seconds_render;
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

CaseResult scoreImageLensPsf(const LensPsfImageSetup& s, const render::RenderResult& img) {
  const double a = s.aperture_width_m, b = s.aperture_height_m, lf = s.wavelength_m * s.imageDistance();
  const double I0 = s.source_distance_m > 0.0 ? s.power_w / (4.0 * kPi * s.source_distance_m * s.source_distance_m)
                                              : s.power_w / (a * b);
  const double peak = s.albedo / kPi * I0 * (a * b / lf) * (a * b / lf);  // ρ/π · I₀(ab/λL)²
  auto radiance = [&](double x, double y) { return peak * sincSquared(a * x / lf) * sincSquared(b * y / lf); };
  const WallView view{s.camera_distance_m, s.fovDeg(), s.width, s.height};
  const int cx = s.width / 2, cy = s.height / 2;
  CaseResult r;
  r.name = "image-lens-psf";
  r.rays = img.photons;
  auto add = [&](int ix, int iy, const char* label) {
    Row row;
    row.x_m = view.columnX(ix);
    row.y_m = view.rowY(iy);
    row.reference = view.pixelMean(ix, iy, radiance);
    row.traced = img.pixelRadiance(ix, iy);
    row.std_error = img.pixelStdError(ix, iy);
    row.label = label;
    r.rows.push_back(row);
  };
  for (int ix = 0; ix < s.width; ++ix) add(ix, cy, "row");
  for (int iy = 0; iy < s.height; ++iy) add(cx, iy, "column");
  r.negative_energy_fraction = img.negativePixelFraction();
  r.target_rel_peak = 0.01;
  r.extra["negative_score_fraction"] = img.negativeScoreFraction();
  r.detail = "central row and column vs the focal- (image-) plane sinc² pattern averaged over each pixel, absolute radiance, "
             "no fitted scale";
  scoreRows(r);
  return r;
}

CaseInfo imageLensPsfCase() {
  CaseInfo c{"image-lens-psf",
             "rendered thin-lens PSF (diffray render): the focal- or image-plane central row and column vs sinc²",
             {},
             80'000'000,
             {}};
  c.params = {{"wavelength", {550e-9}, "laser wavelength (m), visible"},
              {"width", {1e-3}, "lens opening along x, a (m)"},
              {"height", {1e-3}, "lens opening along y, b (m)"},
              {"focal", {0.5}, "focal length f (m); the wall stands in the focal plane (or the image plane)"},
              {"source", {0.0}, "0: a laser beam filling the lens; > 1.05 f: a point light this far before it, the "
                                "wall at 1/(1/f - 1/source)", 0.0, true},
              {"lobes", {4.0}, "first zeros λf/a the camera's field spans either side of the centre"},
              {"pixels", {121}, "image width and height in pixels (odd)", 2.0, true, 4097.0}};
  c.param("pixels").whole = true;
  c.run = [](const Params& p, const RunOptions& o) {
    return runImageLensPsf(lensPsfImageSetup(p), imageRunOptions(o, "image-lens-psf"));
  };
  return c;
}

}  // namespace diffray::validate
