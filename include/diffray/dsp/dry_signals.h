#pragma once
// Dry test signals made locally: the exponential sine sweep of Farina (AES 108, 2000) and
// a click train. Samples are float, peak `amplitude` (linear, 1 = full scale), at `rate_hz`; sample n sits
// at time t = n / rate_hz. Pure functions; calls may run concurrently.
//  * Sweep from f1 to f2 over T seconds, L = ln(f2/f1): x(t) = A·w(t)·sin φ(t) with
//    φ(t) = 2π·f1·T/L·(e^{tL/T} − 1), so the instantaneous frequency φ'(t)/2π = f1·e^{tL/T} rises from f1 at
//    t = 0 to f2 at t = T, one octave in equal time. w(t) is a raised-cosine fade-in over the first `fade_s`
//    seconds and a fade-out over the last (each at most T/4), 1 in between, so the sweep starts and ends
//    without a click.
//  * Click train: clicks start at t = 0 and every `interval_s` after, at sample round(k·interval_s·rate_hz)
//    while inside the signal. A click of width 1 is one sample of value A; a width w > 1 is a Hann window of
//    w samples, sin²(π(j+1)/(w+1)) for j = 0 … w−1, starting at the click's sample and scaled so its largest
//    sample is A (the middle one for w odd, the two middle ones for w even).
#include <vector>

namespace diffray::dsp {

struct SweepSpec {
  double rate_hz = 48000.0;
  double duration_s = 10.0;
  double from_hz = 20.0;
  double to_hz = 20000.0;
  double amplitude = 0.5;
  double fade_s = 0.01;
};

/// The sweep's phase φ(t) in radians (the formula above), for t in [0, duration_s].
double sweepPhase(const SweepSpec& spec, double t_s);

/// round(duration_s · rate_hz) samples of the sweep. Throws core::InputError for a non-positive or non-finite
/// rate, duration or fade < 0, f1 ≤ 0, f1 ≥ f2, f2 above rate_hz / 2, or an amplitude outside (0, 1].
std::vector<float> exponentialSweep(const SweepSpec& spec);

struct ClickSpec {
  double rate_hz = 48000.0;
  double duration_s = 5.0;
  double interval_s = 0.5;
  double amplitude = 0.5;
  int width_samples = 1;
};

/// Sample index of click k (round(k · interval_s · rate_hz)).
long clickSample(const ClickSpec& spec, long k);

/// round(duration_s · rate_hz) samples of the click train. Throws core::InputError for a non-positive or
/// non-finite rate, duration or interval, an interval shorter than the click width, a width < 1, or an
/// amplitude outside (0, 1].
std::vector<float> clickTrain(const ClickSpec& spec);

}  // namespace diffray::dsp
