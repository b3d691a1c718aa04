#pragma once
// A screen receiver: a planar rectangle (frame, half-extents in metres) divided into nx × ny bins that
// accumulate the signed energy of every ray crossing them. A bin is a finite aperture: negative ray
// energies integrate out there (paper section 2.4), and what stays negative is reported, not clamped.
// Screens absorb the rays they record. The Screen itself is immutable; tallies live in ScreenTally, one
// per thread or chunk, merged in a fixed order (core/parallel.h).
#include <cstdint>
#include <vector>

#include "diffray/geometry/frame.h"

namespace diffray::receiver {

struct Screen {
  geometry::Frame frame;
  double half_x_m = 1.0, half_y_m = 1.0;
  int nx = 1, ny = 1;
  /// false: bins hold the energy crossing them (flux). true: each ray counts energy/|cos| to the screen's
  /// normal, so bin energy / bin area estimates the intensity, as a transparent probe would see it (what
  /// angle-impact rays need to reproduce |U|², wbsdf/angle_impact.h).
  bool intensity = false;

  /// Bin of the local point (x, y), or −1 outside the screen.
  int binOf(double x_m, double y_m) const {
    const double fx = (x_m + half_x_m) * (0.5 / half_x_m), fy = (y_m + half_y_m) * (0.5 / half_y_m);
    if (!(fx >= 0.0 && fx < 1.0 && fy >= 0.0 && fy < 1.0)) return -1;
    return static_cast<int>(fx * nx) + nx * static_cast<int>(fy * ny);
  }
  double binWidthX() const { return 2.0 * half_x_m / nx; }
  double binWidthY() const { return 2.0 * half_y_m / ny; }
  double binCentreX(int ix) const { return -half_x_m + (ix + 0.5) * binWidthX(); }
  double binCentreY(int iy) const { return -half_y_m + (iy + 0.5) * binWidthY(); }
  int bins() const { return nx * ny; }
};

/// Signed energy per bin. Rays are traced in independent chunks (core/parallel.h); the sum of squared
/// chunk totals gives each bin's standard error from the chunk-to-chunk scatter, which stays valid when
/// rays within a chunk are quasi-random rather than independent.
struct ScreenTally {
  std::vector<double> sum, sum_sq;  ///< Σ over chunks of the chunk total, and of its square
  std::vector<double> chunk;        ///< the open chunk's totals
  std::uint64_t chunks = 0;
  explicit ScreenTally(int bins = 0) : sum(bins, 0.0), sum_sq(bins, 0.0), chunk(bins, 0.0) {}
  void add(int bin, double energy) { chunk[bin] += energy; }
  /// Folds the open chunk into the totals.
  void closeChunk() {
    for (std::size_t i = 0; i < chunk.size(); ++i) {
      sum[i] += chunk[i];
      sum_sq[i] += chunk[i] * chunk[i];
      chunk[i] = 0.0;
    }
    ++chunks;
  }
  void merge(const ScreenTally& o) {
    for (std::size_t i = 0; i < sum.size(); ++i) {
      sum[i] += o.sum[i];
      sum_sq[i] += o.sum_sq[i];
    }
    chunks += o.chunks;
  }
  /// Standard error of bin i's total, from the scatter of its chunk totals.
  double standardError(int i) const;
  /// Σ of negative bin energies over Σ|bin energies|.
  double negativeFraction() const;
};

}  // namespace diffray::receiver
