#pragma once
// Inside the spatial syntheses (spatial_synthesis.cpp): the step synthesis.cpp applies to each band part of
// W, done on the band's bins alone. A band part is made from a band spectrum S (on bins [first, first + len)
// of an m-point real DFT, zero elsewhere) as RealFft::inverse(S, samples) (back to time, the response's
// `samples` long) followed by RealFft::forward (to its spectrum again, read on the same bins). That is a
// linear map of S and conj(S) on the band's bins,
//   Z[k'] = (1/m)·Σ_{k∈B} (S[k]·D(k' − k) + conj(S[k])·D(k' + k)),   D(d) = Σ_{j<samples} e^{−2πi·d·j/m},
// a Toeplitz plus a Hankel matrix in the bins (D is the DFT of the truncation window, periodic in m). It is
// applied here by one complex FFT of ~2·len points and its inverse, against the two full-length real FFTs
// of the direct route: the same Z to rounding (~1e-15 of its peak; the kernels' D comes from an FFT of
// the window, not from the closed form, whose sines lose ~m·ε near d ≈ m). A bin at m/2 carries Re(S)
// once, as the real inverse transform reads it; bin 0 is never in a band (BandGains::first ≥ 1).
#include <complex>
#include <vector>

namespace diffray::ir::detail {

/// The DFT of the truncation window, D(k) for k = 0 … m/2 (the rest by D(m − k) = conj(D(k))): what
/// BandRefilter is built from. One per (m, samples), shared read-only by every band.
std::vector<std::complex<double>> truncationWindowSpectrum(int m, long samples);

/// The refilter of one band (bins [first, first + len) of an m-point real DFT) for the window's spectrum
/// `window` (truncationWindowSpectrum(m, samples)). Its own FFTW plans and buffer: not thread-safe, one per
/// thread; planning and destruction hold core::fftwPlannerMutex().
class BandRefilter {
 public:
  BandRefilter(const std::vector<std::complex<double>>& window, int m, int first, int len);
  ~BandRefilter();
  BandRefilter(const BandRefilter&) = delete;
  BandRefilter& operator=(const BandRefilter&) = delete;

  /// z[j] = Z[first + j] of the band spectrum s[j] = S[first + j], j < len (s and z must not overlap).
  void apply(const std::complex<double>* s, std::complex<double>* z);

 private:
  int m_, first_, len_, size_;  ///< size_: the complex FFT's length, ≥ 2·len − 1
  std::vector<std::complex<double>> toeplitz_, hankel_;  ///< the kernels' spectra, scaled by 1/(m·size)
  void* buffer_ = nullptr;   ///< fftw_complex[size_]
  void* forward_ = nullptr;  ///< in place on buffer_
  void* inverse_ = nullptr;
};

}  // namespace diffray::ir::detail
