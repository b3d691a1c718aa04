#include "diffray/reference/band_grid.h"

#include "diffray/core/error.h"

namespace diffray::reference {

std::vector<double> bandGridHz(const std::string& where, double f_lo_hz, double f_hi_hz, int points) {
  core::requirePositive(where + ": f_lo_hz", f_lo_hz);
  core::requirePositive(where + ": f_hi_hz", f_hi_hz);
  if (f_hi_hz < f_lo_hz)
    throw core::InputError(where, "band is reversed: f_hi_hz " + std::to_string(f_hi_hz) + " < f_lo_hz " +
                                      std::to_string(f_lo_hz));
  if (points < 1 || points > 1000000)
    throw core::InputError(where + ": points", "must lie in [1, 1e6], got " + std::to_string(points));
  std::vector<double> grid(static_cast<std::size_t>(points));
  const double step_hz = (f_hi_hz - f_lo_hz) / points;
  for (int j = 0; j < points; ++j) grid[static_cast<std::size_t>(j)] = f_lo_hz + (j + 0.5) * step_hz;
  return grid;
}

}  // namespace diffray::reference
