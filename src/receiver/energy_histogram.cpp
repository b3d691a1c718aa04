#include "diffray/receiver/energy_histogram.h"

#include <cmath>

namespace diffray::receiver {

double EnergyHistogram::standardError(int band, int bin) const {
  if (chunks_ < 2) return 0.0;
  const std::size_t i = index(band, bin);
  const double n = static_cast<double>(chunks_);
  const double mean = sum_[i] / n;
  const double var = (sum_sq_[i] / n - mean * mean) * n / (n - 1.0);  // of one chunk total
  return var > 0.0 ? std::sqrt(var * n) : 0.0;                          // of the sum of n chunks
}

}  // namespace diffray::receiver
