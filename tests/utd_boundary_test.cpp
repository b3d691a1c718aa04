// UTD geometric paths at the edges of their validity (utd/paths.h). Oracles, sharing no code with utd/:
// the closed form of a point source over a rigid plane, |1 + (r1/r2)e^{−ik(r2−r1)}|² re free field, for a
// listener or source down to the plane (no step where it comes within the model's offset of it); and
// Macdonald's exact half-plane (reference/half_plane_point.h) for a listener on a reflection shadow
// boundary of a thin rigid screen, against the same reference 1 cm to either side.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>

#include "diffray/reference/half_plane_point.h"
#include "diffray/transport/room_geometry.h"
#include "diffray/utd/paths.h"
#include "utd_fixtures.h"

namespace {

using namespace utd_fixtures;

// Level re free field of a unit point source over an infinite rigid plane z = 0 (image source closed form).
double groundClosedFormDb(const Vec3& s, const Vec3& r, double f) {
  const double k = 2.0 * kPi * f / kC;
  const double r1 = (r - s).norm(), r2 = (r - Vec3(s.x(), s.y(), -s.z())).norm();
  return 10.0 * std::log10(std::norm(1.0 + (r1 / r2) * std::exp(Complex(0.0, -k * (r2 - r1)))));
}

}  // namespace

TEST(UtdBoundary, PointNearARigidPlaneKeepsItsCoincidentImage) {
  // A 60 × 60 m rigid ground plate (extent 60 m: the model's offset is 6 mm), source 1 m up, listener 10 m
  // away at heights through the offset; then source and listener swapped (the source near the plane).
  dr::Room room;
  addPlate(room, Vec3(-30, -30, 0), Vec3(60, 0, 0), Vec3(0, 60, 0), rigidMaterial(room));
  const Vec3 s(-4, 0, 1);
  room.sources.push_back({"S", s, 1.0, {}});
  const diffray::transport::RoomGeometry geometry(room);
  utd::UtdOptions o;
  o.max_order = 0;  // the plate's far edges would add their (small) diffraction: geometric part only
  const utd::UtdModel model(room, geometry, o);
  double worst = 0.0;
  for (bool swap : {false, true}) {
    for (double h : {1e-5, 1e-3, 3e-3, 5e-3, 5.9e-3, 6.1e-3, 7e-3, 2e-2, 0.1, 1.0}) {
      const Vec3 l(6, 0, h);
      const auto paths = swap ? model.paths(l, s) : model.paths(s, l);
      ASSERT_EQ(paths.size(), 2u) << "h " << h;  // direct and ground reflection
      for (double f : {63.0, 500.0, 2000.0}) {
        const double level = 10.0 * std::log10(std::norm(model.total(paths, f, kC) * (l - s).norm()));
        const double expected = groundClosedFormDb(s, l, f);
        worst = std::max(worst, std::abs(level - expected));
        EXPECT_NEAR(level, expected, 1e-9) << "h " << h << " f " << f << " swapped " << swap;
      }
    }
  }
  // As h → 0 the level tends to +6.02 dB at 63 Hz (kh → 0): no step at the offset.
  const double at_zero = groundClosedFormDb(s, Vec3(6, 0, 0), 63.0);
  EXPECT_NEAR(at_zero, 20.0 * std::log10(2.0), 1e-9);
  std::printf("rigid ground, listener 0.01 mm to 1 m up: worst |UTD - closed form| = %.2g dB\n", worst);
}

TEST(UtdBoundary, ListenerOnAReflectionShadowBoundaryMatchesTheExactHalfPlane) {
  // A thin rigid screen x = 0, z <= 3 (40 × 40 m: only diffraction through its top edge z = 3 is summed,
  // the far edges are its finiteness), source at (−4, 0, 1) on the face's side.
  // The listener (−4, 0, 5) lies on the screen's reflection boundary (the image (4, 0, 1) sees it through
  // the edge); (−4, 0, 4.99) and (−4, 0, 5.01) are 1 cm either side; 5 ∓ 1e-10 m, ~2e-11 rad off it, count
  // as on it (utd::kBoundaryTolRad) for the geometric field and the diffracted one alike (when the two
  // tolerances differed, the field there was off by half the reflected one). Half-plane frame: edge on its z
  // axis, screen along its +x: x_ref = 3 − z, y_ref = x, z_ref = y.
  dr::Room room;
  addPlate(room, Vec3(0, -20, -37), Vec3(0, 40, 0), Vec3(0, 0, 40), rigidMaterial(room));
  const Vec3 s(-4, 0, 1);
  room.sources.push_back({"S", s, 1.0, {}});
  const diffray::transport::RoomGeometry geometry(room);
  utd::UtdOptions o;
  o.max_order = 1;
  const utd::UtdModel model(room, geometry, o);
  const auto frame = [](const Vec3& p) { return ref::halfPlaneFrameFromCartesian(3.0 - p.z(), p.x(), p.y()); };
  double worst[5] = {0.0, 0.0, 0.0, 0.0, 0.0};
  const double heights[5] = {4.99, 5.0 - 1e-10, 5.0, 5.0 + 1e-10, 5.01};
  for (int i = 0; i < 5; ++i) {
    const Vec3 l(-4, 0, heights[i]);
    std::vector<utd::Path> paths;
    for (const auto& p : model.paths(s, l))
      if (p.kind != utd::PathKind::Diffraction || (p.points[1] - Vec3(0, 0, 3)).norm() < 1e-9) paths.push_back(p);
    int reflections = 0;
    for (const auto& p : paths) {
      if (p.kind != utd::PathKind::Reflection) continue;
      ++reflections;
      if (i >= 1 && i <= 3) {
        EXPECT_EQ(p.gain, 0.5) << heights[i];  // on the boundary: half the reflected field
      }
    }
    EXPECT_EQ(reflections, i == 4 ? 0 : 1);  // lit by the image below the boundary, not above
    for (int j = 0; j < 48; ++j) {
      const double f = 63.0 * std::pow(2.0, j / 8.0);  // 63 Hz to 4 kHz, 8 per octave
      const double r = (l - s).norm();
      const double level = 20.0 * std::log10(std::abs(model.total(paths, f, kC)) * r);
      const double exact = ref::halfPlaneLevelDb(kC / f, frame(s), frame(l), true);
      worst[i] = std::max(worst[i], std::abs(level - exact));
    }
  }
  std::printf("reflection boundary of a rigid screen, worst |UTD - exact| over 63 Hz-4 kHz: 1 cm below %.3f dB, "
              "1e-10 m below %.3f dB, on it %.3f dB, 1e-10 m above %.3f dB, 1 cm above %.3f dB\n",
              worst[0], worst[1], worst[2], worst[3], worst[4]);
  for (int i = 1; i <= 3; ++i) EXPECT_LE(worst[i], std::max(worst[0], worst[4])) << heights[i];
}
