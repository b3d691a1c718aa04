#pragma once
// A light scene (rooms/light/README.md): diffuse rectangles with a (spectral) albedo, WBSDF
// occluders (slit, double slit, rectangular aperture, reflecting phase grating, thin lens), lights (a point
// light or a collimated laser beam, each with a spectrum) and a pinhole camera. Units: metres, watts, nanometres for
// wavelengths; positions and directions in the world frame. Rectangles and occluders are centred on
// `frame.origin` with half-extents along frame.ex (x, the width) and frame.ey (y, the height); the frame comes
// from a normal and an up vector: ey = up projected on the plane, ex = ey × normal, so n = ex × ey.
// Plain data, built by loadLightScene() or in code (tests); safe to share between threads once built.
#include <cstdint>
#include <string>
#include <vector>

#include "diffray/core/math.h"
#include "diffray/geometry/frame.h"
#include "diffray/render/camera.h"

namespace diffray::render {

/// The visible range every spectrum lives in (the wavelength sampler's default range, color/).
inline constexpr double kVisibleLoNm = 380.0, kVisibleHiNm = 780.0;

/// A light's spectral power: equal energy per nanometre over [380, 780] nm (White), or one line (Laser).
struct Spectrum {
  enum class Kind { White, Laser };
  Kind kind = Kind::White;
  double wavelength_nm = 550.0;  ///< Laser only
  double loNm() const { return kind == Kind::Laser ? wavelength_nm : kVisibleLoNm; }
  double hiNm() const { return kind == Kind::Laser ? wavelength_nm : kVisibleHiNm; }
};

/// Albedo (0…1) against wavelength: a constant (one value, no knots) or piecewise linear through
/// (wavelengths_nm[i], values[i]), constant beyond the first and last knot.
struct Albedo {
  std::vector<double> wavelengths_nm;
  std::vector<double> values{0.8};
  double at(double wavelength_nm) const;
  double max() const;
};

/// A two-sided Lambertian rectangle: light arriving on either face leaves from that face.
struct DiffuseRect {
  std::string name;
  geometry::Frame frame;
  double half_x_m = 0.5, half_y_m = 0.5;
  Albedo albedo;
};

/// An opaque rectangle whose microstructure lets light through (openings) or reflects it (gratings), all
/// centred on the frame's origin. Slit and double slit: openings along x, uniform along y (the slits run the
/// occluder's height) unless slit_height_m > 0. Aperture: an opening a × b (separable: W(x,y,u,v) = W_x(x,u)·W_y(y,v)).
/// Grating: t = exp(i(m/2)·sin(2πx/Λ)) (paper eq. 14–15), reflecting the diffracted wave (paper eq. 9) with
/// power reflectance `reflectance` (the metal layer: a CD's aluminium reflects about 0.9 of the visible).
/// Lens: an ideal thin lens of focal length focal_length_m behind a rectangular opening a × b centred on the
/// frame's origin, t = rect(x/a)·rect(y/b)·exp(−iπ(x² + y²)/(λf)) (transport::Occluder::focal_length_m:
/// the opening's WBSDF plus the geometric deflection). Rectangular only: a circular pupil's WDF is not
/// separable in x and y.
struct OccluderSpec {
  enum class Kind { Slit, DoubleSlit, Aperture, Grating, Lens };
  std::string name;
  Kind kind = Kind::Slit;
  geometry::Frame frame;
  double half_x_m = 0.01, half_y_m = 0.01;
  double slit_width_m = 0.0, slit_height_m = 0.0, spacing_m = 0.0;  ///< Slit, DoubleSlit
  double aperture_width_m = 0.0, aperture_height_m = 0.0;           ///< Aperture, Lens
  double focal_length_m = 0.0;                                       ///< Lens: > 0
  double period_m = 0.0, modulation = 0.0;                           ///< Grating (m in radians)
  double reflectance = 1.0;                                          ///< Grating: power reflectance, [0, 1]
};

/// Point light: isotropic, radiant power power_w; with `aim` ≥ 0 its photons are drawn only toward that
/// object's rectangle (index into LightScene::targets()), the rest of its light is left out (use it when
/// that rectangle is all the light can reach that matters, e.g. the opening of an occluder).
/// Collimated: a beam of direction `direction` through the rectangle frame (normal = direction) of
/// half-extents half_x_m × half_y_m around position_m, power_w spread evenly over it (a laser).
/// Area: a Lambertian rectangle (a frosted lamp) centred on position_m, frame.n the normal of the face that
/// emits, half-extents half_x_m × half_y_m; power_w leaves that face with the uniform radiance
/// L = P/(πA) (two_sided: both faces, P/2 each, L = P/(2πA)). With `aim` ≥ 0 its photons are drawn only toward
/// that rectangle, as for a point light. A light is not an object: it blocks nothing and the camera does not
/// see it.
struct Light {
  enum class Kind { Point, Collimated, Area };
  std::string name;
  Kind kind = Kind::Point;
  Spectrum spectrum;
  double power_w = 1.0;
  Vec3 position_m{0, 0, 0};
  geometry::Frame frame;  ///< Collimated: the beam's cross-section (n = direction)
  double half_x_m = 0.0, half_y_m = 0.0;
  int aim = -1;
  bool two_sided = false;  ///< Area: both faces emit
};

struct RenderSettings {
  std::uint64_t photons = 1'000'000;
  std::uint64_t seed = 1;
  int max_bounces = 16;     ///< scattering events (occluders and diffuse) per photon path
  int diffuse_bounces = 0;  ///< diffuse reflections a photon may continue after (0: direct light only)
  double exposure = 0.0;    ///< PNG scale; 0 = automatic (render/film.h: autoExposure)
};

struct LightScene {
  std::string name, file;
  std::vector<DiffuseRect> rects;
  std::vector<OccluderSpec> occluders;
  std::vector<Light> lights;
  CameraSpec camera;
  RenderSettings settings;

  /// A rectangle an `aim` can name: index i < rects.size() is rects[i], else occluders[i − rects.size()].
  struct Target {
    const geometry::Frame* frame;
    double half_x_m, half_y_m;
  };
  Target target(int i) const;
  int targetCount() const { return static_cast<int>(rects.size() + occluders.size()); }
  double shortestWavelengthNm() const;
  double longestWavelengthNm() const;
};

/// The frame of a rectangle from its centre, normal and up (ey = up projected, ex = ey × n); throws
/// InputError(field, …) for a zero normal or an up parallel to it.
geometry::Frame rectFrame(const Vec3& centre, const Vec3& normal, const Vec3& up, const std::string& field);

/// Reads a light scene file (rooms/light/README.md). Errors: core::InputError "FILE: FIELD: what".
LightScene loadLightScene(const std::string& path);
/// The same from JSON text; `file` names it in messages (and relative paths, none so far).
LightScene parseLightScene(const std::string& text, const std::string& file);

}  // namespace diffray::render
