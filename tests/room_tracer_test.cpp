// The acoustic tracer and the image-source method against closed forms: the free-field fluence P·D/r²
// with its exact delay and air absorption, a source's power pattern, first-order images of a
// box by hand, and the hybrid (rays + image sources) against rays alone, which must agree in expectation
// because the tracer leaves out exactly the paths the image sources add. Monte Carlo tolerances are 5σ
// of the chunk-scatter standard error.
#include <gtest/gtest.h>

#include <cmath>

#include "diffray/core/error.h"
#include "diffray/core/parallel.h"
#include "diffray/transport/image_sources.h"
#include "diffray/room/checks.h"
#include "diffray/transport/room_simulation.h"
#include "diffray/transport/room_tracer.h"

namespace {

using diffray::core::Vec3;
namespace dr = diffray::room;
namespace dt = diffray::transport;

constexpr double kC = 343.0;

// A closed box room [0, dims] with one material on every wall.
dr::Room boxRoom(const Vec3& dims, double alpha, double scattering) {
  dr::Room room;
  dr::Material m;
  m.name = "wall";
  for (int b = 0; b < room.bands.size(); ++b) {
    m.absorption[b] = alpha;
    m.scattering[b] = scattering;
  }
  const int id = room.addMaterial(m);
  const int walls[6] = {id, id, id, id, id, id};
  room.addBox(Vec3(0, 0, 0), dims, walls);
  return room;
}

// Sum of a listener's histogram over [0, t_end) in band b, and its standard error (bins' chunk totals are
// correlated only through the chunk, so the variance of the sum is that of the chunk sums: bound it by the
// sum of the bins' standard errors, a conservative upper bound).
std::pair<double, double> windowSum(const diffray::receiver::EnergyHistogram& h, int b, double t_end) {
  double sum = 0, se = 0;
  for (int i = 0; i < h.bins() && i * h.binSeconds() < t_end; ++i) {
    sum += h.value(b, i);
    se += h.standardError(b, i);
  }
  return {sum, se};
}

TEST(StatRoomTracer, FreeFieldFluenceDelayAndAirAbsorption) {
  // A fully absorbing box far larger than the source–listener distance: only the direct sound reaches.
  dr::Room room = boxRoom(Vec3(200, 200, 200), 1.0, 0.0);
  room.sources.push_back({"S", Vec3(100, 100, 100), 2.0, {}});
  const double r = 3.0;
  room.listeners.push_back({"L", Vec3(100 + r, 100, 100), 0.25});
  const dt::RoomGeometry geometry(room);
  dt::RoomTraceOptions opt;
  opt.rays = 400000;
  opt.length_s = 0.05;
  opt.skip_order = -1;  // rays alone
  opt.speed_of_sound_m_s = kC;
  for (int b = 0; b < room.bands.size(); ++b) opt.air_m_per_m[b] = 0.002 * b;
  const auto res = dt::traceRoom(room, geometry, 0, opt);
  const auto& h = res.listeners[0];
  for (int b = 0; b < room.bands.size(); ++b) {
    const auto [sum, se] = windowSum(h, b, 1.0);
    const double expected = 2.0 / (r * r) * std::exp(-0.002 * b * r);
    EXPECT_NEAR(sum, expected, 5 * se + 1e-12) << "band " << b;
    EXPECT_LT(se, 0.05 * expected);  // the test has power
  }
  // Every scored bin lies within the sphere's chord times around the exact delay r/c.
  for (int i = 0; i < h.bins(); ++i) {
    if (h.value(0, i) == 0.0) continue;
    EXPECT_GE((i + 1) * h.binSeconds(), (r - 0.25) / kC);
    EXPECT_LE(i * h.binSeconds(), (r + 0.25) / kC);
  }
}

TEST(RoomTracer, DirectivityGainHasUnitMeanAndCardioidOnAxis) {
  dr::Directivity card;
  card.a = 0.5;
  EXPECT_NEAR(dt::directivityGain(card, 1.0), 3.0, 1e-12);  // (1)² / (1/4 + 1/12)
  EXPECT_NEAR(dt::directivityGain(card, -1.0), 0.0, 1e-12);
  for (double a : {0.0, 0.25, 0.37, 0.5, 0.7, 1.0}) {
    dr::Directivity d;
    d.a = a;
    // Mean over the sphere = ½∫D(cosθ) dcosθ, by Gauss–Legendre (exact for this quadratic).
    const double mean = 0.5 * (dt::directivityGain(d, -1 / std::sqrt(3.0)) + dt::directivityGain(d, 1 / std::sqrt(3.0)));
    EXPECT_NEAR(mean, 1.0, 1e-12) << "a = " << a;
  }
}

// A 1.4 × 0.8 m upright rectangle centred at (1, −0.5, 2), the aimed emissions' target below.
dt::EmissionTarget uprightTarget() {
  dt::EmissionTarget aim;
  aim.origin = Vec3(1.0, -0.5, 2.0);
  aim.ex = Vec3(0.6, 0.8, 0.0);
  aim.ey = Vec3(0.0, 0.0, 1.0);
  aim.half_x_m = 0.7;
  aim.half_y_m = 0.4;
  aim.edge_scale_m = 0.01;
  return aim;
}

// An aimed emission's weights 1/(4π·pdf) integrate, over the unit square of its two uniforms, to the
// aim rectangle's solid angle over 4π, whatever the sampling inside it (uniform, or partly log-uniform
// near the −x edge). Oracle: the solid angle of a rectangle [x1, x2] × [y1, y2] at height h above the
// foot of the viewpoint, Σ ± atan(x·y/(h·√(x² + y² + h²))) over its corners. Midpoint rule on a 2000 ×
// 2000 grid whose cell edges include ξ1 = edge_fraction (where the sampling switches branch), so the
// integrand is smooth in each cell: its error is O(1/N²), below 1e-5 here.
TEST(RoomTracer, AimedEmissionWeightsIntegrateToTheRectanglesSolidAngle) {
  dt::EmissionTarget aim = uprightTarget();
  const Vec3 source(-1.0, 2.5, 1.7);
  const Vec3 n = aim.ex.cross(aim.ey);
  const Vec3 rel = source - aim.origin;
  const double h = std::abs(rel.dot(n)), sx = rel.dot(aim.ex), sy = rel.dot(aim.ey);
  const auto corner = [h](double x, double y) { return std::atan(x * y / (h * std::sqrt(x * x + y * y + h * h))); };
  const double x1 = -aim.half_x_m - sx, x2 = aim.half_x_m - sx, y1 = -aim.half_y_m - sy, y2 = aim.half_y_m - sy;
  const double omega = corner(x2, y2) - corner(x1, y2) - corner(x2, y1) + corner(x1, y1);
  ASSERT_GT(omega, 0.05);  // a sizeable target
  for (const double edge_fraction : {0.0, 0.25}) {
    aim.edge_fraction = edge_fraction;
    const int n_grid = 2000;
    double sum = 0.0;
    for (int i = 0; i < n_grid; ++i)
      for (int j = 0; j < n_grid; ++j) {
        double scale = 0.0;
        const Vec3 d = dt::emissionDirection(&aim, source, (i + 0.5) / n_grid, (j + 0.5) / n_grid, scale);
        ASSERT_NEAR(d.norm(), 1.0, 1e-12);
        // The ray does go toward the rectangle: it meets its plane inside it.
        const double t = -rel.dot(n) / d.dot(n);
        const Vec3 hit = source + t * d - aim.origin;
        ASSERT_GT(t, 0.0);
        ASSERT_LE(std::abs(hit.dot(aim.ex)), aim.half_x_m * (1 + 1e-9));
        ASSERT_LE(std::abs(hit.dot(aim.ey)), aim.half_y_m * (1 + 1e-9));
        sum += scale;
      }
    EXPECT_NEAR(sum / (static_cast<double>(n_grid) * n_grid), omega / (4.0 * diffray::core::kPi), 1e-5 * omega)
        << "edge_fraction " << edge_fraction;
  }
  double scale = 0.0;
  const Vec3 d = dt::emissionDirection(nullptr, source, 0.3, 0.7, scale);
  EXPECT_EQ(scale, 1.0);  // uniform emission: weight 1
  EXPECT_NEAR(d.norm(), 1.0, 1e-12);
}

// Aimed through a ground (EmissionTarget::mirrored): the weights integrate to the solid angles of the
// rectangle and of its mirror image in the ground, over 4π, and every ray meets the rectangle's plane inside
// one of the two; then with a second rectangle (EmissionTarget::also). Oracle: the same corner formula for
// each rectangle; the grid's cell edges include the ξ2 where the sampling switches target (¼, ½, ¾).
TEST(RoomTracer, AimedThroughAGroundWeightsIntegrateToBothRectanglesSolidAngles) {
  dt::EmissionTarget aim = uprightTarget();
  aim.edge_fraction = 0.25;
  aim.mirrored = true;
  aim.mirror_normal = Vec3(0.0, 0.0, 1.0);  // the ground z = 0.5, below the rectangle (z 1.6 to 2.4)
  aim.mirror_offset = 0.5;
  const Vec3 source(-1.0, 2.5, 1.7);
  const Vec3 n = aim.ex.cross(aim.ey);
  const auto solidAngle = [&](const Vec3& origin) {
    const Vec3 rel = source - origin;
    const double h = std::abs(rel.dot(n)), sx = rel.dot(aim.ex), sy = rel.dot(aim.ey);
    const auto corner = [h](double x, double y) { return std::atan(x * y / (h * std::sqrt(x * x + y * y + h * h))); };
    const double x1 = -aim.half_x_m - sx, x2 = aim.half_x_m - sx, y1 = -aim.half_y_m - sy, y2 = aim.half_y_m - sy;
    return corner(x2, y2) - corner(x1, y2) - corner(x2, y1) + corner(x1, y1);
  };
  const Vec3 image_origin(1.0, -0.5, -1.0);  // 2·0.5 − 2.0
  const double omega = solidAngle(aim.origin) + solidAngle(image_origin);
  const int n_grid = 2000;
  double sum = 0.0;
  int to_image = 0;
  for (int i = 0; i < n_grid; ++i)
    for (int j = 0; j < n_grid; ++j) {
      double scale = 0.0;
      const Vec3 d = dt::emissionDirection(&aim, source, (i + 0.5) / n_grid, (j + 0.5) / n_grid, scale);
      const double t = -(source - aim.origin).dot(n) / d.dot(n);
      ASSERT_GT(t, 0.0);
      const Vec3 hit = source + t * d;
      const bool image = hit.z() < 0.5;
      to_image += image;
      const Vec3 local = hit - (image ? image_origin : aim.origin);
      ASSERT_LE(std::abs(local.dot(aim.ex)), aim.half_x_m * (1 + 1e-9));
      ASSERT_LE(std::abs(local.dot(aim.ey)), aim.half_y_m * (1 + 1e-9));
      sum += scale;
    }
  EXPECT_EQ(to_image, n_grid * n_grid / 2);
  EXPECT_NEAR(sum / (static_cast<double>(n_grid) * n_grid), omega / (4.0 * diffray::core::kPi), 1e-5 * omega);
  // With a second rectangle beside it in the same plane (EmissionTarget::also, 0.8 m further along ex, so
  // that the two and their images do not overlap): half the rays each, weights integrating to all four
  // solid angles.
  dt::EmissionTarget beside = aim;
  beside.origin = aim.origin + 1.6 * aim.ex;
  aim.also = {beside};
  const Vec3 beside_image = image_origin + 1.6 * aim.ex;
  const double omega2 = omega + solidAngle(beside.origin) + solidAngle(beside_image);
  sum = 0.0;
  for (int i = 0; i < n_grid; ++i)
    for (int j = 0; j < n_grid; ++j) {
      double scale = 0.0;
      const Vec3 d = dt::emissionDirection(&aim, source, (i + 0.5) / n_grid, (j + 0.5) / n_grid, scale);
      const Vec3 hit = source + (-(source - aim.origin).dot(n) / d.dot(n)) * d;
      const bool second = (hit - aim.origin).dot(aim.ex) > aim.half_x_m;
      EXPECT_EQ(second, j >= n_grid / 2);
      const Vec3 local = hit - (second ? beside.origin : aim.origin);
      ASSERT_LE(std::abs(local.dot(aim.ex)), aim.half_x_m * (1 + 1e-9));
      sum += scale;
    }
  EXPECT_NEAR(sum / (static_cast<double>(n_grid) * n_grid), omega2 / (4.0 * diffray::core::kPi), 1e-5 * omega2);
}

// The eight-band bounce loop (Octaves: floats relative to the emitted level) against the general one
// (double BandArray): a 9-band room whose first eight bands are an 8-band room's, traced with no scattering,
// transmission or roulette, so that no uniform is drawn after the emission and both rooms' rays take the
// same paths. Bands 0–7 agree per bin to 1e-5 (float rounding over ≤ ~40 weights: ≤ 40·6e-8 = 2.4e-6).
// And the source power only scales the result, exactly to double rounding, even at 1e-35 W and 1e30 W,
// where each ray's absolute energy lies outside float's range.
TEST(RoomTracer, EightBandLoopMatchesTheGeneralOneAndAnyPowerFits) {
  const auto make = [](const diffray::core::Bands& bands, double power) {
    dr::Room room;
    room.bands = bands;
    dr::Material m;
    m.name = "wall";
    for (int b = 0; b < bands.size(); ++b) m.absorption[b] = b < 8 ? 0.05 + 0.03 * b : 0.4;
    const int id = room.addMaterial(m);
    const int walls[6] = {id, id, id, id, id, id};
    room.addBox(Vec3(0, 0, 0), Vec3(6, 5, 3), walls);
    room.sources.push_back({"S", Vec3(1.5, 2.0, 1.2), power, {}});
    room.listeners.push_back({"A", Vec3(4.5, 3.0, 1.5), 0.4});
    room.listeners.push_back({"B", Vec3(2.0, 4.0, 2.0), 0.3});
    return room;
  };
  const auto trace = [](const dr::Room& room) {
    const dt::RoomGeometry geometry(room);
    dt::RoomTraceOptions opt;
    opt.rays = 4000;
    opt.length_s = 0.25;
    opt.skip_order = -1;
    opt.roulette_level = 0.0;
    opt.speed_of_sound_m_s = kC;
    for (int b = 0; b < room.bands.size(); ++b) opt.air_m_per_m[b] = 0.001 * b;
    return dt::traceRoom(room, geometry, 0, opt);
  };
  const auto eight = trace(make(diffray::core::Bands::octave(63.0, 8000.0), 1.0));
  const auto nine = trace(make(diffray::core::Bands::octave(63.0, 16000.0), 1.0));
  ASSERT_EQ(eight.listeners[0].bands(), 8);
  ASSERT_EQ(nine.listeners[0].bands(), 9);
  EXPECT_EQ(eight.segments, nine.segments);
  int scored = 0;
  for (std::size_t l = 0; l < 2; ++l)
    for (int b = 0; b < 8; ++b)
      for (int i = 0; i < eight.listeners[l].bins(); ++i) {
        const double want = nine.listeners[l].value(b, i);
        ASSERT_NEAR(eight.listeners[l].value(b, i), want, 1e-5 * std::abs(want)) << "listener " << l << " band " << b
                                                                                 << " bin " << i;
        scored += want != 0.0;
      }
  EXPECT_GT(scored, 500);  // the comparison has substance
  for (const double power : {1e-35, 1e30}) {
    const auto scaled = trace(make(diffray::core::Bands::octave(63.0, 8000.0), power));
    for (std::size_t l = 0; l < 2; ++l)
      for (int b = 0; b < 8; ++b)
        for (int i = 0; i < eight.listeners[l].bins(); ++i) {
          const double want = power * eight.listeners[l].value(b, i);
          ASSERT_NEAR(scaled.listeners[l].value(b, i), want, 1e-12 * std::abs(want)) << "power " << power;
        }
  }
}

TEST(StatRoomTracer, CardioidSourceOnAxisFluence) {
  dr::Room room = boxRoom(Vec3(200, 200, 200), 1.0, 0.0);
  dr::Source s{"S", Vec3(100, 100, 100), 1.0, {}};
  s.directivity.a = 0.5;
  s.directivity.axis = Vec3(0, 1, 0);
  room.sources.push_back(s);
  room.listeners.push_back({"L", Vec3(100, 102, 100), 0.2});
  const dt::RoomGeometry geometry(room);
  dt::RoomTraceOptions opt;
  opt.rays = 300000;
  opt.length_s = 0.05;
  opt.skip_order = -1;
  const auto res = dt::traceRoom(room, geometry, 0, opt);
  const auto [sum, se] = windowSum(res.listeners[0], 0, 1.0);
  EXPECT_NEAR(sum, 3.0 / 4.0, 5 * se + 0.01);  // +0.01: D varies by ~1 % across the sphere's 0.1 rad
}

TEST(ImageSources, DirectAndFirstOrderOfABoxByHand) {
  const Vec3 dims(5, 4, 3);
  dr::Room room = boxRoom(dims, 0.1, 0.2);
  const Vec3 s(1, 1, 1), l(3, 2, 1.5);
  room.sources.push_back({"S", s, 1.0, {}});
  room.listeners.push_back({"L", l, 0.1});
  const dt::RoomGeometry geometry(room);
  dt::ImageSourceOptions opt;
  opt.max_order = 1;
  opt.speed_of_sound_m_s = kC;
  const auto arrivals = dt::imageSources(room, geometry, 0, 0, opt);
  ASSERT_EQ(arrivals.size(), 7u);  // direct + 6 walls, all visible in a box
  // Images across x = 0, x = 5, y = 0, y = 4, z = 0, z = 3.
  const Vec3 images[7] = {s, Vec3(-1, 1, 1), Vec3(9, 1, 1), Vec3(1, -1, 1), Vec3(1, 7, 1), Vec3(1, 1, -1), Vec3(1, 1, 5)};
  for (const Vec3& img : images) {
    const double d = (img - l).norm();
    const bool direct = &img == &images[0];
    const double e = (direct ? 1.0 : 0.9 * 0.8) / (d * d);
    bool found = false;
    for (const auto& a : arrivals)
      if (std::abs(a.delay_s - d / kC) < 1e-12) {
        found = true;
        EXPECT_NEAR(a.energy[0], e, 1e-12 * e);
        EXPECT_EQ(a.order, direct ? 0 : 1);
      }
    EXPECT_TRUE(found) << "image at distance " << d;
  }
}

TEST(ImageSources, WallBlocksAndOpeningPasses) {
  // A box split by a wall at x = 2.5 with a doorway: the direct path through the door exists only when
  // the doorway is an opening (τ = 1) and not when it is a wall.
  for (bool open : {true, false}) {
    dr::Room room = boxRoom(Vec3(5, 4, 3), 0.3, 0.0);
    dr::Material door;
    door.name = "door";
    for (int b = 0; b < room.bands.size(); ++b) {
      door.absorption[b] = 1.0;
      door.transmission[b] = open ? 1.0 : 0.0;
    }
    const int id = room.addMaterial(door);
    room.addPolygon({Vec3(2.5, 1.5, 0), Vec3(2.5, 2.5, 0), Vec3(2.5, 2.5, 2), Vec3(2.5, 1.5, 2)}, id, "door");
    room.addPolygon({Vec3(2.5, 0, 0), Vec3(2.5, 1.5, 0), Vec3(2.5, 1.5, 3), Vec3(2.5, 0, 3)}, 0, "wall");
    room.sources.push_back({"S", Vec3(1, 2, 1), 1.0, {}});
    room.listeners.push_back({"L", Vec3(4, 2, 1), 0.1});
    const dt::RoomGeometry geometry(room);
    dt::ImageSourceOptions opt;
    opt.max_order = 0;
    const auto arrivals = dt::imageSources(room, geometry, 0, 0, opt);
    EXPECT_EQ(arrivals.size(), open ? 1u : 0u);
  }
}

TEST(ImageSources, NoPathThroughABlockingOpeningNotEvenAtItsEdge) {
  // A box split at x = 2.5 by a black wall with a doorway (an opening) whose triangles block, as the WBSDF's
  // occluders do: no path may pass the doorway or the wall. The source and the listener stand
  // mirror-symmetric about them at equal heights, so every reflection that could pass meets its mirror on
  // the plane x = 2.5, where its legs only touch the wall's or the doorway's edge: the floor's at
  // (2.5, 2, 0), on the doorway's sill; the side walls' and the ceiling's where the wall meets them.
  // Without the mask the opening passes the direct sound and that floor reflection (the control).
  dr::Room room = boxRoom(Vec3(5, 4, 3), 0.3, 0.0);
  dr::Material open, black;
  open.name = "doorway";
  black.name = "black";
  for (int b = 0; b < room.bands.size(); ++b) {
    open.absorption[b] = open.transmission[b] = 1.0;
    black.absorption[b] = 1.0;
  }
  const int id_open = room.addMaterial(open), id_black = room.addMaterial(black);
  room.addPolygon({Vec3(2.5, 1.5, 0), Vec3(2.5, 2.5, 0), Vec3(2.5, 2.5, 2), Vec3(2.5, 1.5, 2)}, id_open, "doorway");
  room.addPolygon({Vec3(2.5, 0, 0), Vec3(2.5, 1.5, 0), Vec3(2.5, 1.5, 3), Vec3(2.5, 0, 3)}, id_black, "wall");
  room.addPolygon({Vec3(2.5, 2.5, 0), Vec3(2.5, 4, 0), Vec3(2.5, 4, 3), Vec3(2.5, 2.5, 3)}, id_black, "wall");
  room.addPolygon({Vec3(2.5, 1.5, 2), Vec3(2.5, 2.5, 2), Vec3(2.5, 2.5, 3), Vec3(2.5, 1.5, 3)}, id_black, "wall");
  room.sources.push_back({"S", Vec3(1, 2, 1), 1.0, {}});
  room.listeners.push_back({"L", Vec3(4, 2, 1), 0.1});
  const dt::RoomGeometry geometry(room);
  std::vector<char> mask(room.mesh.triangleCount(), 0);
  for (std::size_t t = 0; t < mask.size(); ++t) mask[t] = room.group_of_triangle[t] == "doorway" ? 1 : 0;
  dt::ImageSourceOptions opt;
  opt.max_order = 2;
  const double direct = 3.0, via_floor = std::sqrt(3.0 * 3.0 + 2.0 * 2.0);
  const auto passing = dt::imageSources(room, geometry, 0, 0, opt);
  auto has = [&](double d) {
    for (const auto& a : passing)
      if (std::abs(a.delay_s * opt.speed_of_sound_m_s - d) < 1e-9) return true;
    return false;
  };
  EXPECT_TRUE(has(direct));
  EXPECT_TRUE(has(via_floor));
  opt.blocking_triangles = &mask;
  for (const auto& a : dt::imageSources(room, geometry, 0, 0, opt))
    ADD_FAILURE() << "order " << a.order << " at " << a.delay_s * opt.speed_of_sound_m_s << " m passes";
  room.listeners[0].position_m = Vec3(4, 2.2, 1.3);  // off the symmetry: the intersector's own case
  EXPECT_TRUE(dt::imageSources(room, geometry, 0, 0, opt).empty());
}

TEST(ImageSources, AReflectionAtAConvexCornerStays) {
  // A pillar [4, 5] × [2, 3] × [0, 3] in a 10 × 6 × 3 m box. The reflection off its face x = 4 from
  // S = (1.5, 2, 1.5) to L = (2, 3.8, 1.5) meets the face at (4, 3, 1.5), on the pillar's corner: its second
  // leg touches the plane of the pillar's face y = 3 at that face's edge, but the face lies behind the
  // mirror. The path is the limit of valid ones (reflections a little lower on the face), so it stays, at
  // |S' − L| = |(6.5, 2) − (2, 3.8)| = √23.49 m, S' the image of S in x = 4 (no other path has that length).
  dr::Room room = boxRoom(Vec3(10, 6, 3), 0.3, 0.0);
  const int pillar[6] = {0, 0, 0, 0, 0, 0};
  room.addBox(Vec3(4, 2, 0), Vec3(5, 3, 3), pillar, "pillar");
  room.sources.push_back({"S", Vec3(1.5, 2, 1.5), 1.0, {}});
  room.listeners.push_back({"L", Vec3(2, 3.8, 1.5), 0.1});
  const dt::RoomGeometry geometry(room);
  dt::ImageSourceOptions opt;
  opt.max_order = 1;
  bool found = false;
  for (const auto& a : dt::imageSources(room, geometry, 0, 0, opt))
    found = found || std::abs(a.delay_s * opt.speed_of_sound_m_s - std::sqrt(23.49)) < 1e-9;
  EXPECT_TRUE(found);
}

TEST(RoomWorkload, AClosedRoomThatKeepsItsRaysIsRefused) {
  // A 1 m rigid-ish box (α = 0.01) over 10 s: the free path 4V/S = 0.67 m gives 5,100 hits per ray, Russian
  // roulette ends rays after ln(1e6)/−ln(0.99) = 1,375; at 1e7 rays 1.4e10 hits, above the 5e9 allowed.
  dr::Room room = boxRoom(Vec3(1, 1, 1), 0.01, 0.0);
  room.sources.push_back({"S", Vec3(0.3, 0.4, 0.5), 1.0, {}});
  room.listeners.push_back({"L", Vec3(0.7, 0.6, 0.5), 0.1});
  dt::RoomSimulationOptions o;
  o.rays = 10000000;
  o.length_s = 10.0;
  EXPECT_THROW(dt::simulateRoom(room, o), diffray::core::InputError);
}

TEST(RoomWorkload, WallsInTheOpenAreNotTakenForATinyRoom) {
  // A rigid wall with a doorway standing in free field, and specks of surface: the open mesh sums to a
  // volume below 20 litres over 168 m² of surface, and the source beside the wall tests inside it by ray
  // parity. Taken as a room's free path, 4V/S < 0.5 mm would give more than 7e4 hits per ray over 0.1 s, 7e9
  // for 100k rays, and the run would be refused; a mesh with open edges has a free path of at least 1 m
  // (34 hits per ray).
  dr::Room room;
  dr::Material rigid;
  rigid.name = "rigid";
  const int id = room.addMaterial(rigid);
  const double w = 7.0, z0 = -4.0, z1 = 8.0;
  room.addPolygon({Vec3(0, -w, z0), Vec3(0, -0.45, z0), Vec3(0, -0.45, z1), Vec3(0, -w, z1)}, id, "left");
  room.addPolygon({Vec3(0, 0.45, z0), Vec3(0, w, z0), Vec3(0, w, z1), Vec3(0, 0.45, z1)}, id, "right");
  room.addPolygon({Vec3(0, -0.45, 2.1), Vec3(0, 0.45, 2.1), Vec3(0, 0.45, z1), Vec3(0, -0.45, z1)}, id, "above");
  room.addPolygon({Vec3(0, -0.45, z0), Vec3(0, 0.45, z0), Vec3(0, 0.45, 0), Vec3(0, -0.45, 0)}, id, "below");
  room.addPolygon({Vec3(-5, w - 0.1, z1), Vec3(-4.95, w - 0.1, z1), Vec3(-4.95, w, z1)}, id, "speck");
  room.addPolygon({Vec3(5, w - 0.1, z1), Vec3(5.05, w - 0.1, z1), Vec3(5.05, w, z1)}, id, "speck");
  room.addPolygon({Vec3(0, -w, z0), Vec3(0.05, -w, z0), Vec3(0.05, -w + 0.1, z0)}, id, "speck");
  room.sources.push_back({"S", Vec3(-0.52, 2.95, 1.05), 1.0, {}});
  room.listeners.push_back({"L", Vec3(3.0, 0.07, 1.08), 0.3});
  // The premise: what the old estimate was fooled by.
  ASSERT_GT(dr::openEdgeCount(room), 0);
  ASSERT_TRUE(dr::insideRoom(room, room.sources[0].position_m));
  ASSERT_LT(room.volume(), 0.02);
  dt::RoomSimulationOptions o;
  o.rays = 100000;
  o.length_s = 0.1;
  o.ism_order = 1;
  EXPECT_NO_THROW(dt::simulateRoom(room, o));
}

TEST(ImageSources, TooManyCandidatesIsOneLineWithAPositiveCount) {
  // 6 planes at order 50: 1 + 6·(5^50 − 1)/4 ≈ 1.33e35 candidates, far past any integer type (the message
  // used to print a negative count).
  dr::Room room = boxRoom(Vec3(4, 3, 2.5), 0.2, 0.0);
  room.sources.push_back({"S", Vec3(1, 1, 1), 1.0, {}});
  room.listeners.push_back({"L", Vec3(3, 2, 1.2), 0.1});
  const dt::RoomGeometry geometry(room);
  dt::ImageSourceOptions opt;
  opt.max_order = 50;
  try {
    dt::imageSources(room, geometry, 0, 0, opt);
    ADD_FAILURE() << "no error";
  } catch (const diffray::core::InputError& e) {
    const std::string msg = e.what();
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
    EXPECT_EQ(msg.find("makes -"), std::string::npos) << msg;
    EXPECT_NE(msg.find("1.33e+35 image-source candidates"), std::string::npos) << msg;
  }
}

TEST(RoomTracer, HistogramsTooLargeForMemoryAreRefusedBeforeTracing) {
  // By hand: 10 s in 1 ms bins is 10,000 bins; 0.0105 s in 1 ms bins needs 11 (the last one partial).
  EXPECT_EQ(dt::histogramBins(10.0, 1e-3, 8, 2), 10000);
  EXPECT_EQ(dt::histogramBins(0.0105, 1e-3, 8, 2), 11);
  // 100 s in 0.1 ms bins × 8 bands × 1 listener = 8e6 cells: within the 1e7 cap, but not when the direction
  // tallies (3 doubles per cell beside the histogram's 4) count too: 8e6 × 7/4 = 1.4e7.
  EXPECT_EQ(dt::histogramBins(100.0, 1e-4, 8, 1), 1000000);
  EXPECT_THROW(dt::histogramBins(100.0, 1e-4, 8, 1, true), diffray::core::InputError);
  // 600 s in 0.1 ms bins × 8 bands = 4.8e7 cells: the scene file accepts it, the machine's memory did not.
  dr::Room room = boxRoom(Vec3(4, 3, 2.5), 0.2, 0.0);
  room.sources.push_back({"S", Vec3(1, 1, 1), 1.0, {}});
  room.listeners.push_back({"L", Vec3(3, 2, 1.2), 0.1});
  const dt::RoomGeometry geometry(room);
  dt::RoomTraceOptions opt;
  opt.rays = 1000;
  opt.length_s = 600.0;
  opt.bin_s = 1e-4;
  try {
    dt::traceRoom(room, geometry, 0, opt);
    ADD_FAILURE() << "no error";
  } catch (const diffray::core::InputError& e) {
    EXPECT_EQ(e.where(), "output.histogram_bin_s");
    EXPECT_NE(std::string(e.what()).find("4.8e+07 histogram cells"), std::string::npos) << e.what();
  }
}

// Rays with image sources to order 2 (the tracer skipping those paths) against rays alone, in every band:
// the total energy in the first 60 ms must agree within the two runs' combined 5σ, and the image sources
// must carry more than 5σ of it, so that counting them twice or not at all would fail.
void expectHybridEqualsRaysAlone(const dr::Room& room) {
  const dt::RoomGeometry geometry(room);
  dt::RoomTraceOptions opt;
  opt.rays = 200000;
  opt.length_s = 0.06;
  opt.bin_s = 0.06;  // one bin: its chunk-scatter error is the window sum's own
  opt.speed_of_sound_m_s = kC;
  opt.skip_order = -1;
  const auto alone = dt::traceRoom(room, geometry, 0, opt);
  opt.skip_order = 2;
  opt.seed = 2;
  const auto hybrid = dt::traceRoom(room, geometry, 0, opt);
  dt::ImageSourceOptions iopt;
  iopt.max_order = 2;
  iopt.length_s = opt.length_s;
  iopt.speed_of_sound_m_s = kC;
  const auto arrivals = dt::imageSources(room, geometry, 0, 0, iopt);
  for (int b = 0; b < room.bands.size(); ++b) {
    double ism = 0;
    for (const auto& a : arrivals) ism += a.energy[b];
    const auto [ra, sa] = windowSum(alone.listeners[0], b, 1.0);
    const auto [rh, sh] = windowSum(hybrid.listeners[0], b, 1.0);
    EXPECT_GT(ism, 5 * std::hypot(sa, sh)) << "band " << b;
    EXPECT_NEAR(rh + ism, ra, 5 * std::hypot(sa, sh)) << "band " << b << ": rays alone " << ra << ", hybrid " << rh
                                                      << " + " << ism;
  }
}

TEST(StatRoomTracer, HybridEqualsRaysAlone) {
  dr::Room room = boxRoom(Vec3(6, 5, 3), 0.25, 0.3);
  room.sources.push_back({"S", Vec3(1.5, 1.2, 1.4), 1.0, {}});
  room.listeners.push_back({"L", Vec3(4.2, 3.1, 1.6), 0.4});
  expectHybridEqualsRaysAlone(room);
}

TEST(StatRoomTracer, HybridEqualsRaysAloneInEveryBandWithBandDependentMaterials) {
  // α and s differ per band, so the tracer's fixed band-mean event probabilities differ from every band's
  // own and the per-band weights do the work: rays alone minus the hybrid's rays is the specular part of
  // orders 0–2 as the tracer weights it, which must equal the image sources' closed form
  // Π(1 − α_b)(1 − s_b)/d² in every band. (Specular weights set to the band-mean ones fail bands 4–7, by
  // 6 to 45σ; the uniform room above cannot see that.)
  dr::Room room;
  dr::Material m;
  m.name = "wall";
  for (int b = 0; b < room.bands.size(); ++b) {
    m.absorption[b] = 0.05 + 0.06 * b;  // 0.05 … 0.47
    m.scattering[b] = 0.7 - 0.09 * b;   // 0.70 … 0.07
  }
  const int id = room.addMaterial(m);
  const int walls[6] = {id, id, id, id, id, id};
  room.addBox(Vec3(0, 0, 0), Vec3(6, 5, 3), walls);
  room.sources.push_back({"S", Vec3(1.5, 1.2, 1.4), 1.0, {}});
  room.listeners.push_back({"L", Vec3(4.2, 3.1, 1.6), 0.4});
  expectHybridEqualsRaysAlone(room);
}

TEST(RoomTracer, SameSeedGivesIdenticalHistogramsForAnyThreadCount) {
  dr::Room room = boxRoom(Vec3(6, 5, 3), 0.2, 0.4);
  room.sources.push_back({"S", Vec3(1.5, 1.2, 1.4), 1.0, {}});
  room.listeners.push_back({"L", Vec3(4.2, 3.1, 1.6), 0.4});
  const dt::RoomGeometry geometry(room);
  dt::RoomTraceOptions opt;
  opt.rays = 20000;
  opt.length_s = 0.3;
  std::vector<double> runs[2];
  for (int threads : {1, 2}) {
    diffray::core::ThreadLimit limit(threads);
    const auto res = dt::traceRoom(room, geometry, 0, opt);
    const diffray::receiver::EnergyHistogram& h = res.listeners[0];
    for (int b = 0; b < room.bands.size(); ++b)
      for (int k = 0; k < h.bins(); ++k) runs[threads - 1].push_back(h.value(b, k));
    // The batches too (the metrics' standard errors): each holds its share of the rays, and they add up
    // to the whole (to rounding: the whole sums the chunks in another order).
    ASSERT_EQ(h.batches(), opt.batches);
    double weights = 0.0;
    for (int j = 0; j < h.batches(); ++j) {
      EXPECT_NEAR(h.batchWeight(j), static_cast<double>(opt.rays) / opt.batches, static_cast<double>(opt.chunk_rays)) << j;
      weights += h.batchWeight(j);
    }
    EXPECT_EQ(weights, static_cast<double>(opt.rays));
    for (int b = 0; b < room.bands.size(); ++b)
      for (int k = 0; k < h.bins(); ++k) {
        double sum = 0.0, scale = 0.0;
        for (int j = 0; j < h.batches(); ++j) {
          sum += h.batchValue(j, b, k);
          scale += std::abs(h.batchValue(j, b, k));
          runs[threads - 1].push_back(h.batchValue(j, b, k));
        }
        ASSERT_NEAR(sum, h.value(b, k), 1e-12 * scale) << b << " " << k;
      }
  }
  ASSERT_EQ(runs[0].size(), runs[1].size());
  double total = 0;
  for (double v : runs[0]) total += v;
  EXPECT_GT(total, 0.0);  // the comparison is not of two empty histograms
  for (std::size_t i = 0; i < runs[0].size(); ++i) ASSERT_EQ(runs[0][i], runs[1][i]) << i;  // bit-identical
}

}  // namespace
