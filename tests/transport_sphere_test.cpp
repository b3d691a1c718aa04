// Sphere receivers (receiver/sphere.h): transparent listeners that collect the signed energy of every ray
// segment passing through them. Oracles, written here: the geometric cross-section of a disc inside (or
// cut by the edge of) a uniform beam, and the far-field slit pattern of diffray::reference averaged over
// the sphere's disc by quadrature. Tolerances: 5 chunk-based standard errors (receiver/screen.h) plus the
// quadrature's own accuracy; the chance of a false alarm per assertion is below 1e-5.
#include <gtest/gtest.h>

#include <cmath>

#include "diffray/core/math.h"
#include "diffray/reference/fraunhofer.h"
#include "diffray/transport/tracer.h"
#include "diffray/wbsdf/microstructure.h"
#include "transport_fixtures.h"

namespace dtr = diffray::transport;
namespace dr = diffray::receiver;
using diffray::core::kPi;
using diffray::core::Vec3;

namespace {

// Expected track-length tally of a sphere of radius r centred at (cx, 0) in a unit beam that covers
// x < edge: ∫ over the lit part of the disc of the chord 2√(r² − ρ²), divided by the mean chord 4r/3
// (midpoint rule on a fine grid). For an uncut sphere it is πr², the cross-section.
double litChordIntegral(double cx, double r, double edge) {
  const int n = 2000;
  double sum = 0.0;
  const double h = 2.0 * r / n;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const double x = -r + (i + 0.5) * h, y = -r + (j + 0.5) * h;
      const double rho2 = x * x + y * y;
      if (rho2 < r * r && cx + x < edge) sum += 2.0 * std::sqrt(r * r - rho2) * h * h;
    }
  return sum * 0.75 / r;
}

}  // namespace

TEST(StatSphereReceiver, UniformBeamDepositsIntensityTimesCrossSection) {
  // A 1 m × 1 m collimated beam of unit intensity along +z, no occluder; rays end on an absorber.
  dtr::Scene scene;
  dtr::Absorber stop;
  stop.frame.origin = Vec3(0, 0, 3);
  stop.half_x_m = stop.half_y_m = 2.0;
  scene.addAbsorber(stop);
  const double r = 0.1;
  scene.addSphere({Vec3(0.0, 0.0, 1.0), r});     // inside the beam
  scene.addSphere({Vec3(0.2, -0.1, 2.0), r});    // inside, elsewhere
  scene.addSphere({Vec3(0.45, 0.0, 1.5), r});    // cut by the beam's edge at x = 0.5
  scene.addSphere({Vec3(0.0, 0.0, -2.0), r});    // behind the source: never crossed
  scene.build();
  dtr::CollimatedSource src;
  src.frame.origin = Vec3(0, 0, 0);
  src.half_x_m = src.half_y_m = 0.5;
  src.wavelength_m = 0.1;
  dtr::TraceOptions to;
  to.rays = 400'000;
  to.seed = 3;
  const dtr::TraceResult tr = dtr::trace(scene, src, to);
  const double expected[4] = {kPi * r * r, kPi * r * r, litChordIntegral(0.45, r, 0.5), 0.0};
  EXPECT_NEAR(litChordIntegral(0.0, r, 1.0), kPi * r * r, 1e-4 * kPi * r * r);  // the oracle's own check
  for (int i = 0; i < 4; ++i) {
    const auto& t = tr.spheres[i];
    // 1e-4 πr²: the midpoint rule's error on the cut disc.
    EXPECT_NEAR(t.sum[0], expected[i], 5.0 * t.standardError(0) + 1e-4 * kPi * r * r) << "sphere " << i;
  }
  // Spheres are transparent: all the power still reaches the absorber.
  EXPECT_NEAR(tr.on_absorbers, src.power(), 1e-9);
}

TEST(StatSphereReceiver, SpheresBehindASlitIntegrateTheSignedFarField) {
  // A 100 µm slit (uniform along y: a 1 m strip), λ = 500 nm, spheres of radius 3 mm 5 m behind it at
  // several offsets across the pattern; a screen behind them stops the rays.
  const double a = 100e-6, lambda = 500e-9, z = 5.0, r = 3e-3;
  dtr::Scene scene;
  dtr::Occluder occ;
  diffray::wbsdf::TableOptions o;
  o.wavelength_m = lambda;
  o.u_half_range_per_m = 0.05 / lambda;  // shifts that can reach |x| < 0.25 m at 5 m
  o.cells_per_coherence = 256;
  o.rows_per_feature = 8;
  occ.table_x = diffray::wbsdf::WbsdfTable::build(*diffray::wbsdf::Openings::slit(a), o);
  occ.half_x_m = a;
  occ.half_y_m = 0.6;
  scene.addOccluder(occ);
  dtr::Absorber stop;
  stop.frame.origin = Vec3(0, 0, z + 1.0);
  stop.half_x_m = stop.half_y_m = 2.0;
  scene.addAbsorber(stop);
  const double offsets[] = {0.0, 0.012, 0.025, 0.04};
  for (double x : offsets) scene.addSphere({Vec3(x, 0.0, z), r});
  scene.build();
  dtr::CollimatedSource src;
  src.frame.origin = Vec3(0, 0, -0.5);
  src.half_x_m = 0.5 * a;
  src.half_y_m = 0.5;
  src.wavelength_m = lambda;
  dtr::TraceOptions to;
  to.rays = 4'000'000;
  to.seed = 11;
  const dtr::TraceResult tr = dtr::trace(scene, src, to);
  // Expected: ∫_disc I(x) dA = ∫ I(x)·2√(r² − (x − X)²) dx, I from the far-field slit pattern (the beam
  // is a 2D problem, so I depends on x only; whole chords, so the track-length weights average to the
  // crossing count). Midpoint rule in the angle parameter x = X + r·sin φ.
  auto intensity = [&](double x) {
    namespace ref = diffray::reference;
    return ref::farFieldScreenIntensity2D(x, z, lambda, ref::slitFraunhofer(ref::screenU(x, z, lambda), a));
  };
  const double peak = intensity(0.0) * kPi * r * r;
  for (std::size_t i = 0; i < std::size(offsets); ++i) {
    const int n = 4000;
    double expected = 0.0;
    for (int k = 0; k < n; ++k) {
      const double phi = -0.5 * kPi + (k + 0.5) * kPi / n;
      const double c = std::cos(phi);
      expected += intensity(offsets[i] + r * std::sin(phi)) * 2.0 * r * c * r * c * (kPi / n);
    }
    const auto& t = tr.spheres[i];
    EXPECT_NEAR(t.sum[0], expected, 5.0 * t.standardError(0) + 1e-4 * peak) << "sphere at x = " << offsets[i];
  }
}

TEST(StatSphereReceiver, ARayScatteredInsideTheSphereCountsOnce) {
  // A fully open occluder (W = δ(u'), weight 1) through the sphere's centre splits every chord in two
  // segments; the sphere must still read its cross-section πr², not twice that.
  dtr::Scene scene;
  dtr::Occluder occ;
  occ.table_x = diffray::testing::deltaTable(-1.0, 1.0, 0.0);
  occ.frame.origin = Vec3(0, 0, 1.0);
  occ.half_x_m = occ.half_y_m = 1.0;
  scene.addOccluder(occ);
  dtr::Absorber stop;
  stop.frame.origin = Vec3(0, 0, 3);
  stop.half_x_m = stop.half_y_m = 2.0;
  scene.addAbsorber(stop);
  const double r = 0.1;
  scene.addSphere({Vec3(0.1, 0.0, 1.0), r});
  scene.build();
  dtr::CollimatedSource src;
  src.half_x_m = src.half_y_m = 0.5;
  src.wavelength_m = 0.1;
  dtr::TraceOptions to;
  to.rays = 400'000;
  to.seed = 5;
  const dtr::TraceResult tr = dtr::trace(scene, src, to);
  EXPECT_NEAR(tr.spheres[0].sum[0], kPi * r * r, 5.0 * tr.spheres[0].standardError(0) + 1e-12);
}
