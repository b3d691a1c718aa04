#pragma once
// Zero-phase band splitting by FFT (FFTW r2c/c2r), for the room metrics and the IR synthesis.
//
// Contract. Band b's gain W_b(f) is real and non-negative (zero phase: no group delay, so band signals line
// up in time with the input and with energy histograms). On a log-frequency axis x = log10 f each band edge
// e carries a raised-cosine crossover of half-width h: the band below falls as ½(1 + cos(π(x − e + h)/2h))
// over [e − h, e + h] while the band above rises as 1 minus that, so adjacent bands are amplitude
// complementary and Σ_b W_b(f) = 1 exactly on [coveredLowHz, coveredHighHz] (the outer edges roll off with
// the same shape). h is the smaller of crossover × the band's half-width in log f (0 < crossover ≤ 1; 0.5
// by default) and a transition max_transition_hz wide in Hz (40 Hz by default). Why narrow in Hz: adjacent
// bands overlap only in their crossovers, and a band that decays more slowly than its neighbour leaks
// into it there (with half-band crossovers ∫W_b²W_{b+1}² is ~−12 dB of a band: T30 at 8 kHz read 20 %
// long behind a 4 kHz band decaying twice as slowly); 40 Hz at 5.6 kHz is ~−30 dB. Why not narrower: a
// transition Δf wide rings for ~1/Δf (25 ms at 40 Hz), which smears the early metrics. Below ~180 Hz the
// half-band limit is the narrower one (15 Hz at the 63 Hz band's lower edge). Filtering is a product of
// spectra on a zero-padded FFT whose length keeps the filters' circular wrap-around negligible
// (fftLengthFor); outputs have the input's length.
// Thread-safety: a BandFilter is immutable and may be shared; RealFft objects are one per thread. FFTW plan
// creation and destruction hold core::fftwPlannerMutex().
#include <complex>
#include <cstddef>
#include <vector>

#include "diffray/core/bands.h"

namespace diffray::ir {

/// A real DFT of fixed length n with its own FFTW plans and buffers. Not thread-safe (one per thread).
class RealFft {
 public:
  explicit RealFft(int n);
  ~RealFft();
  RealFft(const RealFft&) = delete;
  RealFft& operator=(const RealFft&) = delete;

  int size() const { return n_; }
  int bins() const { return n_ / 2 + 1; }  ///< spectrum length: k = 0 … n/2, frequency k·fs/n
  /// spectrum[k] = Σ_j x[j]·e^{−2πi·jk/n}, x zero-padded (or truncated) to n.
  void forward(const std::vector<double>& x, std::vector<std::complex<double>>& spectrum);
  /// The inverse of forward (scaled by 1/n); returns the first `count` samples.
  std::vector<double> inverse(const std::vector<std::complex<double>>& spectrum, long count);
  /// The same into `out` (resized to count; no allocation once it has the capacity).
  void inverse(const std::vector<std::complex<double>>& spectrum, long count, std::vector<double>& out);
  /// The transforms on the object's own buffers, for callers that build a signal or a spectrum in place
  /// (no copy in or out): input() holds size() samples, spectrum() bins() values, both left as the last
  /// transform left them. forwardInput(): spectrum() = the DFT of input(), input() kept.
  /// inverseSpectrum(): input() = size() · the inverse of spectrum() (unscaled), spectrum() overwritten.
  double* input() { return real_; }
  std::complex<double>* spectrum();
  void forwardInput();
  void inverseSpectrum();

 private:
  int n_;
  double* real_ = nullptr;
  void* complex_ = nullptr;  ///< fftw_complex[n/2 + 1]
  void* forward_plan_ = nullptr;
  void* inverse_plan_ = nullptr;
};

/// x with its mean removed and `lead` zeros in front: how a response is prepared for the zero-phase band
/// filters (a pre-delay of their ringing time, so nothing ahead of an arrival at sample 0 is lost, and no
/// DC offset whose steps at both ends would read as a low-frequency noise floor).
std::vector<double> withLeadAndNoMean(const std::vector<double>& x, long lead);

/// The smallest length ≥ n whose factors are 2, 3, 5 and 7 only (fast for FFTW).
int fastFftLength(long n);

/// A band's gains on the spectrum bins of one FFT length: W_b(k·fs/n) for k = first … first + w.size() − 1,
/// zero elsewhere.
struct BandGains {
  int first = 0;
  std::vector<double> w;
};

class BandFilter {
 public:
  static constexpr double kDefaultTransitionHz = 40.0;
  /// Throws core::InputError if the bands are not contiguous, the sample rate is not positive, the top
  /// crossover reaches the Nyquist frequency, crossover is outside (0, 1] or max_transition_hz ≤ 0.
  BandFilter(const core::Bands& bands, double sample_rate_hz, double crossover = 0.5,
             double max_transition_hz = kDefaultTransitionHz);

  const core::Bands& bands() const { return bands_; }
  double sampleRateHz() const { return fs_; }
  /// W_b(freq_hz).
  double gain(int band, double freq_hz) const;
  /// Where the bands sum exactly to 1.
  double coveredLowHz() const;
  double coveredHighHz() const;
  /// FFT length for filtering `samples` samples: the input plus enough zeros for the filters' tails
  /// (6 / the narrowest crossover width in Hz), rounded up to a fast length.
  int fftLengthFor(long samples) const;
  /// How far (samples) the filters ring on either side of an impulse: 6 / the narrowest crossover width in
  /// Hz, beyond which their tails are negligible (what fftLengthFor pads with).
  long ringSamples() const;
  /// The same for band `band` alone (its two crossovers): the largest of these is ringSamples().
  long ringSamples(int band) const;
  BandGains gains(int band, int fft_length) const;

  /// Every band of x: out[b] has x's length. The bands go back to time in parallel (TBB), each alone.
  std::vector<std::vector<double>> split(const std::vector<double>& x) const;

 private:
  core::Bands bands_;
  double fs_;
  std::vector<double> edge_log_;  ///< log10 of the band edges: edge b is band b's lower edge
  std::vector<double> half_log_;  ///< crossover half-width at each edge (log10 units)
};

}  // namespace diffray::ir
