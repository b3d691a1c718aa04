#include "diffray/ir/band_filter.h"

#include <fftw3.h>

#include <algorithm>
#include <cmath>
#include <deque>
#include <mutex>

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include "diffray/core/error.h"
#include "diffray/core/fftw_planner.h"
#include "diffray/core/math.h"

namespace diffray::ir {

namespace {

// Above this FFT length something is wrong with the input (2^28 doubles = 2 GiB per buffer).
constexpr long kMaxFftLength = 1L << 28;

/// 1 below e − h, 0 above e + h, a raised cosine in between (x, e, h in log10 f).
double fallAt(double x, double e, double h) {
  if (x <= e - h) return 1.0;
  if (x >= e + h) return 0.0;
  return 0.5 * (1.0 + std::cos(core::kPi * (x - e + h) / (2.0 * h)));
}

// FFTW computes a transform size's twiddle factors when a plan of that size is made and frees them with the
// last plan that uses them: planning a size no live plan has takes ~4 ms at 190512 points (mostly those
// trigonometric tables), against ~0.1 ms while one is alive. The IR synthesis, the metrics and the spatial
// syntheses make their RealFft objects afresh per listener, so a pair of plans of each of the last
// kKeptSizes sizes planned stays alive to hold the tables (never executed: the buffers they were planned
// on are not theirs to use). Called with core::fftwPlannerMutex() held.
constexpr std::size_t kKeptSizes = 8;

void keepTwiddles(int n, double* real, fftw_complex* spectrum) {
  struct Kept {
    int n;
    fftw_plan forward, inverse;
  };
  static auto* kept = new std::deque<Kept>();  // for the process's life
  if (std::any_of(kept->begin(), kept->end(), [n](const Kept& k) { return k.n == n; })) return;
  kept->push_back({n, fftw_plan_dft_r2c_1d(n, real, spectrum, FFTW_ESTIMATE), fftw_plan_dft_c2r_1d(n, spectrum, real, FFTW_ESTIMATE)});
  if (kept->size() > kKeptSizes) {
    fftw_destroy_plan(kept->front().forward);
    fftw_destroy_plan(kept->front().inverse);
    kept->pop_front();
  }
}

}  // namespace

RealFft::RealFft(int n) : n_(n) {
  DIFFRAY_CHECK(n >= 2);
  real_ = fftw_alloc_real(static_cast<size_t>(n));
  auto* spectrum = fftw_alloc_complex(static_cast<size_t>(n / 2 + 1));
  complex_ = spectrum;
  DIFFRAY_CHECK(real_ != nullptr && spectrum != nullptr);
  std::lock_guard<std::mutex> lock(core::fftwPlannerMutex());
  // FFTW_ESTIMATE leaves the buffers alone while planning; the plans are reused for every execute.
  forward_plan_ = fftw_plan_dft_r2c_1d(n, real_, spectrum, FFTW_ESTIMATE);
  inverse_plan_ = fftw_plan_dft_c2r_1d(n, spectrum, real_, FFTW_ESTIMATE);
  DIFFRAY_CHECK(forward_plan_ != nullptr && inverse_plan_ != nullptr);
  keepTwiddles(n, real_, spectrum);
}

RealFft::~RealFft() {
  std::lock_guard<std::mutex> lock(core::fftwPlannerMutex());
  fftw_destroy_plan(static_cast<fftw_plan>(forward_plan_));
  fftw_destroy_plan(static_cast<fftw_plan>(inverse_plan_));
  fftw_free(real_);
  fftw_free(complex_);
}

void RealFft::forward(const std::vector<double>& x, std::vector<std::complex<double>>& spectrum) {
  const size_t n = std::min(x.size(), static_cast<size_t>(n_));
  std::copy(x.begin(), x.begin() + static_cast<long>(n), real_);
  std::fill(real_ + n, real_ + n_, 0.0);
  fftw_execute(static_cast<fftw_plan>(forward_plan_));
  const auto* c = reinterpret_cast<const std::complex<double>*>(complex_);  // layout-compatible
  spectrum.assign(c, c + bins());
}

std::complex<double>* RealFft::spectrum() {
  return reinterpret_cast<std::complex<double>*>(complex_);  // layout-compatible
}

void RealFft::forwardInput() {
  fftw_execute(static_cast<fftw_plan>(forward_plan_));  // an out-of-place r2c keeps its input
}

void RealFft::inverseSpectrum() {
  fftw_execute(static_cast<fftw_plan>(inverse_plan_));
}

std::vector<double> RealFft::inverse(const std::vector<std::complex<double>>& spectrum, long count) {
  std::vector<double> out;
  inverse(spectrum, count, out);
  return out;
}

void RealFft::inverse(const std::vector<std::complex<double>>& spectrum, long count, std::vector<double>& out) {
  DIFFRAY_CHECK(static_cast<int>(spectrum.size()) == bins() && count >= 0 && count <= n_);
  std::copy(spectrum.begin(), spectrum.end(), reinterpret_cast<std::complex<double>*>(complex_));
  fftw_execute(static_cast<fftw_plan>(inverse_plan_));  // c2r overwrites its input: hence the copy
  out.assign(real_, real_ + count);
  const double scale = 1.0 / n_;
  for (double& v : out) v *= scale;
}

int fastFftLength(long n) {
  if (n < 2) return 2;
  if (n > kMaxFftLength) throw core::InputError("FFT", "signal too long (" + std::to_string(n) + " samples)");
  for (long m = n;; ++m) {
    long r = m;
    for (long p : {2L, 3L, 5L, 7L})
      while (r % p == 0) r /= p;
    if (r == 1) return static_cast<int>(m);
  }
}

BandFilter::BandFilter(const core::Bands& bands, double sample_rate_hz, double crossover, double max_transition_hz)
    : bands_(bands), fs_(sample_rate_hz) {
  core::requirePositive("sample rate", sample_rate_hz);
  if (!(crossover > 0.0 && crossover <= 1.0)) throw core::InputError("band filter", "crossover must lie in (0, 1]");
  core::requirePositive("band filter: transition width", max_transition_hz);
  const int nb = bands.size();
  DIFFRAY_CHECK(nb >= 1);
  for (int b = 0; b < nb; ++b) {
    edge_log_.push_back(std::log10(bands.lowerHz(b)));
    if (b > 0 && std::abs(std::log10(bands.upperHz(b - 1)) - edge_log_.back()) > 1e-9)
      throw core::InputError("bands", "band " + bands.label(b) + " Hz does not start where the band below ends");
  }
  edge_log_.push_back(std::log10(bands.upperHz(nb - 1)));
  // An edge's crossover may span at most half of each band beside it, so crossovers never overlap.
  for (int e = 0; e <= nb; ++e) {
    const double below = e > 0 ? edge_log_[e] - edge_log_[e - 1] : 1e300;
    const double above = e < nb ? edge_log_[e + 1] - edge_log_[e] : 1e300;
    // The transition spans [e·10^−h, e·10^h], 2·sinh(h·ln10)·e wide in Hz: at most max_transition_hz.
    const double edge_hz = std::pow(10.0, edge_log_[e]);
    const double h_hz = std::asinh(0.5 * max_transition_hz / edge_hz) / std::log(10.0);
    half_log_.push_back(std::min(crossover * 0.5 * std::min(below, above), h_hz));
  }
  if (std::pow(10.0, edge_log_[nb] + half_log_[nb]) >= 0.5 * fs_)
    throw core::InputError("bands", "band " + bands.label(nb - 1) + " Hz reaches the Nyquist frequency at " +
                                        std::to_string(fs_) + " Hz sampling");
}

double BandFilter::gain(int band, double freq_hz) const {
  if (!(freq_hz > 0.0)) return 0.0;
  const double x = std::log10(freq_hz);
  const double rise = 1.0 - fallAt(x, edge_log_[band], half_log_[band]);
  return rise * fallAt(x, edge_log_[band + 1], half_log_[band + 1]);
}

double BandFilter::coveredLowHz() const { return std::pow(10.0, edge_log_.front() + half_log_.front()); }
double BandFilter::coveredHighHz() const { return std::pow(10.0, edge_log_.back() - half_log_.back()); }

long BandFilter::ringSamples() const {
  long longest = 0;
  for (int b = 0; b < bands_.size(); ++b) longest = std::max(longest, ringSamples(b));
  return longest;
}

long BandFilter::ringSamples(int band) const {
  DIFFRAY_CHECK(band >= 0 && band < bands_.size());
  double narrowest_hz = 1e300;
  for (int e = band; e <= band + 1; ++e)  // edge b is band b's lower edge, edge b + 1 its upper one
    narrowest_hz = std::min(narrowest_hz, std::pow(10.0, edge_log_[e] + half_log_[e]) -
                                              std::pow(10.0, edge_log_[e] - half_log_[e]));
  // A raised-cosine crossover Δf wide gives filter tails that fall as 1/t³ beyond ~1/Δf: at 6/Δf they
  // are far below anything the metrics resolve.
  return static_cast<long>(std::ceil(6.0 * fs_ / narrowest_hz));
}

int BandFilter::fftLengthFor(long samples) const { return fastFftLength(samples + ringSamples()); }

BandGains BandFilter::gains(int band, int fft_length) const {
  DIFFRAY_CHECK(band >= 0 && band < bands_.size() && fft_length >= 2);
  const double df = fs_ / fft_length;
  const double lo_hz = std::pow(10.0, edge_log_[band] - half_log_[band]);
  const double hi_hz = std::pow(10.0, edge_log_[band + 1] + half_log_[band + 1]);
  BandGains g;
  g.first = std::max(1, static_cast<int>(std::floor(lo_hz / df)));
  const int last = std::min(fft_length / 2, static_cast<int>(std::ceil(hi_hz / df)));
  for (int k = g.first; k <= last; ++k) g.w.push_back(gain(band, k * df));
  return g;
}

std::vector<std::vector<double>> BandFilter::split(const std::vector<double>& x) const {
  const int m = fftLengthFor(static_cast<long>(x.size()));
  std::vector<std::complex<double>> spectrum;
  RealFft(m).forward(x, spectrum);
  // Per thread: an FFT and a band spectrum, zero but on the band last written (cleared after use).
  struct Work {
    RealFft fft;
    std::vector<std::complex<double>> band_spectrum;
    explicit Work(int size) : fft(size), band_spectrum(static_cast<size_t>(size / 2 + 1)) {}
  };
  tbb::enumerable_thread_specific<Work> works(m);
  std::vector<std::vector<double>> out(static_cast<size_t>(bands_.size()));
  tbb::parallel_for(0, bands_.size(), [&](int b) {
    Work& work = works.local();
    const BandGains g = gains(b, m);
    for (size_t i = 0; i < g.w.size(); ++i) work.band_spectrum[g.first + i] = g.w[i] * spectrum[g.first + i];
    work.fft.inverse(work.band_spectrum, static_cast<long>(x.size()), out[static_cast<size_t>(b)]);
    std::fill(work.band_spectrum.begin() + g.first, work.band_spectrum.begin() + g.first + static_cast<long>(g.w.size()),
              std::complex<double>(0.0, 0.0));
  });
  return out;
}

std::vector<double> withLeadAndNoMean(const std::vector<double>& x, long lead) {
  double mean = 0.0;
  for (double v : x) mean += v;
  mean /= static_cast<double>(std::max<std::size_t>(1, x.size()));
  std::vector<double> out(static_cast<std::size_t>(lead) + x.size(), 0.0);
  for (std::size_t n = 0; n < x.size(); ++n) out[static_cast<std::size_t>(lead) + n] = x[n] - mean;
  return out;
}

}  // namespace diffray::ir
