#include "diffray/dsp/spectrogram.h"

#include <fftw3.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <mutex>
#include <string>

#include "diffray/core/error.h"
#include "diffray/core/fftw_planner.h"

namespace diffray::dsp {

namespace {

constexpr int kMaxSize = 1 << 20;

/// FFTW buffers and one r2c plan, destroyed (under the planner mutex) when the spectrogram is done.
struct RealFft {
  explicit RealFft(int n) {
    real = fftw_alloc_real(static_cast<size_t>(n));
    spectrum = fftw_alloc_complex(static_cast<size_t>(n / 2 + 1));
    DIFFRAY_CHECK(real != nullptr && spectrum != nullptr);
    std::lock_guard<std::mutex> lock(core::fftwPlannerMutex());
    plan = fftw_plan_dft_r2c_1d(n, real, spectrum, FFTW_ESTIMATE);
    DIFFRAY_CHECK(plan != nullptr);
  }
  ~RealFft() {
    {
      std::lock_guard<std::mutex> lock(core::fftwPlannerMutex());
      fftw_destroy_plan(plan);
    }
    fftw_free(real);
    fftw_free(spectrum);
  }
  RealFft(const RealFft&) = delete;
  RealFft& operator=(const RealFft&) = delete;

  double* real = nullptr;
  fftw_complex* spectrum = nullptr;
  fftw_plan plan = nullptr;
};

}  // namespace

namespace {

/// Frames of `hop` folded by runs of `group` (≥ 1): row r holds, per bin, the loudest of frames
/// [r·group, (r+1)·group), and its time is the mean of their centres.
Spectrogram folded(const float* x, long n, double fs_hz, int window, int hop, long group) {
  const std::string where = "spectrogram";
  core::requirePositive(where + " sample rate", fs_hz);
  if (x == nullptr || n < 1) throw core::InputError(where, "the signal is empty");
  if (window < 8 || window > kMaxSize || window % 2 != 0)
    throw core::InputError(where, "window must be an even number of samples from 8 to " + std::to_string(kMaxSize) +
                                      ", got " + std::to_string(window));
  if (hop < 1 || hop > kMaxSize)
    throw core::InputError(where, "hop must lie between 1 and " + std::to_string(kMaxSize) + " samples, got " +
                                      std::to_string(hop));
  for (long i = 0; i < n; ++i)
    if (!std::isfinite(x[i])) throw core::InputError(where, "sample " + std::to_string(i) + " is not finite");
  const long frames = frameCount(n, window, hop);
  const long rows = (frames + group - 1) / group;
  const int bins = window / 2 + 1;
  core::checkedCount(where + " (frames x bins)", static_cast<double>(rows) * bins, static_cast<double>(1 << 28));

  Spectrogram s;
  s.sample_rate_hz = fs_hz;
  s.window = window;
  s.hop = static_cast<int>(std::min<long>(group * hop, 1L << 30));
  for (int k = 0; k < bins; ++k) s.freq_hz.push_back(k * fs_hz / window);
  s.time_s.resize(static_cast<size_t>(rows));
  s.magnitude_db.assign(static_cast<size_t>(rows) * static_cast<size_t>(bins), static_cast<float>(Spectrogram::kFloorDb));

  std::vector<double> hann(static_cast<size_t>(window));
  for (int m = 0; m < window; ++m) hann[static_cast<size_t>(m)] = 0.5 * (1.0 - std::cos(2.0 * M_PI * m / window));
  const double amplitude_scale = 2.0 / (0.5 * window);  // 2/Σw: Σw = window/2 for the periodic Hann window
  const double floor_amplitude = std::pow(10.0, Spectrogram::kFloorDb / 20.0);

  RealFft fft(window);
  for (long i = 0; i < frames; ++i) {
    const long start = i * hop;
    for (int m = 0; m < window; ++m) {
      const long t = start + m;
      fft.real[m] = t < n ? hann[static_cast<size_t>(m)] * x[t] : 0.0;
    }
    fftw_execute(fft.plan);
    const long r = i / group;
    float* row = s.magnitude_db.data() + static_cast<size_t>(r) * static_cast<size_t>(bins);
    for (int k = 0; k < bins; ++k) {
      const double amplitude = std::hypot(fft.spectrum[k][0], fft.spectrum[k][1]) * amplitude_scale;
      row[k] = std::max(row[k], static_cast<float>(20.0 * std::log10(std::max(amplitude, floor_amplitude))));
    }
  }
  for (long r = 0; r < rows; ++r) {
    const long first = r * group, last = std::min(first + group, frames) - 1;
    s.time_s[static_cast<size_t>(r)] = (0.5 * static_cast<double>(first + last) * hop + 0.5 * window) / fs_hz;
  }
  return s;
}

}  // namespace

long frameCount(long n, int window, int hop) { return n <= window ? 1 : 1 + (n - window + hop - 1) / hop; }

Spectrogram spectrogram(const float* x, long n, double fs_hz, int window, int hop) {
  return folded(x, n, fs_hz, window, hop, 1);
}

Spectrogram spectrogramPeaks(const float* x, long n, double fs_hz, int window, int hop, long max_frames) {
  if (max_frames < 1) throw core::InputError("spectrogram", "at least one frame must be kept");
  const long frames = n >= 1 && window >= 1 && hop >= 1 ? frameCount(n, window, hop) : 1;
  return folded(x, n, fs_hz, window, hop, (frames + max_frames - 1) / max_frames);
}

}  // namespace diffray::dsp
