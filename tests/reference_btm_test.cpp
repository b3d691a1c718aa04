// Oracles of the BTM edge-diffraction reference (reference/btm_edge.h):
// - the infinite thin plate (θ_w = 2π) against Macdonald's exact solution (reference/half_plane_point.h,
//   its own integral on a complex path: no shared code), at many angles, heights and two frequencies, and
//   within 1e-6 rad of the shadow and reflection boundaries;
// - a finite edge against a brute-force Simpson quadrature of the BTM integral written here (the plain
//   acosh/cosh form of the integrand, uniform panels);
// - reciprocity (source and receiver exchanged) on a right-angled wedge and on a finite edge;
// - continuity of the total field across the shadow and reflection boundaries of a right-angled wedge, and
//   the diffracted field's jump there equal to the geometric wave that switches;
// - the finite plate (reference/btm_plate.h): a 400 m square plate near the middle of one edge against
//   Macdonald's half-plane; reciprocity and continuity across an edge's shadow and reflection boundaries on
//   a 4 × 2 m plate, and the field exactly on such a boundary.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <vector>

#include "diffray/core/error.h"
#include "diffray/reference/btm_edge.h"
#include "diffray/reference/btm_plate.h"
#include "diffray/reference/btm_spectrum.h"
#include "diffray/reference/half_plane_point.h"
#include "quadrature_rules.h"

namespace {

namespace ref = diffray::reference;
using Complex = std::complex<double>;
constexpr double kPi = 3.14159265358979323846;
constexpr double kC = 343.0;

ref::CylindricalPoint point(double rho, double phi, double z) { return {rho, phi, z}; }

double freeField(const ref::CylindricalPoint& s, const ref::CylindricalPoint& r) {
  const double dx = r.rho_m * std::cos(r.phi_rad) - s.rho_m * std::cos(s.phi_rad);
  const double dy = r.rho_m * std::sin(r.phi_rad) - s.rho_m * std::sin(s.phi_rad);
  return 1.0 / std::sqrt(dx * dx + dy * dy + (r.z_m - s.z_m) * (r.z_m - s.z_m));
}

TEST(ReferenceBtm, InfinitePlateEqualsMacdonald) {
  const ref::CylindricalPoint s = point(1.5, 0.6, 0.3);
  double worst = 0.0;
  for (double f : {250.0, 1000.0}) {
    const double k = 2.0 * kPi * f / kC, lambda = kC / f;
    for (double rho : {0.7, 2.5})
      for (double z : {-0.4, 1.1})
        for (int i = 1; i < 62; ++i) {
          const ref::CylindricalPoint r = point(rho, 0.1 * i, z);
          const Complex btm = ref::btmInfiniteWedgeField(k, 2.0 * kPi, s, r);
          const Complex exact = ref::halfPlanePointSource(lambda, s, r, true);
          // Relative to the free field: both are exact, so the difference is quadrature, ~1e-11 measured
          // (both integrals' own error estimates are ~1e-12 relative); 1e-9 leaves a factor 100.
          const double err = std::abs(btm - exact) / freeField(s, r);
          worst = std::max(worst, err);
          EXPECT_LT(err, 1e-9) << "f " << f << " rho " << rho << " z " << z << " phi " << 0.1 * i;
        }
  }
  std::printf("worst |BTM − Macdonald| / free field: %.2e\n", worst);
}

TEST(ReferenceBtm, InfinitePlateEqualsMacdonaldNextToTheBoundaries) {
  const ref::CylindricalPoint s = point(1.2, 0.9, 0.0);
  const double f = 500.0, k = 2.0 * kPi * f / kC, lambda = kC / f;
  for (double boundary : {kPi - 0.9, kPi + 0.9})  // reflection and shadow boundaries
    for (double d : {-1e-3, -1e-6, -1e-8, 0.0, 1e-8, 1e-6, 1e-3}) {
      const ref::CylindricalPoint r = point(2.0, boundary + d, 0.5);
      const Complex btm = ref::btmInfiniteWedgeField(k, 2.0 * kPi, s, r);
      const Complex exact = ref::halfPlanePointSource(lambda, s, r, true);
      // ≤ 2.5e-11 measured; a boundary handled wrongly misses by 0.5.
      EXPECT_LT(std::abs(btm - exact) / freeField(s, r), 1e-9) << boundary << " " << d;
    }
}

// The BTM integrand written plainly (acosh, cosh), for the brute-force check below.
Complex plainIntegrand(double k, double nu, const ref::CylindricalPoint& s, const ref::CylindricalPoint& r, double z) {
  const double m = std::sqrt(s.rho_m * s.rho_m + (z - s.z_m) * (z - s.z_m));
  const double l = std::sqrt(r.rho_m * r.rho_m + (z - r.z_m) * (z - r.z_m));
  const double eta = std::acosh((m * l + (z - s.z_m) * (z - r.z_m)) / (s.rho_m * r.rho_m));
  double beta = 0.0;
  for (double a : {1.0, -1.0})
    for (double b : {1.0, -1.0}) {
      const double phi = kPi + a * s.phi_rad + b * r.phi_rad;
      beta += std::sin(nu * phi) / (std::cosh(nu * eta) - std::cos(nu * phi));
    }
  return -(nu / (4.0 * kPi)) * beta * std::polar(1.0 / (m * l), -k * (m + l));
}

TEST(ReferenceBtm, FiniteEdgeEqualsBruteForceQuadrature) {
  // A right-angled wedge (θ_w = 3π/2, ν = 2/3) with an edge from −0.5 to 0.8 m; receivers well away from
  // every boundary, so the integrand is smooth. Simpson on 200000 panels: error ~1e-12.
  ref::BtmWedge wedge;
  wedge.exterior_angle_rad = 1.5 * kPi;
  wedge.z_start_m = -0.5;
  wedge.z_end_m = 0.8;
  const double nu = 2.0 / 3.0, k = 2.0 * kPi * 700.0 / kC;
  const ref::CylindricalPoint s = point(1.1, 0.5, 0.2);
  for (const ref::CylindricalPoint& r : {point(0.9, 4.2, -0.3), point(2.0, 2.5, 1.5), point(0.6, 4.6, 0.1)}) {
    const auto re = [&](double z) { return plainIntegrand(k, nu, s, r, z).real(); };
    const auto im = [&](double z) { return plainIntegrand(k, nu, s, r, z).imag(); };
    const Complex brute(diffray::testing::simpson(re, -0.5, 0.8, 200000),
                        diffray::testing::simpson(im, -0.5, 0.8, 200000));
    const Complex btm = ref::btmEdgeDiffraction(k, wedge, s, r);
    EXPECT_LT(std::abs(btm - brute), 1e-9 * std::abs(brute) + 1e-12) << r.phi_rad;
  }
}

TEST(ReferenceBtm, Reciprocity) {
  const double k = 2.0 * kPi * 400.0 / kC;
  const ref::CylindricalPoint a = point(0.8, 0.4, -0.2), b = point(1.7, 4.0, 0.9);
  ref::BtmWedge infinite;
  infinite.exterior_angle_rad = 1.5 * kPi;
  ref::BtmWedge finite = infinite;
  finite.z_start_m = 0.1;
  finite.z_end_m = 2.0;  // the apex lies outside: the integral starts at an end
  for (const ref::BtmWedge& w : {infinite, finite}) {
    const Complex ab = ref::btmEdgeDiffraction(k, w, a, b), ba = ref::btmEdgeDiffraction(k, w, b, a);
    EXPECT_LT(std::abs(ab - ba), 1e-9 * std::abs(ab)) << w.z_start_m;
  }
}

TEST(ReferenceBtm, TotalFieldContinuousAcrossEveryBoundaryOfAWedge) {
  // θ_w = 3π/2. The direct wave's (shadow) boundary θ = π + θS, the reflection boundaries θ = π − θS (face
  // θ = 0) and 2θ_w − π − θS (face θ = θ_w), each where it lies inside the air: θS = 0.7 has the first two,
  // θS = 3.0 the last two.
  const double tw = 1.5 * kPi, k = 2.0 * kPi * 300.0 / kC;
  ref::BtmWedge wedge;
  wedge.exterior_angle_rad = tw;
  int boundaries = 0;
  for (double ts : {0.7, 3.0}) {
    const ref::CylindricalPoint s = point(1.3, ts, 0.0);
    for (double boundary : {kPi + ts, kPi - ts, 2.0 * tw - kPi - ts}) {
      if (!(boundary > 0.0 && boundary < tw)) continue;
      ++boundaries;
      const double d = 1e-7;
      const ref::CylindricalPoint below = point(1.9, boundary - d, 0.4), above = point(1.9, boundary + d, 0.4);
      const Complex u_below = ref::btmInfiniteWedgeField(k, tw, s, below);
      const Complex u_above = ref::btmInfiniteWedgeField(k, tw, s, above);
      // The field's change over 2e-7 rad at kρ ≈ 10 is ~1e-6 of its size; a missing half wave would be ~0.5.
      EXPECT_LT(std::abs(u_above - u_below), 1e-4 * std::abs(u_below)) << ts << " " << boundary;
      // The diffracted part alone jumps by the whole geometric wave that the boundary switches, which comes
      // from the source or from its image in the face the boundary belongs to.
      const Complex jump = ref::btmEdgeDiffraction(k, wedge, s, above) - ref::btmEdgeDiffraction(k, wedge, s, below);
      const double image = boundary == kPi + ts ? ts : boundary == kPi - ts ? -ts : 2.0 * tw - ts;
      const double r_geo = 1.0 / freeField(point(s.rho_m, image, s.z_m), below);
      EXPECT_NEAR(std::abs(jump) * r_geo, 1.0, 1e-4) << ts << " " << boundary;
    }
  }
  EXPECT_EQ(boundaries, 4);
}

TEST(ReferenceBtm, RejectsBadInput) {
  ref::BtmWedge w;
  const ref::CylindricalPoint s = point(1.0, 0.5, 0.0), r = point(1.0, 4.0, 0.0);
  EXPECT_THROW(ref::btmEdgeDiffraction(0.0, w, s, r), diffray::core::InputError);
  EXPECT_THROW(ref::btmEdgeDiffraction(1.0, w, point(0.0, 0.5, 0.0), r), diffray::core::InputError);
  w.exterior_angle_rad = 0.9 * kPi;
  EXPECT_THROW(ref::btmEdgeDiffraction(1.0, w, s, r), diffray::core::InputError);
  w.exterior_angle_rad = 1.5 * kPi;
  EXPECT_THROW(ref::btmEdgeDiffraction(1.0, w, s, point(1.0, 4.8, 0.0)), diffray::core::InputError);  // > 3π/2
  w.exterior_angle_rad = 2.0 * kPi;
  w.z_start_m = 1.0;
  w.z_end_m = 1.0;
  EXPECT_THROW(ref::btmEdgeDiffraction(1.0, w, s, r), diffray::core::InputError);
}

using diffray::core::Vec3;

Vec3 cartesian(const ref::CylindricalPoint& p) {
  return Vec3(p.rho_m * std::cos(p.phi_rad), p.rho_m * std::sin(p.phi_rad), p.z_m);
}

TEST(ReferenceBtmPlate, LargePlateNearAnEdgeTendsToMacdonald) {
  // The plate y = 0, x in [0, L], z in [−L/2, L/2]: near the middle of its edge x = 0 it tends to the
  // half-plane of half_plane_point.h as L grows. What differs is the other three edges, L/2 to L away,
  // whose diffracted waves fall as L^{−3/2} (β ~ 1/L at the far edges, 1/(ml) ~ 1/L², and a stationary
  // stretch ~√(λL)): measured 1.1e-3, 1.3e-4, 1.7e-5 of the free field at L = 100, 400, 1600 m.
  const ref::CylindricalPoint s = point(1.5, 0.6, 0.3);
  const double f = 500.0, k = 2.0 * kPi * f / kC, lambda = kC / f;
  std::vector<double> worst;
  for (double L : {400.0, 1600.0}) {
    ref::BtmPlate plate;
    plate.vertices = {Vec3(0, 0, -0.5 * L), Vec3(0, 0, 0.5 * L), Vec3(L, 0, 0.5 * L), Vec3(L, 0, -0.5 * L)};
    double w = 0.0;
    for (double phi : {0.3, 1.0, 2.0, 3.0, 3.6, 4.0, 4.5, 5.5, 6.1})
      for (double z : {-0.5, 0.8}) {
        const ref::CylindricalPoint r = point(2.2, phi, z);
        const Complex plate_u = ref::btmPlateField(k, plate, cartesian(s), cartesian(r), 1).total();
        const Complex exact = ref::halfPlanePointSource(lambda, s, r, true);
        w = std::max(w, std::abs(plate_u - exact) / freeField(s, r));
      }
    worst.push_back(w);
    std::printf("L = %g m: worst |plate − Macdonald| / free field %.2e\n", L, w);
  }
  EXPECT_LT(worst[1], 5e-5);
  // L^{−3/2}: a factor 8 from 400 to 1600 m; a wrong frame or zone would not shrink with L.
  EXPECT_GT(worst[0] / worst[1], 5.0);
}

ref::BtmPlate plate4x2() {
  ref::BtmPlate plate;  // the 4 × 2 m plate x = 0, y in [−2, 2], z in [0, 2]
  plate.vertices = {Vec3(0, -2, 0), Vec3(0, 2, 0), Vec3(0, 2, 2), Vec3(0, -2, 2)};
  return plate;
}

TEST(ReferenceBtmPlate, Reciprocity) {
  const ref::BtmPlate plate = plate4x2();
  const double k = 2.0 * kPi * 250.0 / kC;
  const Vec3 a(-2.0, 0.3, 0.5), b(2.0, -0.7, 1.2), c(-1.0, 3.0, 2.5);
  for (const auto& [p, q] : {std::pair{a, b}, std::pair{a, c}, std::pair{b, c}}) {
    const ref::BtmPlateField pq = ref::btmPlateField(k, plate, p, q, 1), qp = ref::btmPlateField(k, plate, q, p, 1);
    EXPECT_LT(std::abs(pq.total() - qp.total()), 1e-9 * std::abs(pq.total()));
  }
  // Second order: the sum over ordered pairs of edges is reciprocal as a whole (pair (i, j) from S to R is
  // pair (j, i) from R to S), with the two integrals nested the other way round: 4e-13 measured, so the
  // quadrature resolves the corners the adjacent edges share.
  const Complex ab = ref::btmPlateField(k, plate, a, b, 2).second_order, ba = ref::btmPlateField(k, plate, b, a, 2).second_order;
  EXPECT_LT(std::abs(ab - ba), 1e-9 * std::abs(ab));
}

TEST(ReferenceBtmPlate, ContinuousAcrossAnEdgesShadowAndReflectionBoundaries) {
  // Source in front of the 4 × 2 m plate; receivers cross the plane through the top edge (z = 2) and the
  // source, behind the plate (the shadow boundary) and in front (the reflection boundary, through the
  // image), at y = 0.2, far from the corners.
  const ref::BtmPlate plate = plate4x2();
  const double k = 2.0 * kPi * 250.0 / kC;
  const Vec3 s(-2.0, 0.2, 0.5);
  for (const Vec3& from : {s, Vec3(2.0, 0.2, 0.5)}) {  // the source, its image in the plate x = 0
    const Vec3 edge(0.0, 0.2, 2.0), dir = (edge - from).normalized();
    const Vec3 on = edge + 2.0 * dir;  // 2 m past the edge on the boundary
    const Vec3 up(-dir.z(), 0.0, dir.x());  // across the boundary, in the plane y = 0.2
    const double d = 1e-7;
    const ref::BtmPlateField lo = ref::btmPlateField(k, plate, s, on - d * up, 1);
    const ref::BtmPlateField hi = ref::btmPlateField(k, plate, s, on + d * up, 1);
    // The geometric part switches on one side only; the sum does not jump (a missing half wave: ~0.5).
    EXPECT_GT(std::abs((hi.direct + hi.specular) - (lo.direct + lo.specular)), 0.1);
    EXPECT_LT(std::abs(hi.total() - lo.total()), 1e-4 * std::abs(lo.total())) << from.x();
  }
}

TEST(ReferenceBtmPlate, ExactlyOnAnEdgesBoundaryTheFieldIsItsLimitFromEitherSide) {
  // Receivers exactly on the top edge's shadow boundary (2 m past the edge on the line from the source
  // through it) and on its reflection boundary (the same from the source's image): the edge's term is
  // dropped there and the wave it switches counts half, so the field is the limit from either side, one
  // frequency at a time and in a spectrum. Without the half wave the shadow point reads the far edges only
  // (about −20 dB re the half wave at 2 kHz).
  const ref::BtmPlate plate = plate4x2();
  const Vec3 s(-2.0, 0.2, 0.5);
  for (const Vec3& on : {Vec3(2.0, 0.2, 3.5), Vec3(-2.0, 0.2, 3.5)}) {  // through the edge (0, 0.2, 2)
    const Vec3 across(-0.6, 0.0, 0.8);  // in the plane y = 0.2, through both boundaries
    for (const double f : {250.0, 2000.0}) {
      const double k = 2.0 * kPi * f / kC, d = 1e-7;
      const Complex lo = ref::btmPlateField(k, plate, s, on - d * across, 2).total();
      const Complex hi = ref::btmPlateField(k, plate, s, on + d * across, 2).total();
      const Complex at = ref::btmPlateField(k, plate, s, on, 2).total();
      const Complex spectrum = ref::btmPlateSpectrum({k}, plate, std::nan(""), s, on, 2)[0].total();
      EXPECT_LT(std::abs(hi - lo), 1e-4 * std::abs(lo)) << on.transpose() << " " << f;
      EXPECT_LT(std::abs(at - lo), 1e-4 * std::abs(lo)) << on.transpose() << " " << f;
      EXPECT_LT(std::abs(spectrum - lo), 1e-4 * std::abs(lo)) << on.transpose() << " " << f;
    }
  }
}

TEST(ReferenceBtmPlate, SecondOrderTakesBackTheJumpBeyondThePlate) {
  // Each edge's first-order term treats the plate as a half-plane without end, so it jumps where the
  // receiver crosses the plate's plane beyond the plate (above the top edge, beside a side edge, past a
  // corner). The edge-to-edge terms jump there by the opposite amount, up to what third order would take
  // back: at 250 Hz the jump falls from 0.079–0.124 to 0.006–0.015 (a factor 5.6–20) at these three points
  // (at 1 kHz, above the top edge, from 0.106 to 0.003). A second order with the wrong factor leaves
  // 0.10–0.11 (no ½ for the path along the plate) or 0.034–0.065 (one face of the two, a factor ≤ 2.5):
  // a factor 4 tells them apart.
  const ref::BtmPlate plate = plate4x2();
  const double k = 2.0 * kPi * 250.0 / kC, d = 1e-5;
  const Vec3 s(-2.0, 0.2, 0.5);
  for (const Vec3& on : {Vec3(0, 0.2, 2.5), Vec3(0, 2.6, 1.0), Vec3(0, 2.5, 2.5)}) {
    const ref::BtmPlateField front = ref::btmPlateField(k, plate, s, on - Vec3(d, 0, 0));
    const ref::BtmPlateField back = ref::btmPlateField(k, plate, s, on + Vec3(d, 0, 0));
    const Complex first_front = front.total() - front.second_order, first_back = back.total() - back.second_order;
    const double jump1 = std::abs(first_back - first_front), jump2 = std::abs(back.total() - front.total());
    EXPECT_GT(jump1, 0.15 * std::abs(front.total())) << on.transpose();
    EXPECT_LT(jump2, jump1 / 4.0) << on.transpose();
  }
}

TEST(ReferenceBtmPlate, OnAGroundTendsToTwoHalfPlanesNearTheTopOfALargePlate) {
  // A plate x = 0, y in [−L, L], z in [0, H = L/2] standing on the rigid ground z = 0: the ground is the
  // source's image S' and the plate's mirror (image principle). Near the middle of its top edge the field
  // tends to the half-plane's for S plus the half-plane's for S' (Macdonald, the edge at z = H): both
  // waves cross the same top edge. What differs falls as 1/L: S' sits 0.8 m from the union's bottom edge
  // (z = −H), whose wave reaches the receiver over about 2H (measured: 4.1e-3, 1.0e-3, 2.6e-4 of the free
  // field at L = 100, 400, 1600 m; the free plate's far edges alone fall as L^{−3/2}).
  const double f = 500.0, k = 2.0 * kPi * f / kC, lambda = kC / f;
  std::vector<double> worst;
  for (double L : {400.0, 1600.0}) {
    const double H = 0.5 * L;
    ref::BtmPlate plate;
    plate.vertices = {Vec3(0, -L, 0), Vec3(0, L, 0), Vec3(0, L, H), Vec3(0, -L, H)};
    const Vec3 s(-1.5, 0.3, H - 0.8), s_image(s.x(), s.y(), -s.z());
    // The half-plane frame of the top edge: edge along +y at z = H, the screen below it (x = 0, z < H).
    const auto frame = [&](const Vec3& p) { return ref::halfPlaneFrameFromCartesian(H - p.z(), p.x(), p.y()); };
    double w = 0.0;
    for (const Vec3& r : {Vec3(2.0, 0.0, H - 1.0), Vec3(1.0, -0.5, H + 1.5), Vec3(-2.0, 0.4, H + 0.7)}) {
      const Complex u = ref::btmPlateOnGroundField(k, plate, 0.0, s, r, 1).total();
      const Complex half_planes = ref::halfPlanePointSource(lambda, frame(s), frame(r), true) +
                                  ref::halfPlanePointSource(lambda, frame(s_image), frame(r), true);
      w = std::max(w, std::abs(u - half_planes) / freeField(frame(s), frame(r)));
    }
    worst.push_back(w);
    std::printf("plate on ground, L = %g m, vs two half-planes: worst %.2e of the free field\n", L, w);
  }
  EXPECT_LT(worst[1], 5e-4);
  EXPECT_GT(worst[0] / worst[1], 3.0);  // 1/L: a factor 4 (a wrong image or union would not shrink)
  // Refused: a plate off the ground, or a source below it.
  ref::BtmPlate lifted;
  lifted.vertices = {Vec3(0, -2, 1), Vec3(0, 2, 1), Vec3(0, 2, 3), Vec3(0, -2, 3)};
  EXPECT_THROW(ref::btmPlateOnGroundField(k, lifted, 0.0, Vec3(-1, 0, 1), Vec3(2, 0, 1), 1), diffray::core::InputError);
  EXPECT_THROW(ref::btmPlateOnGroundField(k, plate4x2(), 0.0, Vec3(-1, 0, -1), Vec3(2, 0, 1), 1), diffray::core::InputError);
}

TEST(ReferenceBtmPlate, BandLevelIsTheEnergyMeanOfItsFrequencies) {
  // The band level against the mean of |u·R|² computed here at the band grid's midpoints.
  const ref::BtmPlate plate = plate4x2();
  const Vec3 s(-2.0, 0.2, 0.5), r(2.0, -0.4, 1.1);
  const double lo = 177.0, hi = 355.0, c = 343.0;
  double mean = 0.0;
  for (int j = 0; j < 3; ++j) {
    const double hz = lo + (j + 0.5) * (hi - lo) / 3.0;
    mean += std::norm(ref::btmPlateField(2.0 * kPi * hz / c, plate, s, r, 1).total() * (r - s).norm()) / 3.0;
  }
  // The band level sums the spectrum (btm_spectrum.h: ~1e-13 of the free field from one frequency at a
  // time), so 1e-9 dB.
  EXPECT_NEAR(ref::btmPlateBandLevelDb(lo, hi, 3, c, plate, std::nan(""), s, r, 1), 10.0 * std::log10(mean), 1e-9);
}

}  // namespace
