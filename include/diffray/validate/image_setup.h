#pragma once
// The rendered-image cases: rooms/light/double-slit.json's set-up built in code — a laser
// beam through Young's double slit onto a diffuse wall, seen by the pinhole camera of render/camera.h — and
// the comparison of the image's central band of rows with the Fraunhofer pattern (reference/fraunhofer.h)
// averaged over each pixel's solid angle, in absolute radiance (W m⁻² sr⁻¹: ρ/π times the irradiance
// I₀·|T(u)|²·cos²θ/(λr), I₀ the beam's power over its cross-section). No scale is fitted.
// The oracle's pixel geometry (image-plane coordinates, Gauss–Legendre over each pixel) is written here,
// not taken from the renderer's Camera. Units: metres, watts. Pure functions; thread-safe.
#include <cstdint>
#include <functional>
#include <string>

#include "diffray/render/light_scene.h"
#include "diffray/render/light_tracer.h"
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

/// The oracles' pinhole camera (its own geometry, not render::Camera's): on the z axis at distance_m in front
/// of a wall normal to z, looking down +z with up +y, so right = −x; horizontal field fov_deg over width ×
/// height square pixels. The image-plane point (X, Y) (at distance 1) sees the wall point (−X·D, Y·D).
struct WallView {
  double distance_m = 1.0, fov_deg = 10.0;
  int width = 1, height = 1;
  double tanHalf() const;  ///< T = tan(fov/2): the image plane spans X ∈ [−T, T]
  double pitch() const;    ///< one pixel in image-plane units, 2T/width
  double topY() const;     ///< the image's top edge, Y = pitch·height/2
  double columnX(int ix) const;  ///< wall x seen through the centre of column ix
  double rowY(int iy) const;     ///< wall y seen through the centre of row iy
  /// Mean of radiance(x_wall, y_wall) over pixel (ix, iy)'s solid angle, dω = dX dY/(1 + X² + Y²)^{3/2}
  /// (Gauss–Legendre 8 × 8 in image-plane coordinates).
  double pixelMean(int ix, int iy, const std::function<double(double, double)>& radiance) const;
};

struct ImageRunOptions {
  std::uint64_t photons = 0;
  std::uint64_t seed = 1;
  bool uniform_shifts = false;  ///< render::RenderOptions::uniform_shifts (the render-is bench)
  std::uint64_t chunk_photons = render::RenderOptions{}.chunk_photons;  ///< more chunks: steadier std errors
  std::function<void(std::uint64_t)> on_progress;
};

/// A validate case's run options as image options (photons = --rays, 0 for the case's default; seed;
/// progress), after checking that the case was asked for the wigner model (image cases have no other).
ImageRunOptions imageRunOptions(const RunOptions& o, const std::string& case_name);

/// Renders `scene` with the options (o.photons, or `default_photons` when it is 0); `seconds_render` gets the
/// render's own wall time (preparing the tables excluded).
render::RenderResult renderImageScene(const render::LightScene& scene, const ImageRunOptions& o,
                                      std::uint64_t default_photons, double& seconds_render);

/// Renders the scene and scores each column of the band of rows lying wholly inside the beam (averaged
/// over those rows: the pattern does not depend on y there) against the pixel-averaged oracle.
/// Rows: one per column, x_m the column's centre on the wall. extra: rows_averaged, seconds_render.
CaseResult runImageDoubleSlit(const DoubleSlitImageSetup& s, const ImageRunOptions& o);

/// The lens image (rooms/light/lens-psf.json, src/validate/image_lens_case.cpp): a thin lens with a rectangular
/// opening a × b (focal length f, at z = 0, transport::Occluder::focal_length_m) lit either by a laser beam
/// exactly filling the opening (source_distance_m = 0) or by a point light on the axis at s_o =
/// source_distance_m > f before it, aimed at it; a diffuse wall where the lens images the source, z = L with
/// L = f for the beam and L = s_i = 1/(1/f − 1/s_o) for the point (the thin-lens equation); the camera on
/// the axis at camera_distance_m before the wall, its field spanning `lobes` first zeros λL/a either side.
/// Oracle: the Fraunhofer pattern of the opening in that plane, E(x, y) = I₀·(ab/λL)²·sinc²(ax/λL)·
/// sinc²(by/λL), I₀ the intensity on the opening (P/(ab) for the beam, P/(4π s_o²) for the point; paraxial,
/// as the lens is), times ρ/π, averaged over each pixel.
struct LensPsfImageSetup {
  double wavelength_m = 550e-9, aperture_width_m = 1e-3, aperture_height_m = 1e-3, focal_length_m = 0.5;
  double source_distance_m = 0.0;  ///< 0: a collimated beam; > f: a point light this far before the lens
  double albedo = 0.9, power_w = 1e-3, camera_distance_m = 0.05, lobes = 4.0;
  int width = 121, height = 121;  ///< odd: a central row and column of pixels
  double imageDistance() const;  ///< L: f, or s_i from 1/s_o + 1/s_i = 1/f
  double fovDeg() const;  ///< the field that spans `lobes` zeros of the wider lobe either side
};
/// From the case's parameters (wavelength, width, height, focal, source, lobes, pixels).
LensPsfImageSetup lensPsfImageSetup(const Params& p);
render::LightScene lensPsfImageScene(const LensPsfImageSetup& s);
/// Renders and scores the central row (label "row", x_m its columns' wall x) then the central column (label
/// "column", y_m) against the oracle, absolute radiance, no fitted scale. extra: seconds_render.
CaseResult runImageLensPsf(const LensPsfImageSetup& s, const ImageRunOptions& o);
/// The scoring alone, for an image rendered from lensPsfImageScene(s) (or a variant of it: a test's defocused
/// lens): rows, errors against the oracle of `s`.
CaseResult scoreImageLensPsf(const LensPsfImageSetup& s, const render::RenderResult& img);

}  // namespace diffray::validate
