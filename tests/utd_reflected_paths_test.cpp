// UTD diffraction paths with reflections around the edges, and between the edges of a thin plate (utd/paths.h).
// Oracles, sharing no code with utd/: Macdonald's exact half-plane (reference/half_plane_point.h) for a
// half-plane standing on a rigid ground, by the image principle written here (the field of the source plus
// that of its mirror image in the ground, the plate and its mirror forming one half-plane); the four paths
// over a long barrier on a ground (direct, with the ground before, after, or both) by hand in its plane of
// symmetry; the continuity of the total field across the shadow boundary of the source's image; reciprocity;
// and the BTM second-order term of a long thin strip (reference/btm_spectrum.h) for the paths from one edge
// to the other along either face.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <cstdio>
#include <vector>

#include "diffray/core/error.h"
#include "diffray/reference/btm_spectrum.h"
#include "diffray/reference/half_plane_point.h"
#include "diffray/transport/room_geometry.h"
#include "diffray/utd/paths.h"
#include "utd_fixtures.h"

using namespace utd_fixtures;

namespace {

Vec3 cylindrical(double rho, double phi_deg, double z) {
  const double t = phi_deg * kPi / 180.0;
  return Vec3(rho * std::cos(t), rho * std::sin(t), z);
}

// A long thin barrier y = 0, x in [−100, 100], z in [0, 3] standing on a 400 × 400 m rigid ground z = 0.
dr::Room barrierOnGround(const Vec3& source) {
  dr::Room room;
  const int m = rigidMaterial(room);
  addPlate(room, Vec3(-200, -200, 0), Vec3(400, 0, 0), Vec3(0, 400, 0), m);
  addPlate(room, Vec3(-100, 0, 0), Vec3(200, 0, 0), Vec3(0, 0, 3), m);
  room.sources.push_back({"S", source, 1.0, {}});
  return room;
}

bool onTopEdge(const utd::Path& p, const utd::UtdModel& model) {
  for (int e : p.edges)
    if (std::abs(model.edges()[e].start.z() - 3.0) > 1e-9 || std::abs(model.edges()[e].end.z() - 3.0) > 1e-9) return false;
  return true;
}

}  // namespace

TEST(UtdReflectedPaths, HalfPlaneStandingOnARigidGroundIsTwoMacdonaldHalfPlanes) {
  // The half-plane y = 0, x >= 0 (400 × 400 m) standing on a rigid ground z = 0 (800 × 800 m), its edge the
  // z axis. By the image principle the field is Macdonald's for the source plus Macdonald's for its image
  // (x, y, −z), the plate and its image one half-plane. UTD sums the direct sound, the ground reflection and
  // the diffraction paths through the edge on the z axis (the far edges are the finite model's, not the
  // half-plane's), with the ground before or after the edge. Listeners in the lit zone (not in the plate's
  // reflection zone, φ < 120°, where the plate's reflection of the image, a second-order reflection, would
  // be needed) and in the shadow (φ > 240°), below and above the source's height, and at z = 2/3 m, where
  // the image source's apex is at the foot of the edge (z_r·ρ_s = z_s·ρ_r): there the paths with the ground
  // before and after the edge are one.
  const Vec3 s = cylindrical(3.0, 60.0, 1.0), s_image(s.x(), s.y(), -s.z());
  dr::Room room;
  const int m = rigidMaterial(room);
  addPlate(room, Vec3(-400, -400, 0), Vec3(800, 0, 0), Vec3(0, 800, 0), m);
  addPlate(room, Vec3(0, 0, 0), Vec3(400, 0, 0), Vec3(0, 0, 400), m);
  room.sources.push_back({"S", s, 1.0, {}});
  const diffray::transport::RoomGeometry geometry(room);
  const auto frame = [](const Vec3& p) { return ref::halfPlaneFrameFromCartesian(p.x(), p.y(), p.z()); };
  const auto onAxis = [](const utd::Path& p) {
    for (std::size_t i = 0; i < p.diffractions.size(); ++i)
      if (p.points[p.diffractions[i].point].head<2>().norm() > 1e-6) return false;
    return true;
  };
  double worst[2] = {0.0, 0.0};
  for (bool reflected : {true, false}) {
    utd::UtdOptions o;
    o.max_order = 1;
    o.reflected_diffraction = reflected;
    const utd::UtdModel model(room, geometry, o);
    for (double phi : {150.0, 200.0, 255.0, 290.0, 330.0}) {
      for (double z : {0.4, 2.0 / 3.0, 1.0, 2.5}) {
        const Vec3 r = cylindrical(2.0, phi, z);
        std::vector<utd::Path> kept;
        for (const auto& p : model.paths(s, r))
          if (p.kind != utd::PathKind::Diffraction || onAxis(p)) kept.push_back(p);
        for (double band : {125.0, 250.0, 500.0, 1000.0, 2000.0, 4000.0}) {
          const double lo = band / std::sqrt(2.0), hi = band * std::sqrt(2.0);
          double e_utd = 0.0, e_exact = 0.0;
          const int points = 16;
          for (int j = 0; j < points; ++j) {
            const double f = lo + (j + 0.5) * (hi - lo) / points, lambda = kC / f;
            const Complex exact = ref::halfPlanePointSource(lambda, frame(s), frame(r), true) +
                                  ref::halfPlanePointSource(lambda, frame(s_image), frame(r), true);
            e_utd += std::norm(model.total(kept, f, kC));
            e_exact += std::norm(exact);
          }
          const double diff = 10.0 * std::log10(e_utd / e_exact);
          worst[reflected ? 0 : 1] = std::max(worst[reflected ? 0 : 1], std::abs(diff));
          if (reflected) {
            EXPECT_NEAR(diff, 0.0, 0.5) << "phi " << phi << " z " << z << " band " << band;
          }
        }
      }
    }
  }
  std::printf("half-plane on a rigid ground vs two Macdonald half-planes, octave bands 125 Hz-4 kHz: worst "
              "|UTD - exact| %.3f dB with the reflections around the edge, %.2f dB without\n",
              worst[0], worst[1]);
  EXPECT_GT(worst[1], 3.0);  // without them the shadow misses the image source's diffraction
}

TEST(UtdReflectedPaths, FourPathsOverABarrierOnAGroundByHand) {
  // In the barrier's plane of symmetry x = 0 (source (0, −4, 1), listener (0, 6, 1.5), top edge at z = 3)
  // every path over the top meets it at Q = (0, 0, 3): with the source's image S′ = (0, −4, −1) and the
  // listener's L′ = (0, 6, −1.5) the lengths are |S Q| + |Q L| with either or both replaced by its image's,
  // and the ground reflection points are where S′Q and QL′ cross z = 0: (0, −3, 0) and (0, 4, 0). A low panel
  // standing on the ground across the leg from S to (0, −3, 0) removes the two paths that use it (and its
  // back faces Q: it reflects nothing towards the top edge).
  const Vec3 s(0, -4, 1), r(0, 6, 1.5), q(0, 0, 3), s_image(0, -4, -1), r_image(0, 6, -1.5);
  const Vec3 before(0, -3, 0), after(0, 4, 0);
  for (bool blocked : {false, true}) {
    dr::Room room = barrierOnGround(s);
    if (blocked) addPlate(room, Vec3(-1, -3.5, 0), Vec3(2, 0, 0), Vec3(0, 0, 0.7), 0);
    const diffray::transport::RoomGeometry geometry(room);
    utd::UtdOptions o;
    o.max_order = 1;
    const utd::UtdModel model(room, geometry, o);
    int found = 0, with_before = 0;
    for (const auto& p : model.paths(s, r)) {
      if (p.kind != utd::PathKind::Diffraction || !onTopEdge(p, model)) continue;
      ++found;
      const Vec3 apex = p.points[p.diffractions[0].point];
      EXPECT_NEAR((apex - q).norm(), 0.0, 1e-9);
      bool b = false, a = false;
      for (const auto& bounce : p.bounces) {
        const Vec3 at = p.points[bounce.point];
        EXPECT_EQ(geometry.triangle(bounce.triangle).plane, geometry.triangle(0).plane);  // the ground
        if (bounce.point < p.diffractions[0].point) {
          b = true;
          EXPECT_NEAR((at - before).norm(), 0.0, 1e-9);
        } else {
          a = true;
          EXPECT_NEAR((at - after).norm(), 0.0, 1e-9);
        }
      }
      with_before += b;
      const double expected = ((b ? s_image : s) - q).norm() + ((a ? r_image : r) - q).norm();
      EXPECT_NEAR(p.length_m, expected, 1e-9);
      EXPECT_EQ(static_cast<int>(p.points.size()), 3 + (a ? 1 : 0) + (b ? 1 : 0));
    }
    EXPECT_EQ(found, blocked ? 2 : 4);
    EXPECT_EQ(with_before, blocked ? 0 : 2);
  }
}

TEST(UtdReflectedPaths, TotalFieldIsContinuousAcrossTheImageSourcesShadowBoundary) {
  // Over the barrier on the ground, the ground reflection S → ground → L is cut by the top edge Q = (0, 0, 3)
  // where the listener crosses the line from the source's image (0, −4, −1) through Q (45° above the
  // horizontal): the diffraction of the image (the ground before the edge) must take up the jump.
  const Vec3 s(0, -4, 1), q(0, 0, 3);
  const dr::Room room = barrierOnGround(s);
  const diffray::transport::RoomGeometry geometry(room);
  utd::UtdOptions o;
  o.max_order = 1;
  const utd::UtdModel model(room, geometry, o);
  const auto at = [&](double deg) {
    const double t = deg * kPi / 180.0;
    return Vec3(0.0, q.y() + 5.0 * std::cos(t), q.z() + 5.0 * std::sin(t));
  };
  const double d = 1e-4 * 180.0 / kPi;
  for (double f : {125.0, 500.0, 2000.0}) {
    Complex side[2], geometric[2];
    for (int k = 0; k < 2; ++k) {
      const double sg = k == 0 ? -1.0 : 1.0;
      const auto p1 = model.paths(s, at(45.0 + sg * d)), p2 = model.paths(s, at(45.0 + 2 * sg * d));
      side[k] = 2.0 * model.total(p1, f, kC) - model.total(p2, f, kC);
      Complex g1 = 0.0, g2 = 0.0;
      for (const auto& p : p1)
        if (p.kind != utd::PathKind::Diffraction) g1 += model.pressure(p, f, kC);
      for (const auto& p : p2)
        if (p.kind != utd::PathKind::Diffraction) g2 += model.pressure(p, f, kC);
      geometric[k] = 2.0 * g1 - g2;
    }
    const double jump = std::abs(geometric[1] - geometric[0]);
    EXPECT_GT(jump, 0.05);  // the ground reflection, ~1/10.6 m, switches on
    EXPECT_NEAR(std::abs(side[1] - side[0]), 0.0, 1e-4 * jump) << f;
  }
}

TEST(UtdReflectedPaths, ReflectedDiffractionIsReciprocal) {
  // First order with the ground before and after the edges is exactly reciprocal: the same paths backwards,
  // D(φ, φ′) = D(φ′, φ), and the spreading symmetric in the unfolded distances.
  const Vec3 s(0.7, -4, 1.2), r(-1.9, 5, 0.6);
  const dr::Room room = barrierOnGround(s);
  const diffray::transport::RoomGeometry geometry(room);
  utd::UtdOptions o;
  o.max_order = 1;
  const utd::UtdModel model(room, geometry, o);
  const auto forward = model.paths(s, r), backward = model.paths(r, s);
  const auto reflected = [&](const std::vector<utd::Path>& paths, double f, int& count) {
    Complex sum = 0.0;
    count = 0;
    for (const auto& p : paths)
      if (p.kind == utd::PathKind::Diffraction && !p.bounces.empty()) {
        sum += model.pressure(p, f, kC);
        ++count;
      }
    return sum;
  };
  for (double f : {63.0, 500.0, 4000.0}) {
    int n_forward = 0, n_backward = 0;
    const Complex a = reflected(forward, f, n_forward), b = reflected(backward, f, n_backward);
    EXPECT_EQ(n_forward, n_backward);
    EXPECT_GE(n_forward, 3);  // over the top with the ground before, after and both
    EXPECT_NEAR(std::abs(a - b) / std::abs(a), 0.0, 1e-12) << f;
  }
}

TEST(UtdReflectedPaths, EdgeToEdgeAlongAThinStripMatchesTheBtmSecondOrderTerm) {
  // A 20 × 2 m thin rigid strip: the second-order paths from its foot to its top edge and back run along the
  // strip, one along each face, each grazing at its second edge. Their band energy is the BTM second-order
  // term's (Svensson et al. 1999, both faces with the ½ of a path along a plane) within 1 dB in the 250 Hz to
  // 1 kHz octaves (measured −0.23 to +0.09 dB: the strip's corners are BTM's alone).
  const Vec3 s(0, -2, 0.5), r(0.3, 2, 0.5);
  dr::Room room;
  addPlate(room, Vec3(-10, 0, 0), Vec3(20, 0, 0), Vec3(0, 0, 2), rigidMaterial(room));
  room.sources.push_back({"S", s, 1.0, {}});
  const diffray::transport::RoomGeometry geometry(room);
  const utd::UtdModel model(room, geometry);
  const auto paths = model.paths(s, r);
  int second = 0;
  for (const auto& p : paths) {
    if (p.kind != utd::PathKind::Diffraction || p.order != 2) continue;
    ++second;
    EXPECT_TRUE(p.diffractions[1].grazing);
  }
  EXPECT_EQ(second % 2, 0);  // in pairs, one along each face
  EXPECT_GE(second, 4);      // foot to top and top to foot
  const ref::BtmPlate strip{{Vec3(-10, 0, 0), Vec3(10, 0, 0), Vec3(10, 0, 2), Vec3(-10, 0, 2)}};
  for (double band : {250.0, 500.0, 1000.0}) {
    std::vector<double> f, k;
    for (int j = 0; j < 32; ++j) {
      f.push_back(band / std::sqrt(2.0) * (1.0 + (j + 0.5) / 32.0));
      k.push_back(2.0 * kPi * f.back() / kC);
    }
    const auto exact = ref::btmPlateSpectrum(k, strip, std::nan(""), s, r, 2);
    double e_utd = 0.0, e_exact = 0.0;
    for (std::size_t j = 0; j < f.size(); ++j) {
      Complex u = 0.0;
      for (const auto& p : paths)
        if (p.kind == utd::PathKind::Diffraction && p.order == 2) u += model.pressure(p, f[j], kC);
      e_utd += std::norm(u);
      e_exact += std::norm(exact[j].second_order);
    }
    const double diff = 10.0 * std::log10(e_utd / e_exact);
    EXPECT_NEAR(diff, 0.0, 1.0) << band;
    std::printf("thin strip, %g Hz octave: second order UTD - BTM %.2f dB\n", band, diff);
  }
}

TEST(UtdReflectedPaths, CountsOfReflectionsOnSecondOrderPaths) {
  // 0 to 3 reflections on a second-order path, each allowance finding more paths over a barrier on a ground
  // (the top edge twice, down the barrier to the ground at its foot and back up between; the side edges; the
  // ground before and after).
  const Vec3 s(0.7, -4, 1.2), r(-1.9, 5, 0.6);
  const dr::Room room = barrierOnGround(s);
  const diffray::transport::RoomGeometry geometry(room);
  for (int bad : {-1, 4}) {
    utd::UtdOptions o;
    o.second_order_reflections = bad;
    EXPECT_THROW(utd::UtdModel(room, geometry, o), diffray::core::InputError) << bad;
  }
  int previous = -1;
  for (int most = 0; most <= 3; ++most) {
    utd::UtdOptions o;
    o.second_order_reflections = most;
    const utd::UtdModel model(room, geometry, o);
    int second = 0;
    for (const auto& p : model.paths(s, r)) {
      if (p.kind != utd::PathKind::Diffraction || p.order != 2) continue;
      ++second;
      EXPECT_LE(static_cast<int>(p.bounces.size()), most);
    }
    EXPECT_GT(second, previous) << most;
    previous = second;
  }
}
