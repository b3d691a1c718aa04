#include "band_refilter.h"

#include <fftw3.h>

#include <algorithm>
#include <cmath>
#include <mutex>

#include "diffray/core/error.h"
#include "diffray/core/fftw_planner.h"
#include "diffray/core/math.h"
#include "diffray/ir/band_filter.h"

namespace diffray::ir::detail {

std::vector<std::complex<double>> truncationWindowSpectrum(int m, long samples) {
  DIFFRAY_CHECK(samples >= 0 && samples <= m);
  RealFft fft(m);
  std::vector<std::complex<double>> spectrum;
  fft.forward(std::vector<double>(static_cast<std::size_t>(samples), 1.0), spectrum);
  return spectrum;
}

BandRefilter::BandRefilter(const std::vector<std::complex<double>>& window, int m, int first, int len)
    : m_(m), first_(first), len_(len), size_(fastFftLength(2L * len - 1)) {
  DIFFRAY_CHECK(static_cast<int>(window.size()) == m / 2 + 1 && first >= 1 && len >= 1 && first + len - 1 <= m / 2);
  const auto at = [&](long d) {  // D(d), periodic in m, Hermitian
    const long k = ((d % m) + m) % m;
    return k <= m / 2 ? window[static_cast<std::size_t>(k)] : std::conj(window[static_cast<std::size_t>(m - k)]);
  };
  const auto size = static_cast<std::size_t>(size_);
  buffer_ = fftw_alloc_complex(size);
  DIFFRAY_CHECK(buffer_ != nullptr);
  auto* buffer = static_cast<fftw_complex*>(buffer_);
  {
    std::lock_guard<std::mutex> lock(core::fftwPlannerMutex());
    // FFTW_ESTIMATE leaves the buffer alone while planning.
    forward_ = fftw_plan_dft_1d(size_, buffer, buffer, FFTW_FORWARD, FFTW_ESTIMATE);
    inverse_ = fftw_plan_dft_1d(size_, buffer, buffer, FFTW_BACKWARD, FFTW_ESTIMATE);
  }
  DIFFRAY_CHECK(forward_ != nullptr && inverse_ != nullptr);
  auto* data = reinterpret_cast<std::complex<double>*>(buffer);
  // The kernels, t < 2·len − 1: the Toeplitz one D(t − (len − 1)), the Hankel one D(2·first + t); their
  // results both land at t = len − 1 + j for bin first + j. The Hankel kernel is applied to conj(S)
  // reversed, whose spectrum is e^{−2πi·p·(len − 1)/size}·conj(X[p]) for X the spectrum of S: that phase
  // goes into its kernel.
  const double scale = 1.0 / (static_cast<double>(m) * size_);
  const auto spectrumOf = [&](long offset) {
    std::fill(data, data + size_, std::complex<double>(0.0, 0.0));
    for (long t = 0; t < 2L * len - 1; ++t) data[t] = at(offset + t);
    fftw_execute(static_cast<fftw_plan>(forward_));
    return std::vector<std::complex<double>>(data, data + size_);
  };
  toeplitz_ = spectrumOf(-(len - 1L));
  hankel_ = spectrumOf(2L * first);
  for (long p = 0; p < size_; ++p) {
    toeplitz_[static_cast<std::size_t>(p)] *= scale;
    const long turns = (p * (len - 1L)) % size_;  // exact, so the phase is exact to rounding for any size
    hankel_[static_cast<std::size_t>(p)] *= scale * std::polar(1.0, -core::kTwoPi * static_cast<double>(turns) / size_);
  }
}

BandRefilter::~BandRefilter() {
  std::lock_guard<std::mutex> lock(core::fftwPlannerMutex());
  fftw_destroy_plan(static_cast<fftw_plan>(forward_));
  fftw_destroy_plan(static_cast<fftw_plan>(inverse_));
  fftw_free(buffer_);
}

void BandRefilter::apply(const std::complex<double>* s, std::complex<double>* z) {
  auto* data = reinterpret_cast<std::complex<double>*>(buffer_);
  std::copy(s, s + len_, data);
  if (m_ % 2 == 0 && first_ + len_ - 1 == m_ / 2)  // the real inverse reads Re(S) there, once
    data[len_ - 1] = 0.5 * std::real(data[len_ - 1]);
  std::fill(data + len_, data + size_, std::complex<double>(0.0, 0.0));
  fftw_execute(static_cast<fftw_plan>(forward_));
  for (int p = 0; p < size_; ++p) data[p] = data[p] * toeplitz_[static_cast<std::size_t>(p)] + std::conj(data[p]) * hankel_[static_cast<std::size_t>(p)];
  fftw_execute(static_cast<fftw_plan>(inverse_));
  std::copy(data + len_ - 1, data + 2 * len_ - 1, z);
}

}  // namespace diffray::ir::detail
