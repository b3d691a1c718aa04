#pragma once
// The frequency grid of the band-averaged reference levels (halfPlaneBandLevelDb, apertureBandLevelDb):
// `points` frequencies at the midpoints of equal parts of [f_lo, f_hi], so that adjacent bands never share
// a frequency and the mean over the grid is the midpoint rule for the band average of an energy.
// Invalid input throws core::InputError naming `where`. Pure function; thread-safe.
#include <string>
#include <vector>

namespace diffray::reference {

/// f_j = f_lo + (j + ½)(f_hi − f_lo)/points, j = 0 … points − 1 (hertz). Requires finite 0 < f_lo <= f_hi
/// and 1 <= points <= 1e6.
std::vector<double> bandGridHz(const std::string& where, double f_lo_hz, double f_hi_hz, int points);

}  // namespace diffray::reference
