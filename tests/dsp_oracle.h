#pragma once
// Test oracles for the convolvers, sharing no code with the FFT paths: direct time-domain convolution in
// double and seeded white noise.
#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

namespace diffray::test {

/// y[t] = Σ_k h[k]·x[t−k], t = 0 … |x|+|h|−2, in double.
inline std::vector<double> directConvolution(const std::vector<float>& x, const std::vector<float>& h) {
  std::vector<double> y(x.size() + h.size() - 1, 0.0);
  for (size_t i = 0; i < x.size(); ++i)
    for (size_t k = 0; k < h.size(); ++k) y[i + k] += static_cast<double>(x[i]) * h[k];
  return y;
}

/// n samples uniform in [−1, 1).
inline std::vector<float> uniformNoise(std::mt19937& rng, size_t n) {
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  std::vector<float> v(n);
  for (float& s : v) s = u(rng);
  return v;
}

/// max_t |got[t] − want[t]| / max_t |want[t]| (sizes must agree).
inline double relativeError(const std::vector<float>& got, const std::vector<double>& want) {
  double peak = 0.0, err = 0.0;
  for (size_t i = 0; i < want.size(); ++i) {
    peak = std::max(peak, std::abs(want[i]));
    err = std::max(err, std::abs(static_cast<double>(got[i]) - want[i]));
  }
  return peak > 0.0 ? err / peak : err;
}

}  // namespace diffray::test
