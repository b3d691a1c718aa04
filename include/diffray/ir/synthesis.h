#pragma once
// Impulse response synthesis from an EnergyResponse (a Poisson Dirac sequence of rate min(4πc³t²/V, 10⁴ s⁻¹), the
// reflection density of Kuttruff, "Room Acoustics", with random signs, weighted per band by √E_band).
//
// Contract. The output p (sample 0 at emission, sample_rate_hz) follows the convention that Σ p_b[n]² over
// a span is the energy (J/m²) of that span in band b, p_b being band b of p (BandFilter::split, as the
// metrics analyse it), exactly for the arrivals and to within the bias noted for the traced part:
//  * Traced (diffuse) part: a Poisson sequence of Diracs with random signs and rate
//    μ(t) = min(4πc³t²/V, 10⁴ s⁻¹) (the density of image sources at time t in a room of volume V). Per
//    band, each Dirac is weighted by a gain per bin and band-passed by the zero-phase BandFilter; the
//    gains start at √(E_b(bin)/Diracs in its bin) and are corrected (six rounds, each a new filtering
//    of the weighted Diracs) until the band part's Σ² over a window of w_b bins around each bin equals the
//    histogram's energy over that window; w_b spans 2 cycles of the band's bandwidth (w = 1, i.e. bin by
//    bin as the classic method does, for bands wider than 2/bin_s: 4 and 8 kHz octaves at 1 ms). Why not bin
//    by bin everywhere: a band of bandwidth B cannot hold an envelope finer than ~1/B. Why gains on the
//    Diracs rather than on the filtered signal: the band part stays inside its filter's pass band, so no
//    energy is modulated into the neighbouring bands (synthesis.cpp). The part's energy per window matches
//    to the convergence of the rounds, not to rounding. A bin holding energy in which the Poisson draw put
//    no Dirac gets one at a uniformly drawn time inside it, so that no energy is lost where the rate is
//    low (the first milliseconds). Negative bin energies (signed-energy noise) are synthesised as zero.
//    The bands' analysed energies (p_b) exceed what the parts were matched to by 3–10 % from 125 Hz to
//    2 kHz and fall short by ~7 % at 63 Hz on smooth decays (a band also holds its neighbours' parts in
//    its crossovers); matching the analysed energies jointly fixed that for octaves but made third-octave
//    responses' metrics agree worse with the histogram's, so it is not done.
//    The traced part is silent before its first bin holding energy (in any band): the zero-phase filters
//    would ring ahead of an abrupt start (up to a sixth of a low band's energy in a decay that starts at
//    once), and the onset, time zero of every metric, would be found early. The gains match what is left.
//  * Arrivals (direct sound, image sources) are placed at their exact delays, fractional ones included:
//    each is built in the frequency domain as Σ_b A_b·W_b(f)·e^{−2πifτ}·e^{−iφ_b} with A_b chosen so that
//    band b of the whole pulse (W_b applied to the sum of its band parts, what an octave analysis sees)
//    carries exactly the arrival's energy in that band (Parseval, a few Jacobi rounds over the
//    neighbouring bands' crossovers). The pulse's broadband Σ p² is then slightly more than the sum of
//    its band energies (the crossovers count in two bands), and a pulse within a low band's ringing time
//    of t = 0 loses the part of it that would lie before the response (at 12 ms, 15 % of its 63 Hz band). The energy model adds
//    arrivals' energies, i.e. treats them as incoherent; pulses that overlap within a band's time
//    resolution (~1/B: 22 ms at 63 Hz; or coincide exactly, as mirror-symmetric image sources do) would
//    otherwise interfere, up to twice or down to none of the summed energy; so do an arrival and the
//    sparse early Diracs of the traced part (at 63 Hz the first 50 ms hold ~2 degrees of freedom: C50 of
//    one realisation swung by up to 7 dB). So, in order of delay, each arrival's band part gets the
//    carrier phase φ_b (envelope unchanged) that makes it orthogonal to what the band already holds (its
//    traced part and the arrivals before it): the band energies then add exactly, as in the histogram. Of
//    the two such phases the one nearer 0 is taken. The energy model carries no phase, so this is a
//    choice the model leaves open, not a loss: the geometry's own phases are not modelled anyway.
//    Arrivals are not in the traced histogram (ir/response.h), so nothing is counted twice.
// Reproducible: the same (response, parameters, seed) gives the same samples. Thread-safe (no shared
// state; FFTW planning is serialised).
#include <cstddef>
#include <cstdint>
#include <vector>

#include "diffray/ir/response.h"

namespace diffray::ir {

/// How the arrivals and the traced part are phased within a band. Orthogonal: as above, so that band energies
/// add exactly in one response. Coherent: every arrival at phase 0 and the traced part as drawn, so that band
/// energies add on average only, but responses synthesized from similar energy responses with the same seed
/// stay alike sample for sample: what crossfading between them needs (the closing door, door/closing.h). The
/// orthogonal phases are picked per response, and of two responses that differ a little one may take the
/// other of the two phases for a band's traced part, which a crossfade between them then cancels at mid-fade.
enum class Phasing { Orthogonal, Coherent };

/// The impulse response, length_s·sample_rate_hz samples. Throws core::InputError for a non-positive or
/// non-finite sample rate, length, volume or speed of sound, or bands above the Nyquist frequency.
/// The synthesis seed of listener `listener` in a run seeded `seed`: each listener's noise differs, and a
/// program given the same seed (diffray ir, the facade, the Python module) gives the same samples.
inline std::uint64_t listenerSeed(std::uint64_t seed, std::size_t listener) {
  return seed + 7919ull * static_cast<std::uint64_t>(listener);
}

std::vector<double> synthesize(const EnergyResponse& response, double sample_rate_hz, double length_s,
                               double volume_m3, double speed_of_sound_m_s, std::uint64_t seed,
                               Phasing phasing = Phasing::Orthogonal);

/// The Poisson Dirac sequence alone (±1 at the sample of each event, events in one sample add up), for
/// `samples` samples from emission: what synthesize() band-passes. Exposed for tests of its rate.
std::vector<double> poissonDiracs(long samples, double sample_rate_hz, double volume_m3,
                                  double speed_of_sound_m_s, std::uint64_t seed);

}  // namespace diffray::ir
