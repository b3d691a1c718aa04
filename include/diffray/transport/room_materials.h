#pragma once
// What a room's surfaces do to a ray in the acoustic tracer (transport/room_tracer.cpp): per material, the
// fixed event probabilities and per-band weights of a hit, and the Lambert (diffuse) direction sampler.
//
// Contract. A hit reflects with probability p_reflect (else it transmits), and a reflection is diffuse
// (Lambert) with probability p_diffuse (else specular). The probabilities are band means, fixed per
// material, and each event's per-band weight keeps every band unbiased for them:
// E[e_b'] = e_b·(p_r·(1 − α_b)/p_r + p_t·τ_b/p_t) = e_b·((1 − α_b) + τ_b), and likewise for the split of a
// reflection into Lambert (s_b/p_s) and specular ((1 − s_b)/(1 − p_s)) parts. Fixed probabilities cost no
// reduction or division per bounce (the tracer's hot path). Units: α, s, τ are energy fractions; directions
// are unit vectors in the room's frame. Immutable after makeMaterials; thread-safe to share.
#include <vector>

#include "diffray/core/bands.h"
#include "diffray/core/math.h"
#include "diffray/room/room.h"

namespace diffray::transport {

struct MaterialTable {
  std::vector<double> p_reflect, p_diffuse;
  /// Per-band weights of the three events: w_diffuse = (1 − α_b)·s_b/(p_r·p_s), w_specular =
  /// (1 − α_b)(1 − s_b)/(p_r(1 − p_s)), w_transmit = τ_b/(1 − p_r); 0 for an event that cannot happen.
  std::vector<core::BandArray> w_transmit, w_diffuse, w_specular;
  std::vector<char> opening;  ///< τ = 1 in every band: a hole, not a surface (never an event)
  std::vector<char> absorbing;  ///< nothing reflected or transmitted in any band
};

/// The table of every material of `room` (indexed as room.materials), for its bands.
MaterialTable makeMaterials(const room::Room& room);

/// A unit vector with the cosine-weighted (Lambert) density cos θ/π about the unit normal n, from two
/// uniforms in [0, 1): cos²θ = 1 − u1 and the azimuth 2π·u2 about n.
core::Vec3 sampleLambert(const core::Vec3& n, double u1, double u2);

}  // namespace diffray::transport
