// UTD paths (utd/paths.h, utd/apex.h). Oracles: Keller's cone (equal angles with the edge on both legs)
// and a brute-force scan of the path length along the edge for the Fermat apex; the continuity of the total
// field (geometric optics + first-order diffraction) across the shadow and reflection boundaries of a
// right-angled wedge (n = 1.5) for a point source, where geometric optics alone jumps; reciprocity of the
// diffracted field; a leg blocked by an obstacle; free-field units of the band energies; the BTM reference of a
// plate on a ground for a listener behind its foot.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <complex>
#include <string>

#include "diffray/reference/btm_plate.h"
#include "diffray/reference/fresnel.h"
#include "diffray/reference/half_plane_point.h"
#include "diffray/room/scene_file.h"
#include "diffray/transport/room_geometry.h"
#include "diffray/utd/paths.h"
#include "utd_fixtures.h"

namespace {

using namespace utd_fixtures;

utd::UtdOptions options(int max_order, bool reflections) {
  utd::UtdOptions o;
  o.max_order = max_order;
  o.reflections = reflections;
  return o;
}

double coneCos(const Vec3& from, const Vec3& to, const Vec3& t) { return (to - from).normalized().dot(t); }

Complex sumOf(const utd::UtdModel& m, const std::vector<utd::Path>& paths, double f, bool diffraction) {
  Complex s = 0.0;
  for (const auto& p : paths)
    if ((p.kind == utd::PathKind::Diffraction) == diffraction) s += m.pressure(p, f, kC);
  return s;
}

// A 4 × 4 × 8 m box whose vertical edge on the z axis is a right-angled wedge: the air spans the polar
// angles θ ∈ [−90°, 180°] about it. A source at θ = 120° sees the face y = 0 (x < 0): its shadow boundary
// is θ = −60°, its reflection boundary θ = 60°.
dr::Room wedgeScene(const Vec3& source) {
  dr::Room room;
  addBox(room, Vec3(-4, -4, -4), Vec3(0, 0, 4), rigidMaterial(room));
  room.sources.push_back({"S", source, 1.0, {}});
  return room;
}

Vec3 polar(double r, double theta_deg, double z) {
  const double t = theta_deg * kPi / 180.0;
  return Vec3(r * std::cos(t), r * std::sin(t), z);
}

}  // namespace

TEST(UtdPaths, FirstOrderApexIsOnKellersConeAndShortest) {
  dr::Room room;
  addPlate(room, Vec3(0, 0, 0), Vec3(3, 0.4, 1), Vec3(-0.5, 0.2, 2), rigidMaterial(room));
  const diffray::transport::RoomGeometry geometry(room);
  const utd::UtdModel model(room, geometry, options(1, false));
  ASSERT_EQ(model.edges().size(), 4u);
  int checked = 0;
  for (const Vec3& s : {Vec3(0.5, -1.5, 2.0), Vec3(1.0, -2.0, 0.5)}) {
    for (const Vec3& r : {Vec3(2.5, 1.5, -0.5), Vec3(0.8, 2.0, 2.2), Vec3(1.5, 0.1, 4.0)}) {
      for (const auto& p : model.paths(s, r)) {
        if (p.kind != utd::PathKind::Diffraction) continue;
        const utd::Edge& e = model.edges()[p.edges[0]];
        const Vec3 q = p.points[1];
        // A corner's wave (apex on the edge's line beyond its end) is no apex on the edge: utd_finite_edges_test.
        const double arc = (q - e.start).dot(e.tangent);
        if (arc < -1e-9 || arc > e.length_m + 1e-9) continue;
        EXPECT_NEAR(coneCos(s, q, e.tangent), coneCos(q, r, e.tangent), 1e-12);
        // Brute force: no point of the edge gives a shorter path.
        double best = 1e300;
        for (int i = 0; i <= 100000; ++i) {
          const Vec3 x = e.at(e.length_m * i / 100000.0);
          best = std::min(best, (x - s).norm() + (r - x).norm());
        }
        EXPECT_LE(p.length_m, best + 1e-12);
        EXPECT_NEAR(p.length_m, best, 1e-6);
        ++checked;
      }
    }
  }
  EXPECT_GE(checked, 6);
}

TEST(UtdPaths, SecondOrderApexesAreOnBothCones) {
  // Around a tall box: source and listener on opposite sides, the paths turn at two vertical edges.
  dr::Room room;
  addBox(room, Vec3(0, 0, -5), Vec3(1, 1, 5), rigidMaterial(room));
  room.sources.push_back({"S", Vec3(-2, 0.3, 0.4), 1.0, {}});
  const diffray::transport::RoomGeometry geometry(room);
  const utd::UtdModel model(room, geometry);
  const Vec3 s(-2, 0.3, 0.4), r(3, 0.8, -0.6);
  int second = 0;
  for (const auto& p : model.paths(s, r)) {
    // Paths with reflections around the edges meet the cones on their unfolded form (utd_reflected_paths_test).
    if (p.order != 2 || p.kind != utd::PathKind::Diffraction || !p.bounces.empty()) continue;
    const Vec3 &q1 = p.points[1], &q2 = p.points[2];
    const Vec3 &t1 = model.edges()[p.edges[0]].tangent, &t2 = model.edges()[p.edges[1]].tangent;
    EXPECT_NEAR(coneCos(s, q1, t1), coneCos(q1, q2, t1), 1e-10);
    EXPECT_NEAR(coneCos(q1, q2, t2), coneCos(q2, r, t2), 1e-10);
    EXPECT_TRUE(p.diffractions[1].grazing);  // the leg between the edges runs along a face
    ++second;
  }
  EXPECT_GE(second, 2);  // at least around either side (y = 0 and y = 1)
}

TEST(UtdPaths, TotalFieldIsContinuousAcrossShadowAndReflectionBoundaries) {
  const Vec3 s = polar(3.0, 120.0, 0.5);
  const dr::Room room = wedgeScene(s);
  const diffray::transport::RoomGeometry geometry(room);
  const utd::UtdModel model(room, geometry, options(1, true));
  for (double boundary : {-60.0, 60.0}) {
    for (double f : {125.0, 500.0, 2000.0}) {
      for (double z : {0.0, 1.3}) {
        // Extrapolate each side linearly to the boundary from 1e-4 and 2e-4 rad away; the geometric part
        // (direct or reflected sound) appears on one side only.
        const double d = 1e-4 * 180.0 / kPi;
        Complex side[2], go_side[2];
        for (int k = 0; k < 2; ++k) {
          const double sg = k == 0 ? -1.0 : 1.0;
          const auto p1 = model.paths(s, polar(2.0, boundary + sg * d, z));
          const auto p2 = model.paths(s, polar(2.0, boundary + 2 * sg * d, z));
          side[k] = 2.0 * model.total(p1, f, kC) - model.total(p2, f, kC);
          go_side[k] = 2.0 * sumOf(model, p1, f, false) - sumOf(model, p2, f, false);
        }
        const double go_jump = std::abs(go_side[1] - go_side[0]);
        EXPECT_GT(go_jump, 0.1);  // one leg of geometric optics switches on: ~1/5 m
        EXPECT_NEAR(std::abs(side[1] - side[0]), 0.0, 1e-4 * go_jump)
            << "boundary " << boundary << " f " << f << " z " << z;
      }
    }
  }
}

TEST(UtdPaths, DiffractedFieldIsReciprocal) {
  const Vec3 s = polar(3.0, 120.0, 0.5), r = polar(2.0, -30.0, -0.7);
  const dr::Room room = wedgeScene(s);
  const diffray::transport::RoomGeometry geometry(room);
  for (int order : {1, 2}) {
    const utd::UtdModel model(room, geometry, options(order, true));
    const auto forward = model.paths(s, r), backward = model.paths(r, s);
    ASSERT_EQ(forward.size(), backward.size());
    for (double f : {63.0, 250.0, 1000.0, 4000.0}) {
      const Complex a = sumOf(model, forward, f, true), b = sumOf(model, backward, f, true);
      const double rel = std::abs(a - b) / std::abs(a);
      if (order == 1) {
        EXPECT_NEAR(rel, 0.0, 1e-12) << f;  // exact: D(φ, φ′) = D(φ′, φ) and L, spreading symmetric
      }
      // Order 2 is not exactly reciprocal: the cascade's L1, L2 (paths.h) change when the path is reversed.
      std::printf("reciprocity, diffraction up to order %d at %g Hz: |p(S,R) - p(R,S)|/|p| = %.2g\n", order, f, rel);
    }
  }
}

TEST(UtdPaths, DistantPointSourceOnAPlateEdgeIsSommerfeldsHalfPlane) {
  // The whole chain (edge extraction, apex, angles, L, geometric optics by visibility) for a source 10⁶ m
  // from the edge of a large plate, normalised by the incident field at the edge, against Sommerfeld's
  // plane-wave solution (reference/fresnel.h); the plate is y = 0, x in [0, 200], z in [−100, 100], its
  // edge on the z axis, the source in the z = 0 plane at φ0 = 60°. The plane-wave limit is reached to
  // about kρ²/(2D) ~ 3e-5; only paths through the edge on the z axis are summed (the far edges are
  // the plate's finiteness, not part of the half-plane).
  const double dist = 1e6, rho = 3.0, lambda = 1.0, phi0 = 60.0;
  const Vec3 s = polar(dist, phi0, 0.0);
  for (bool rigid : {true, false}) {
    dr::Room room;
    addPlate(room, Vec3(0, 0, -100), Vec3(200, 0, 0), Vec3(0, 0, 200), rigidMaterial(room));
    room.sources.push_back({"S", s, 1.0, {}});
    const diffray::transport::RoomGeometry geometry(room);
    utd::UtdOptions o = options(1, true);
    o.face_reflection = rigid ? 1.0 : -1.0;
    o.finite_edges = false;  // the half-plane's edge has no ends
    const utd::UtdModel model(room, geometry, o);
    double worst = 0.0;
    for (double phi = 5.0; phi < 357.0; phi += 7.0) {
      const Vec3 r = polar(rho, phi, 0.0);
      Complex p = 0.0;
      for (const auto& path : model.paths(s, r)) {
        if (path.kind == utd::PathKind::Diffraction && path.points[1].head<2>().norm() > 1e-6) continue;
        p += model.pressure(path, kC / lambda, kC);
      }
      const double k = 2.0 * kPi / lambda;
      const Complex normalised = p * dist * std::exp(Complex(0.0, k * dist));
      const Complex ref = diffray::reference::sommerfeldHalfPlane(lambda, rho, phi * kPi / 180.0, phi0 * kPi / 180.0, rigid);
      worst = std::max(worst, std::abs(normalised - ref));
      EXPECT_NEAR(std::abs(normalised - ref), 0.0, 1e-4) << "rigid " << rigid << " phi " << phi;
    }
    std::printf("point source at 1e6 m on a plate edge vs Sommerfeld (%s): worst |error| = %.2g\n",
                rigid ? "rigid" : "soft", worst);
  }
}

TEST(UtdPaths, BlockedLegIsNotAPath) {
  // A vertical screen y = 0, x in [−5, 5], z in [−5, 0] (top edge at z = 0); source and listener below the
  // top on either side. Without the blocker the path over the top edge exists; a box on the listener's
  // leg removes it.
  for (bool blocked : {false, true}) {
    dr::Room room;
    const int m = rigidMaterial(room);
    addPlate(room, Vec3(-5, 0, -5), Vec3(10, 0, 0), Vec3(0, 0, 5), m);
    if (blocked) addBox(room, Vec3(-1, 0.5, -0.5), Vec3(1, 1, 0.5), m);
    room.sources.push_back({"S", Vec3(0, -2, -1), 1.0, {}});
    const diffray::transport::RoomGeometry geometry(room);
    const utd::UtdModel model(room, geometry, options(1, true));
    int over_top = 0;
    for (const auto& p : model.paths(Vec3(0, -2, -1), Vec3(0, 2, -1))) {
      EXPECT_NE(p.kind, utd::PathKind::Direct);
      if (p.kind == utd::PathKind::Diffraction && std::abs(p.points[1].z()) < 1e-9 && std::abs(p.points[1].y()) < 1e-9)
        ++over_top;
    }
    EXPECT_EQ(over_top, blocked ? 0 : 1);
  }
}

TEST(UtdPaths, BandEnergyOfDirectSoundIsFreeFieldFluence) {
  dr::Room room;
  addPlate(room, Vec3(50, 50, 50), Vec3(0.1, 0, 0), Vec3(0, 0.1, 0), rigidMaterial(room));
  const diffray::transport::RoomGeometry geometry(room);
  const utd::UtdModel model(room, geometry);
  const auto paths = model.paths(Vec3(0, 0, 0), Vec3(3, 4, 0));
  ASSERT_EQ(paths.size(), 1u);
  const auto energies = model.bandEnergies(paths, kC, 8, false);
  ASSERT_EQ(energies.size(), 1u);
  EXPECT_NEAR(energies[0].delay_s, 5.0 / kC, 1e-15);
  for (int b = 0; b < room.bands.size(); ++b) EXPECT_NEAR(energies[0].energy[b], 1.0 / 25.0, 1e-15);
  EXPECT_TRUE(model.bandEnergies(paths, kC).empty());  // diffraction only by default
}

TEST(UtdPaths, TwoRoomsIsFast) {
  const dr::Room room = dr::loadRoom(std::string(DIFFRAY_SOURCE_DIR) + "/rooms/two-rooms.json");
  const diffray::transport::RoomGeometry geometry(room);
  const utd::UtdModel model(room, geometry);
  const Vec3 s = room.sources[0].position_m;
  for (const auto& listener : room.listeners) {
    const auto t0 = std::chrono::steady_clock::now();
    const auto paths = model.paths(s, listener.position_m);
    const auto energies = model.bandEnergies(paths, kC, 16);
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    int counts[3] = {0, 0, 0};
    for (const auto& p : paths) ++counts[p.kind == utd::PathKind::Diffraction ? p.order : 0];
    double e1k = 0.0;
    for (const auto& e : energies) e1k += e.energy[room.bands.find(1000)];
    std::printf("two-rooms %s: %d geometric, %d first- and %d second-order diffraction paths; diffracted energy "
                "at 1 kHz %.3g (free field at that distance %.3g); %.2f ms\n",
                listener.name.c_str(), counts[0], counts[1], counts[2], e1k,
                1.0 / (listener.position_m - s).squaredNorm(), ms);
    EXPECT_LT(ms, 1000.0);
    if (listener.name == "B-hidden") {
      EXPECT_EQ(counts[0], 0);  // no direct sound or first-order reflection reaches it
      EXPECT_GT(counts[1] + counts[2], 0);
    }
  }
}

TEST(UtdPaths, DoesNotDependOnTheSceneSize) {
  // Tolerances in absolute units: a listener 8.7 cm behind a 1000 m plate, 0.5 m into the shadow of its
  // edge, is behind the plate (not on its face), and the field there is the half-plane's: against
  // Macdonald's exact solution (reference/half_plane_point.h) within 0.5 dB at 500 Hz (UTD's own error on
  // one edge is ~0.1 dB in bands, a few tenths at one frequency; a listener taken to be on the face reads
  // about 0 dB re free field instead of −16 to −23). And a 1 cm triangle added 500 m away changes nothing.
  const double f = 500.0, lambda = kC / f;
  const Vec3 s = polar(3.0, 60.0, 0.3), r(0.5, -0.087, 0.0);
  auto field = [&](bool far_triangle) {
    dr::Room room;
    const int m = rigidMaterial(room);
    addPlate(room, Vec3(0, 0, -500), Vec3(1000, 0, 0), Vec3(0, 0, 1000), m);
    if (far_triangle) room.addPolygon({Vec3(-500, 300, 0), Vec3(-499.99, 300, 0), Vec3(-500, 300.01, 0)}, m, "speck");
    room.sources.push_back({"S", s, 1.0, {}});
    const diffray::transport::RoomGeometry geometry(room);
    const utd::UtdModel model(room, geometry, options(1, true));
    Complex p = 0.0;
    for (const auto& path : model.paths(s, r)) p += model.pressure(path, f, kC);
    return p;
  };
  const Complex alone = field(false), with_speck = field(true);
  const auto cyl = [](const Vec3& v) { return diffray::reference::halfPlaneFrameFromCartesian(v.x(), v.y(), v.z()); };
  const Complex exact = diffray::reference::halfPlanePointSource(lambda, cyl(s), cyl(r), true);
  const double level_utd = 20.0 * std::log10(std::abs(alone)), level_exact = 20.0 * std::log10(std::abs(exact));
  EXPECT_NEAR(level_utd, level_exact, 0.5);
  EXPECT_LT(std::abs(with_speck - alone), 1e-9 * std::abs(alone));
}

TEST(UtdPaths, NoGroundReflectionThroughTheFootOfABarrier) {
  // A 4 × 2 m rigid plate standing on a rigid ground (z = 0), the source 2 m before it and the listeners
  // 2 m behind it at the source's height: the ground reflection point lies on the plate's foot, where the
  // plate meets the ground, so the specular ground path goes through the plate and must not count. The
  // level in the 500 Hz octave is the exact one of the plate on the ground (the BTM reference,
  // reference/btm_plate.h, second order, the ground by the image principle) within 1 dB; the path through
  // the foot would add a wave of about the free field's strength (0 dB re free field, where the exact level
  // is −4 to −10 dB).
  dr::Room room;
  const int m = rigidMaterial(room);
  addPlate(room, Vec3(-50, -50, 0), Vec3(100, 0, 0), Vec3(0, 100, 0), m);  // the ground
  addPlate(room, Vec3(0, -2, 0), Vec3(0, 4, 0), Vec3(0, 0, 2), m);        // the barrier, x = 0
  const Vec3 s(-2.0, 0.0, 0.5);
  room.sources.push_back({"S", s, 1.0, {}});
  const diffray::transport::RoomGeometry geometry(room);
  utd::UtdOptions o = options(2, true);
  o.second_order_reflections = 3;
  const utd::UtdModel model(room, geometry, o);
  const diffray::reference::BtmPlate plate{{Vec3(0, -2, 0), Vec3(0, 2, 0), Vec3(0, 2, 2), Vec3(0, -2, 2)}};
  const double lo = 500.0 / std::sqrt(2.0), hi = 500.0 * std::sqrt(2.0);
  const int points = 32;
  for (const Vec3& r : {Vec3(2.0, 0.0, 0.5), Vec3(2.0, 0.7, 0.5), Vec3(2.0, -1.2, 0.5)}) {
    const auto paths = model.paths(s, r);
    for (const auto& path : paths)
      EXPECT_FALSE(path.kind == utd::PathKind::Reflection && path.points.size() == 3 &&
                   std::abs(path.points[1].x()) < 1e-6)
          << "a reflection through the barrier's foot to " << r.transpose();
    double energy = 0.0;
    for (int j = 0; j < points; ++j)
      energy += std::norm(model.total(paths, lo + (j + 0.5) * (hi - lo) / points, kC) * (r - s).norm()) / points;
    const double level = 10.0 * std::log10(energy);
    const double exact = diffray::reference::btmPlateBandLevelDb(lo, hi, points, kC, plate, 0.0, s, r, 2);
    EXPECT_NEAR(level, exact, 1.0) << r.transpose();
    std::printf("barrier on ground, listener (%.1f, %.1f, %.1f), 500 Hz octave: UTD %.2f dB, BTM %.2f dB re free field\n",
                r.x(), r.y(), r.z(), level, exact);
  }
}
