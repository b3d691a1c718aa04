#pragma once
// Shared by the FDTD oracle tests: a closed box room in code, its grid, and a Hann-windowed DFT magnitude at
// any frequency (the tests' own spectral estimate: no FFT library, no solver code).
#include <cmath>
#include <complex>
#include <vector>

#include "diffray/reference/fdtd_grid.h"
#include "diffray/room/room.h"

namespace diffray::test {

inline room::Room fdtdBoxRoom(const core::Vec3& dims, double alpha) {
  room::Room room;
  room::Material m;
  m.name = "wall";
  for (int b = 0; b < room.bands.size(); ++b) m.absorption[b] = alpha;
  const int id = room.addMaterial(m);
  const int walls[6] = {id, id, id, id, id, id};
  room.addBox(core::Vec3(0, 0, 0), dims, walls);
  return room;
}

/// The box voxelised at h (2 margin cells) and flood-filled from the node nearest to `seed`.
inline reference::FdtdGrid fdtdBoxGrid(const room::Room& room, double h, const core::Vec3& seed) {
  reference::FdtdGrid g = reference::voxelise(room, h, 2);
  g.floodFill({static_cast<std::size_t>(g.nearestNode(seed))});
  return g;
}

/// |Σ_n w_n x_n e^{−iωn·dt}| with the Hann window w over the whole record.
inline double hannDftMagnitude(const std::vector<double>& x, double dt, double f_hz) {
  const double pi = 3.14159265358979323846;
  const std::size_t n = x.size();
  std::complex<double> acc = 0.0, rot = std::polar(1.0, -2.0 * pi * f_hz * dt), ph = 1.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double w = 0.5 - 0.5 * std::cos(2.0 * pi * static_cast<double>(i) / static_cast<double>(n - 1));
    acc += w * x[i] * ph;
    ph *= rot;
    if ((i & 1023) == 1023) ph /= std::abs(ph);  // keep the rotating phasor on the unit circle
  }
  return std::abs(acc);
}

/// The frequency of the largest hannDftMagnitude in [lo, hi] (dense scan, then golden-section refinement).
inline double spectralPeak(const std::vector<double>& x, double dt, double lo, double hi) {
  const int scan = 64;
  double best_f = lo, best = -1.0;
  for (int i = 0; i <= scan; ++i) {
    const double f = lo + (hi - lo) * i / scan;
    const double m = hannDftMagnitude(x, dt, f);
    if (m > best) best = m, best_f = f;
  }
  double a = std::max(lo, best_f - (hi - lo) / scan), b = std::min(hi, best_f + (hi - lo) / scan);
  const double g = 0.5 * (std::sqrt(5.0) - 1.0);
  for (int it = 0; it < 50; ++it) {
    const double x1 = b - g * (b - a), x2 = a + g * (b - a);
    if (hannDftMagnitude(x, dt, x1) < hannDftMagnitude(x, dt, x2)) a = x1;
    else b = x2;
  }
  return 0.5 * (a + b);
}

}  // namespace diffray::test
