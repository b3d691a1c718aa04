// Oracle 5 of the FDTD wave reference (reference/fdtd_scheme.h): the scheme's discrete energy, written
// here from Bilbao's form H^{n+½} = Σ_air (p^{n+1} − p^n)² + λ²·Σ_open links (Δp^{n+1})(Δp^n), is constant
// in a rigid box once the source has stopped, and never grows with absorbing walls (it falls by
// Σ g_i (p^{n+1} − p^{n−1})² per step). Also the wall model's inversion of the Paris formula against
// an independent quadrature of the random-incidence average, and the voxeliser on a wall thinner than h.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "diffray/reference/fdtd_scheme.h"
#include "reference_fdtd_fixtures.h"

namespace {

using diffray::core::Vec3;
namespace ref = diffray::reference;
constexpr double kPi = 3.14159265358979323846;

// H^{n+½} from the fields p^{n+1} (cur) and p^n (prev), summed in double.
double discreteEnergy(const ref::FdtdGrid& g, const float* cur, const float* prev, double lambda) {
  double kinetic = 0.0, potential = 0.0;
  for (std::size_t i = 0; i < g.nodes(); ++i) {
    if (!g.isAir(i)) continue;
    kinetic += std::pow(double(cur[i]) - double(prev[i]), 2);
    for (int d = 1; d < 6; d += 2) {  // each open link once, from its lower node
      if (g.flags[i] & (1u << d)) continue;
      const std::size_t j = i + static_cast<std::size_t>(g.offset(d));
      potential += (double(cur[i]) - double(cur[j])) * (double(prev[i]) - double(prev[j]));
    }
  }
  return kinetic + lambda * lambda * potential;
}

// Energies of a box (alpha on every wall) after a 500 Hz Ricker pulse, one per step from step `from` on.
std::vector<double> boxEnergies(double alpha, int from, int steps, double lambda = ref::kSrlCourantLimit,
                                int stride = 1) {
  const double h = 0.05, fp = 500.0, c = 343.0, dt = lambda * h / c;
  const auto room = diffray::test::fdtdBoxRoom(Vec3(0.8, 0.6, 0.5), alpha);
  const ref::FdtdGrid grid = diffray::test::fdtdBoxGrid(room, h, Vec3(0.3, 0.3, 0.2));
  ref::FdtdScheme scheme(grid, lambda, {ref::admittanceForAbsorption(alpha)});
  const auto s = static_cast<std::size_t>(grid.nearestNode(Vec3(0.3, 0.3, 0.2)));
  std::vector<double> e;
  for (int n = 0; n < steps; ++n) {
    scheme.step();
    const double a = kPi * fp * (n * dt - 1.6 / fp);
    scheme.inject(s, static_cast<float>((1.0 - 2.0 * a * a) * std::exp(-a * a)));
    if (n >= from && (n - from) % stride == 0) e.push_back(discreteEnergy(grid, scheme.current(), scheme.previous(), lambda));
  }
  return e;
}

TEST(ReferenceFdtdEnergy, ConstantInARigidBoxAfterTheSourceStops) {
  // The pulse is below 1e-9 after 3.2/fp = 6.4 ms = 76 steps; 2000 steps after step 100.
  const auto e = boxEnergies(0.0, 100, 2100);
  ASSERT_GT(e.front(), 0.0);
  double worst = 0.0;
  for (double v : e) worst = std::max(worst, std::abs(v / e.front() - 1.0));
  // Float fields: each step rounds every p to 2^-24 relative; the energy's drift is a random walk of
  // such errors, ~1e-7·√2000 ≈ 5e-6 relative. 1e-4 leaves a factor 20 and still fails any real leak (an
  // absorbing link would remove percent per hundred steps here).
  EXPECT_LT(worst, 1e-4);
}

TEST(ReferenceFdtdEnergy, BoundedOverLongRunsAtTheCourantLimit) {
  // Two modes of a closed rigid box sit on the edge of stability at λ = 1/√3: the uniform field (double root
  // z = 1 of z² − 2z + 1 = 0) and the highest grid mode (the checkerboard, near z = −1). Any rounding that
  // puts the float update's coefficients outside the exact scheme (a row sum above 2, a λ² above 1/3) makes
  // one of them grow by e^{√(6·err)} per step: ~2.4e-4 per step for err = 6e-8, a factor 10¹⁰ in energy by
  // 50000 steps. 150000 steps (13 s of sound at h = 5 cm): the energy must stay within the rounding walk of
  // the short test above (~1e-7·√150000 ≈ 4e-5 relative; 1.3e-4 measured); 1e-3 is ten orders below
  // the growth.
  const auto e = boxEnergies(0.0, 100, 150000, ref::kSrlCourantLimit, 1000);
  double worst = 0.0;
  for (double v : e) worst = std::max(worst, std::abs(v / e.front() - 1.0));
  EXPECT_LT(worst, 1e-3);
  std::printf("worst relative energy drift over 150000 steps: %.2e\n", worst);
}

TEST(ReferenceFdtdEnergy, NonIncreasingWithAbsorbingWallsAndDecaying) {
  const auto e = boxEnergies(0.3, 100, 2100);
  for (std::size_t i = 1; i < e.size(); ++i) EXPECT_LE(e[i], e[i - 1] * (1.0 + 1e-6)) << i;
  EXPECT_LT(e.back(), 0.2 * e.front());
}

TEST(ReferenceFdtdWalls, AdmittanceReproducesTheRandomIncidenceAbsorption) {
  // α_st = ∫₀^{π/2} α(θ)·sin 2θ dθ with α(θ) = 4ξcosθ/(ξcosθ + 1)² (locally reacting, real ξ; Kuttruff),
  // by the midpoint rule on 20000 panels (error ~1e-9).
  auto alphaSt = [](double xi) {
    const int n = 20000;
    double sum = 0.0;
    for (int i = 0; i < n; ++i) {
      const double th = (i + 0.5) * (0.5 * kPi) / n, u = xi * std::cos(th);
      sum += 4.0 * u / ((u + 1.0) * (u + 1.0)) * std::sin(2.0 * th);
    }
    return sum * (0.5 * kPi) / n;
  };
  for (double alpha : {0.01, 0.05, 0.1, 0.3, 0.6, 0.9, 0.95}) {
    const double beta = ref::admittanceForAbsorption(alpha);
    EXPECT_NEAR(alphaSt(1.0 / beta), alpha, 1e-6) << alpha;
    EXPECT_LE(beta, 1.0 / 1.5);  // the stiff branch
  }
  EXPECT_EQ(ref::admittanceForAbsorption(0.0), 0.0);
  bool clamped = false;
  ref::admittanceForAbsorption(0.99, &clamped);
  EXPECT_TRUE(clamped);
  EXPECT_NEAR(ref::maxParisAbsorption(), 0.9512, 1e-4);  // Kuttruff: 0.951 at ξ = 1.567
}

TEST(ReferenceFdtdGrid, ThinWallSeparatesAndAnOpeningConnects) {
  // Two 1 m boxes sharing a 4 cm-thick partition (thinner than h = 0.1 m) at x ∈ [1, 1.04].
  auto twoBoxes = [](bool door) {
    diffray::room::Room room;
    diffray::room::Material wall, open;
    wall.name = "wall";
    open.name = "open";
    for (int b = 0; b < room.bands.size(); ++b) open.transmission[b] = 1.0;
    const int w = room.addMaterial(wall), o = room.addMaterial(open);
    int left[6] = {w, w, w, w, w, w}, right[6] = {w, w, w, w, w, w};
    if (door) left[1] = o, right[0] = o;  // the partition's two faces as openings: a gap through it
    room.addBox(Vec3(0, 0, 0), Vec3(1, 1, 1), left);
    room.addBox(Vec3(1.04, 0, 0), Vec3(2.04, 1, 1), right);
    return room;
  };
  for (bool door : {false, true}) {
    const auto room = twoBoxes(door);
    ref::FdtdGrid g = ref::voxelise(room, 0.1, 2);
    g.floodFill({static_cast<std::size_t>(g.nearestNode(Vec3(0.45, 0.45, 0.45)))});
    EXPECT_FALSE(g.air_reaches_edge);
    // Without the door: the left box's 10³ nodes. With it: both boxes' (no node lies in the 4 cm gap).
    EXPECT_EQ(g.air_nodes, door ? 2000 : 1000);
    EXPECT_EQ(g.isAir(static_cast<std::size_t>(g.nearestNode(Vec3(1.55, 0.45, 0.45)))), door);
  }
}

}  // namespace
