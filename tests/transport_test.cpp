// Tests of the transport scene and the signed-energy tracer. Oracles, all written here:
//  * intersection: an analytic ray–rectangle intersection (plane distance + in-rectangle test in local
//    coordinates) against both back ends (Embree, brute force) built from the same scene;
//  * energy: exact bookkeeping for a fully open occluder (W = δ(u), every ray weight 1), binomial standard
//    errors for geometric fate fractions, and for signed WBSDFs the expectation and variance of the
//    per-ray tallies computed directly from the table's cell masses (independent sums over cells);
//  * directions: straight-line geometry (angle-shift invariance u_o = u_i + u', the grating equation
//    sinθ_o = sinθ_i + λu', the mirror law for reflecting occluders) checked by landing positions;
//  * determinism: bit-identical tallies for 1 and 2 threads.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <random>
#include <utility>
#include <vector>

#include "chi2.h"
#include "transport_fixtures.h"
#include "diffray/core/math.h"
#include "diffray/core/parallel.h"
#include "diffray/geometry/frame.h"
#include "diffray/geometry/mesh.h"
#include "diffray/receiver/screen.h"
#include "diffray/transport/scene.h"
#include "diffray/transport/tracer.h"
#include "diffray/wbsdf/microstructure.h"
#include "diffray/wbsdf/table.h"

namespace dw = diffray::wbsdf;
namespace dtr = diffray::transport;
namespace dg = diffray::geometry;
namespace dt = diffray::testing;
using namespace diffray::testing;  // fixtures

// ---- Intersection ------------------------------------------------------------------------------------------
// Six rectangles (an occluder, three screens, two absorbers) at random orientations, centres ≥ √2 apart and
// half-diagonals ≤ 0.57 so they never intersect; 20000 rays from a sphere of radius 4 aimed at them.
// Oracle: the analytic nearest rectangle. Both back ends must agree on the object and on the distance (brute
// force, double: 1e-9 relative; Embree, float: 1e-4 relative; both plus 16 round-off units times 1/|cosθ|
// for grazing rays, whose ray–plane distance is ill-conditioned). Disagreements are allowed on at most 0.1 % of
// rays and only where the oracle's hit point, or the back end's, lies within 1e-5 m of a triangle edge
// (rectangle border or diagonal), where float round-off may flip the decision.

namespace {

struct RectDef {
  dg::Frame frame;
  double hx, hy;
  int id;
};

struct RefHit {
  int object = -1;
  double t = 0.0;
  double edge = 0.0;  ///< distance of the hit point to the nearest triangle edge of its rectangle
  double cos = 1.0;   ///< |cos| of the angle between the ray and the rectangle's normal
};

/// Distance from local point (lx, ly) to the nearest edge of either triangulation of the rectangle:
/// borders and both diagonals (negative outside).
double edgeDistance(const RectDef& r, double lx, double ly) {
  const double diag = std::hypot(r.hx, r.hy);
  return std::min({r.hx - std::abs(lx), r.hy - std::abs(ly), std::abs(lx * r.hy - ly * r.hx) / diag,
                   std::abs(lx * r.hy + ly * r.hx) / diag});
}

RefHit analyticHit(const std::vector<RectDef>& rects, const Vec3& o, const Vec3& d) {
  RefHit best;
  best.t = 1e300;
  for (const RectDef& r : rects) {
    const double denom = d.dot(r.frame.n);
    if (denom == 0.0) continue;
    const double t = (r.frame.origin - o).dot(r.frame.n) / denom;
    if (!(t > 0.0) || t >= best.t) continue;
    const Vec3 p = o + t * d - r.frame.origin;
    const double lx = p.dot(r.frame.ex), ly = p.dot(r.frame.ey);
    if (std::abs(lx) > r.hx || std::abs(ly) > r.hy) continue;
    best.object = r.id;
    best.t = t;
    best.edge = edgeDistance(r, lx, ly);
    best.cos = std::abs(denom);
  }
  return best;
}

/// |edge distance| of the point at distance t along the ray, in rectangle `id`'s local frame.
double edgeDistanceOfHit(const std::vector<RectDef>& rects, int id, const Vec3& o, const Vec3& d, double t) {
  for (const RectDef& r : rects) {
    if (r.id != id) continue;
    const Vec3 p = o + t * d - r.frame.origin;
    return std::abs(edgeDistance(r, p.dot(r.frame.ex), p.dot(r.frame.ey)));
  }
  return 1e300;
}

Vec3 randomUnit(std::mt19937_64& rng) {
  std::normal_distribution<double> g(0.0, 1.0);
  Vec3 v(g(rng), g(rng), g(rng));
  return v.normalized();
}

}  // namespace

// geometry::rayTriangleT, the double-precision test the brute-force back end and the room checks share:
// the line through a point built from chosen barycentrics (u, v) at a chosen t comes back with that t,
// behind the origin too, for points inside and 1e-9 inside an edge or a corner (on an edge itself the
// answer is rounding's); points 1e-9 outside and a line parallel to its plane give NaN.
TEST(TransportIntersection, RayTriangleTIsTheLineParameterInsideAndNaNOutside) {
  const Vec3 a(0.3, -0.2, 1.0), b(1.5, 0.1, 0.8), c(0.2, 1.1, 1.4);
  const Vec3 n = (b - a).cross(c - a).normalized();
  std::mt19937_64 rng(11);
  const double e = 1e-9;
  const double inside[][2] = {{0.2, 0.3}, {e, 0.5}, {0.5, e}, {0.4, 0.6 - 2 * e}, {e, e}, {1 - 3 * e, e}, {e, 1 - 3 * e}};
  for (const auto& [u, v] : inside)
    for (const double t : {2.5, -0.75}) {
      const Vec3 d = randomUnit(rng);
      if (std::abs(d.dot(n)) < 0.1) continue;  // grazing: t is ill-conditioned
      const Vec3 p = a + u * (b - a) + v * (c - a);
      EXPECT_NEAR(dg::rayTriangleT(p - t * d, d, a, b, c), t, 1e-12) << "u " << u << ", v " << v;
    }
  const double outside[][2] = {{-e, 0.5}, {0.5, -e}, {0.4, 0.6 + e}};
  for (const auto& [u, v] : outside) {
    const Vec3 p = a + u * (b - a) + v * (c - a);
    EXPECT_TRUE(std::isnan(dg::rayTriangleT(p - 2.0 * n, n, a, b, c))) << "u " << u << ", v " << v;
  }
  // A line parallel to the plane (exactly, in an axis-aligned triangle, so that det is exactly 0).
  const Vec3 o(0, 0, 0), x(1, 0, 0), y(0, 1, 0);
  EXPECT_TRUE(std::isnan(dg::rayTriangleT(Vec3(0.2, 0.2, 1.0), x, o, x, y)));
}

TEST(TransportIntersection, EmbreeAndBruteForceMatchAnalyticRectangles) {
  std::mt19937_64 rng(20240611);
  std::uniform_real_distribution<double> half(0.2, 0.4);
  const Vec3 centres[] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  struct Def {
    dg::Frame frame;
    double hx, hy;
  };
  std::vector<Def> defs;
  for (const Vec3& c : centres) {
    Def def;
    def.frame.origin = c;
    def.frame.n = randomUnit(rng);
    const Vec3 hint = randomUnit(rng);
    def.frame.ex = (hint - hint.dot(def.frame.n) * def.frame.n).normalized();
    def.frame.ey = def.frame.n.cross(def.frame.ex);
    def.hx = half(rng);
    def.hy = half(rng);
    defs.push_back(def);
  }
  const auto table = deltaTable(-1.0, 1.0, 0.0);
  std::vector<RectDef> rects;
  const auto build = [&](bool brute) {
    auto scene = std::make_unique<dtr::Scene>();
    std::vector<RectDef> r;
    for (std::size_t i = 0; i < defs.size(); ++i) {
      const Def& d = defs[i];
      int id = -1;
      if (i == 0) {
        dtr::Occluder occ;
        occ.frame = d.frame;
        occ.half_x_m = d.hx;
        occ.half_y_m = d.hy;
        occ.table_x = table;
        id = scene->addOccluder(occ);
      } else if (i <= 3) {
        diffray::receiver::Screen s;
        s.frame = d.frame;
        s.half_x_m = d.hx;
        s.half_y_m = d.hy;
        id = scene->addScreen(s);
      } else {
        dtr::Absorber a;
        a.frame = d.frame;
        a.half_x_m = d.hx;
        a.half_y_m = d.hy;
        id = scene->addAbsorber(a);
      }
      r.push_back({d.frame, d.hx, d.hy, id});
    }
    scene->build(brute);
    rects = r;
    return scene;
  };
  const auto embree = build(false);
  const auto brute = build(true);
  ASSERT_NE(embree->embree(), nullptr);
  ASSERT_EQ(brute->embree(), nullptr);
  ASSERT_EQ(embree->mesh().triangleCount(), 12u);

  const int rays = 20000;
  // Aim at a random point of a random rectangle's plane, up to 1.2 half-widths from its centre: most rays
  // hit something and many pass close to borders.
  std::uniform_real_distribution<double> unit(-1.2, 1.2);
  std::uniform_int_distribution<int> pick(0, static_cast<int>(defs.size()) - 1);
  int hits = 0, bad_embree = 0, bad_brute = 0, disagree_embree = 0, disagree_brute = 0, pair_mismatch = 0;
  std::vector<int> per_object(defs.size(), 0);
  std::vector<Vec3> origins, dirs;
  std::vector<RefHit> refs;
  // Distance tolerance: `floor` relative, plus 16 units of round-off ε amplified by the conditioning
  // 1/|cosθ| of a ray–plane distance (grazing rays: Embree's float t is off by ~1e-4 at |cosθ| ~ 1e-4).
  const auto agrees = [](const dg::Hit& h, const RefHit& ref, double floor, double eps) {
    if (h.object != ref.object) return false;
    return ref.object < 0 || std::abs(h.t - ref.t) <= (floor + 16.0 * eps / ref.cos) * ref.t;
  };
  const auto nearEdge = [&](const dg::Hit& h, const RefHit& ref, const Vec3& o, const Vec3& d) {
    if (ref.object >= 0 && std::abs(ref.edge) <= 1e-5) return true;
    return h.object >= 0 && edgeDistanceOfHit(rects, h.object, o, d, h.t) <= 1e-5;
  };
  for (int i = 0; i < rays; ++i) {
    const Vec3 o = 4.0 * randomUnit(rng);
    const Def& aim = defs[pick(rng)];
    const Vec3 target = aim.frame.origin + unit(rng) * aim.hx * aim.frame.ex + unit(rng) * aim.hy * aim.frame.ey;
    const Vec3 d = (target - o).normalized();
    const RefHit ref = analyticHit(rects, o, d);
    origins.push_back(o);
    dirs.push_back(d);
    refs.push_back(ref);
    if (ref.object >= 0) {
      ++hits;
      ++per_object[ref.object];
    }
    const dg::Ray ray{o, d, 0.0, 1e300};
    const dg::Hit he = embree->intersector().intersect(ray);
    const dg::Hit hb = brute->intersector().intersect(ray);
    if (!agrees(he, ref, 1e-4, 0x1.0p-24)) {
      ++disagree_embree;
      if (!nearEdge(he, ref, o, d)) {
        ++bad_embree;
        ADD_FAILURE() << "Embree: ray " << i << " object " << he.object << " t " << he.t << " vs analytic "
                      << ref.object << " t " << ref.t;
      }
    }
    if (!agrees(hb, ref, 1e-9, 0x1.0p-53)) {
      ++disagree_brute;
      if (!nearEdge(hb, ref, o, d)) {
        ++bad_brute;
        ADD_FAILURE() << "brute force: ray " << i << " object " << hb.object << " t " << hb.t << " vs analytic "
                      << ref.object << " t " << ref.t;
      }
    }
    if (he.object != hb.object) ++pair_mismatch;
  }
  // The same rays in Embree's packets (the tracer's path): intersectPacket (one rtcIntersect16 where the CPU
  // has native 16-wide packets, else two rtcIntersect8 halves; which one is recorded) and the halves on any
  // CPU. Inactive lanes hold NaN rays (Embree must ignore them) and are not checked: every third lane, and in
  // one packet of five the whole upper half (the tracer's last packet of a chunk; one half's mask is all
  // zero). Same tolerance as the single rays.
  const auto* es = embree->embree();
  RecordProperty("native_packet16", es->nativePacket16() ? 1 : 0);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  int bad_packet = 0, checked = 0;
  for (int by8 = 0; by8 < 2; ++by8) {
    for (int first = 0; first + dg::RayPacket::kSize <= rays; first += dg::RayPacket::kSize) {
      const bool upper_half_off = (first / dg::RayPacket::kSize) % 5 == 4;
      dg::RayPacket packet;
      dg::HitPacket packet_hits;
      for (int k = 0; k < dg::RayPacket::kSize; ++k) {
        const bool active = upper_half_off ? k < dg::RayPacket::kSize / 2 : (first + k) % 3 != 2;
        const Vec3& o = origins[first + k];
        const Vec3& d = dirs[first + k];
        packet.org_x[k] = active ? static_cast<float>(o.x()) : nan;
        packet.org_y[k] = active ? static_cast<float>(o.y()) : nan;
        packet.org_z[k] = active ? static_cast<float>(o.z()) : nan;
        packet.dir_x[k] = active ? static_cast<float>(d.x()) : nan;
        packet.dir_y[k] = active ? static_cast<float>(d.y()) : nan;
        packet.dir_z[k] = active ? static_cast<float>(d.z()) : nan;
        packet.tnear[k] = 0.0f;
        packet.active[k] = active ? -1 : 0;
      }
      if (by8) es->intersectPacketBy8(packet, packet_hits);
      else es->intersectPacket(packet, packet_hits);
      for (int k = 0; k < dg::RayPacket::kSize; ++k) {
        if (!packet.active[k]) continue;
        ++checked;
        dg::Hit h;
        h.object = packet_hits.object[k];
        h.t = packet_hits.t[k];
        const RefHit& ref = refs[first + k];
        if (!agrees(h, ref, 1e-4, 0x1.0p-24) && !nearEdge(h, ref, origins[first + k], dirs[first + k])) {
          ++bad_packet;
          ADD_FAILURE() << (by8 ? "rtcIntersect8 halves" : es->nativePacket16() ? "rtcIntersect16" : "intersectPacket")
                        << ": ray " << first + k << " object " << h.object << " t " << h.t << " vs analytic "
                        << ref.object << " t " << ref.t;
        }
      }
    }
  }
  EXPECT_EQ(bad_packet, 0);
  EXPECT_GT(checked, rays);  // both packet paths saw most of the rays
  EXPECT_EQ(bad_embree, 0);
  EXPECT_EQ(bad_brute, 0);
  EXPECT_LE(disagree_embree, rays / 1000);
  EXPECT_LE(disagree_brute, rays / 1000);
  EXPECT_LE(pair_mismatch, rays / 1000);
  EXPECT_GT(hits, rays / 2);  // the comparison is not vacuous
  for (std::size_t k = 0; k < per_object.size(); ++k) EXPECT_GT(per_object[k], 1000) << "object " << k;
}

// ---- Determinism -------------------------------------------------------------------------------------------

TEST(TransportDeterminism, SameSeedSameBitsForAnyThreadCount) {
  const double lambda = 1e-6, a = 20 * lambda;
  const auto table = dw::WbsdfTable::build(*dw::Openings::slit(a), optionsFor(lambda));
  dtr::Scene scene;
  dtr::Occluder occ;
  occ.frame = frameAt(Vec3(0, 0, 0));
  occ.half_x_m = a;
  occ.half_y_m = 1.0;
  occ.table_x = table;
  scene.addOccluder(occ);
  diffray::receiver::Screen screen;
  screen.frame = frameAt(Vec3(0, 0, 0.01));
  screen.half_x_m = 5e-3;
  screen.half_y_m = 1.0;
  screen.nx = 64;
  scene.addScreen(screen);
  scene.build();
  dtr::CollimatedSource src;
  src.frame = frameAt(Vec3(0, 0, -0.01));
  src.half_x_m = 0.6 * a;
  src.half_y_m = 1e-3;
  src.wavelength_m = lambda;
  const auto run = [&](int threads, std::uint64_t seed) {
    diffray::core::ThreadLimit limit(threads);
    dtr::TraceOptions opt;
    opt.rays = 150000;
    opt.chunk_rays = 8192;
    opt.seed = seed;
    return dtr::trace(scene, src, opt);
  };
  const dtr::TraceResult one = run(1, 42), two = run(2, 42), other = run(2, 43);
  ASSERT_EQ(one.screens[0].sum.size(), 64u);
  bool differs = false;
  for (std::size_t i = 0; i < one.screens[0].sum.size(); ++i) {
    EXPECT_EQ(one.screens[0].sum[i], two.screens[0].sum[i]) << "bin " << i;
    EXPECT_EQ(one.screens[0].sum_sq[i], two.screens[0].sum_sq[i]) << "bin " << i;
    differs = differs || one.screens[0].sum[i] != other.screens[0].sum[i];
  }
  EXPECT_EQ(one.emitted, two.emitted);
  EXPECT_EQ(one.absorbed, two.absorbed);
  EXPECT_EQ(one.evanescent, two.evanescent);
  EXPECT_EQ(one.escaped, two.escaped);
  EXPECT_EQ(one.segments, two.segments);
  EXPECT_TRUE(differs) << "a different seed gave identical tallies";
}

// ---- Directions --------------------------------------------------------------------------------------------
// A pencil beam (window 2 µm wide) through a δ table lands in the single screen bin (101 × 101 bins of
// 0.1 mm, the prediction at the centre of the middle bin) that straight-line geometry predicts from the
// outgoing direction; the whole power must be in that bin (1e-9 relative). A direction wrong by more than
// 0.05 mm over the path to the screen (1e-4 rad for 0.5 m; 1e-3 rad for the mirror's 0.058 m) would move
// the beam to another bin.

namespace {

/// Traces a pencil beam from `start` along `dir` and returns the fraction of the power in the screen bin
/// centred on `expected_landing` (the screen is parallel to z = const).
double powerInPredictedBin(const dtr::Occluder& occ, const Vec3& start, const Vec3& dir, const Vec3& expected_landing,
                           double lambda) {
  dtr::Scene scene;
  scene.addOccluder(occ);
  diffray::receiver::Screen screen;
  screen.frame = frameAt(expected_landing);
  screen.half_x_m = screen.half_y_m = 101 * 0.5e-4;
  screen.nx = screen.ny = 101;
  scene.addScreen(screen);
  scene.build();
  dtr::CollimatedSource src;
  src.frame = dg::Frame::make(start, dir, Vec3(1, 0, 0));
  src.half_x_m = src.half_y_m = 1e-6;
  src.dir = dir;
  src.wavelength_m = lambda;
  dtr::TraceOptions opt;
  opt.rays = 2000;
  const dtr::TraceResult r = dtr::trace(scene, src, opt);
  return r.screens[0].sum[50 + 101 * 50] / src.power();
}

/// Where a ray from p along unit d meets the plane z = z_plane.
Vec3 onPlaneZ(const Vec3& p, const Vec3& d, double z_plane) { return p + ((z_plane - p.z()) / d.z()) * d; }

}  // namespace

TEST(TransportDirections, OpenRegionKeepsObliqueBeamDirection) {
  const double lambda = 1e-6;
  dtr::Occluder occ;
  occ.frame = dg::Frame::make(Vec3(0, 0, 0), Vec3(0.2, 0.1, 1.0), Vec3(1, 0.3, 0));  // tilted
  ASSERT_NEAR(occ.frame.ex.dot(occ.frame.ey), 0.0, 1e-15);
  ASSERT_NEAR(occ.frame.ex.cross(occ.frame.ey).dot(occ.frame.n), 1.0, 1e-15);
  occ.half_x_m = occ.half_y_m = 0.05;
  occ.table_x = deltaTable(-0.05, 0.05, 0.0);
  occ.table_y = deltaTable(-0.05, 0.05, 0.0);
  const Vec3 dir = Vec3(0.3, -0.2, 1.0).normalized();
  const Vec3 start = -0.1 / dir.z() * dir;  // passes through the origin
  EXPECT_NEAR(powerInPredictedBin(occ, start, dir, onPlaneZ(start, dir, 0.5), lambda), 1.0, 1e-9);
}

// Grating equation with a single diffraction line: u' = 0.25/λ along x and v' = 0.1/λ along y at incidence
// α_i = 0.2: the outgoing direction cosines are (0.45, 0.1, √(1 − 0.45² − 0.1²)).
TEST(TransportDirections, ShiftedLineObeysGratingEquation) {
  const double lambda = 1e-6;
  dtr::Occluder occ;
  occ.frame = frameAt(Vec3(0, 0, 0));
  occ.half_x_m = occ.half_y_m = 0.05;
  occ.table_x = deltaTable(-0.05, 0.05, 0.25 / lambda);
  occ.table_y = deltaTable(-0.05, 0.05, 0.1 / lambda);
  const Vec3 dir(0.2, 0.0, std::sqrt(1.0 - 0.04));
  const Vec3 start = -0.1 / dir.z() * dir;
  const Vec3 out(0.45, 0.1, std::sqrt(1.0 - 0.45 * 0.45 - 0.1 * 0.1));
  EXPECT_NEAR(powerInPredictedBin(occ, start, dir, onPlaneZ(Vec3(0, 0, 0), out, 0.5), lambda), 1.0, 1e-9);
}

// A reflecting occluder with u' = 0 is a mirror (paper eq. 9): incidence 30° from −z returns at 30° towards
// −z; the screen (z = −0.05, x > 0) lies beside the incident beam, not across it.
TEST(TransportDirections, ReflectingOccluderIsAMirror) {
  const double lambda = 1e-6, s = 0.5;
  dtr::Occluder occ;
  occ.frame = frameAt(Vec3(0, 0, 0));
  occ.half_x_m = occ.half_y_m = 0.05;
  occ.table_x = deltaTable(-0.05, 0.05, 0.0);
  occ.reflect = true;
  const Vec3 dir(s, 0.0, std::sqrt(1.0 - s * s));
  const Vec3 start = -0.1 / dir.z() * dir;
  const Vec3 out(s, 0.0, -std::sqrt(1.0 - s * s));
  EXPECT_NEAR(powerInPredictedBin(occ, start, dir, onPlaneZ(Vec3(0, 0, 0), out, -0.05), lambda), 1.0, 1e-9);
}
