#pragma once
// Sample-rate conversion through libsamplerate (Debian's libsamplerate0, SRC_SINC_BEST_QUALITY: band-limited
// sinc interpolation, about 97 dB of stopband rejection). A signal resampler: the samples of the underlying
// band-limited waveform are kept, so a sine of amplitude A at f Hz stays a sine of amplitude A at f Hz (below
// both Nyquist frequencies). To keep a *filter's* frequency response instead (an impulse response whose
// samples are convolved with a signal), resampleImpulseResponse() scales the result by from_hz / to_hz:
// y[n] = Σ h[k]·x[n−k] approximates ∫h(τ)x(t−τ)dτ with h[k] = h(k/fs)/fs, so the samples carry a 1/fs.
// Whole buffers in memory, meant for impulse responses and generated signals, not hours of audio.
// Pure function; calls may run concurrently.
#include <vector>

namespace diffray::dsp {

/// Resamples `interleaved` (frames × `channels` samples, interleaved) from `from_hz` to `to_hz`. The result
/// has exactly round(frames · to_hz / from_hz) frames (at least 1 for a non-empty input), aligned so that
/// output frame j sits at time j / to_hz like input frame i at i / from_hz. Equal rates return a copy.
/// Throws core::InputError for channels < 1, a sample count not a multiple of `channels`, a non-finite or
/// non-positive rate, or a ratio to_hz / from_hz outside libsamplerate's [1/256, 256].
std::vector<float> resample(const std::vector<float>& interleaved, int channels, double from_hz, double to_hz);

/// An impulse response moved to another rate as a *filter*: resample() scaled by from_hz / to_hz, so that its
/// frequency response (below both Nyquist frequencies) is unchanged: Σ h stays the DC gain, a Dirac stays a
/// pass-through. Same contract and errors as resample().
std::vector<float> resampleImpulseResponse(const std::vector<float>& interleaved, int channels, double from_hz,
                                           double to_hz);

}  // namespace diffray::dsp
