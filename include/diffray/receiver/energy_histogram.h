#pragma once
// A listener's energy field: a dense band × time-bin array of signed energy (style.md: the energy field
// as channel × band × bin, with a named bin width; stored bin-major, see index()), plus the sum of squared chunk totals per cell so that
// each cell has a standard error from the chunk-to-chunk scatter (as ScreenTally, receiver/screen.h).
// Closing a chunk into batch k (closeChunk(k, weight)) also adds it to that batch's own band × bin totals:
// K independent sub-histograms (allocated when first used, so a chunk accumulator holds only the batches of
// its chunks), from which nonlinear figures of the whole get a jackknife standard error (ir/uncertainty.h).
// Memory: bands × bins doubles per batch used, K·bands·bins in a merged total.
// Units: energy per unit area (J/m², the fluence through the listener), normalised by the tracer so that
// a source of power 1 W gives 1/r² at distance r in free field; bin b covers [b·bin_s, (b+1)·bin_s).
// One per chunk, merged in a fixed order (core/parallel.h); not synchronised.
#include <cstdint>
#include <vector>

namespace diffray::receiver {

class EnergyHistogram {
 public:
  EnergyHistogram() = default;
  EnergyHistogram(int bands, int bins, double bin_s)
      : bands_(bands), bins_(bins), bin_s_(bin_s), sum_(std::size_t(bands) * bins, 0.0),
        sum_sq_(std::size_t(bands) * bins, 0.0), chunk_(std::size_t(bands) * bins, 0.0),
        exact_(std::size_t(bands) * bins, 0.0) {}

  int bands() const { return bands_; }
  int bins() const { return bins_; }
  double binSeconds() const { return bin_s_; }
  double lengthSeconds() const { return bins_ * bin_s_; }
  /// Bin of time t, or −1 if t is outside [0, length).
  int binOf(double t_s) const {
    if (!(t_s >= 0.0)) return -1;
    const double f = t_s / bin_s_;
    return f < bins_ ? static_cast<int>(f) : -1;
  }
  /// Adds energy to the open chunk.
  void add(int band, int bin, double energy) { chunk_[index(band, bin)] += energy; }
  /// The open chunk's cells of one bin, one per band (adjacent): add(b, bin, e) is openRow(bin)[b] += e.
  double* openRow(int bin) { return &chunk_[index(0, bin)]; }
  /// Adds energy straight to the totals (deterministic contributions such as image sources: no scatter).
  void addExact(int band, int bin, double energy) { exact_[index(band, bin)] += energy; }
  /// Folds the open chunk into the totals and, with batch ≥ 0, into batch `batch` (of `batches`), whose
  /// weight grows by `weight` (e.g. the chunk's rays: a batch's share of the whole).
  void closeChunk(int batch = -1, int batches = 0, double weight = 0.0);
  void merge(const EnergyHistogram& o);
  /// Multiplies totals (and squared totals consistently, and the batches) by `factor`, e.g. 1/rays.
  void scale(double factor);
  /// Traced plus exact energy of a cell.
  double value(int band, int bin) const {
    const std::size_t i = index(band, bin);
    return sum_[i] + exact_[i];
  }
  /// The traced (Monte Carlo) part alone.
  double traced(int band, int bin) const { return sum_[index(band, bin)]; }
  /// Standard error of value(band, bin) (of its traced part: exact energy has none) from the chunk scatter (0 with fewer than 2 chunks). Valid after
  /// scale() too, since sum and sum_sq scale together.
  double standardError(int band, int bin) const;
  /// The band's whole time series (bins values).
  std::vector<double> band(int b) const {
    std::vector<double> out(bins_);
    for (int i = 0; i < bins_; ++i) out[i] = value(b, i);
    return out;
  }
  std::uint64_t chunks() const { return chunks_; }
  /// Batches (0: none kept); batch k's traced energy in a cell (0 for a batch no chunk went to), and its weight.
  int batches() const { return static_cast<int>(batch_.size()); }
  double batchValue(int k, int band, int bin) const {
    const auto& b = batch_[static_cast<std::size_t>(k)];
    return b.empty() ? 0.0 : b[index(band, bin)];
  }
  double batchWeight(int k) const { return batch_weight_[static_cast<std::size_t>(k)]; }

 private:
  /// Cells are bin-major: a bin's bands are adjacent, so that a listener's score (every band at one time)
  /// touches one or two cache lines instead of one per band (half the room tracer's scoring time).
  std::size_t index(int band, int bin) const { return std::size_t(bin) * std::size_t(bands_) + std::size_t(band); }
  int bands_ = 0, bins_ = 0;
  double bin_s_ = 0.001;
  std::vector<double> sum_, sum_sq_, chunk_, exact_;
  std::vector<std::vector<double>> batch_;  ///< per batch: its cells (empty until a chunk goes to it)
  std::vector<double> batch_weight_;
  std::uint64_t chunks_ = 0;
};

}  // namespace diffray::receiver
