#pragma once
// What a room's surfaces do to a ray in the acoustic tracer (transport/room_tracer.cpp): per material, the
// fixed event probabilities and per-band weights of a hit, and the Lambert (diffuse) direction sampler;
// and Octaves, the single-precision form in which the tracer carries eight bands' energies and weights.
//
// Contract. A hit reflects with probability p_reflect (else it transmits), and a reflection is diffuse
// (Lambert) with probability p_diffuse (else specular). The probabilities are band means, fixed per
// material, and each event's per-band weight keeps every band unbiased for them:
// E[e_b'] = e_b·(p_r·(1 − α_b)/p_r + p_t·τ_b/p_t) = e_b·((1 − α_b) + τ_b), and likewise for the split of a
// reflection into Lambert (s_b/p_s) and specular ((1 − s_b)/(1 − p_s)) parts. Fixed probabilities cost no
// reduction or division per bounce (the tracer's hot path). Units: α, s, τ are energy fractions; directions
// are unit vectors in the room's frame. Immutable after makeMaterials; thread-safe to share.
#include <cmath>
#include <cstdint>
#include <vector>

#include "diffray/core/bands.h"
#include "diffray/core/math.h"
#include "diffray/room/room.h"

namespace diffray::transport {

/// Four floats operated on together (GCC/Clang vector extension: one SSE register on x86-64).
using Quad = float __attribute__((vector_size(16)));

/// Eight bands' energies (or weights) in two SSE registers, single precision: the acoustic tracer's bounce
/// loop carries a path's band energies so when a room has eight bands (octaves), relative to the emitted
/// level (so that float's range covers any source power), and its band weights and roulette level are a
/// few vector instructions. Each weight rounds by at most 6e-8 relative: over the N weights of a path
/// (N ≈ 700 to −60 dB on walls absorbing 2 %) a random walk of ~√N·6e-8 per band, 4e-5 at worst, far
/// below the Monte Carlo noise; scores are summed in double. Plain value type.
struct Octaves {
  Quad lo, hi;  ///< bands 0–3 and 4–7
  float operator[](int b) const { return b < 4 ? lo[b & 3] : hi[b & 3]; }
};
/// Bands 0–7 of `a`, rounded to float.
Octaves toOctaves(const core::BandArray& a);
/// A BandArray holding `o` in bands 0–7 and 0 above.
core::BandArray toBands(const Octaves& o);
/// max(|lo|, |hi|) lane by lane: its largest lane is the largest |band energy|.
inline Quad maxAbs(const Octaves& o) {
  using Bits = std::uint32_t __attribute__((vector_size(16)));
  const Bits mask = {0x7fffffffu, 0x7fffffffu, 0x7fffffffu, 0x7fffffffu};
  const Quad a = reinterpret_cast<Quad>(reinterpret_cast<Bits>(o.lo) & mask);
  const Quad b = reinterpret_cast<Quad>(reinterpret_cast<Bits>(o.hi) & mask);
  return a > b ? a : b;
}

struct MaterialTable {
  std::vector<double> p_reflect, p_diffuse;
  /// Per-band weights of the three events: w_diffuse = (1 − α_b)·s_b/(p_r·p_s), w_specular =
  /// (1 − α_b)(1 − s_b)/(p_r(1 − p_s)), w_transmit = τ_b/(1 − p_r); 0 for an event that cannot happen.
  std::vector<core::BandArray> w_transmit, w_diffuse, w_specular;
  /// The same weights as Octaves, for rooms with eight bands (else empty).
  std::vector<Octaves> octave_transmit, octave_diffuse, octave_specular;
  std::vector<char> opening;  ///< τ = 1 in every band: a hole, not a surface (never an event)
  std::vector<char> absorbing;  ///< nothing reflected or transmitted in any band
};

/// The table of every material of `room` (indexed as room.materials), for its bands.
MaterialTable makeMaterials(const room::Room& room);

/// A unit vector with the cosine-weighted (Lambert) density cos θ/π about the unit normal n, drawing its
/// uniforms in [0, 1) from `uniform()` (4/π ≈ 1.27 pairs on average). Malley's method: a point (x, y)
/// uniform in the unit disk (by rejection from the square), lifted to the hemisphere, x·t1 + y·t2 +
/// √(1 − x² − y²)·n, has density cos θ/π; no trigonometry (sincos was ~8 % of the room tracer's own time).
/// Inline: the room tracer's bounce loop calls it.
template <class Uniform>
core::Vec3 sampleLambert(const core::Vec3& n, Uniform&& uniform) {
  double x, y, r2;
  do {
    x = 2.0 * uniform() - 1.0;
    y = 2.0 * uniform() - 1.0;
    r2 = x * x + y * y;
  } while (r2 >= 1.0);
  // Orthonormal basis about n (Duff et al. 2017, branchless).
  const double sign = std::copysign(1.0, n.z());
  const double a = -1.0 / (sign + n.z()), b = n.x() * n.y() * a;
  const core::Vec3 t1(1.0 + sign * n.x() * n.x() * a, sign * b, -sign * n.x());
  const core::Vec3 t2(b, sign + n.y() * n.y() * a, -n.y());
  return x * t1 + y * t2 + std::sqrt(1.0 - r2) * n;
}

}  // namespace diffray::transport
