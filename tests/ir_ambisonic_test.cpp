// Ambisonic IR synthesis (ir/spatial_synthesis.h). Oracles: the omnidirectional synthesis (W must be it,
// sample for sample); the closed-form SN3D harmonics of orders 1 and 2 written out here (a plane wave's
// channel c is Y_c(d)·W); the sphere averages of Y² for a diffuse field (1/(2n + 1)), with a tolerance
// from the variance of the Dirac directions and of the band's finite bandwidth-time product.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "diffray/core/error.h"
#include "diffray/ir/spatial_synthesis.h"
#include "diffray/ir/band_filter.h"
#include "diffray/ir/synthesis.h"
#include "response_fixtures.h"

namespace diffray::ir {
namespace {

using core::Vec3;
constexpr double kFs = 48000.0;
constexpr double kVolume = 2000.0, kC = 343.0;
const Vec3 kForward(1, 0, 0), kLeft(0, 1, 0), kUp(0, 0, 1);

// The SN3D harmonics of orders 0–2 in ACN order (AmbiX), written out: W; Y, Z, X; V, T, R, S, U.
std::vector<double> sn3d2(const Vec3& d) {
  const double x = d.x(), y = d.y(), z = d.z(), r3 = std::sqrt(3.0);
  return {1.0, y, z, x, r3 * x * y, r3 * y * z, 0.5 * (3 * z * z - 1), r3 * x * z, 0.5 * r3 * (x * x - y * y)};
}

// A decaying traced part (T = 0.6 s) from 5 ms on, and one arrival (direct sound) at 5 ms.
EnergyResponse decay(bool with_arrival) {
  EnergyResponse r;
  r.bands = core::Bands::octave();
  r.bin_s = 0.001;
  r.traced.assign(8, std::vector<double>(800, 0.0));
  for (auto& band : r.traced)
    for (int i = 5; i < 800; ++i) band[i] = 1e-3 * std::exp(-6.9 * i * 1e-3 / 0.6);
  if (with_arrival) {
    Arrival a;
    a.delay_s = 0.005;
    a.energy = core::bandFill(0.05);
    r.arrivals.push_back(a);
  }
  return r;
}

double energy(const std::vector<double>& x) {
  double s = 0.0;
  for (double v : x) s += v * v;
  return s;
}

TEST(IrAmbisonic, WIsTheOmniResponseSampleForSample) {
  EnergyResponse r = decay(true);
  r.arrivals[0].direction = Vec3(0.6, 0.8, 0.0);
  const auto amb = synthesizeAmbisonic(r, kFs, 0.8, kVolume, kC, 17, 2, kForward, kLeft, kUp);
  const auto omni = synthesize(r, kFs, 0.8, kVolume, kC, 17);
  ASSERT_EQ(amb.size(), 9u);
  ASSERT_EQ(amb[0].size(), omni.size());
  for (std::size_t s = 0; s < omni.size(); ++s) ASSERT_EQ(amb[0][s], omni[s]) << s;
  for (const auto& ch : amb) EXPECT_EQ(ch.size(), omni.size());
}

TEST(IrAmbisonic, PlaneWaveGivesEachChannelItsHarmonicTimesW) {
  // Everything from one direction: the arrival's direction and the traced energy vector e·d in every bin
  // (r_E = 1). Channel c is then Y_c(d)·W to rounding: the same Diracs, gains, band parts and phases.
  const Vec3 d = Vec3(-0.3, 0.5, 0.7).normalized();
  EnergyResponse r = decay(true);
  r.arrivals[0].direction = d;
  r.directions.assign(8, std::vector<Vec3>(800, Vec3(0, 0, 0)));
  for (int b = 0; b < 8; ++b)
    for (int i = 0; i < 800; ++i) r.directions[b][i] = r.traced[b][i] * d;
  const auto amb = synthesizeAmbisonic(r, kFs, 0.8, kVolume, kC, 3, 2, kForward, kLeft, kUp);
  const std::vector<double> y = sn3d2(d);
  double peak = 0.0;
  for (double v : amb[0]) peak = std::max(peak, std::abs(v));
  for (int c = 1; c < 9; ++c) {
    double worst = 0.0;
    for (std::size_t s = 0; s < amb[0].size(); ++s) worst = std::max(worst, std::abs(amb[c][s] - y[c] * amb[0][s]));
    EXPECT_LT(worst, 1e-12 * peak) << "channel " << c;
  }
}

TEST(IrAmbisonic, ListenerFrameTurnsTheField) {
  // An arrival from world +y heard by a listener facing +y (yaw 90°): straight ahead, X = W, Y = Z = 0.
  const EnergyResponse r = test::singleArrival(0.01, Vec3(0, 1, 0));
  const auto amb = synthesizeAmbisonic(r, kFs, 0.2, kVolume, kC, 1, 1, Vec3(0, 1, 0), Vec3(-1, 0, 0), kUp);
  double w = 0.0;
  for (std::size_t s = 0; s < amb[0].size(); ++s) {
    w = std::max(w, std::abs(amb[0][s]));
    EXPECT_NEAR(amb[3][s], amb[0][s], 1e-12);
    EXPECT_NEAR(amb[1][s], 0.0, 1e-12);
    EXPECT_NEAR(amb[2][s], 0.0, 1e-12);
  }
  EXPECT_GT(w, 0.1);
}

TEST(IrAmbisonic, DiffuseFieldGivesEachOrderItsShareOfTheEnergy) {
  // No recorded directions: every Dirac from a uniformly drawn direction, so channel (n, m) holds on average
  // E[Y²] = 1/(2n + 1) of W's energy in each band, and the 2n + 1 channels of order n together hold W's
  // energy (Σ_m Y_n^m² = 1 in SN3D, the addition theorem). Read in the 2, 4 and 8 kHz octaves together over
  // 3 s at the Dirac rate cap (3e4 Diracs). Two scatters: the directions, √(Var Y²/N) ≤ √(0.8/3e4) = 0.5 %
  // relative; and the chance interference of the channel's band-limited noise, relative SD √(1/(B·T)) per
  // band, (1/3)·√(Σ_b 1/(B_b·T)) = 0.68 % for the three bands together (W's own is undone by its gains).
  // Four standard deviations of the two together: 3.4 %.
  EnergyResponse r;
  r.bands = core::Bands::octave();
  r.bin_s = 0.001;
  r.traced.assign(8, std::vector<double>(3000, 1e-4));
  const auto amb = synthesizeAmbisonic(r, kFs, 3.0, 1.0, kC, 5, 3, kForward, kLeft, kUp);
  const BandFilter filter(r.bands, kFs);
  const auto high = [&](const std::vector<double>& x) {
    const auto parts = filter.split(x);
    return energy(parts[5]) + energy(parts[6]) + energy(parts[7]);
  };
  const double w = high(amb[0]);
  for (int n = 1; n <= 3; ++n) {
    double order_sum = 0.0;
    for (int c = n * n; c < (n + 1) * (n + 1); ++c) {
      const double share = high(amb[c]) / w;
      order_sum += share;
      if (n == 1) {
        EXPECT_NEAR(share * 3.0, 1.0, 0.034) << "channel " << c;
      }
    }
    EXPECT_NEAR(order_sum, 1.0, 0.034) << "order " << n;
  }
}

TEST(IrAmbisonic, RefusesOrdersOutsideOneToThree) {
  const EnergyResponse r = decay(false);
  EXPECT_THROW(synthesizeAmbisonic(r, kFs, 0.8, kVolume, kC, 1, 0, kForward, kLeft, kUp), core::InputError);
  EXPECT_THROW(synthesizeAmbisonic(r, kFs, 0.8, kVolume, kC, 1, 4, kForward, kLeft, kUp), core::InputError);
}

}  // namespace
}  // namespace diffray::ir
