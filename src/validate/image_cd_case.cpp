// `diffray validate image-cd`: a CD under a monochromatic laser, rendered by the light
// tracer (render/light_tracer.h), its first diffraction order found in the image and compared with where
// the grating equation sends it.
//
// Set-up (world metres): the CD is a reflecting sinusoidal phase grating (paper eq. 14–15) lying in the
// plane y = 0, facing +y, its grating vector along +z; a square laser beam comes down onto it in the y–z
// plane at `incidence` degrees from the normal (travelling toward +z); a diffuse ceiling at y = H catches the
// reflected orders. A camera below the ceiling looks straight up at the strip around the predicted +1 order
// (image columns run along +z), so the brightest lobe in the image is that order.
//
// Oracle (shares no code with the tracer): the grating equation for the reflected order q,
// sinθ_q = sinθ_i + qλ/Λ (direction cosines along the grating vector), and straight-line geometry from the
// beam's centre on the CD to the ceiling: z_1 = z_hit + H·tanθ_1. Every point of the beam leaves in the same
// direction (a collimated beam on a plane grating), so the lobe on the ceiling is the beam's footprint moved
// rigidly, and its centroid is the image of the beam's centre.
//
// Measurement: the image's columns summed over rows, the brightest column, the lobe around it (contiguous
// columns above 5 % of that column), and the radiance-weighted centroid of the columns' ceiling positions
// (each column's centre ray from the pinhole met with the plane y = H): sub-pixel. The error is
// |z_measured − z_1| in units of the pixel footprint on the ceiling there; target ≤ 1 footprint.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>

#include "diffray/core/error.h"
#include "diffray/render/light_scene.h"
#include "diffray/render/light_setup.h"
#include "diffray/render/light_tracer.h"
#include "diffray/validate/case.h"
#include "diffray/validate/image_setup.h"

namespace diffray::validate {

namespace {

using core::Vec3;

constexpr double kDegToRad = 3.14159265358979323846 / 180.0;

// The ceiling position z where the camera ray through image-plane point (X, 0) meets the plane y = H.
double ceilingZ(const render::Camera& cam, double X, double height_m) {
  const Vec3 d = cam.direction(X, 0.0);
  const double t = (height_m - cam.position().y()) / d.y();
  return cam.position().z() + t * d.z();
}

}  // namespace

CaseInfo imageCdCase() {
  CaseInfo c{"image-cd", "CD (phase grating) under a laser: the rendered first order vs the grating equation",
             {}, 2'000'000, {}};
  c.params = {{"wavelength", {550e-9}, "laser wavelength (m), within 380-780 nm", 380e-9, true, 780.000001e-9},
              {"period", {1.6e-6}, "grating period Λ (m); a CD's track pitch is 1.6 µm"},
              {"modulation", {3.0}, "phase modulation m: t = exp(i(m/2)·sin(2πx/Λ))", 0.0, false, 1000.0},
              {"incidence", {0.0}, "angle of the beam from the CD's normal (degrees), toward +z", -80.0, true, 80.0},
              {"height", {0.2}, "distance from the CD to the diffuse ceiling (m)"},
              {"beam", {0.002}, "side of the square laser beam (m)"},
              {"pixels", {64}, "image columns across the 4 cm strip around the first order", 8.0, true, 4097.0}};
  c.param("pixels").whole = true;
  c.run = [](const Params& p, const RunOptions& o) {
    const auto t0 = std::chrono::steady_clock::now();
    const ImageRunOptions io = imageRunOptions(o, "image-cd");
    const double lambda = p.at("wavelength")[0], period = p.at("period")[0], m = p.at("modulation")[0];
    const double inc = p.at("incidence")[0] * kDegToRad, height = p.at("height")[0], beam = p.at("beam")[0];
    const int columns = static_cast<int>(p.at("pixels")[0]);

    // The oracle: the grating equation and straight lines (see the file comment).
    const double sin_i = std::sin(inc), sin_1 = sin_i + lambda / period;
    if (!(std::abs(sin_1) < 0.95))
      throw core::InputError("--wavelength", "the first order leaves at sinθ = " + std::to_string(sin_1) +
                                                 " (must be within ±0.95 to reach the ceiling)");
    const double tan_1 = sin_1 / std::sqrt(1.0 - sin_1 * sin_1);
    const Vec3 beam_dir(0.0, -std::cos(inc), sin_i);
    const Vec3 beam_start(0.0, 0.5 * height, 0.0);
    const double t_hit = -beam_start.y() / beam_dir.y();
    const double z_hit = beam_start.z() + t_hit * beam_dir.z();
    const double z_pred = z_hit + height * tan_1;

    // The scene: CD (grating vector +z: ex = ey × n with ey = +x, n = +y), laser, ceiling, camera.
    render::LightScene s;
    s.name = "image-cd";
    const double cd_half = 2.0 * beam / std::max(std::cos(inc), 0.1);
    render::OccluderSpec cd;
    cd.name = "cd";
    cd.kind = render::OccluderSpec::Kind::Grating;
    cd.frame = render::rectFrame(Vec3(0, 0, z_hit), Vec3(0, 1, 0), Vec3(1, 0, 0), "cd");
    cd.half_x_m = cd.half_y_m = cd_half;
    cd.period_m = period;
    cd.modulation = m;
    s.occluders.push_back(cd);
    const double strip_m = 0.04;
    render::DiffuseRect ceiling;
    ceiling.name = "ceiling";
    ceiling.frame = render::rectFrame(Vec3(0, height, z_pred), Vec3(0, -1, 0), Vec3(1, 0, 0), "ceiling");
    ceiling.half_x_m = ceiling.half_y_m = strip_m;  // twice the camera's strip: the lobe never falls off it
    ceiling.albedo.values = {1.0};
    s.rects.push_back(ceiling);
    render::Light laser;
    laser.name = "laser";
    laser.kind = render::Light::Kind::Collimated;
    laser.spectrum.kind = render::Spectrum::Kind::Laser;
    laser.spectrum.wavelength_nm = lambda * 1e9;
    laser.position_m = beam_start;
    laser.frame = render::rectFrame(beam_start, beam_dir, Vec3(1, 0, 0), "laser");
    laser.half_x_m = laser.half_y_m = 0.5 * beam;
    s.lights.push_back(laser);
    // Camera below the ceiling, looking up; up = −x makes image right = +z. It is centred 0.37 of a pixel
    // off the prediction, so a correct lobe does not sit symmetrically on the pixel grid by construction
    // (the centroid's binning bias is then part of what is measured).
    const double cam_y = 0.1 * height, z_cam = z_pred + 0.37 * strip_m / columns;
    s.camera.position_m = Vec3(0, cam_y, z_cam);
    s.camera.look_at_m = Vec3(0, height, z_cam);
    s.camera.up = Vec3(-1, 0, 0);
    s.camera.fov_x_deg = 2.0 * std::atan(0.5 * strip_m / (height - cam_y)) / kDegToRad;
    s.camera.width = columns;
    s.camera.height = std::max(4, columns / 4);

    double seconds_render = 0.0;  // not reported: the case's whole time is (r.seconds)
    const render::RenderResult img = renderImageScene(s, io, 2'000'000, seconds_render);
    const render::Camera cam(s.camera);

    // Columns summed over rows, the brightest one and its lobe.
    std::vector<double> col(static_cast<std::size_t>(cam.width()), 0.0), col_var(col.size(), 0.0);
    for (int iy = 0; iy < cam.height(); ++iy)
      for (int ix = 0; ix < cam.width(); ++ix) {
        col[ix] += img.pixelRadiance(ix, iy);
        col_var[ix] += img.pixelStdError(ix, iy) * img.pixelStdError(ix, iy);  // pixels nearly independent
      }
    const int peak = static_cast<int>(std::max_element(col.begin(), col.end()) - col.begin());
    const double floor_level = 0.05 * col[peak];
    int lo = peak, hi = peak;
    while (lo > 0 && col[lo - 1] > floor_level) --lo;
    while (hi + 1 < cam.width() && col[hi + 1] > floor_level) ++hi;
    const double pitch = cam.pixelPitch(), T = cam.halfWidthTan();
    double sum = 0.0, sum_z = 0.0;
    for (int ix = lo; ix <= hi; ++ix) {
      const double z = ceilingZ(cam, -T + (ix + 0.5) * pitch, height);
      sum += col[ix];
      sum_z += col[ix] * z;
    }
    const double z_meas = sum > 0 ? sum_z / sum : 0.0;
    // Standard error of the centroid, to first order: ∂z_c/∂col_i = (z_i − z_c)/Σcol.
    double var_zc = 0.0;
    for (int ix = lo; ix <= hi; ++ix) {
      const double dz = (ceilingZ(cam, -T + (ix + 0.5) * pitch, height) - z_meas) / sum;
      var_zc += dz * dz * col_var[ix];
    }
    const double footprint = ceilingZ(cam, -T + (peak + 1) * pitch, height) - ceilingZ(cam, -T + peak * pitch, height);

    CaseResult r;
    r.name = "image-cd";
    r.rays = img.photons;
    Row row;
    row.x_m = z_pred;
    row.traced = z_meas;
    row.reference = z_pred;
    row.std_error = std::sqrt(var_zc);
    row.label = "order=1";
    r.rows.push_back(row);
    r.max_abs_error_rel_peak = r.rms_error_rel_peak = std::abs(z_meas - z_pred) / footprint;
    r.max_std_error_rel_peak = std::sqrt(var_zc) / footprint;
    r.target_rel_peak = 1.0;
    r.passed = sum > 0 && r.max_abs_error_rel_peak <= r.target_rel_peak;
    r.negative_energy_fraction = img.negativePixelFraction();
    r.extra["z_predicted_m"] = z_pred;
    r.extra["z_measured_m"] = z_meas;
    r.extra["pixel_footprint_m"] = footprint;
    r.extra["theta1_deg"] = std::asin(sin_1) / kDegToRad;
    r.extra["lobe_columns"] = hi - lo + 1;
    std::ostringstream d;
    d.precision(4);
    d << "first order at " << std::asin(sin_1) / kDegToRad << " deg: ceiling z " << 1e3 * z_meas
      << " mm rendered vs " << 1e3 * z_pred << " mm predicted; errors are in pixel footprints ("
      << 1e3 * footprint << " mm), shown as %, target 1 footprint";
    r.detail = d.str();
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return r;
  };
  return c;
}

}  // namespace diffray::validate
