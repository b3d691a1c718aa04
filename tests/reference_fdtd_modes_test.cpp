// Oracle 1 of the FDTD wave reference (reference/fdtd_scheme.h): the resonances of a small rigid box,
// excited by an impulse and read off a Hann-windowed DFT, against (a) the continuous modes
// c/2·√((l/Lx)² + (m/Ly)² + (n/Lz)²) within the scheme's dispersion bound and (b) the exact discrete modes of
// the SRL scheme with rigid finite-volume walls, written here from first principles: the Neumann Laplacian
// of N nodes has eigenvectors cos(πl(i + ½)/N) and eigenvalues −(4/h²)sin²(πl/(2N)), so a mode of the
// leapfrog satisfies sin²(ω·dt/2) = λ²·Σ_axes sin²(πl_a/(2N_a)). And the stated axial dispersion
// relation sin(ω·dt/2) = λ·sin(kh/2), at 10 points per wavelength, against a measured duct mode.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "diffray/reference/fdtd_scheme.h"
#include "reference_fdtd_fixtures.h"

namespace {

using diffray::core::Vec3;
namespace ref = diffray::reference;
constexpr double kPi = 3.14159265358979323846;
constexpr double kC = 343.0;

// The pressure at `listen` after the impulse +1, −1 (no net mass: the box's uniform mode stays at rest)
// at `source`, over `steps` steps of a rigid box.
std::vector<double> rigidBoxResponse(const Vec3& dims, double h, const Vec3& source, const Vec3& listen, int steps) {
  const auto room = diffray::test::fdtdBoxRoom(dims, 0.0);
  const ref::FdtdGrid grid = diffray::test::fdtdBoxGrid(room, h, source);
  ref::FdtdScheme scheme(grid, ref::kSrlCourantLimit, {0.0});
  const auto s = static_cast<std::size_t>(grid.nearestNode(source));
  const auto r = static_cast<std::size_t>(grid.nearestNode(listen));
  std::vector<double> out;
  for (int n = 0; n < steps; ++n) {
    scheme.step();
    if (n < 2) scheme.inject(s, n == 0 ? 1.0f : -1.0f);
    out.push_back(scheme.current()[r]);
  }
  return out;
}

struct Mode {
  int l, m, n;
  double discrete, continuous;
};

TEST(ReferenceFdtdModes, RigidBoxResonancesMatchDiscreteAndContinuousModes) {
  const double h = 0.1, lambda = ref::kSrlCourantLimit, dt = lambda * h / kC;
  const int N[3] = {12, 9, 7};
  const Vec3 dims(N[0] * h, N[1] * h, N[2] * h);
  const int steps = 8192;
  // Corner nodes: cos(πl(i + ½)/N) is nonzero at i = 0 and N − 1 for every l, so every mode is excited and heard.
  const auto x = rigidBoxResponse(dims, h, Vec3(0.05, 0.05, 0.05), dims - Vec3(0.05, 0.05, 0.05), steps);
  std::vector<Mode> modes;
  for (int l = 0; l < 4; ++l)
    for (int m = 0; m < 4; ++m)
      for (int n = 0; n < 4; ++n) {
        if (l + m + n == 0) continue;
        double s2 = 0.0, k2 = 0.0;
        const int idx[3] = {l, m, n};
        for (int a = 0; a < 3; ++a) {
          s2 += std::pow(std::sin(kPi * idx[a] / (2.0 * N[a])), 2);
          k2 += std::pow(idx[a] / (N[a] * h), 2);
        }
        modes.push_back({l, m, n, 2.0 * std::asin(lambda * std::sqrt(s2)) / (2.0 * kPi * dt), 0.5 * kC * std::sqrt(k2)});
      }
  std::sort(modes.begin(), modes.end(), [](const Mode& a, const Mode& b) { return a.discrete < b.discrete; });
  const double df = 1.0 / (steps * dt);  // the DFT's bin width, 0.73 Hz
  int checked = 0;
  for (std::size_t i = 0; i < modes.size() && checked < 8; ++i) {
    // Isolated modes only (≥ 8 bins from any other), so that no neighbour's Hann leakage (below −60 dB there)
    // moves the peak.
    bool isolated = true;
    for (std::size_t j = 0; j < modes.size(); ++j)
      if (j != i && std::abs(modes[j].discrete - modes[i].discrete) < 8.0 * df) isolated = false;
    if (!isolated) continue;
    const Mode& md = modes[i];
    const double f = diffray::test::spectralPeak(x, dt, md.discrete - 3.0 * df, md.discrete + 3.0 * df);
    // (b) The scheme's own modes: a pure, undamped sinusoid's Hann peak sits on its frequency; 0.02 bins
    // allows for the other modes' far leakage.
    EXPECT_NEAR(f, md.discrete, 0.02 * df) << md.l << md.m << md.n;
    // (a) The continuous modes, within the dispersion bound: the SRL lags most along an axis, by
    // 1 − srlAxialPhaseVelocityRatio(f) (the box's wavenumbers are exact, so only the phase velocity errs).
    const double bound = 1.0 - ref::srlAxialPhaseVelocityRatio(f, h, dt, kC);
    EXPECT_LE(f, md.continuous * (1.0 + 1e-9)) << md.l << md.m << md.n;
    EXPECT_GE(f, md.continuous * (1.0 - bound) - 0.02 * df) << md.l << md.m << md.n;
    ++checked;
  }
  EXPECT_EQ(checked, 8);
}

TEST(ReferenceFdtdModes, AxialDispersionAtTenPointsPerWavelength) {
  // A rigid duct one node wide: its axial modes are plane waves along x. Mode l = 8 of 40 nodes has the
  // wavelength 2·4 m/8 = 1 m = 10 h: its frequency over the continuous c·l/(2L) is the phase velocity over c.
  const double h = 0.1, dt = ref::kSrlCourantLimit * h / kC;
  const Vec3 dims(4.0, 0.1, 0.1);
  const int steps = 16384;
  const auto x = rigidBoxResponse(dims, h, Vec3(0.05, 0.05, 0.05), Vec3(3.95, 0.05, 0.05), steps);
  const double f_cont = kC * 8 / (2.0 * 4.0), df = 1.0 / (steps * dt);
  const double f = diffray::test::spectralPeak(x, dt, 0.95 * f_cont, f_cont);
  const double measured = f / f_cont;
  EXPECT_NEAR(measured, ref::srlAxialPhaseVelocityRatio(f, h, dt, kC), 0.02 * df / f_cont);
  // fdtd.h's statement: −1.1 % at 10 points per wavelength and λ = 1/√3.
  EXPECT_NEAR(measured - 1.0, -0.011, 0.0005);
}

}  // namespace
