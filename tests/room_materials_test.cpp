// The acoustic tracer's surface events (transport/room_materials.h), each against an oracle of its own:
// the Lambert sampler against the cosine density by chi-square tests (cos²θ and the azimuth are uniform
// under it), and the per-band event weights against the energy balance they must keep on average.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "chi2.h"
#include "diffray/transport/room_materials.h"

namespace diffray::transport {
namespace {

using core::Vec3;

// For the cosine density p(ω) = cos θ/π about n, cos²θ is uniform on [0, 1] and the azimuth about n is
// uniform on [0, 2π), whatever tangent it is measured from. The tangent here is built from n by
// Gram-Schmidt on the coordinate axis least aligned with it (not the sampler's branchless basis).
// 200k draws per normal into 20 and 16 equal bins; fixed seed. The normals include ±z, where the
// sampler's basis switches sign, and an oblique one.
TEST(StatRoomSurfaceEvents, LambertSamplerHasTheCosineDensity) {
  std::mt19937_64 gen(2026);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  for (const Vec3& n_raw : {Vec3(0, 0, 1), Vec3(0, 0, -1), Vec3(1, 0, 0), Vec3(0.3, -0.5, 0.81),
                            Vec3(-0.2, 0.1, -0.97)}) {
    const Vec3 n = n_raw.normalized();
    SCOPED_TRACE(::testing::Message() << "n = " << n.transpose());
    Vec3 axis(0, 0, 0);
    int least = 0;
    for (int c = 1; c < 3; ++c)
      if (std::abs(n[c]) < std::abs(n[least])) least = c;
    axis[least] = 1.0;
    const Vec3 t1 = (axis - axis.dot(n) * n).normalized(), t2 = n.cross(t1);
    const int draws = 200000, cos_bins = 20, phi_bins = 16;
    std::vector<double> cos_counts(cos_bins, 0.0), phi_counts(phi_bins, 0.0);
    double worst_norm = 0.0, worst_side = 1.0;
    for (int i = 0; i < draws; ++i) {
      const Vec3 d = sampleLambert(n, uni(gen), uni(gen));
      worst_norm = std::max(worst_norm, std::abs(d.norm() - 1.0));
      const double c = d.dot(n);
      worst_side = std::min(worst_side, c);
      cos_counts[std::min(cos_bins - 1, static_cast<int>(c * c * cos_bins))] += 1.0;
      const double phi = std::atan2(d.dot(t2), d.dot(t1)) + core::kPi;  // [0, 2π]
      phi_counts[std::min(phi_bins - 1, static_cast<int>(phi / core::kTwoPi * phi_bins))] += 1.0;
    }
    EXPECT_LT(worst_norm, 1e-12);
    EXPECT_GE(worst_side, 0.0);  // never into the surface
    const testing::Chi2Result cos_test = testing::chiSquareTest(cos_counts, std::vector<double>(cos_bins, 1.0 / cos_bins));
    const testing::Chi2Result phi_test = testing::chiSquareTest(phi_counts, std::vector<double>(phi_bins, 1.0 / phi_bins));
    EXPECT_GT(cos_test.p_value, 1e-3) << "X² = " << cos_test.statistic << " on " << cos_test.dof << " dof";
    EXPECT_GT(phi_test.p_value, 1e-3) << "X² = " << phi_test.statistic << " on " << phi_test.dof << " dof";
  }
}

// Whatever the fixed event probabilities, each band's expected energy after a hit is (1 − α_b) + τ_b:
// p_r·(p_s·w_diffuse + (1 − p_s)·w_specular) + (1 − p_r)·w_transmit, and the diffuse part alone is
// (1 − α_b)·s_b. Materials: absorbing only, scattering, transmitting, an opening (α = τ = 1) and a
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
           [](int b) { return 0.4 - 0.04 * b; });
  material("opening", [](int) { return 1.0; }, [](int) { return 0.0; }, [](int) { return 1.0; });
  material("absorber", [](int) { return 1.0; }, [](int) { return 0.0; }, [](int) { return 0.0; });
  const MaterialTable t = makeMaterials(room);
  ASSERT_EQ(t.p_reflect.size(), room.materials.size());
  for (std::size_t i = 0; i < room.materials.size(); ++i) {
    const room::Material& m = room.materials[i];
    SCOPED_TRACE(m.name);
    if (t.absorbing[i]) {
      for (int b = 0; b < nb; ++b) EXPECT_EQ(m.absorption[b] - m.transmission[b], 1.0);
      continue;
    }
    const double pr = t.p_reflect[i], ps = t.p_diffuse[i];
    EXPECT_GE(pr, 0.0);
    EXPECT_LE(pr, 1.0);
    EXPECT_GE(ps, 0.0);
    EXPECT_LE(ps, 1.0);
    for (int b = 0; b < nb; ++b) {
      const double expected = pr * (ps * t.w_diffuse[i][b] + (1.0 - ps) * t.w_specular[i][b]) +
                              (1.0 - pr) * t.w_transmit[i][b];
      EXPECT_NEAR(expected, (1.0 - m.absorption[b]) + m.transmission[b], 1e-12) << "band " << b;
      EXPECT_NEAR(pr * ps * t.w_diffuse[i][b], (1.0 - m.absorption[b]) * m.scattering[b], 1e-12) << "band " << b;
    }
  }
  EXPECT_EQ(t.absorbing[4], 1);
  EXPECT_EQ(t.absorbing[0], 0);
}

}  // namespace
}  // namespace diffray::transport
