#include "diffray/core/rng.h"

#include "diffray/core/error.h"

namespace diffray::core {

ChunkSampler::ChunkSampler(Rng& rng, const double* alpha, int dims, bool qmc) : rng_(rng), dims_(dims), qmc_(qmc) {
  DIFFRAY_CHECK(dims >= 0 && dims <= kMaxDims);
  for (int i = 0; i < dims; ++i) {
    alpha_[i] = alpha[i];
    shift_[i] = rng_.uniform();
  }
}

}  // namespace diffray::core
