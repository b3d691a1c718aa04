#include "diffray/render/light_setup.h"

#include <algorithm>
#include <cmath>

#include "diffray/core/error.h"
#include "diffray/render/direction_bounds.h"
#include "diffray/wbsdf/microstructure.h"

namespace diffray::render {

namespace {

constexpr std::size_t kMaxTableCells = 8'000'000;

struct ShiftBounds {
  double dx = 0.0, dy = 0.0;  ///< largest change of the direction cosine along ex and along ey
};

/// A rectangle as the parallelotope of its points: centre and half-side vectors.
struct Box {
  Vec3 centre, gx, gy;
};

// Cells per side of the occluder region over which incident and outgoing directions are bounded together:
// within a cell the two are bounded separately (exactly, render/direction_bounds.h), which over-counts only
// by their variation across the cell.
constexpr int kRegionCells = 8;
// A lens's opening is sampled at points instead (a grid of this many intervals per side, corners included):
// there the outgoing direction and the lens's deflection −x/f nearly cancel (for objects near the focal
// plane), which bounding them separately over a cell would lose; what is left varies with x about linearly,
// so its extremes lie at the corners.
constexpr int kLensPoints = 16;

ShiftBounds shiftBounds(const LightScene& s, int k, const Box& region, double focal_m) {
  const geometry::Frame& f = s.occluders[k].frame;
  std::vector<Box> others, senders;  // every other object; those light can come from
  for (int i = 0; i < s.targetCount(); ++i) {
    if (i == static_cast<int>(s.rects.size()) + k) continue;
    const LightScene::Target t = s.target(i);
    const Box box{t.frame->origin, t.half_x_m * t.frame->ex, t.half_y_m * t.frame->ey};
    others.push_back(box);
    // A diffuse rectangle sends light on only if photons continue after a diffuse bounce.
    if (i >= static_cast<int>(s.rects.size()) || s.settings.diffuse_bounces > 0) senders.push_back(box);
  }
  for (const Light& l : s.lights)
    if (l.kind == Light::Kind::Area) senders.push_back({l.frame.origin, l.half_x_m * l.frame.ex, l.half_y_m * l.frame.ey});
  ShiftBounds b;
  const bool lens = focal_m > 0.0;
  const int n = lens ? kLensPoints : kRegionCells;
  const Vec3 cx = lens ? Vec3::Zero() : Vec3(region.gx / n), cy = lens ? Vec3::Zero() : Vec3(region.gy / n);
  for (int ix = 0; ix < n + (lens ? 1 : 0); ++ix)
    for (int iy = 0; iy < n + (lens ? 1 : 0); ++iy) {
      // A cell's centre, or a grid point (lens).
      const double fx = lens ? 2.0 * ix / n - 1.0 : (2.0 * ix + 1.0) / n - 1.0;
      const double fy = lens ? 2.0 * iy / n - 1.0 : (2.0 * iy + 1.0) / n - 1.0;
      const Vec3 h = region.centre + fx * region.gx + fy * region.gy;
      CosineRange out_x, out_y, in_x, in_y;
      const auto join = [](CosineRange& into, const CosineRange& r) {
        if (!r.empty()) into.add(r.lo), into.add(r.hi);
      };
      for (const Box& o : others) {  // p − h, p on the object, h in the cell
        const std::vector<Vec3> g{o.gx, o.gy, cx, cy};
        join(out_x, cosineRange(o.centre - h, g, f.ex));
        join(out_y, cosineRange(o.centre - h, g, f.ey));
      }
      for (const Box& src : senders) {  // h − p, p on the sender
        const std::vector<Vec3> g{src.gx, src.gy, cx, cy};
        join(in_x, cosineRange(h - src.centre, g, f.ex));
        join(in_y, cosineRange(h - src.centre, g, f.ey));
      }
      for (const Light& l : s.lights) {
        if (l.kind == Light::Kind::Point) {
          join(in_x, cosineRange(h - l.position_m, {cx, cy}, f.ex));
          join(in_y, cosineRange(h - l.position_m, {cx, cy}, f.ey));
        } else if (l.kind == Light::Kind::Collimated) {
          in_x.add(l.frame.n.dot(f.ex));
          in_y.add(l.frame.n.dot(f.ey));
        }
      }
      if (out_x.empty() || in_x.empty()) continue;
      // The lens's deflection over the cell: −r/f for r the offset from the lens centre along each axis.
      // The lens's deflection at the point: d = −r/f, r the offset from the lens centre along each axis.
      const Vec3 r = h - f.origin;
      const double ax = lens ? r.dot(f.ex) / focal_m : 0.0, ay = lens ? r.dot(f.ey) / focal_m : 0.0;
      // max |o − i − d| with d = −a: the larger of o_hi − i_lo + a and i_hi − a − o_lo.
      b.dx = std::max({b.dx, out_x.hi - in_x.lo + ax, in_x.hi - ax - out_x.lo});
      b.dy = std::max({b.dy, out_y.hi - in_y.lo + ay, in_y.hi - ay - out_y.lo});
    }
  return b;
}

// The plate's own bound: every point of it can pass light (t = 0 only absorbs).
ShiftBounds shiftBounds(const LightScene& s, int k) {
  const OccluderSpec& occ = s.occluders[k];
  return shiftBounds(s, k, {occ.frame.origin, occ.half_x_m * occ.frame.ex, occ.half_y_m * occ.frame.ey}, 0.0);
}

// A lens leaves a ray at α_o = α_i + λu' − x/f (transport::Occluder::focal_length_m): the table draws only
// u', the diffraction around the geometric ray, so its range is the largest |α_o − α_i + x/f| (and along y)
// that reaches an object, at each point of the opening (t = 0 elsewhere, so the plate's corners need no
// shift) with that point's own deflection. The plain bound (whole plate, no deflection) would be wrong
// both ways: it misses the shifts a ray needs where −x/f and α_o − α_i differ in sign (a strong lens, f well
// below the distances to the objects: a focal spot partly outside the table), and it counts the geometric
// spread of the whole plate, which the lens undoes (rays from every x meet at the focus), so it is wider
// than needed ((W + h)/f against W/f for a beam onto a wall of half-width W in the focal plane, plate
// half-width h: 1.44× for rooms/light/lens-psf.json, test RenderLens): more u-cells at the same du, and past
// the 8-million-cell cap coarser ones that blur the focal spot.
ShiftBounds lensShiftBounds(const LightScene& s, int k) {
  const OccluderSpec& occ = s.occluders[k];
  const geometry::Frame& f = occ.frame;
  return shiftBounds(s, k, {f.origin, 0.5 * occ.aperture_width_m * f.ex, 0.5 * occ.aperture_height_m * f.ey},
                     occ.focal_length_m);
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

std::unique_ptr<PreparedScene> prepareScene(const LightScene& s, bool brute_force,
                                            const core::ProgressFactory& table_progress) {
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
    const auto build = [&](const wbsdf::Microstructure& m, double delta_cos, const char* axis) {
      wbsdf::TableOptions o = axisTableOptions(m, delta_cos, lambda_min, lambda_max, fp_at_throw, throw_m);
      if (table_progress)
        o.on_row = table_progress("WBSDF table " + (spec.name.empty() ? "#" + std::to_string(k + 1) : spec.name) +
                                  " " + axis);
      return wbsdf::WbsdfTable::build(m, o);  // o, and with it the progress bar, ends here
    };
    occ.table_x = build(*mx, b.dx, "x");
    if (my) occ.table_y = build(*my, b.dy, "y");
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
