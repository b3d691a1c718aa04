#pragma once
// The acoustic tracer's lane functions (transport/room_tracer.cpp): Pair, two doubles in one SSE2 register
// for the listener pre-test, with its sign-bit, minimum and any-lane tests; and the form in which the bounce
// loop carries a path's band energies (Octaves for eight bands, else a BandArray), with the conversions
// to and from a Path's BandArray. Plain values and pure functions: thread-safe. Other targets than x86-64
// get the same results lane by lane.
#include <cmath>
#include <cstdint>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "diffray/core/bands.h"
#include "diffray/transport/room_materials.h"

namespace diffray::transport {

// Two doubles operated on together (GCC/Clang vector extension: an SSE2 register on x86-64).
using Pair = double __attribute__((vector_size(16)));
// The lanes' sign bits (bit 0: lane 0), whether either is set, and whether some lane of a four-float
// comparison is true: one movemask each with SSE2, else the lanes one by one (other targets).
using QuadMask = std::int32_t __attribute__((vector_size(16)));
inline int signBits(Pair v) {
#if defined(__SSE2__)
  return _mm_movemask_pd(v);
#else
  return (std::signbit(v[0]) ? 1 : 0) | (std::signbit(v[1]) ? 2 : 0);
#endif
}
inline bool anySignBit(Pair v) { return signBits(v) != 0; }
// Per lane, a < b ? a : b (so b when either is NaN): one minpd with SSE2.
inline Pair lesser(Pair a, Pair b) {
#if defined(__SSE2__)
  return _mm_min_pd(a, b);
#else
  return a < b ? a : b;
#endif
}
inline bool anyLane(QuadMask m) {
#if defined(__SSE2__)
  return _mm_movemask_ps(reinterpret_cast<__m128>(m)) != 0;
#else
  return (m[0] | m[1] | m[2] | m[3]) != 0;
#endif
}

// The band energies the bounce loop carries: Octaves for octave bands (NB = 8), else a BandArray.
template <int NB>
struct EnergyOf {
  using type = core::BandArray;
};
template <>
struct EnergyOf<8> {
  using type = Octaves;
};
// The bounce loop's energies from a Path's (Octaves: relative to `scale`, so that float's range covers any
// source power), and back.
template <int NB>
typename EnergyOf<NB>::type carried(const core::BandArray& e, double scale) {
  if constexpr (NB == 8) {
    core::BandArray relative = e;
    for (int b = 0; b < 8; ++b) relative[b] /= scale;
    return toOctaves(relative);
  } else {
    return e;
  }
}
inline const core::BandArray& asBands(const core::BandArray& e, double) { return e; }
inline core::BandArray asBands(const Octaves& e, double scale) {
  core::BandArray a = toBands(e);
  for (int b = 0; b < 8; ++b) a[b] *= scale;
  return a;
}

}  // namespace diffray::transport
