#pragma once
// Ambisonic and binaural impulse responses synthesized from an EnergyResponse that recorded directions
// (transport::RoomSimulationOptions::directions), from the events of W, the omnidirectional response.
//
// Ambisonics (AmbiX: ACN channel order, SN3D normalisation, spatial/spherical_harmonics.h).
// Contract. Channel 0 (W) is the omnidirectional response of ir::synthesize with the same arguments, sample
// for sample; channel c holds the same events, each weighted by Y_c of its direction in the listener's
// frame (x forward, y left, z up), so every channel shares W's time structure and, per band, the energy
// the directions give it (the mean of Y_c² over the sphere is 1/(2n + 1) in a diffuse field).
//  * Arrivals (direct sound, image sources, UTD paths) carry their exact direction (Arrival::direction):
//    channel c holds Y_c(d)·(the arrival's pulse in W). An arrival without a direction stays in W alone.
//  * The traced part: per band, the Diracs W is built from, each with its own direction drawn from a
//    two-part model of the band's energy vector around its time (Directional Audio Coding, Pulkki, J. Audio
//    Eng. Soc. 55(6), 2007: a directional part from the energy vector's direction and a diffuse part from
//    everywhere): with probability r_E the energy vector's direction u, otherwise a direction drawn
//    uniformly over the sphere, so that the expected energy vector of the Diracs is r_E·u, the traced one.
//    r_E and u are read from the recorded directions summed over the bins within ±max(2 bins, 10 % of the
//    time) of the Dirac's bin (few rays reach a listener in one late bin: a sum over one bin would read
//    r_E near 1 from a handful of rays). Directional Diracs keep W's gains (rescaled per window for the
//    share of W's interference they keep), diffuse ones take one gain per window, so that each channel
//    holds its expected share of W's band energy (spatial_synthesis.cpp, tracedOutputs); every band part
//    is then filtered and turned as W's.
//  Without recorded directions the traced part is diffuse (r_E = 0). Reproducible from `seed` (its own
//  stream for the directions). Thread-safe (no shared state; FFTW planning is serialised).
#include <cstdint>
#include <vector>

#include "diffray/core/math.h"
#include "diffray/ir/response.h"
#include "diffray/ir/synthesis.h"

namespace diffray::spatial {
class Hrtf;
}

namespace diffray::ir {

/// The (order + 1)² channels of the Ambisonic IR, each length_s·sample_rate_hz samples, for a listener whose
/// head frame is (forward, left, up) in world coordinates. Throws core::InputError as synthesize() does, and
/// for an order outside 1…3.
std::vector<std::vector<double>> synthesizeAmbisonic(const EnergyResponse& response, double sample_rate_hz,
                                                     double length_s, double volume_m3, double speed_of_sound_m_s,
                                                     std::uint64_t seed, int order, const core::Vec3& forward,
                                                     const core::Vec3& left, const core::Vec3& up);

/// The binaural impulse response (left, right), each length_s·sample_rate_hz samples, through `hrtf`
/// (prepared at sample_rate_hz) for a listener whose head frame is (forward, left, up). The same events as
/// W, each through the HRIR of the measured direction nearest its own: arrivals at the sample nearest their
/// delay with their band coefficients of W (an arrival without a direction is heard from straight ahead);
/// the traced part's Diracs with the directions and amplitudes of the Ambisonic synthesis (above), each
/// band's Diracs convolved with their HRIRs before the band filter: every reflection of the late part
/// rendered from its own direction, as the spatial decomposition method renders measured responses (Tervo,
/// Pätynen, Kuusinen & Lokki, J. Audio Eng. Soc. 61(1/2), 2013). The HRIRs' diffuse-field normalisation
/// (spatial/hrtf.h) keeps each ear's energy equal to W's on average in a diffuse field. Throws
/// core::InputError as synthesize() does, and for an HRTF set prepared at another rate. `phasing` as
/// synthesize()'s (Coherent for responses a crossfade moves between: the closing door). With `omni` given,
/// it receives the omnidirectional response synthesize() makes with the same arguments (drawn anyway).
std::vector<std::vector<double>> synthesizeBinaural(const EnergyResponse& response, double sample_rate_hz,
                                                    double length_s, double volume_m3, double speed_of_sound_m_s,
                                                    std::uint64_t seed, const spatial::Hrtf& hrtf,
                                                    const core::Vec3& forward, const core::Vec3& left,
                                                    const core::Vec3& up, Phasing phasing = Phasing::Orthogonal,
                                                    std::vector<double>* omni = nullptr);

}  // namespace diffray::ir
