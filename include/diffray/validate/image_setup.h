#pragma once
// The rendered-image cases (issue 6, item 3): rooms/light/double-slit.json's set-up built in code — a laser
// beam through Young's double slit onto a diffuse wall, seen by the pinhole camera of render/camera.h — and
// the comparison of the image's central band of rows with the Fraunhofer pattern (reference/fraunhofer.h)
// averaged over each pixel's solid angle, in absolute radiance (W m⁻² sr⁻¹: ρ/π times the irradiance
// I₀·|T(u)|²·cos²θ/(λr), I₀ the beam's power over its cross-section). No scale is fitted.
// The oracle's pixel geometry (image-plane coordinates, Gauss–Legendre over each pixel) is written here,
// not taken from the renderer's Camera. Units: metres, watts. Pure functions; thread-safe.
#include <cstdint>
#include <functional>

#include "diffray/render/light_scene.h"
#include "diffray/validate/case.h"

namespace diffray::validate {

/// The double-slit image: slits at z = 0, the wall at z = distance, the camera at z = 0.6·distance looking
/// at the wall (fov 5.7°, 480 × 160 pixels), a laser beam 0.3 mm × 6 mm (exactly the slits' extent across
/// x for the default slits) of 1 mW. Defaults: rooms/light/double-slit.json.
struct DoubleSlitImageSetup {
  double wavelength_m = 632.8e-9, slit_width_m = 50e-6, spacing_m = 250e-6, distance_m = 2.0;
  double albedo = 0.9, power_w = 1e-3, beam_half_x_m = 0.15e-3, beam_half_y_m = 3e-3;
  int width = 480, height = 160;
  double fov_deg = 5.7;
};

/// From the case's parameters (wavelength, width, spacing, distance); throws InputError when the beam
/// would not cover both slits.
DoubleSlitImageSetup doubleSlitImageSetup(const Params& p);
render::LightScene doubleSlitImageScene(const DoubleSlitImageSetup& s);

struct ImageRunOptions {
  std::uint64_t photons = 0;
  std::uint64_t seed = 1;
  bool uniform_shifts = false;  ///< render::RenderOptions::uniform_shifts (the render-is bench)
  std::function<void(std::uint64_t)> on_progress;
};

/// Renders the scene and scores each column of the band of rows lying wholly inside the beam (averaged
/// over those rows: the pattern does not depend on y there) against the pixel-averaged oracle.
/// Rows: one per column, x_m the column's centre on the wall. extra: rows_averaged, seconds_render.
CaseResult runImageDoubleSlit(const DoubleSlitImageSetup& s, const ImageRunOptions& o);

}  // namespace diffray::validate
