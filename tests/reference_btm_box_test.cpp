// Oracles of the rigid box's BTM reference (reference/btm_box.h). Each shares with the box no code but the
// BTM kernel (btm_edge.h, itself checked against Macdonald's exact half-plane and a brute-force quadrature
// in reference_btm_test.cpp):
// - a very large box near the middle of one edge against the infinite right-angled wedge
//   (btmInfiniteWedgeField, θ_w = 3π/2, its zones written there), the difference shrinking as the box grows;
// - reciprocity (source and receiver exchanged), first and second order, also with a point 1e-4 m from a
//   face's plane (the second order's sharpest integrand) and on a ground;
// - the first-order sum continuous across the shadow and reflection boundaries of an edge away from the
//   corners; where the receiver stops seeing an edge, the second order taking back most of the first
//   order's jump;
// - on a rigid ground, a large box near its top edge against the wedges of the source and of its image;
// - the spectrum (many frequencies from one set of nodes) equal to the field one frequency at a time, the
//   same on one thread as on all; bad input refused.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <vector>

#include "diffray/core/error.h"
#include "diffray/core/parallel.h"
#include "diffray/reference/btm_box.h"
#include "diffray/reference/btm_edge.h"

namespace {

namespace ref = diffray::reference;
using Complex = std::complex<double>;
using diffray::core::Vec3;
constexpr double kPi = 3.14159265358979323846;
constexpr double kC = 343.0;

double wavenumber(double hz) { return 2.0 * kPi * hz / kC; }

ref::BtmBox cupboard() { return {Vec3(0, 0, 0), Vec3(1.2, 0.6, 1.8)}; }  // 1.2 × 0.6 × 1.8 m

// A point of a wedge's cylindrical frame in Cartesian coordinates: the edge on the z axis, θ = 0 along +x.
Vec3 cartesian(const ref::CylindricalPoint& p) {
  return Vec3(p.rho_m * std::cos(p.phi_rad), p.rho_m * std::sin(p.phi_rad), p.z_m);
}

TEST(ReferenceBtmBox, LargeBoxNearAnEdgeTendsToTheRightAngledWedge) {
  // The box x in [0, L], y in [−L, 0], z in [−L/2, L/2]: its edge on the z axis is the wedge of exterior
  // angle 3π/2 with the face θ = 0 along +x (the face y = 0) and θ = 3π/2 along −y (the face x = 0). Near
  // the middle of that edge the box tends to the infinite wedge as L grows; what differs is the other
  // edges, L/2 to L away, whose waves fall as about L^{−3/2} (β = O(1) at a far edge of a face both points
  // see, 1/(m·l) ~ 1/L², a stationary stretch ~ √(λL)). Measured at 500 Hz: 4.6e-4, 9.4e-5, 1.0e-5 of the
  // free field at L = 100, 400, 1600 m (a factor 4.9 and 9.4 per fourfold L: the far edges' waves
  // interfere). Receivers at θ > π see no far edge that the source sees: there the two agree to 2e-9.
  const ref::CylindricalPoint s{1.5, 0.6, 0.3};
  const double k = wavenumber(500.0), tw = 1.5 * kPi;
  std::vector<double> worst;
  for (double L : {100.0, 400.0, 1600.0}) {
    const ref::BtmBox box{Vec3(0, -L, -0.5 * L), Vec3(L, 0, 0.5 * L)};
    double w = 0.0;
    for (double phi : {0.3, 1.0, 2.0, 3.0, 3.6, 4.0, 4.5})
      for (double z : {-0.5, 0.8}) {
        const ref::CylindricalPoint r{2.2, phi, z};
        const Complex box_u = ref::btmBoxField(k, box, cartesian(s), cartesian(r), 1).total();
        const Complex wedge_u = ref::btmInfiniteWedgeField(k, tw, s, r);
        w = std::max(w, std::abs(box_u - wedge_u) * (cartesian(r) - cartesian(s)).norm());
      }
    worst.push_back(w);
    std::printf("L = %g m: worst |box − wedge| / free field %.2e\n", L, w);
  }
  EXPECT_LT(worst[2], 5e-5);
  // A wrong frame, zone or visibility would not shrink with L.
  EXPECT_GT(worst[1] / worst[2], 5.0);
}

TEST(ReferenceBtmBox, Reciprocity) {
  // Each first-order term is reciprocal by itself; the second order as a whole (pair (i, j) from S to R is
  // pair (j, i) from R to S, its two integrals nested the other way round, so the quadrature must resolve
  // the sharp parts of both). Measured at 250 Hz: first order ≤ 5e-16 of the free field, second order
  // ≤ 2e-13 (4e-12 of itself), also with the source 1e-4 m above the top face's plane, where β of the top's
  // edges peaks 1e-4 rad wide; on the ground 3e-13.
  const ref::BtmBox box = cupboard();
  const double k = wavenumber(250.0);
  const Vec3 a(-0.8, 0.3, 0.5), b(2.0, 1.4, 1.2), c(0.5, -1.0, 2.4), near_top(0.4, -1.0, 1.8 + 1e-4);
  for (const auto& [p, q] : {std::pair{a, b}, std::pair{b, c}, std::pair{near_top, b}}) {
    const ref::BtmBoxField pq = ref::btmBoxField(k, box, p, q), qp = ref::btmBoxField(k, box, q, p);
    const double free = 1.0 / (q - p).norm();
    EXPECT_GT(std::abs(pq.second_order), 0.05 * free);  // a term there is to compare
    EXPECT_LT(std::abs(pq.diffracted - qp.diffracted), 1e-9 * std::abs(pq.diffracted)) << p.transpose();
    EXPECT_LT(std::abs(pq.second_order - qp.second_order), 1e-9 * std::abs(pq.second_order)) << p.transpose();
    std::printf("reciprocity %s: first %.1e, second %.1e of the free field\n", p == near_top ? "near the top" : "",
                std::abs(pq.diffracted - qp.diffracted) / free, std::abs(pq.second_order - qp.second_order) / free);
  }
  const ref::BtmBoxField ac = ref::btmBoxOnGroundField(k, box, 0.0, a, c);
  const ref::BtmBoxField ca = ref::btmBoxOnGroundField(k, box, 0.0, c, a);
  const double ground_error = std::abs(ac.total() - ca.total()) * (c - a).norm();
  EXPECT_LT(ground_error, 1e-9);
  std::printf("reciprocity on the ground: %.1e of the free field\n", ground_error);
}

TEST(ReferenceBtmBox, ContinuousAcrossAnEdgesShadowAndReflectionBoundaries) {
  // The top front edge (y = 0, z = 1.8) at x = 0.45, away from the corners. A source in front below the top
  // has its shadow boundary behind the edge (the direct wave switches) and its front face's reflection
  // boundary (through its image in y = 0); a source in front above the top has the top face's and the
  // front face's reflection boundaries. Receivers 2 m past the edge on each, 1e-7 m to either side.
  const ref::BtmBox box = cupboard();
  const double k = wavenumber(250.0), d = 1e-7;
  const Vec3 edge(0.45, 0.0, 1.8);
  const Vec3 low(0.45, -1.5, 0.7), high(0.45, -0.5, 2.6);
  const auto front_image = [](const Vec3& p) { return Vec3(p.x(), -p.y(), p.z()); };
  const auto top_image = [](const Vec3& p) { return Vec3(p.x(), p.y(), 3.6 - p.z()); };
  const std::pair<Vec3, Vec3> cases[] = {
      {low, low}, {low, front_image(low)}, {high, top_image(high)}, {high, front_image(high)}};
  for (const auto& [s, from] : cases) {  // the source, and the source or image whose wave switches
    const Vec3 dir = (edge - from).normalized();
    const Vec3 on = edge + 2.0 * dir, across(0.0, -dir.z(), dir.y());  // in the plane x = 0.45
    const ref::BtmBoxField lo = ref::btmBoxField(k, box, s, on - d * across, 1);
    const ref::BtmBoxField hi = ref::btmBoxField(k, box, s, on + d * across, 1);
    // The geometric wave switches on one side only (its size 1/r); the sum does not jump (a missing half
    // wave would be ~0.5/r; the field's change over 2e-7 m is ~1e-6 of it: measured 1e-7 to 6e-7).
    const double r_geo = (on - from).norm();
    EXPECT_GT(std::abs((hi.direct + hi.specular) - (lo.direct + lo.specular)) * r_geo, 0.9) << from.transpose();
    EXPECT_LT(std::abs(hi.total() - lo.total()), 1e-4 * std::abs(lo.total())) << from.transpose();
    std::printf("across a boundary: the geometric part jumps %.3f, the sum %.1e of the field\n",
                std::abs((hi.direct + hi.specular) - (lo.direct + lo.specular)) * r_geo,
                std::abs(hi.total() - lo.total()) / std::abs(lo.total()));
  }
}

TEST(ReferenceBtmBox, SecondOrderTakesBackTheJumpWhereAnEdgeHides) {
  // Each first-order term treats its wedge as one without end, so it jumps where the receiver crosses one of
  // the edge's face planes beyond the box and stops seeing the edge. The edge-to-edge terms along that face
  // jump there by the opposite amount (β of their second edge has its boundary there), up to what third
  // order would take back. The source in front; receivers crossing the top face's plane behind the box, the
  // right face's plane behind it, the front face's plane beside it (three edges hide at once), and the top
  // face's plane behind and beside it. Measured at 250 Hz: the jump falls from 0.21–0.77 to 0.016–0.11 of
  // the free field (a factor 5.8–13). A second order without the ½ of a path along a plane leaves 0.20–0.89
  // (a factor 0.9–1.4), one with the shared face's azimuths swapped 0.31–0.78 (0.7–1.0): a factor 4 tells
  // them apart. What remains is the jump of the edge-to-edge terms whose second edge the receiver stops
  // seeing at the same plane (at the first point the pair along the top cancels the front edge's jump to
  // 1e-5 of the free field, and the pairs into the top's side edges leave 0.11; at 1 kHz 0.41 falls to 0.13
  // the same way): third order would take those back.
  const ref::BtmBox box = cupboard();
  const double k = wavenumber(250.0), d = 1e-5;
  const Vec3 s(0.45, -1.5, 0.7);
  const std::pair<Vec3, Vec3> crossings[] = {{Vec3(0.45, 1.1, 1.8), Vec3::UnitZ()},
                                             {Vec3(1.2, 1.1, 0.9), Vec3::UnitX()},
                                             {Vec3(1.7, 0.0, 0.9), Vec3::UnitY()},
                                             {Vec3(1.7, 1.1, 1.8), Vec3::UnitZ()}};
  for (const auto& [on, across] : crossings) {
    const ref::BtmBoxField a = ref::btmBoxField(k, box, s, on - d * across);
    const ref::BtmBoxField b = ref::btmBoxField(k, box, s, on + d * across);
    const double jump1 = std::abs((b.total() - b.second_order) - (a.total() - a.second_order));
    const double jump2 = std::abs(b.total() - a.total()), free = 1.0 / (on - s).norm();
    std::printf("crossing at (%g, %g, %g): first-order jump %.3f, with second order %.4f of the free field\n",
                on.x(), on.y(), on.z(), jump1 / free, jump2 / free);
    EXPECT_GT(jump1, 0.1 * std::abs(a.total())) << on.transpose();
    EXPECT_LT(jump2, jump1 / 4.0) << on.transpose();
  }
}

TEST(ReferenceBtmBox, OnAGroundTendsToTwoWedgesNearTheTopOfALargeBox) {
  // A box x in [0, L], y in [−L, L], z in [0, H = L/2] standing on the rigid ground z = 0 (image principle:
  // the source's image S' and the box's mirror). Near the middle of its top edge (x = 0, z = H) the field
  // tends to the right-angled wedge's for S plus the wedge's for S' (both cross the same top edge). What
  // differs falls as 1/L: S' sits 0.8 m from the mirror's bottom edge (z = −H), whose wave reaches the
  // receiver over about 2H. Measured at 500 Hz: 1.8e-3, 3.5e-4, 9.1e-5 of the free field at L = 100, 400,
  // 1600 m; receivers behind the top see no such edge (3e-9 there).
  const double k = wavenumber(500.0), tw = 1.5 * kPi;
  std::vector<double> worst;
  for (double L : {400.0, 1600.0}) {
    const double H = 0.5 * L;
    const ref::BtmBox box{Vec3(0, -L, 0), Vec3(L, L, H)};
    const Vec3 s(-1.5, 0.3, H - 0.8), s_image(s.x(), s.y(), -s.z());
    // The top edge's wedge frame: θ = 0 along +x (the top face), the air above it (+z), the edge along −y.
    const auto frame = [&](const Vec3& p) {
      double theta = std::atan2(p.z() - H, p.x());
      if (theta < 0.0) theta += 2.0 * kPi;
      return ref::CylindricalPoint{std::hypot(p.x(), p.z() - H), theta, -p.y()};
    };
    double w = 0.0;
    for (const Vec3& r : {Vec3(2.0, 0.0, H + 1.0), Vec3(-2.0, 0.4, H + 0.7), Vec3(-1.0, 0.2, H - 1.5),
                          Vec3(-0.5, -0.3, H + 0.2)}) {
      const Complex u = ref::btmBoxOnGroundField(k, box, 0.0, s, r, 1).total();
      const Complex wedges = ref::btmInfiniteWedgeField(k, tw, frame(s), frame(r)) +
                             ref::btmInfiniteWedgeField(k, tw, frame(s_image), frame(r));
      w = std::max(w, std::abs(u - wedges) * (r - s).norm());
    }
    worst.push_back(w);
    std::printf("box on ground, L = %g m, vs two wedges: worst %.2e of the free field\n", L, w);
  }
  EXPECT_LT(worst[1], 3e-4);
  EXPECT_GT(worst[0] / worst[1], 2.5);  // 1/L: a factor 4 (a wrong image or union would not shrink)
}

TEST(ReferenceBtmBox, RejectsBadInput) {
  using diffray::core::InputError;
  const ref::BtmBox box = cupboard();
  const Vec3 s(-1.0, 0.3, 0.5), r(2.0, 0.3, 1.0);
  const double nan = std::nan("");
  EXPECT_THROW(ref::btmBoxField(0.0, box, s, r), InputError);
  EXPECT_THROW(ref::btmBoxField(nan, box, s, r), InputError);
  EXPECT_THROW(ref::btmBoxField(1.0, box, s, r, 3), InputError);
  EXPECT_THROW(ref::btmBoxField(1.0, box, Vec3(nan, 0, 0), r), InputError);
  EXPECT_THROW(ref::btmBoxField(1.0, ref::BtmBox{Vec3(0, 0, 0), Vec3(1, 0, 1)}, s, r), InputError);  // flat
  EXPECT_THROW(ref::btmBoxField(1.0, ref::BtmBox{Vec3(0, 0, 0), Vec3(1, -1, 1)}, s, r), InputError);  // inverted
  EXPECT_THROW(ref::btmBoxField(1.0, ref::BtmBox{Vec3(0, 0, 0), Vec3(1, nan, 1)}, s, r), InputError);
  EXPECT_THROW(ref::btmBoxField(1.0, box, Vec3(0.6, 0.3, 0.9), r), InputError);  // inside
  EXPECT_THROW(ref::btmBoxField(1.0, box, s, Vec3(1.2, 0.3, 0.9)), InputError);  // on a face
  EXPECT_THROW(ref::btmBoxField(1.0, box, s, Vec3(1.2, 0.6, 1.8)), InputError);  // on a corner
  EXPECT_THROW(ref::btmBoxOnGroundField(1.0, box, 0.5, s, r), InputError);       // not standing on it
  EXPECT_THROW(ref::btmBoxOnGroundField(1.0, box, nan, s, r), InputError);
  EXPECT_THROW(ref::btmBoxOnGroundField(1.0, box, 0.0, Vec3(-1.0, 0.3, -0.5), r), InputError);  // below
  EXPECT_THROW(ref::btmBoxSpectrum({}, box, 0.0, s, r), InputError);
  EXPECT_THROW(ref::btmBoxSpectrum({1.0, -2.0}, box, 0.0, s, r), InputError);
  EXPECT_THROW(ref::btmBoxSpectrum({1.0}, box, 0.0, s, Vec3(0.6, 0.3, 0.9)), InputError);
}

// The spectrum (btm_box.h, btm_spectrum.h's gridding) against the field one frequency at a time.
ref::BtmBox smallBox() { return {Vec3(0, 0, 0), Vec3(0.5, 0.3, 0.4)}; }

TEST(ReferenceBtmBoxSpectrum, EqualsTheFieldOneFrequencyAtATime) {
  // The spectrum builds its nodes for its highest frequency (panels up to two of its wavelengths) and sums
  // them on a path-length grid; one frequency at a time builds them for that frequency (panels up to half
  // a wavelength) and sums them directly. Both quadratures are converged and the grid's error is ~1e-13 of
  // Σ|a|: measured ≤ 1.3e-12 of the free field here (the box's nodes are many more than the plate's), so
  // 1e-10 fails on any misplaced node, weight or phase while leaving the rounding a factor 75.
  const ref::BtmBox box = smallBox();
  const std::vector<double> hz{125.0, 1500.0};
  std::vector<double> k;
  for (double f : hz) k.push_back(wavenumber(f));
  const Vec3 s(-0.6, 0.1, 0.2), r(1.0, 0.2, 0.6);  // beside the box, and beyond it above the top
  double worst = 0.0;
  for (int order : {1, 2})
    for (double ground : {std::nan(""), 0.0}) {
      const std::vector<ref::BtmBoxField> spectrum = ref::btmBoxSpectrum(k, box, ground, s, r, order);
      ASSERT_EQ(spectrum.size(), k.size());
      for (std::size_t i = 0; i < k.size(); ++i) {
        const ref::BtmBoxField one = std::isnan(ground) ? ref::btmBoxField(k[i], box, s, r, order)
                                                        : ref::btmBoxOnGroundField(k[i], box, ground, s, r, order);
        const double free = 1.0 / (r - s).norm();
        EXPECT_EQ(spectrum[i].direct, one.direct);
        EXPECT_EQ(spectrum[i].specular, one.specular);
        const double d1 = std::abs(spectrum[i].diffracted - one.diffracted) / free;
        const double d2 = std::abs(spectrum[i].second_order - one.second_order) / free;
        worst = std::max({worst, d1, d2});
        EXPECT_LT(d1, 1e-10) << hz[i] << " Hz, order " << order << ", ground " << ground;
        EXPECT_LT(d2, 1e-10) << hz[i] << " Hz, order " << order << ", ground " << ground;
        EXPECT_GT(std::abs(one.diffracted), 1e-3 * free);  // terms there are to compare
        if (order == 2) {
          EXPECT_GT(std::abs(one.second_order), 1e-3 * free);
        }
      }
    }
  std::printf("worst |box spectrum − one frequency at a time| / free field: %.2e\n", worst);
}

TEST(ReferenceBtmBoxSpectrum, SameNumbersOnOneThreadAsOnAll) {
  std::vector<double> k{wavenumber(200.0), wavenumber(900.0)};
  const Vec3 s(-0.6, 0.1, 0.2), r(1.0, 0.2, 0.3);
  std::vector<ref::BtmBoxField> one;
  {
    diffray::core::ThreadLimit limit(1);
    one = ref::btmBoxSpectrum(k, smallBox(), 0.0, s, r, 2);
  }
  const std::vector<ref::BtmBoxField> all = ref::btmBoxSpectrum(k, smallBox(), 0.0, s, r, 2);
  for (std::size_t i = 0; i < k.size(); ++i) {
    EXPECT_EQ(one[i].diffracted, all[i].diffracted);
    EXPECT_EQ(one[i].second_order, all[i].second_order);
  }
}

}  // namespace
