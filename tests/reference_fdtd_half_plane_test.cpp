// Oracle 3 of the FDTD wave reference: a rigid thin screen (a half-plane as far as the record reaches) in
// the grid, the band level around and behind its edge re free field against Macdonald's exact point-source
// solution (reference/half_plane_point.h, which shares no code with the FDTD). The scene: the screen
// {y = 0, 0 ≤ x ≤ 1.2, |z| ≤ 1.2} inside a transparent (opening) box that sets the domain, so the
// domain's faces absorb (an open scene). The screen's plane and edge lie half-way between nodes.
// Per receiver the FDTD gives |P_screen(f)|²/|P_free(f)|² (DFTs of the records with and without the screen,
// same source node); its mean over 20 frequencies across the 1 kHz octave is compared, in dB, with
// halfPlaneBandLevelDb at the same frequencies. The record stops at 5.2 ms, after the direct and edge
// pulses (≤ 0.63 m + 3.2 ms of pulse = 5.0 ms) and before anything from the screen's far edges (≥ 2.1 m:
// 6.1 ms) or the domain's faces (≥ 2.2 m).
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <vector>

#include "diffray/reference/fdtd_grid.h"
#include "diffray/reference/fdtd_scheme.h"
#include "diffray/reference/half_plane_point.h"

namespace {

using diffray::core::Vec3;
namespace ref = diffray::reference;
constexpr double kPi = 3.14159265358979323846;
constexpr double kC = 343.0;

diffray::room::Room screenScene(bool with_screen) {
  diffray::room::Room room;
  diffray::room::Material rigid, open;
  rigid.name = "screen";
  open.name = "open";
  for (int b = 0; b < room.bands.size(); ++b) open.transmission[b] = 1.0;
  const int r = room.addMaterial(rigid), o = room.addMaterial(open);
  const int all_open[6] = {o, o, o, o, o, o};
  room.addBox(Vec3(-1.4, -1.4, -1.4), Vec3(1.4, 1.4, 1.4), all_open);
  if (with_screen) room.addPolygon({Vec3(0, 0, -1.2), Vec3(1.2, 0, -1.2), Vec3(1.2, 0, 1.2), Vec3(0, 0, 1.2)}, r, "screen");
  return room;
}

// Records at `receivers` (node positions) of a 1 kHz Ricker pulse at `source`, to `t_end`.
std::vector<std::vector<double>> run(bool with_screen, double h, const Vec3& source, const std::vector<Vec3>& receivers,
                                     double t_end) {
  const auto room = screenScene(with_screen);
  ref::FdtdGrid grid = ref::voxelise(room, h, 2);
  const auto s = static_cast<std::size_t>(grid.nearestNode(source));
  grid.floodFill({s});
  EXPECT_TRUE(grid.air_reaches_edge);
  ref::FdtdScheme scheme(grid, ref::kSrlCourantLimit, {0.0, 0.0});
  const double dt = ref::kSrlCourantLimit * h / kC, fp = 1000.0;
  std::vector<std::vector<double>> rec(receivers.size());
  for (int n = 0; n * dt < t_end; ++n) {
    scheme.step();
    const double a = kPi * fp * (n * dt - 1.6 / fp);
    scheme.inject(s, static_cast<float>((1.0 - 2.0 * a * a) * std::exp(-a * a)));
    for (std::size_t q = 0; q < receivers.size(); ++q)
      rec[q].push_back(scheme.current()[static_cast<std::size_t>(grid.nearestNode(receivers[q]))]);
  }
  return rec;
}

std::complex<double> dft(const std::vector<double>& x, double dt, double f) {
  std::complex<double> acc = 0.0;
  for (std::size_t n = 0; n < x.size(); ++n) acc += x[n] * std::polar(1.0, -2.0 * kPi * f * dt * static_cast<double>(n));
  return acc;
}

TEST(ReferenceFdtdHalfPlane, BandLevelAroundARigidEdgeMatchesMacdonald) {
  const double h = 0.02, dt = ref::kSrlCourantLimit * h / kC, t_end = 5.2e-3;
  // Node positions: x, y, z on (k + ½)·h, the screen's plane and edge half-way between nodes.
  auto node = [h](double x, double y) {
    return Vec3((std::floor(x / h) + 0.5) * h, (std::floor(y / h) + 0.5) * h, 0.5 * h);
  };
  const double rho = 0.3;
  const Vec3 source = node(rho * std::cos(0.25 * kPi), rho * std::sin(0.25 * kPi));
  std::vector<Vec3> receivers;
  for (double phi : {0.5 * kPi, 0.9 * kPi, 1.25 * kPi, 1.5 * kPi, 1.75 * kPi})
    receivers.push_back(node(rho * std::cos(phi), rho * std::sin(phi)));
  const auto with = run(true, h, source, receivers, t_end);
  const auto without = run(false, h, source, receivers, t_end);
  const double lo = 1000.0 / std::sqrt(2.0), hi = 1000.0 * std::sqrt(2.0);
  const int points = 20;
  const auto src = ref::halfPlaneFrameFromCartesian(source.x(), source.y(), source.z());
  for (std::size_t q = 0; q < receivers.size(); ++q) {
    double mean = 0.0;
    for (int j = 0; j < points; ++j) {
      const double f = lo + (j + 0.5) * (hi - lo) / points;
      mean += std::norm(dft(with[q], dt, f)) / std::norm(dft(without[q], dt, f)) / points;
    }
    const double fdtd_db = 10.0 * std::log10(mean);
    const auto rcv = ref::halfPlaneFrameFromCartesian(receivers[q].x(), receivers[q].y(), receivers[q].z());
    const double exact_db = ref::halfPlaneBandLevelDb(lo, hi, points, kC, src, rcv, true);
    // Tolerance 1 dB: the SRL's anisotropic phase error (≤ 1.1 % at the band's top, 12 points per
    // wavelength there) shifts the edge wave against the direct one by up to ~0.07 rad over these paths, and
    // the grid places the edge only to within h/2 = 1 cm of its nominal line (±0.3 dB in the shadow at ρ =
    // 0.3 m, where the level falls ~ as the edge distance); a thin screen in an SRL grid is known to read
    // within ~1 dB of the exact solution at such resolutions.
    EXPECT_NEAR(fdtd_db, exact_db, 1.0) << "phi = " << rcv.phi_rad << " exact " << exact_db;
  }
}

}  // namespace
