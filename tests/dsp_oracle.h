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

/// Feeds x then ir_length − 1 zeros through `conv` (any convolver with process(in, out, n) and blockSize())
/// in calls of random size (0 … 3 blocks), returning all of the output: the whole linear convolution.
template <class Convolver>
std::vector<float> runInRandomCalls(Convolver& conv, const std::vector<float>& x, long ir_length, std::mt19937& rng) {
  std::vector<float> in(x);
  in.resize(x.size() + static_cast<size_t>(ir_length) - 1, 0.0f);
  std::vector<float> out(in.size(), 0.0f);
  std::uniform_int_distribution<long> call(0, 3L * conv.blockSize());
  for (size_t pos = 0; pos < in.size();) {
    const long n = std::min<long>(call(rng), static_cast<long>(in.size() - pos));
    conv.process(in.data() + pos, out.data() + pos, n);
    pos += static_cast<size_t>(n);
  }
  return out;
}

}  // namespace diffray::test
