#include "diffray/receiver/screen.h"

#include <cmath>

namespace diffray::receiver {

double ScreenTally::standardError(int i) const {
  // Total = Σ_c S_c over K independent chunks: Var(total) = K·Var(S), Var(S) by the unbiased sample
  // variance of the chunk totals.
  if (chunks < 2) return 0.0;
  const double k = static_cast<double>(chunks);
  const double var = std::max(0.0, (sum_sq[i] - sum[i] * sum[i] / k) / (k - 1.0));
  return std::sqrt(k * var);
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
