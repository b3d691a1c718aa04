#include "diffray/receiver/screen.h"

#include <cmath>

namespace diffray::receiver {

double ScreenTally::standardError(int i, std::uint64_t rays) const {
  // Each ray contributes X_r (0 when it misses the bin); total = Σ X_r, Var(total) = N·Var(X) with
  // Var(X) = E[X²] − E[X]² estimated from the sums.
  if (rays < 2) return 0.0;
  const double n = static_cast<double>(rays);
  const double mean = sum[i] / n;
  const double var = std::max(0.0, sum_sq[i] / n - mean * mean) * n / (n - 1.0);
  return std::sqrt(n * var);
}

double ScreenTally::negativeFraction() const {
  double neg = 0.0, all = 0.0;
  for (double s : sum) {
    all += std::abs(s);
    if (s < 0) neg -= s;
  }
  return all > 0 ? neg / all : 0.0;
}

}  // namespace diffray::receiver
