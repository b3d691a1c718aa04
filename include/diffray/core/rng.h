#pragma once
// Random numbers: std::mt19937_64 seeded from (seed, stream) through std::seed_seq, so every chunk of a
// parallel loop has its own reproducible stream. Not thread-safe: one Rng per thread or chunk.
#include <cstdint>
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
