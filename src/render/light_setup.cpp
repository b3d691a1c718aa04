#include "diffray/render/light_setup.h"

#include <algorithm>
#include <cmath>

#include "diffray/core/error.h"
#include "diffray/wbsdf/microstructure.h"

namespace diffray::render {

namespace {

constexpr std::size_t kMaxTableCells = 8'000'000;

// Centre and corners of a rectangle: the points whose directions bound what an occluder sends or receives.
std::vector<Vec3> rectPoints(const geometry::Frame& f, double hx, double hy) {
  return {f.origin, f.origin + hx * f.ex + hy * f.ey, f.origin + hx * f.ex - hy * f.ey,
          f.origin - hx * f.ex + hy * f.ey, f.origin - hx * f.ex - hy * f.ey};
}

struct ShiftBounds {
  double dx = 0.0, dy = 0.0;  ///< largest change of the direction cosine along ex and along ey
};

// Δ along the occluder's axes between every incident direction (lights, other occluders, and diffuse
// rectangles when photons bounce on from them: settings.diffuse_bounces > 0) and every outgoing one (other
// objects), sampled at the points `here` of the occluder (its centre and corners), plus
// `deflection` (the direction cosines' change a lens adds at those points, along ex and ey, which the table
// need not hold: lensShiftBounds).
ShiftBounds shiftBounds(const LightScene& s, int k, const std::vector<Vec3>& here, double deflection_x = 0.0,
                        double deflection_y = 0.0) {
  const OccluderSpec& occ = s.occluders[k];
  const geometry::Frame& f = occ.frame;
  std::vector<Vec3> others, senders;  // points of every other object; of those light can come from
  for (int i = 0; i < s.targetCount(); ++i) {
    if (i == static_cast<int>(s.rects.size()) + k) continue;
    const LightScene::Target t = s.target(i);
    // A diffuse rectangle sends light on only if photons continue after a diffuse bounce.
    const bool sends = i >= static_cast<int>(s.rects.size()) || s.settings.diffuse_bounces > 0;
    for (const Vec3& p : rectPoints(*t.frame, t.half_x_m, t.half_y_m)) {
      others.push_back(p);
      if (sends) senders.push_back(p);
    }
  }
  std::vector<Vec3> in_dirs, out_dirs;
  for (const Vec3& h : here) {
    for (const Light& l : s.lights)
      if (l.kind == Light::Kind::Point) {
        if ((h - l.position_m).norm() > 0) in_dirs.push_back((h - l.position_m).normalized());
      }
    for (const Light& l : s.lights)  // an area light: its centre and corners, as point lights
      if (l.kind == Light::Kind::Area)
        for (const Vec3& p : rectPoints(l.frame, l.half_x_m, l.half_y_m))
          if ((h - p).norm() > 0) in_dirs.push_back((h - p).normalized());
    for (const Vec3& p : others)
      if ((p - h).norm() > 0) out_dirs.push_back((p - h).normalized());
    for (const Vec3& p : senders)
      if ((p - h).norm() > 0) in_dirs.push_back((h - p).normalized());
  }
  for (const Light& l : s.lights)
    if (l.kind == Light::Kind::Collimated) in_dirs.push_back(l.frame.n);
  ShiftBounds b;
  for (const Vec3& i : in_dirs)
    for (const Vec3& o : out_dirs) {
      b.dx = std::max(b.dx, std::abs(o.dot(f.ex) - i.dot(f.ex) - deflection_x));
      b.dy = std::max(b.dy, std::abs(o.dot(f.ey) - i.dot(f.ey) - deflection_y));
    }
  return b;
}

ShiftBounds shiftBounds(const LightScene& s, int k) {
  const OccluderSpec& occ = s.occluders[k];
  return shiftBounds(s, k, rectPoints(occ.frame, occ.half_x_m, occ.half_y_m));
}

// A lens leaves a ray at α_o = α_i + λu' − x/f (transport::Occluder::focal_length_m): the table draws only
// u', the diffraction around the geometric ray, so its range is the largest |α_o − α_i + x/f| (and along y)
// that reaches an object, at each point of the opening (t = 0 elsewhere, so the plate's corners need no
// shift) with that point's own deflection. The plain bound (plate corners, no deflection) would be wrong
// both ways: it misses the shifts a ray needs where −x/f and α_o − α_i differ in sign (a strong lens, f well
// below the distances to the objects: a focal spot partly outside the table), and it counts the geometric
// spread of the whole plate, which the lens undoes (rays from every x meet at the focus), so it is wider
// than needed ((W + h)/f against W/f for a beam onto a wall of half-width W in the focal plane, plate
// half-width h: 1.44× for rooms/light/lens-psf.json, test RenderLens): more u-cells at the same du, and past
// the 8-million-cell cap coarser ones that blur the focal spot.
ShiftBounds lensShiftBounds(const LightScene& s, int k) {
  const OccluderSpec& occ = s.occluders[k];
  const geometry::Frame& f = occ.frame;
  ShiftBounds b;
  for (const Vec3& h : rectPoints(f, 0.5 * occ.aperture_width_m, 0.5 * occ.aperture_height_m)) {
    const Vec3 r = h - f.origin;
    const ShiftBounds at =
        shiftBounds(s, k, {h}, -r.dot(f.ex) / occ.focal_length_m, -r.dot(f.ey) / occ.focal_length_m);
    b.dx = std::max(b.dx, at.dx);
    b.dy = std::max(b.dy, at.dy);
  }
  return b;
}

}  // namespace

wbsdf::TableOptions axisTableOptions(const wbsdf::Microstructure& m, double delta_cos, double lambda_min_m,
                                     double lambda_max_m, double footprint_m, double throw_m) {
  wbsdf::TableOptions o;
  o.wavelength_m = lambda_min_m;
  o.u_half_range_per_m = std::min(2.0 / lambda_min_m, std::max(1.02 * delta_cos, 1e-6) / lambda_min_m);
  if (m.lineSpacing() <= 0.0) {
    const double du = footprint_m / (8.0 * lambda_max_m * std::max(throw_m, 1e-9));
    o.cells_per_coherence =
        std::max(o.cells_per_coherence, core::checkedCount("table columns", 1.0 / (du * m.coherenceLength()), 1e9));
  }
  const double dx = std::min(footprint_m, m.featureSize()) / 8.0;
  o.rows_per_feature = std::clamp(core::checkedCount("table rows", m.featureSize() / dx, 1e9), 8, 1024);
  o.max_cells = kMaxTableCells;
  o.coarsen_to_fit = true;
  return o;
}

std::unique_ptr<PreparedScene> prepareScene(const LightScene& s, bool brute_force) {
  auto out = std::make_unique<PreparedScene>();
  out->spec = &s;
  out->camera = Camera(s.camera);
  const Camera& cam = out->camera;
  const double lambda_min = s.shortestWavelengthNm() * 1e-9, lambda_max = s.longestWavelengthNm() * 1e-9;

  for (std::size_t k = 0; k < s.occluders.size(); ++k) {
    const OccluderSpec& spec = s.occluders[k];
    // The diffuse rectangle needing the finest cells: the smallest ratio of pixel footprint to throw.
    double ratio = 1e300, throw_m = 1.0;
    for (const DiffuseRect& r : s.rects) {
      const double fp = cam.pixelPitch() * (r.frame.origin - cam.position()).norm();
      const double z = std::max((r.frame.origin - spec.frame.origin).norm(), 1e-9);
      if (fp / z < ratio) ratio = fp / z, throw_m = z;
    }
    const double fp_at_throw = ratio * throw_m;
    const ShiftBounds b = spec.kind == OccluderSpec::Kind::Lens ? lensShiftBounds(s, static_cast<int>(k))
                                                                 : shiftBounds(s, static_cast<int>(k));
    std::shared_ptr<wbsdf::Microstructure> mx, my;
    transport::Occluder occ;
    switch (spec.kind) {
      case OccluderSpec::Kind::Slit:
        mx = wbsdf::Openings::slit(spec.slit_width_m);
        if (spec.slit_height_m > 0) my = wbsdf::Openings::slit(spec.slit_height_m);
        break;
      case OccluderSpec::Kind::DoubleSlit:
        mx = wbsdf::Openings::slits(2, spec.slit_width_m, spec.spacing_m);
        if (spec.slit_height_m > 0) my = wbsdf::Openings::slit(spec.slit_height_m);
        break;
      case OccluderSpec::Kind::Aperture:
        mx = wbsdf::Openings::slit(spec.aperture_width_m);
        my = wbsdf::Openings::slit(spec.aperture_height_m);
        break;
      case OccluderSpec::Kind::Grating:
        mx = std::make_shared<wbsdf::PhaseGrating>(spec.period_m, spec.modulation);
        occ.reflect = true;
        break;
      case OccluderSpec::Kind::Lens:  // the opening's tables; the lens's deflection is geometric (scene.h)
        mx = wbsdf::Openings::slit(spec.aperture_width_m);
        my = wbsdf::Openings::slit(spec.aperture_height_m);
        occ.focal_length_m = spec.focal_length_m;
        break;
    }
    occ.table_x = wbsdf::WbsdfTable::build(*mx, axisTableOptions(*mx, b.dx, lambda_min, lambda_max, fp_at_throw, throw_m));
    if (my) occ.table_y = wbsdf::WbsdfTable::build(*my, axisTableOptions(*my, b.dy, lambda_min, lambda_max, fp_at_throw, throw_m));
    occ.frame = spec.frame;
    occ.half_x_m = spec.half_x_m;
    occ.half_y_m = spec.half_y_m;
    out->scene.addOccluder(std::move(occ));
  }
  for (const DiffuseRect& r : s.rects) {
    receiver::Screen scr;
    scr.frame = r.frame;
    scr.half_x_m = r.half_x_m;
    scr.half_y_m = r.half_y_m;
    out->scene.addScreen(scr);
  }
  out->scene.build(brute_force);

  out->pixel_solid_angle_sr.resize(static_cast<std::size_t>(cam.width()) * cam.height());
  for (int iy = 0; iy < cam.height(); ++iy)
    for (int ix = 0; ix < cam.width(); ++ix)
      out->pixel_solid_angle_sr[static_cast<std::size_t>(iy) * cam.width() + ix] = cam.pixelSolidAngle(ix, iy);
  return out;
}

}  // namespace diffray::render
