#pragma once
// Random numbers: std::mt19937_64 seeded from (seed, stream) through std::seed_seq, so every chunk of a
// parallel loop has its own reproducible stream. Not thread-safe: one Rng per thread or chunk.
#include <cstdint>
#include <cmath>
#include <random>

namespace diffray::core {

class Rng {
 public:
  Rng(std::uint64_t seed, std::uint64_t stream) {
    std::seed_seq seq{static_cast<std::uint32_t>(seed), static_cast<std::uint32_t>(seed >> 32),
                      static_cast<std::uint32_t>(stream), static_cast<std::uint32_t>(stream >> 32),
                      0x9e3779b9u};
    engine_.seed(seq);
  }
  /// Uniform in [0, 1).
  double uniform() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }
  std::uint64_t next() { return engine_(); }

 private:
  std::mt19937_64 engine_;
};

}  // namespace diffray::core

namespace diffray::core {

/// xoshiro256** (Blackman & Vigna 2018): a small, fast generator for hot loops that draw a few uniforms
/// per step (the room tracer's bounces). Seeded from an Rng, so it inherits the (seed, stream)
/// reproducibility of core::Rng. Not thread-safe: one per chunk.
class FastRng {
 public:
  explicit FastRng(Rng& seeder) {
    for (auto& w : s_) w = seeder.next();
    if ((s_[0] | s_[1] | s_[2] | s_[3]) == 0) s_[0] = 1;  // the all-zero state is a fixed point
  }
  /// An explicit state (not all zero), for the published test vectors.
  FastRng(std::uint64_t s0, std::uint64_t s1, std::uint64_t s2, std::uint64_t s3) : s_{s0, s1, s2, s3} {}
  std::uint64_t next() {
    const std::uint64_t result = rotl(s_[1] * 5, 7) * 9;
    const std::uint64_t t = s_[1] << 17;
    s_[2] ^= s_[0];
    s_[3] ^= s_[1];
    s_[1] ^= s_[2];
    s_[0] ^= s_[3];
    s_[2] ^= t;
    s_[3] = rotl(s_[3], 45);
    return result;
  }
  /// Uniform in [0, 1).
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }

 private:
  static std::uint64_t rotl(std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }
  std::uint64_t s_[4];
};

/// Uniforms for the rays of one chunk. With qmc, a ray's first `dims` uniforms come from a randomly
/// shifted Kronecker lattice (point j = frac(shift + j·α) with the caller's generators α, irrationals
/// independent over the rationals) and later ones from the chunk's Rng: randomised quasi-Monte Carlo, so
/// each chunk is an independent unbiased replicate whose points are evenly spread. Without qmc every uniform
/// comes from the Rng (plain Monte Carlo). Not thread-safe: one per chunk.
class ChunkSampler {
 public:
  static constexpr int kMaxDims = 8;
  /// Kronecker generators alpha[0..dims) (irrationals, independent over the rationals).
  ChunkSampler(Rng& rng, const double* alpha, int dims, bool qmc);
  /// Uniform number `dim` of ray `index` (0-based within the chunk); the caller advances `dim`.
  double next(std::uint64_t index, int& dim) { return at(index, dim++); }
  /// Uniform number `d` of ray `index`: quasi-random for d < dims, from the chunk's Rng otherwise.
  double at(std::uint64_t index, int d) {
    if (!qmc_ || d >= dims_) return rng_.uniform();
    const double v = shift_[d] + static_cast<double>(index + 1) * alpha_[d];
    return v - static_cast<double>(static_cast<std::int64_t>(v));  // v ≥ 0: truncation is floor
  }
  Rng& rng() { return rng_; }

 private:
  Rng& rng_;
  int dims_;
  bool qmc_;
  double shift_[kMaxDims] = {};
  double alpha_[kMaxDims] = {};
};

}  // namespace diffray::core
