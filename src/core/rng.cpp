#include "diffray/core/rng.h"

#include "diffray/core/error.h"

namespace diffray::core {

ChunkSampler::ChunkSampler(Rng& rng, int dims, bool qmc) : rng_(rng), dims_(dims), qmc_(qmc) {
  DIFFRAY_CHECK(dims >= 0 && dims <= kMaxDims);
  // φ_d: the positive root of x^{d+1} = x + 1 (Newton from 2).
  double phi = 2.0;
  for (int it = 0; it < 60; ++it) phi -= (std::pow(phi, dims + 1) - phi - 1.0) / ((dims + 1) * std::pow(phi, dims) - 1.0);
  for (int i = 0; i < dims; ++i) {
    const double a = std::pow(1.0 / phi, i + 1);
    alpha_[i] = a - std::floor(a);
    shift_[i] = rng_.uniform();
  }
}

ChunkSampler::ChunkSampler(Rng& rng, const double* alpha, int dims, bool qmc) : rng_(rng), dims_(dims), qmc_(qmc) {
  DIFFRAY_CHECK(dims >= 0 && dims <= kMaxDims);
  for (int i = 0; i < dims; ++i) {
    alpha_[i] = alpha[i];
    shift_[i] = rng_.uniform();
  }
}

}  // namespace diffray::core
