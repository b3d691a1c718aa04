#pragma once
// Functions for the reference tests, independent of the module: an 8-point Gauss–Legendre panel with the
// nodes and weights of Abramowitz & Stegun, table 25.4 (not the module's reference/quadrature.h), and the
// band level averaged by hand over the midpoint grid that band_grid.h documents.
#include <cmath>

namespace diffray_test {

inline constexpr double kGauss8Nodes[4] = {0.1834346424956498, 0.5255324099163290, 0.7966664774136267,
                                           0.9602898564975363};
inline constexpr double kGauss8Weights[4] = {0.3626837833783620, 0.3137066458778873, 0.2223810344533745,
                                             0.1012285362903763};

/// ∫_a^b f by one 8-point panel; f returns any type supporting + and scalar ·.
template <class F>
auto gauss8(F f, double a, double b) {
  const double mid = 0.5 * (a + b), half = 0.5 * (b - a);
  auto sum = kGauss8Weights[0] * (f(mid - half * kGauss8Nodes[0]) + f(mid + half * kGauss8Nodes[0]));
  for (int i = 1; i < 4; ++i)
    sum += kGauss8Weights[i] * (f(mid - half * kGauss8Nodes[i]) + f(mid + half * kGauss8Nodes[i]));
  return half * sum;
}

/// 10·log10 of the mean of energy(f) over f_j = lo + (j + ½)(hi − lo)/n, j = 0 … n − 1.
template <class F>
double bandLevelByHandDb(double lo_hz, double hi_hz, int n, F energy) {
  double sum = 0.0;
  for (int j = 0; j < n; ++j) sum += energy(lo_hz + (j + 0.5) * (hi_hz - lo_hz) / n);
  return 10.0 * std::log10(sum / n);
}

}  // namespace diffray_test
