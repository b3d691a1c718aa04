// The thin plate's field at many frequencies at once (reference/btm_spectrum.h):
// - equal to the field one frequency at a time (btm_plate.h, itself checked against Macdonald's half-plane,
//   reciprocity and continuity in reference_btm_test.cpp), free and on a ground, first and second order;
// - on its own against Macdonald's exact half-plane (reference/half_plane_point.h, no shared code): a large
//   plate near the middle of one edge, at several frequencies from one call;
// - the same numbers on one thread as on all.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <complex>
#include <vector>

#include "diffray/core/error.h"
#include "diffray/core/parallel.h"
#include "diffray/reference/btm_plate.h"
#include "diffray/reference/btm_spectrum.h"
#include "diffray/reference/half_plane_point.h"

namespace {

namespace ref = diffray::reference;
using Complex = std::complex<double>;
using diffray::core::Vec3;
constexpr double kPi = 3.14159265358979323846;
constexpr double kC = 343.0;

std::vector<double> wavenumbers(const std::vector<double>& hz) {
  std::vector<double> k;
  for (double f : hz) k.push_back(2.0 * kPi * f / kC);
  return k;
}

ref::BtmPlate smallPlate() {  // 1 × 0.5 m in the plane x = 0, its foot on z = 0
  ref::BtmPlate plate;
  plate.vertices = {Vec3(0, -0.5, 0), Vec3(0, 0.5, 0), Vec3(0, 0.5, 0.5), Vec3(0, -0.5, 0.5)};
  return plate;
}

TEST(ReferenceBtmSpectrum, EqualsTheFieldOneFrequencyAtATime) {
  // The spectrum's nodes are built for its highest frequency (panels up to two of its wavelengths) and
  // summed on a path-length grid; one frequency at a time builds them for that frequency (panels up to half
  // a wavelength) and sums them directly. Both quadratures are converged, and
  // the grid's error is ~1e-13 of Σ|a| (btm_spectrum.h): measured ≤ 1e-13 of the free field here, so
  // 1e-10 fails on any misplaced node, weight or phase while leaving the rounding a factor 1000.
  const ref::BtmPlate plate = smallPlate();
  const std::vector<double> hz{125.0, 700.0, 1500.0};
  const std::vector<double> k = wavenumbers(hz);
  const Vec3 s(-1.0, 0.1, 0.2);
  double worst = 0.0;
  for (const Vec3& r : {Vec3(1.0, -0.2, 0.3), Vec3(0.8, 0.7, 0.6), Vec3(-0.6, 0.3, 0.9)})
    for (int order : {1, 2})
      for (double ground : {std::nan(""), 0.0}) {
        const std::vector<ref::BtmPlateField> spectrum = ref::btmPlateSpectrum(k, plate, ground, s, r, order);
        ASSERT_EQ(spectrum.size(), k.size());
        for (std::size_t i = 0; i < k.size(); ++i) {
          const ref::BtmPlateField one = std::isnan(ground) ? ref::btmPlateField(k[i], plate, s, r, order)
                                                            : ref::btmPlateOnGroundField(k[i], plate, ground, s, r, order);
          const double free = 1.0 / (r - s).norm();
          EXPECT_EQ(spectrum[i].direct, one.direct);
          EXPECT_EQ(spectrum[i].specular, one.specular);
          // And the spectrum of this frequency alone (its nodes built for it: the longest panels).
          const ref::BtmPlateField alone = ref::btmPlateSpectrum({k[i]}, plate, ground, s, r, order)[0];
          const double d1 = std::max(std::abs(spectrum[i].diffracted - one.diffracted),
                                     std::abs(alone.diffracted - one.diffracted)) / free;
          const double d2 = std::max(std::abs(spectrum[i].second_order - one.second_order),
                                     std::abs(alone.second_order - one.second_order)) / free;
          worst = std::max({worst, d1, d2});
          EXPECT_LT(d1, 1e-10) << hz[i] << " Hz, order " << order;
          EXPECT_LT(d2, 1e-10) << hz[i] << " Hz, order " << order;
          if (order == 2) {
            EXPECT_GT(std::abs(one.second_order), 1e-4 * free);  // a term there is to compare
          }
        }
      }
  std::printf("worst |spectrum − one frequency at a time| / free field: %.2e\n", worst);
}

TEST(ReferenceBtmSpectrum, LargePlateNearAnEdgeTendsToMacdonaldAtEveryFrequency) {
  // As reference_btm_test.cpp's one-frequency test: the plate y = 0, x in [0, L], z in [−L/2, L/2] near the
  // middle of its edge x = 0 differs from the half-plane by the far edges' waves, ~L^{−3/2} (1.3e-4 of the
  // free field at L = 400 m, 500 Hz). Here five frequencies from one call, each against Macdonald.
  const double L = 400.0;
  ref::BtmPlate plate;
  plate.vertices = {Vec3(0, 0, -0.5 * L), Vec3(0, 0, 0.5 * L), Vec3(L, 0, 0.5 * L), Vec3(L, 0, -0.5 * L)};
  const std::vector<double> hz{150.0, 310.0, 500.0, 820.0, 1000.0};
  const std::vector<double> k = wavenumbers(hz);
  const ref::CylindricalPoint s{1.5, 0.6, 0.3};
  const auto cartesian = [](const ref::CylindricalPoint& p) {
    return Vec3(p.rho_m * std::cos(p.phi_rad), p.rho_m * std::sin(p.phi_rad), p.z_m);
  };
  for (double phi : {0.3, 2.0, 3.6, 4.5, 6.1}) {
    const ref::CylindricalPoint r{2.2, phi, 0.8};
    const double free = 1.0 / (cartesian(r) - cartesian(s)).norm();
    const std::vector<ref::BtmPlateField> u = ref::btmPlateSpectrum(k, plate, std::nan(""), cartesian(s), cartesian(r), 1);
    for (std::size_t i = 0; i < k.size(); ++i) {
      const Complex exact = ref::halfPlanePointSource(kC / hz[i], s, r, true);
      EXPECT_LT(std::abs(u[i].total() - exact), 1e-3 * free) << hz[i] << " Hz, phi " << phi;
    }
  }
}

TEST(ReferenceBtmSpectrum, SameNumbersOnOneThreadAsOnAll) {
  const std::vector<double> k = wavenumbers({200.0, 900.0});
  const Vec3 s(-1.0, 0.1, 0.2), r(1.0, -0.2, 0.3);
  std::vector<ref::BtmPlateField> one;
  {
    diffray::core::ThreadLimit limit(1);
    one = ref::btmPlateSpectrum(k, smallPlate(), 0.0, s, r, 2);
  }
  const std::vector<ref::BtmPlateField> all = ref::btmPlateSpectrum(k, smallPlate(), 0.0, s, r, 2);
  for (std::size_t i = 0; i < k.size(); ++i) {
    EXPECT_EQ(one[i].diffracted, all[i].diffracted);
    EXPECT_EQ(one[i].second_order, all[i].second_order);
  }
}

TEST(ReferenceBtmSpectrum, RejectsBadInput) {
  const Vec3 s(-1.0, 0.1, 0.2), r(1.0, -0.2, 0.3);
  using diffray::core::InputError;
  EXPECT_THROW(ref::btmPlateSpectrum({}, smallPlate(), 0.0, s, r), InputError);
  EXPECT_THROW(ref::btmPlateSpectrum({1.0, -2.0}, smallPlate(), 0.0, s, r), InputError);
  EXPECT_THROW(ref::btmPlateSpectrum({std::nan("")}, smallPlate(), 0.0, s, r), InputError);
  EXPECT_THROW(ref::btmPlateSpectrum({1.0}, smallPlate(), 0.0, s, r, 3), InputError);
  EXPECT_THROW(ref::btmPlateSpectrum({1.0}, smallPlate(), 0.0, Vec3(0, 0, 0.2), r), InputError);   // on the plate
  EXPECT_THROW(ref::btmPlateSpectrum({1.0}, smallPlate(), 0.0, Vec3(-1, 0, -0.2), r), InputError);  // below ground
}

}  // namespace
