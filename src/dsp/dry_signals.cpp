#include "diffray/dsp/dry_signals.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "diffray/core/error.h"
#include "diffray/core/math.h"

namespace diffray::dsp {

namespace {

using core::kPi;

/// round(duration · rate) samples, refused beyond 2^31 (about 12 h at 48 kHz).
long sampleCount(double rate_hz, double duration_s) {
  core::requirePositive("rate", rate_hz);
  core::requirePositive("duration", duration_s);
  return core::checkedCount("duration", std::round(duration_s * rate_hz), 2147483647.0);
}

void requireAmplitude(double amplitude) {
  if (!(amplitude > 0.0 && amplitude <= 1.0))
    throw core::InputError("level", "the peak must lie in (0, 1] of full scale (at most 0 dBFS)");
}

/// Raised-cosine fade: 0 at u = 0, 1 at u = 1.
double fade(double u) { return 0.5 - 0.5 * std::cos(kPi * std::clamp(u, 0.0, 1.0)); }

}  // namespace

double sweepPhase(const SweepSpec& spec, double t_s) {
  const double l = std::log(spec.to_hz / spec.from_hz);
  return 2.0 * kPi * spec.from_hz * spec.duration_s / l * std::expm1(t_s * l / spec.duration_s);
}

std::vector<float> exponentialSweep(const SweepSpec& spec) {
  const long n = sampleCount(spec.rate_hz, spec.duration_s);
  core::requirePositive("--from", spec.from_hz);
  core::requirePositive("--to", spec.to_hz);
  if (spec.from_hz >= spec.to_hz)
    throw core::InputError("--from", "the start frequency must lie below the end frequency (--to)");
  if (spec.to_hz > spec.rate_hz / 2.0)
    throw core::InputError("--to", std::to_string(spec.to_hz) + " Hz lies above the Nyquist frequency " +
                                       std::to_string(spec.rate_hz / 2.0) + " Hz of the sample rate");
  if (!(spec.fade_s >= 0.0) || !std::isfinite(spec.fade_s)) throw core::InputError("fade", "must be finite and >= 0");
  requireAmplitude(spec.amplitude);
  const double fade_s = std::min(spec.fade_s, spec.duration_s / 4.0);
  std::vector<float> x(static_cast<size_t>(n));
  for (long i = 0; i < n; ++i) {
    const double t = static_cast<double>(i) / spec.rate_hz;
    double w = 1.0;
    if (fade_s > 0.0) w = fade(t / fade_s) * fade((spec.duration_s - t) / fade_s);
    x[static_cast<size_t>(i)] = static_cast<float>(spec.amplitude * w * std::sin(sweepPhase(spec, t)));
  }
  return x;
}

long clickSample(const ClickSpec& spec, long k) {
  return std::lround(static_cast<double>(k) * spec.interval_s * spec.rate_hz);
}

std::vector<float> clickTrain(const ClickSpec& spec) {
  const long n = sampleCount(spec.rate_hz, spec.duration_s);
  core::requirePositive("--interval", spec.interval_s);
  requireAmplitude(spec.amplitude);
  if (spec.width_samples < 1) throw core::InputError("click width", "must be at least one sample");
  if (spec.interval_s * spec.rate_hz < spec.width_samples)
    throw core::InputError("--interval", "is shorter than one click (" + std::to_string(spec.width_samples) +
                                             " samples): the clicks would overlap");
  std::vector<float> x(static_cast<size_t>(n), 0.0f);
  const int w = spec.width_samples;
  // Hann window of w samples, zero-free: sin²(π(j+1)/(w+1)). It reaches 1 in the middle for odd w only; for
  // even w its two middle samples sit half a sample off the peak, so it is divided by its largest sample
  // and every click's peak is `amplitude` whatever the width.
  std::vector<double> shape(static_cast<size_t>(w), 1.0);
  if (w > 1) {
    for (int j = 0; j < w; ++j) shape[static_cast<size_t>(j)] = std::pow(std::sin(kPi * (j + 1) / (w + 1)), 2);
    const double top = *std::max_element(shape.begin(), shape.end());
    for (double& v : shape) v /= top;
  }
  for (long k = 0;; ++k) {
    const long start = clickSample(spec, k);
    if (start >= n) break;
    for (int j = 0; j < w && start + j < n; ++j)
      x[static_cast<size_t>(start + j)] = static_cast<float>(spec.amplitude * shape[static_cast<size_t>(j)]);
  }
  return x;
}

}  // namespace diffray::dsp
