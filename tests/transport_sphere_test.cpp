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

// Area of the disc of radius r centred at (cx, 0) that lies in the half-plane x < edge.
double discLeftOf(double cx, double r, double edge) {
  const double d = edge - cx;  // signed distance from the centre to the edge line
  if (d >= r) return kPi * r * r;
  if (d <= -r) return 0.0;
  const double seg = r * r * std::acos(std::abs(d) / r) - std::abs(d) * std::sqrt(r * r - d * d);
  return d >= 0 ? kPi * r * r - seg : seg;
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
  const double expected[4] = {kPi * r * r, kPi * r * r, discLeftOf(0.45, r, 0.5), 0.0};
  for (int i = 0; i < 4; ++i) {
    const auto& t = tr.spheres[i];
    EXPECT_NEAR(t.sum[0], expected[i], 5.0 * t.standardError(0) + 1e-12) << "sphere " << i;
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
  // is a 2D problem, so I depends on x only). Midpoint rule in the angle parameter x = X + r·sin φ.
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
