#pragma once
// Reading an arbitrary occluder microstructure t(x) = a(x)·e^{iΦ(x)} (paper eq. eq:microstructure) from a
// CSV file, and resampling it onto the uniform grid that wignerFFT (wigner_fft.h) needs.
//
// File format: one point per line, three comma-separated columns
//     x (metres, along the occluder's local x axis), amplitude a (0..1), phase Φ (radians)
// with x strictly increasing. '#' starts a comment (whole line or trailing); blank lines are skipped; the
// first non-comment line is a header, and skipped, if its first field is not a number. At least 2 points.
// Every violation throws core::InputError whose message starts with "<path>:<line>:" (or "<path>:" when
// the file cannot be opened): wrong column count, a non-numeric field, NaN/inf, a < 0 or a > 1,
// x not strictly increasing, fewer than 2 data rows (reported at the last line of the file).
//
// Resampling: amplitude and phase are interpolated linearly and separately (the phase as given, so a
// phase that is meant to be continuous must be supplied unwrapped), then t = a·e^{iΦ}. Linear
// interpolation smooths steps over one input interval; supply sharp edges with closely spaced points.
// The grid spacing must oversample t ×2 for wignerFFT: dx ≤ 1/(4·u_max), see wigner_fft.h.
// Thread-safety: free functions without shared state.
#include <string>
#include <vector>

#include "diffray/wbsdf/wigner_fft.h"

namespace diffray::wbsdf {

/// The points of a profile file, one entry per data row.
struct ProfilePoints {
  std::vector<double> x_m;
  std::vector<double> amplitude;
  std::vector<double> phase_rad;
};

/// Reads and validates a profile CSV (format above). Throws core::InputError.
ProfilePoints readProfileCsv(const std::string& path);

/// Linear interpolation onto x_j = x_first + j·dx for every x_j ≤ x_last (up to 1e-9·dx), j ≥ 0.
/// Throws core::InputError for dx ≤ 0, fewer than 2 points, mismatched column lengths, or an
/// out-of-range grid size.
SampledProfile resampleProfile(const ProfilePoints& points, double dx_m);

}  // namespace diffray::wbsdf

#include <memory>

#include "diffray/wbsdf/table.h"

namespace diffray::wbsdf {

/// The WBSDF table of a profile for wavelength λ, the columns |u'| < 2/λ only (every shift that can leave a
/// propagating ray). t is resampled at dx = min(λ/32, half the smallest input spacing): the discrete
/// pseudo-Wigner's first fold then lies at 1/(2dx) ≥ 16/λ, so components of t up to 14/λ, and every pair
/// of components whose mean frequency is within 2/λ of the kept band, land where they belong (wigner_fft.h).
/// A residual alias remains for t that is not band-limited (a sharp edge: at most |T(u+1/(2dx))|² ≤
/// (dx/cos(π/16))² per unit u in the x-integral). The FFT has nu = max(64, the power of 2 ≥ 2 × samples)
/// lags (none truncated) unless the table would exceed `max_cells` stored cells or 4·max_cells FFT inputs;
/// then nu is halved (W smoothed in u) down to 64, and beyond that core::InputError ("too long").
std::shared_ptr<const WbsdfTable> profileTable(const ProfilePoints& points, double wavelength_m,
                                               std::size_t max_cells = 40'000'000);

}  // namespace diffray::wbsdf
