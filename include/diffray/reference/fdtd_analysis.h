#pragma once
// Band analysis of the FDTD wave reference's recordings (fdtd.h): a zero-phase band-pass by FFT and the
// energy histogram of a band-passed pressure signal.
//
// bandPass: the signal zero-padded to a fast FFT length of at least 1.25× its own (so that the filter's
// tails wrap around onto padding, not onto the signal), each FFT bin multiplied by bandGain, transformed
// back and cut to the input's length. bandGain is 1 inside the band and 0 outside, with smooth
// power-complementary transitions over ±1/6 octave about each edge: G_lo(f) = sin(π/2·S(x)), S(x) = x −
// sin(2πx)/(2π), x the position of f across [edge·2^(−1/6), edge·2^(1/6)] in log frequency, and
// G = G_lo(f)·√(1 − G_hi(f)²), so that the energies of adjacent octaves add up to the total and the time
// response decays as 1/t³ (a brick wall's sinc tails fall as 1/t only: −47 dB 0.2 s after the direct sound
// of a 500 Hz octave, a false noise floor for T30).
// energyHistogram: Σ x_n²·dt over the samples whose time n·dt − t0 falls in each bin [k·bin, (k+1)·bin);
// samples before t0 are dropped. FFTW plans are made under core::fftwPlannerMutex(). Thread-safe.
#include <vector>

namespace diffray::reference {

/// Half-width (octaves) of bandGain's transitions.
inline constexpr double kBandTransitionOctaves = 1.0 / 6.0;
/// The band-pass gain at f for the band [f_lo, f_hi] (header).
double bandGain(double f_hz, double f_lo_hz, double f_hi_hz);

std::vector<double> bandPass(const std::vector<double>& x, double dt_s, double f_lo_hz, double f_hi_hz);

std::vector<double> energyHistogram(const std::vector<double>& x, double dt_s, double t0_s, double bin_s, int bins);

}  // namespace diffray::reference
