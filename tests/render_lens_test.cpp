// The thin lens (transport::Occluder::focal_length_m, render OccluderSpec::Kind::Lens) against closed forms
// that share no code with the tracer:
//  - the scattering rule: α_o = α_i + λu' − x/f, β_o = β_i + λv' − y/f with (u', v') the tables' own draw,
//    and with f = 0 exactly the rule without a lens (bit for bit);
//  - an oblique collimated beam (angle θ to the axis) focuses where its chief ray, undeviated through the
//    lens's centre, meets the focal plane: X = f·tanθ (the ray model; paraxial optics would say f·sinθ,
//    which at θ = 0.2 rad lies 2 mm away), measured by transport::trace on a fine screen;
//  - the rendered focal-plane image (validate image-lens-psf at reduced photons): its central row and column
//    against the opening's Fraunhofer pattern I₀(ab/λf)²·sinc²(ax/λf)·sinc²(by/λf)·ρ/π averaged over each
//    pixel, absolute radiance (validate/image_setup.h), within the pixels' standard errors;
//  - a point source at s_o images at s_i with 1/s_o + 1/s_i = 1/f: the wall there shows the same pattern with
//    λs_i for λf (the thin-lens equation), in absolute radiance;
//  - the lens's table range leaves the geometric deflection out (render/light_setup.h).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "diffray/render/light_setup.h"
#include "diffray/render/light_tracer.h"
#include "diffray/transport/tracer.h"
#include "diffray/validate/image_setup.h"
#include "diffray/wbsdf/microstructure.h"
#include "diffray/wbsdf/table.h"
#include "validate_fixtures.h"

namespace {

using namespace diffray;
using core::Vec3;

std::shared_ptr<const wbsdf::WbsdfTable> slitTable(double width_m, double u_half_range_per_m) {
  wbsdf::TableOptions o;
  o.wavelength_m = 550e-9;
  o.u_half_range_per_m = u_half_range_per_m;
  return wbsdf::WbsdfTable::build(*wbsdf::Openings::slit(width_m), o);
}

// An occluder at z = 0 facing +z with a square opening (tables along both axes).
transport::Occluder squareOpening(double width_m, double focal_length_m) {
  transport::Occluder occ;
  occ.frame.origin = Vec3(0, 0, 0);
  occ.frame.ex = Vec3(1, 0, 0), occ.frame.ey = Vec3(0, 1, 0), occ.frame.n = Vec3(0, 0, 1);
  occ.half_x_m = occ.half_y_m = width_m;
  occ.table_x = occ.table_y = slitTable(width_m, 0.01 / 550e-9);
  occ.focal_length_m = focal_length_m;
  return occ;
}

TEST(TransportLens, ScatteringAddsTheGeometricDeflectionAndNothingWithoutALens) {
  const double lambda = 550e-9, a = 1e-3, f = 0.5;
  const transport::Occluder plain = squareOpening(a, 0.0), lens = squareOpening(a, f);
  const double in[3] = {0.03, -0.02, std::sqrt(1.0 - 0.03 * 0.03 - 0.02 * 0.02)};
  int checked = 0;
  for (double x : {-0.45e-3, -0.1e-3, 0.0, 0.2e-3, 0.49e-3})
    for (double y : {-0.3e-3, 0.0, 0.41e-3})
      for (double xi_x : {0.05, 0.5, 0.93})
        for (double xi_y : {0.2, 0.71}) {
          // The rule written out from the tables' own draws (the oracle), then both occluders.
          const auto sx = plain.table_x->sample(x, xi_x), sy = plain.table_y->sample(y, xi_y);
          const double alpha = in[0] + lambda * sx.u_shift, beta = in[1] + lambda * sy.u_shift;
          const double gamma = std::sqrt(1.0 - alpha * alpha - beta * beta);
          double d0[3] = {in[0], in[1], in[2]}, w0 = 0.0;
          ASSERT_EQ(transport::scatterAtOccluder(plain, plain.frame, x, y, lambda, xi_x, xi_y, d0, w0),
                    transport::ScatterFate::Continue);
          EXPECT_EQ(w0, sx.weight * sy.weight);
          EXPECT_EQ(d0[0], alpha);  // f = 0: bit for bit the rule without a lens
          EXPECT_EQ(d0[1], beta);
          EXPECT_EQ(d0[2], gamma);
          double d1[3] = {in[0], in[1], in[2]}, w1 = 0.0;
          ASSERT_EQ(transport::scatterAtOccluder(lens, lens.frame, x, y, lambda, xi_x, xi_y, d1, w1),
                    transport::ScatterFate::Continue);
          EXPECT_EQ(w1, w0);  // the lens is a pure phase: the same weight
          EXPECT_NEAR(d1[0], alpha - x / f, 1e-15);
          EXPECT_NEAR(d1[1], beta - y / f, 1e-15);
          EXPECT_NEAR(d1[2], std::sqrt(1.0 - d1[0] * d1[0] - d1[1] * d1[1]), 1e-15);
          ++checked;
        }
  EXPECT_EQ(checked, 90);
}

// Centroid of the screen's energy over the window [c − half, c + half], the edge bins counted by the
// fraction of them inside, re-centred on the result until it settles: for a lobe symmetric about X0 the
// fixed point is X0, whatever bin the window starts on.
double settledCentroid(const transport::TraceResult& r, const receiver::Screen& scr, double start_m, double half_m) {
  double c = start_m;
  for (int it = 0; it < 50; ++it) {
    double sum = 0.0, sum_x = 0.0;
    for (int i = 0; i < scr.nx; ++i) {
      const double lo = scr.binCentreX(i) - 0.5 * scr.binWidthX(), hi = lo + scr.binWidthX();
      const double in_lo = std::max(lo, c - half_m), in_hi = std::min(hi, c + half_m);
      if (in_hi <= in_lo) continue;
      const double e = r.screens[0].sum[i] * (in_hi - in_lo) / scr.binWidthX();
      sum += e;
      sum_x += e * 0.5 * (in_lo + in_hi);
    }
    c = sum_x / sum;
  }
  return c;
}

TEST(StatTransportLens, ObliqueBeamFocusesAtFTanTheta) {
  // A 1 mm square lens (f = 0.5 m) at z = 0; a 550 nm beam at θ = 0.2 rad to the axis in the x–z plane;
  // a screen in the focal plane z = f, 10 µm bins along x around the focus. Eight seeds give the centroid's
  // scatter.
  const double lambda = 550e-9, a = 1e-3, f = 0.5, theta = 0.2;
  const double expect = f * std::tan(theta), paraxial = f * std::sin(theta);
  transport::Scene scene;
  transport::Occluder lens = squareOpening(a, f);
  lens.half_x_m = lens.half_y_m = 2e-3;
  lens.table_x = lens.table_y = slitTable(a, 0.004 / lambda);
  scene.addOccluder(lens);
  receiver::Screen scr;
  scr.frame.origin = Vec3(expect, 0, f);
  scr.frame.ex = Vec3(1, 0, 0), scr.frame.ey = Vec3(0, 1, 0), scr.frame.n = Vec3(0, 0, -1);
  scr.half_x_m = 1.0e-3, scr.half_y_m = 5e-3;
  scr.nx = 200, scr.ny = 1;
  scene.addScreen(scr);
  scene.build(true);
  transport::CollimatedSource src;
  src.dir = Vec3(std::sin(theta), 0, std::cos(theta));
  src.frame.origin = Vec3(-0.01 * std::tan(theta), 0, -0.01);  // its rays meet z = 0 around the lens's centre
  src.frame.ex = Vec3(1, 0, 0), src.frame.ey = Vec3(0, 1, 0), src.frame.n = Vec3(0, 0, 1);
  src.half_x_m = src.half_y_m = 0.5e-3;
  src.wavelength_m = lambda;
  const double lobe_m = lambda * f / (a * std::pow(std::cos(theta), 3));  // first zero, along x on the screen
  double sum = 0.0, sum_sq = 0.0;
  const int runs = 8;
  for (int k = 0; k < runs; ++k) {
    transport::TraceOptions o;
    o.rays = 100'000;
    o.seed = 100 + k;
    const transport::TraceResult r = transport::trace(scene, src, o);
    const double c = expect + settledCentroid(r, scr, 0.0, 0.7 * lobe_m);
    sum += c;
    sum_sq += c * c;
  }
  const double mean = sum / runs, se = std::sqrt((sum_sq / runs - mean * mean) / (runs - 1));
  std::printf("oblique focus: X = %.7f m ± %.2g (f tanθ = %.7f, f sinθ = %.7f)\n", mean, se, expect, paraxial);
  EXPECT_NEAR(mean, expect, 4.5 * se + 1e-7);  // 0.1 µm: the fixed point's round-off
  EXPECT_LT(se, 0.01 * (expect - paraxial));     // the test can tell f·tanθ from f·sinθ by far
}

TEST(StatRenderLens, FocalPlaneImageMatchesTheOpeningsFraunhoferPattern) {
  validate::LensPsfImageSetup s;  // 1 mm square, f = 0.5 m, 550 nm: first zeros at ±0.275 mm
  s.width = s.height = 61;
  s.lobes = 3.0;
  validate::ImageRunOptions o;
  o.photons = 1'500'000;
  o.seed = 11;
  const validate::CaseResult r = validate::runImageLensPsf(s, o);
  ASSERT_EQ(r.rows.size(), 122u);
  // The peak pixel: radiance ρ/π·I₀(ab/λf)² (pixel-averaged, a little less), independent of the renderer.
  const double peak = 0.9 / 3.14159265358979323846 * 1e-3 / 1e-6 * std::pow(1e-6 / (550e-9 * 0.5), 2);
  EXPECT_GT(r.rows[30].reference, 0.9 * peak);
  EXPECT_LE(r.rows[30].reference, peak);
  diffray::testing::expectRowsMatch(r);
}

// A point light 1.5 m before a 3 × 3 mm lens (f = 0.5 m): the wall at s_i = 0.75 m from 1/s_o + 1/s_i = 1/f
// shows the opening's Fraunhofer pattern at that distance, I₀(ab/λs_i)²·sinc²(ax/λs_i)·sinc²(by/λs_i) with
// I₀ = P/(4π s_o²), first zeros at ±0.14 mm. The opening is wide enough (depth of focus λ/NA² = 14 cm) that a
// lens of 1.1 f, imaging 12 cm behind the wall (defocus 0.37 λ at the opening's edge), must fail it.
validate::LensPsfImageSetup pointSourceSetup() {
  validate::LensPsfImageSetup s;
  s.aperture_width_m = s.aperture_height_m = 3e-3;
  s.source_distance_m = 1.5;
  s.width = s.height = 31;
  s.lobes = 2.5;
  return s;
}

TEST(StatRenderLens, PointSourceImagesWhereTheThinLensEquationSays) {
  const validate::LensPsfImageSetup s = pointSourceSetup();
  ASSERT_NEAR(s.imageDistance(), 0.75, 1e-12);
  validate::ImageRunOptions o;
  o.photons = 1'500'000;
  o.seed = 12;
  // A wide opening's signed weights are large: 92 chunks rather than 23 keep each pixel's standard error
  // (from the chunks' scatter) steady enough for the z-scores.
  o.chunk_photons = 16384;
  const validate::CaseResult r = validate::runImageLensPsf(s, o);
  ASSERT_EQ(r.rows.size(), 62u);
  const double peak = 0.9 / 3.14159265358979323846 * 1e-3 / (4 * 3.14159265358979323846 * 1.5 * 1.5) *
                      std::pow(9e-6 / (550e-9 * 0.75), 2);
  EXPECT_GT(r.rows[15].reference, 0.9 * peak);
  EXPECT_LE(r.rows[15].reference, peak);
  diffray::testing::expectRowsMatch(r);
}

TEST(StatRenderLens, DefocusedLensFailsTheImagePlanePattern) {
  // The same with the lens's focal length 10 % longer: the comparison sees the blur, far beyond the noise.
  const validate::LensPsfImageSetup s = pointSourceSetup();
  render::LightScene defocused = validate::lensPsfImageScene(s);
  defocused.occluders[0].focal_length_m *= 1.1;
  render::RenderOptions ro;
  ro.photons = 300'000;
  ro.seed = 12;
  ro.chunk_photons = 16384;
  const validate::CaseResult d = validate::scoreImageLensPsf(s, render::renderLight(*render::prepareScene(defocused), ro));
  double chi2 = 0.0;
  for (const auto& row : d.rows) chi2 += std::pow((row.traced - row.reference) / row.std_error, 2);
  const double n = static_cast<double>(d.rows.size());
  std::printf("defocused: chi2/dof %.1f, max error %.3f of peak\n", chi2 / n, d.max_abs_error_rel_peak);
  EXPECT_GT(chi2 / n, 10.0);
}

TEST(RenderLens, TableRangeLeavesTheDeflectionOut) {
  // The table of a lens holds only the diffraction around the geometric ray: its shift range is the largest
  // |α_o − α_i + x/f| over the opening's points x. The set-up's shift bound (render/light_setup.h) pairs every
  // incident direction with every outgoing one (to the wall, half-width W at z = f). Photons do not bounce on
  // from the wall (diffuse_bounces = 0), so the only incident direction is the beam's (α_i = 0) and
  // Δ = |(X − x)/f + x/f| ≤ W/f with the lens; without it, at the plate's corners (half-width h), (W + h)/f,
  // wider although no lens deflection is covered.
  validate::LensPsfImageSetup s;
  s.width = s.height = 31;  // coarse pixels: small tables, a fast test (the range does not depend on them)
  const render::LightScene lens_scene = validate::lensPsfImageScene(s);
  render::LightScene aperture_scene = lens_scene;
  aperture_scene.occluders[0].kind = render::OccluderSpec::Kind::Aperture;
  const auto lens = render::prepareScene(lens_scene, true), aperture = render::prepareScene(aperture_scene, true);
  const double W = lens_scene.rects[0].half_x_m, f = s.focal_length_m, lambda = s.wavelength_m;
  const double h = lens_scene.occluders[0].half_x_m;
  const double lens_delta = -lens->scene.occluders()[0].table_x->layout().u0_per_m * lambda;
  const double aperture_delta = -aperture->scene.occluders()[0].table_x->layout().u0_per_m * lambda;
  std::printf("table half-ranges (direction cosine): lens %.5f, same opening without the lens %.5f\n", lens_delta,
              aperture_delta);
  // 1.02: the set-up's margin; 1 %: the distances to the wall differ from f by < 0.1 %, and the table's
  // range is rounded to whole cells.
  ASSERT_EQ(lens_scene.settings.diffuse_bounces, 0);
  EXPECT_NEAR(lens_delta, 1.02 * W / f, 0.01 * lens_delta);
  EXPECT_NEAR(aperture_delta, 1.02 * (W + h) / f, 0.01 * aperture_delta);
  EXPECT_GT(lens->scene.occluders()[0].focal_length_m, 0.0);
  EXPECT_EQ(aperture->scene.occluders()[0].focal_length_m, 0.0);
}

}  // namespace
