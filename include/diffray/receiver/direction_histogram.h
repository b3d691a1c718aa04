#pragma once
// Where a listener's energy comes from: per time bin and band, the energy-weighted sum of the unit vectors
// pointing from the listener towards where each contribution arrives from (world frame, J/m² times a unit
// vector; the first moment of the energy over directions, Gerzon's energy vector before its division by the
// energy). Bins as EnergyHistogram's (bin b covers [b·bin_s, (b+1)·bin_s)), stored bin-major, three
// components per band. Signed energies add with their sign, as in the energy histogram. No standard errors:
// a direction is read from sums over many bins. One per chunk accumulator, merged in a fixed order; not
// synchronised.
#include <vector>

#include "diffray/core/math.h"

namespace diffray::receiver {

class DirectionHistogram {
 public:
  DirectionHistogram() = default;
  DirectionHistogram(int bands, int bins) : bands_(bands), bins_(bins), v_(3 * std::size_t(bands) * bins, 0.0) {}

  int bands() const { return bands_; }
  int bins() const { return bins_; }
  /// The three components (x, y, z) of every band of one bin, band-major: row(bin)[3b + k].
  double* row(int bin) { return &v_[3 * std::size_t(bin) * std::size_t(bands_)]; }
  /// Adds energy arriving from unit direction u.
  void add(int band, int bin, double energy, const core::Vec3& u) {
    double* r = row(bin) + 3 * band;
    r[0] += energy * u.x();
    r[1] += energy * u.y();
    r[2] += energy * u.z();
  }
  core::Vec3 value(int band, int bin) const {
    const double* r = &v_[3 * (std::size_t(bin) * std::size_t(bands_) + std::size_t(band))];
    return {r[0], r[1], r[2]};
  }
  void merge(const DirectionHistogram& o) {
    for (std::size_t i = 0; i < v_.size() && i < o.v_.size(); ++i) v_[i] += o.v_[i];
  }

 private:
  int bands_ = 0, bins_ = 0;
  std::vector<double> v_;
};

}  // namespace diffray::receiver
