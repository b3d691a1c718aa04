// The acoustic tracer's surface events (transport/room_materials.h), each against an oracle of its own:
// the Lambert sampler against the cosine density by chi-square tests (cos²θ and the azimuth are uniform
// under it), and the per-band event weights against the energy balance they must keep on average.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "chi2.h"
#include "diffray/transport/room_materials.h"

namespace diffray::transport {
namespace {

using core::Vec3;

// For the cosine density p(ω) = cos θ/π about n, (cos²θ, azimuth about n) is uniform on [0, 1] × [0, 2π)
// (jointly: the two are independent), whatever tangent the azimuth is measured from. The tangent here is
// built from n by Gram-Schmidt on the coordinate axis least aligned with it (not the sampler's branchless
// basis). 200k draws per normal into 10 × 8 equal cells (2,500 expected each); fixed seed. The normals
// take both branches of the sampler's basis (n.z ≥ 0 and < 0), the poles included, and oblique ones.
TEST(StatRoomSurfaceEvents, LambertSamplerHasTheCosineDensity) {
  std::mt19937_64 gen(2026);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  for (const Vec3& n_raw : {Vec3(0, 0, 1), Vec3(0, 0, -1), Vec3(1, 0, 0), Vec3(1, 0, -0.0), Vec3(0.3, -0.5, 0.81),
                            Vec3(-0.2, 0.1, -0.97)}) {
    const Vec3 n = n_raw.normalized();
    SCOPED_TRACE(::testing::Message() << "n = " << n.transpose());
    Vec3 axis(0, 0, 0);
    int least = 0;
    for (int c = 1; c < 3; ++c)
      if (std::abs(n[c]) < std::abs(n[least])) least = c;
    axis[least] = 1.0;
    const Vec3 t1 = (axis - axis.dot(n) * n).normalized(), t2 = n.cross(t1);
    const int draws = 200000, cos_bins = 10, phi_bins = 8;
    std::vector<double> counts(cos_bins * phi_bins, 0.0);
    double worst_norm = 0.0, worst_side = 1.0;
    for (int i = 0; i < draws; ++i) {
      const Vec3 d = sampleLambert(n, [&] { return uni(gen); });
      worst_norm = std::max(worst_norm, std::abs(d.norm() - 1.0));
      const double c = d.dot(n);
      worst_side = std::min(worst_side, c);
      const int ic = std::min(cos_bins - 1, static_cast<int>(c * c * cos_bins));
      const double phi = std::atan2(d.dot(t2), d.dot(t1)) + core::kPi;  // [0, 2π]
      const int ip = std::min(phi_bins - 1, static_cast<int>(phi / core::kTwoPi * phi_bins));
      counts[static_cast<std::size_t>(ic * phi_bins + ip)] += 1.0;
    }
    EXPECT_LT(worst_norm, 1e-12);
    EXPECT_GE(worst_side, 0.0);  // never into the surface
    const testing::Chi2Result test =
        testing::chiSquareTest(counts, std::vector<double>(counts.size(), 1.0 / static_cast<double>(counts.size())));
    EXPECT_GT(test.p_value, testing::kChi2Alpha) << "X² = " << test.statistic << " on " << test.dof << " dof";
  }
}

// Whatever the fixed event probabilities, each part of a band's expected energy after a hit is what the
// material sends that way: diffuse p_r·p_s·w_diffuse = (1 − α_b)·s_b, specular p_r·(1 − p_s)·w_specular =
// (1 − α_b)(1 − s_b), transmitted (1 − p_r)·w_transmit = τ_b (so the total is (1 − α_b) + τ_b). Materials:
// absorbing only, scattering, transmitting (τ ≤ α, as the loader requires), an opening (α = τ = 1) and a
// perfect absorber (nothing reflected or transmitted).
TEST(RoomSurfaceEvents, EventWeightsKeepEveryBandsEnergyBalance) {
  room::Room room;
  room.bands = core::Bands::octave();
  const int nb = room.bands.size();
  const auto material = [&](const char* name, auto alpha, auto s, auto tau) {
    room::Material m;
    m.name = name;
    for (int b = 0; b < nb; ++b) m.absorption[b] = alpha(b), m.scattering[b] = s(b), m.transmission[b] = tau(b);
    room.materials.push_back(m);
  };
  material("hard", [](int b) { return 0.02 + 0.01 * b; }, [](int) { return 0.0; }, [](int) { return 0.0; });
  material("diffusing", [](int b) { return 0.1 + 0.08 * b; }, [](int b) { return 0.05 + 0.1 * b; },
           [](int) { return 0.0; });
  material("curtain", [](int b) { return 0.3 + 0.05 * b; }, [](int b) { return 0.5 - 0.03 * b; },
           [](int b) { return 0.25 - 0.02 * b; });
  material("opening", [](int) { return 1.0; }, [](int) { return 0.0; }, [](int) { return 1.0; });
  material("absorber", [](int) { return 1.0; }, [](int) { return 0.0; }, [](int) { return 0.0; });
  const MaterialTable t = makeMaterials(room);
  ASSERT_EQ(t.p_reflect.size(), room.materials.size());
  for (std::size_t i = 0; i < room.materials.size(); ++i) {
    const room::Material& m = room.materials[i];
    SCOPED_TRACE(m.name);
    for (int b = 0; b < nb; ++b) ASSERT_LE(m.transmission[b], m.absorption[b]);  // a valid material
    if (t.absorbing[i]) {
      for (int b = 0; b < nb; ++b) EXPECT_TRUE(m.absorption[b] == 1.0 && m.transmission[b] == 0.0);
      continue;
    }
    const double pr = t.p_reflect[i], ps = t.p_diffuse[i];
    EXPECT_GE(pr, 0.0);
    EXPECT_LE(pr, 1.0);
    EXPECT_GE(ps, 0.0);
    EXPECT_LE(ps, 1.0);
    for (int b = 0; b < nb; ++b) {
      const double alpha = m.absorption[b], s = m.scattering[b], tau = m.transmission[b];
      EXPECT_NEAR(pr * ps * t.w_diffuse[i][b], (1.0 - alpha) * s, 1e-12) << "band " << b;
      EXPECT_NEAR(pr * (1.0 - ps) * t.w_specular[i][b], (1.0 - alpha) * (1.0 - s), 1e-12) << "band " << b;
      EXPECT_NEAR((1.0 - pr) * t.w_transmit[i][b], tau, 1e-12) << "band " << b;
      // The same weights in single precision (octave bands): the balance to float rounding.
      EXPECT_NEAR(pr * ps * t.octave_diffuse[i][b], (1.0 - alpha) * s, 1e-6) << "band " << b;
      EXPECT_NEAR(pr * (1.0 - ps) * t.octave_specular[i][b], (1.0 - alpha) * (1.0 - s), 1e-6) << "band " << b;
      EXPECT_NEAR((1.0 - pr) * t.octave_transmit[i][b], tau, 1e-6) << "band " << b;
    }
  }
  room.bands = core::Bands::thirdOctave();  // other band sets carry no single-precision copy
  EXPECT_TRUE(makeMaterials(room).octave_diffuse.empty());
  EXPECT_EQ(t.absorbing[4], 1);
  EXPECT_EQ(t.absorbing[0], 0);
  EXPECT_EQ(t.opening[3], 1);
  EXPECT_EQ(t.opening[2], 0);
}

// Octaves, the bounce loop's single-precision band energies: bands 0–7 round-trip through float, the bands
// above are dropped, and maxAbs's largest lane is the largest |energy| (signed energies: WBSDF weights),
// against std::abs and std::max over the doubles.
TEST(RoomSurfaceEvents, OctavesHoldEightBandsInFloatAndTheirLargestMagnitude) {
  core::BandArray e = core::bandFill(7.0);
  const double v[8] = {1.5e-3, -2.25e-2, 0.0, -0.0, 3.0e-7, -4.0e-1, 2.0e-1, 1.0 / 3.0};
  for (int b = 0; b < 8; ++b) e[b] = v[b];
  const Octaves o = toOctaves(e);
  const core::BandArray back = toBands(o);
  double largest = 0.0;
  for (int b = 0; b < 8; ++b) {
    EXPECT_EQ(o[b], static_cast<float>(v[b])) << "band " << b;
    EXPECT_EQ(back[b], static_cast<double>(static_cast<float>(v[b]))) << "band " << b;
    largest = std::max(largest, std::abs(v[b]));
  }
  for (int b = 8; b < core::kMaxBands; ++b) EXPECT_EQ(back[b], 0.0) << "band " << b;
  const Quad m = maxAbs(o);
  EXPECT_EQ(std::max(std::max(m[0], m[1]), std::max(m[2], m[3])), static_cast<float>(largest));
  for (int k = 0; k < 4; ++k) EXPECT_FALSE(std::signbit(m[k])) << "lane " << k;  // −0 cleared too
}

}  // namespace
}  // namespace diffray::transport
