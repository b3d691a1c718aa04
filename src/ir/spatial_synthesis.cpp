#include "diffray/ir/spatial_synthesis.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <functional>

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include "diffray/core/error.h"
#include "diffray/core/parallel.h"
#include "diffray/core/rng.h"
#include "diffray/ir/band_filter.h"
#include "diffray/spatial/hrtf.h"
#include "diffray/spatial/spherical_harmonics.h"
#include "band_refilter.h"
#include "synthesis_plan.h"

namespace diffray::ir {

namespace {

constexpr std::uint64_t kStreamDirections = 2;  // synthesis.cpp uses streams 0 and 1 of the seed
// The window of W's energy match, in cycles of the band's bandwidth (synthesis.cpp).
constexpr double kResolutionCycles = 2.0;

/// Per bin of one band: the energy vector's unit direction and r_E, from the recorded directions summed
/// over ±max(2, 10 % of the bin index) bins (prefix sums).
struct BandDirections {
  std::vector<core::Vec3> u;
  std::vector<double> r;
};

BandDirections bandDirections(const EnergyResponse& response, int band, int bins) {
  BandDirections out;
  out.u.assign(static_cast<std::size_t>(bins), core::Vec3(0, 0, 0));
  out.r.assign(static_cast<std::size_t>(bins), 0.0);
  if (static_cast<int>(response.directions.size()) <= band) return out;
  const auto& e = response.traced[static_cast<std::size_t>(band)];
  const auto& v = response.directions[static_cast<std::size_t>(band)];
  const int n = std::min<int>(bins, static_cast<int>(std::min(e.size(), v.size())));
  std::vector<double> pe(static_cast<std::size_t>(n) + 1, 0.0);
  std::vector<core::Vec3> pv(static_cast<std::size_t>(n) + 1, core::Vec3(0, 0, 0));
  for (int i = 0; i < n; ++i) {
    pe[static_cast<std::size_t>(i) + 1] = pe[static_cast<std::size_t>(i)] + e[static_cast<std::size_t>(i)];
    pv[static_cast<std::size_t>(i) + 1] = pv[static_cast<std::size_t>(i)] + v[static_cast<std::size_t>(i)];
  }
  for (int i = 0; i < n; ++i) {
    const int h = std::max(2, static_cast<int>(0.1 * i));
    const int lo = std::max(0, i - h), hi = std::min(n, i + h + 1);
    const double energy = pe[static_cast<std::size_t>(hi)] - pe[static_cast<std::size_t>(lo)];
    const core::Vec3 vec = pv[static_cast<std::size_t>(hi)] - pv[static_cast<std::size_t>(lo)];
    const double len = vec.norm();
    if (!(energy > 0.0) || !(len > 0.0)) continue;
    out.u[static_cast<std::size_t>(i)] = vec / len;
    out.r[static_cast<std::size_t>(i)] = std::min(1.0, len / energy);
  }
  return out;
}

core::Vec3 uniformDirection(core::Rng& rng) {
  const double z = 1.0 - 2.0 * rng.uniform(), phi = core::kTwoPi * rng.uniform();
  const double s = std::sqrt(std::max(0.0, 1.0 - z * z));
  return {s * std::cos(phi), s * std::sin(phi), z};
}

/// The traced part's Diracs (W's, from the plan) with the draws the bands share: each Dirac's sample and
/// histogram bin, the uniform that decides whether it is directional in a band, and its diffuse direction.
struct DiracDraws {
  std::vector<long> at;
  std::vector<std::size_t> bin_of;
  std::vector<double> pick;
  std::vector<core::Vec3> diffuse;  ///< world coordinates
};

DiracDraws drawDiracs(const detail::SynthesisPlan& plan, std::uint64_t seed) {
  DiracDraws d;
  const std::size_t bins = plan.bin_start.size() - 1;
  for (std::size_t i = 0; i < bins; ++i)
    for (long s = plan.bin_start[i]; s < plan.bin_start[i + 1]; ++s)
      if (plan.diracs[static_cast<std::size_t>(s)] != 0.0) d.at.push_back(s), d.bin_of.push_back(i);
  core::Rng rng(seed, kStreamDirections);
  d.pick.resize(d.at.size());
  d.diffuse.resize(d.at.size());
  for (std::size_t q = 0; q < d.at.size(); ++q) d.pick[q] = rng.uniform(), d.diffuse[q] = uniformDirection(rng);
  return d;
}

/// The `outputs` signals, each the inverse of its spectrum `direct[o]` (all bins; the arrivals, kept whole)
/// plus its traced part, silent before plan.quiet like W's. The traced part: per band (in parallel, each
/// with its thread's FFT; summed in band order, so the same samples for any thread count), W's Diracs with
/// their directions and amplitudes (below), placed by `renderer` into one sequence per output (built in the
/// FFT's own input, one output at a time), each made into a band part as synthesis.cpp makes W's
/// (filtered, back to the response's length, its spectrum on the band's bins: the last two steps by
/// band_refilter.h) and turned as W's traced part was. The outputs go back to time in parallel, each alone.
///
/// Renderer: `Key key(const core::Vec3& d) const` prepares a direction in the listener's frame (once per
/// Dirac for the diffuse directions, shared by the bands; once per band and bin for the energy vector's),
/// `void place(const Key&, double amp, long at, std::size_t output, double* x, std::size_t n) const` writes
/// a Dirac of amplitude amp at sample `at` into output `output`'s sequence x (n samples; it may assign or
/// add); it is called from several threads at once.
//
// Directions: with probability r_E the band's energy vector's direction u around the Dirac's time, otherwise
// the Dirac's diffuse direction; one uniform and one diffuse direction per Dirac, shared by the bands, so
// that where the bands' fields agree a Dirac keeps one direction across them and its band parts stay
// coherent in the crossovers as in W.
// Amplitudes: W's gains were solved so that W's band part holds the histogram's energy over each window, its
// chance interference between overlapping Diracs included (synthesis.cpp): they undo that interference, and
// take a heavy tail doing so (where the interference happened to cancel, a few Diracs get large gains). An
// output's Diracs interfere otherwise. The directional Diracs (a share r, all from u) keep W's gains,
// rescaled per window so that on average they hold the share r of W's energy: a share r of W's cross terms
// remains over them, r·diag + r²·(W − diag) at W's gains (diag: the Diracs' energies without cross terms),
// hence the factor √(W/(diag + r·(W − diag))), 1 when r = 1 (an output is then W seen from u). The diffuse
// Diracs (independent directions: no cross terms on average) take one gain per window, √(W/Σ d²·unit), so
// that they hold W's energy on average without W's tail.
template <class Renderer>
std::vector<std::vector<double>> tracedOutputs(const EnergyResponse& response, const detail::SynthesisPlan& plan,
                                               const std::vector<BandGains>& gains, std::uint64_t seed,
                                               const std::function<core::Vec3(const core::Vec3&)>& local,
                                               const std::vector<std::vector<std::complex<double>>>& direct,
                                               const Renderer& renderer) {
  using Key = typename Renderer::Key;
  const std::size_t n = static_cast<std::size_t>(plan.samples), outputs = direct.size();
  // Per thread: an FFT of the plan's length, its input zero between the bands' uses.
  struct Workspace {
    RealFft fft;
    explicit Workspace(int m) : fft(m) { std::fill(fft.input(), fft.input() + m, 0.0); }
  };
  tbb::enumerable_thread_specific<Workspace> workspaces(plan.fft_size);
  const std::size_t nbands = std::min(static_cast<std::size_t>(response.bands.size()), plan.gains.size());
  std::vector<std::vector<std::vector<std::complex<double>>>> parts(nbands);  // [band][output][band bin]
  if (nbands > 0) {
    const DiracDraws draws = drawDiracs(plan, seed);
    const std::vector<long>& at = draws.at;
    const std::vector<std::size_t>& bin_of = draws.bin_of;
    const std::size_t bins = plan.bin_start.size() - 1;
    std::vector<Key> diffuse_keys(at.size());
    tbb::parallel_for(std::size_t{0}, at.size(), [&](std::size_t q) { diffuse_keys[q] = renderer.key(local(draws.diffuse[q])); });
    const std::vector<std::complex<double>> window = detail::truncationWindowSpectrum(plan.fft_size, plan.samples);
    DIFFRAY_CHECK(plan.band_energy.size() >= nbands);
    tbb::parallel_for(std::size_t{0}, nbands, [&](std::size_t band) {
      RealFft& fft = workspaces.local().fft;
      const BandGains& bg = gains[band];
      const BandDirections dirs = bandDirections(response, static_cast<int>(band), static_cast<int>(bins));
      const std::vector<double>& g = plan.gains[band];
      const std::vector<double>& w_energy = plan.band_energy[band];  // W's band part's, per bin
      DIFFRAY_CHECK(w_energy.size() == bins);
      const double bandwidth_hz = response.bands.upperHz(static_cast<int>(band)) - response.bands.lowerHz(static_cast<int>(band));
      const auto half = static_cast<std::size_t>(std::lround(0.5 * kResolutionCycles / (bandwidth_hz * response.bin_s)));
      std::vector<double> diag(bins, 0.0), count(bins, 0.0);
      double unit = 0.0;  // the energy of a unit Dirac through the band filter, (2/m)·Σ W_b²
      for (double w : bg.w) unit += w * w;
      unit *= 2.0 / fft.size();
      for (std::size_t q = 0; q < at.size(); ++q)
        if (at[q] >= plan.quiet) {
          const double d = plan.diracs[static_cast<std::size_t>(at[q])], a = g[bin_of[q]] * d;
          diag[bin_of[q]] += a * a * unit;
          count[bin_of[q]] += d * d * unit;
        }
      std::vector<double> f_directional(bins, 1.0), h_diffuse(bins, 0.0);
      for (std::size_t i = 0; i < bins; ++i) {
        const std::size_t lo = i > half ? i - half : 0, hi = std::min(bins - 1, i + half);
        double ws_sum = 0.0, ds = 0.0, cs = 0.0;
        for (std::size_t j = lo; j <= hi; ++j) ws_sum += w_energy[j], ds += diag[j], cs += count[j];
        if (!(ws_sum > 0.0)) continue;
        if (cs > 0.0) h_diffuse[i] = std::sqrt(ws_sum / cs);
        const double mixed = ds + dirs.r[i] * (ws_sum - ds);
        if (mixed > 0.0) f_directional[i] = std::sqrt(ws_sum / mixed);
      }
      // Each bin's energy-vector direction, prepared where a Dirac can take it (r > 0).
      std::vector<Key> toward(bins);
      for (std::size_t i = 0; i < bins; ++i)
        if (dirs.r[i] > 0.0) toward[i] = renderer.key(local(dirs.u[i]));
      std::vector<const Key*> key(at.size());
      std::vector<double> amp(at.size());
      for (std::size_t q = 0; q < at.size(); ++q) {
        const std::size_t i = bin_of[q];
        const bool directional = draws.pick[q] < dirs.r[i];
        key[q] = directional ? &toward[i] : &diffuse_keys[q];
        amp[q] = (directional ? g[i] * f_directional[i] : h_diffuse[i]) * plan.diracs[static_cast<std::size_t>(at[q])];
      }
      // Each output's band spectrum, made a band part as W's was (back to the response's length, forward
      // again) on the band's bins alone (band_refilter.h: the same spectrum to rounding).
      const int len = static_cast<int>(bg.w.size());
      detail::BandRefilter refilter(window, fft.size(), bg.first, len);
      std::vector<std::complex<double>> spectrum(bg.w.size());
      parts[band].assign(outputs, std::vector<std::complex<double>>(bg.w.size()));
      double* x = fft.input();
      const std::complex<double>* all = fft.spectrum() + bg.first;
      for (std::size_t o = 0; o < outputs; ++o) {
        for (std::size_t q = 0; q < at.size(); ++q) renderer.place(*key[q], amp[q], at[q], o, x, n);
        fft.forwardInput();
        std::fill(x, x + n, 0.0);
        for (std::size_t j = 0; j < bg.w.size(); ++j) spectrum[j] = bg.w[j] * all[j];
        refilter.apply(spectrum.data(), parts[band][o].data());
      }
    });
  }
  std::vector<std::vector<double>> out(outputs);
  tbb::parallel_for(std::size_t{0}, outputs, [&](std::size_t o) {
    RealFft& fft = workspaces.local().fft;  // its input is free now: every band is done
    fft.inverse(direct[o], plan.samples, out[o]);
    if (nbands == 0) return;
    std::complex<double>* sum = fft.spectrum();
    std::fill(sum, sum + fft.bins(), std::complex<double>(0.0, 0.0));
    for (std::size_t b = 0; b < nbands; ++b) {
      const std::complex<double> turn = b < plan.traced_turn.size() ? plan.traced_turn[b] : std::complex<double>(1.0, 0.0);
      for (std::size_t j = 0; j < parts[b][o].size(); ++j) sum[static_cast<std::size_t>(gains[b].first) + j] += turn * parts[b][o][j];
    }
    fft.inverseSpectrum();
    const double* traced = fft.input();
    const double scale = 1.0 / fft.size();
    for (std::size_t s = static_cast<std::size_t>(std::min(plan.quiet, plan.samples)); s < n; ++s) out[o][s] += traced[s] * scale;
  });
  return out;
}

core::Vec3 localOf(const core::Vec3& w, const core::Vec3& forward, const core::Vec3& left, const core::Vec3& up) {
  return {w.dot(forward), w.dot(left), w.dot(up)};
}

// Placing HRIRs is most of the binaural synthesis' own work. On x86-64 addHrir is also compiled for AVX2
// (four doubles a step against SSE2's two), the copy picked when the program loads where the CPU has it:
// the same product and sum per sample in either (AVX2 brings no fused multiply-add), so the same samples.
// Not under the sanitizers, whose start-up the load-time pick would precede.
#if defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(undefined_behavior_sanitizer)
#define DIFFRAY_NO_CLONES
#endif
#endif
#if defined(__SANITIZE_ADDRESS__)
#define DIFFRAY_NO_CLONES
#endif
#if defined(__x86_64__) && !defined(DIFFRAY_NO_CLONES)
#define DIFFRAY_AVX2_CLONE __attribute__((target_clones("avx2", "default")))
#else
#define DIFFRAY_AVX2_CLONE
#endif

/// Adds h (taps values, an HRIR) at sample s, scaled, into x (n samples; cut at its end).
DIFFRAY_AVX2_CLONE void addHrir(double* x, std::size_t n, long s, const float* h, std::size_t taps, double scale) {
  const std::size_t from = static_cast<std::size_t>(s), count = std::min(taps, n - from);
  double* to = x + from;
  for (std::size_t k = 0; k < count; ++k) to[k] += scale * static_cast<double>(h[k]);
}

/// tracedOutputs' renderer of the Ambisonic channels 1 … (order + 1)² − 1 (output o is channel o + 1): a
/// direction's key is its spherical harmonics; a Dirac sets its sample to amp·Y (no two Diracs share one).
struct AmbisonicRenderer {
  using Key = std::array<double, spatial::ambisonicChannels(3)>;
  int order;
  Key key(const core::Vec3& d) const {
    Key y{};
    spatial::realSphericalHarmonicsSn3d(order, d, y.data());
    return y;
  }
  void place(const Key& y, double amp, long at, std::size_t output, double* x, std::size_t) const {
    x[at] = amp * y[output + 1];
  }
};

/// tracedOutputs' renderer of the two ears (output 0 left, 1 right): a direction's key is the measured
/// direction nearest it; a Dirac adds its HRIR for that ear, scaled by amp, from its sample on.
struct BinauralRenderer {
  using Key = int;
  const spatial::Hrtf& hrtf;
  Key key(const core::Vec3& d) const { return hrtf.nearest(d); }
  void place(Key i, double amp, long at, std::size_t output, double* x, std::size_t n) const {
    addHrir(x, n, at, hrtf.ear(i, static_cast<int>(output)), static_cast<std::size_t>(hrtf.taps()), amp);
  }
};

}  // namespace

std::vector<std::vector<double>> synthesizeAmbisonic(const EnergyResponse& response, double sample_rate_hz,
                                                     double length_s, double volume_m3, double speed_of_sound_m_s,
                                                     std::uint64_t seed, int order, const core::Vec3& forward,
                                                     const core::Vec3& left, const core::Vec3& up) {
  if (order < 1 || order > 3)
    throw core::InputError("--order", "the Ambisonic order must be 1, 2 or 3, got " + std::to_string(order));
  detail::SynthesisPlan plan;
  const auto channels = static_cast<std::size_t>(spatial::ambisonicChannels(order));
  std::vector<std::vector<double>> out(channels);
  out[0] = detail::synthesizePlanned(response, sample_rate_hz, length_s, volume_m3, speed_of_sound_m_s, seed,
                                     Phasing::Orthogonal, &plan);
  const BandFilter filter(response.bands, sample_rate_hz);
  const int m = plan.fft_size, nb = response.bands.size();
  const std::function<core::Vec3(const core::Vec3&)> local = [&](const core::Vec3& w) { return localOf(w, forward, left, up); };
  std::vector<BandGains> gains;
  for (int b = 0; b < nb; ++b) gains.push_back(filter.gains(b, m));
  // Arrivals: Y_c(d) times the arrival's pulse in W (its band coefficients on W_b·e^{−2πifτ}), each channel's
  // bins summed over the arrivals in order (and each arrival's bands in order). In blocks of bins, so that a
  // block of every channel stays in cache while all the arrivals are added to it; each band's e^{−2πifτ}
  // runs by one recurrence from its first bin, carried from block to block: the same spectra as arrival
  // after arrival over whole bands.
  const std::size_t bins = static_cast<std::size_t>(m / 2 + 1), nbands = static_cast<std::size_t>(nb);
  std::vector<std::vector<std::complex<double>>> arrivals(channels - 1, std::vector<std::complex<double>>(bins));  // [channel − 1][bin]
  const std::size_t count = std::min(response.arrivals.size(), plan.arrival_coefficients.size());
  std::vector<std::size_t> placed;             // the arrivals with a direction
  std::vector<double> y;                       // [placed][channel]
  std::vector<std::complex<double>> step, z;   // [placed], [placed][band]: e^{−2πi·τ·fs/m}, the band's next factor
  for (std::size_t a = 0; a < count; ++a) {
    const Arrival& arrival = response.arrivals[a];
    if (!(arrival.direction.norm() > 0.0)) continue;
    placed.push_back(a);
    y.resize(placed.size() * channels);
    spatial::realSphericalHarmonicsSn3d(order, local(arrival.direction), y.data() + (placed.size() - 1) * channels);
    const double phase_step = -core::kTwoPi * arrival.delay_s * sample_rate_hz / m;
    step.push_back(std::polar(1.0, phase_step));
    for (const BandGains& g : gains) z.push_back(std::polar(1.0, phase_step * g.first));
  }
  constexpr std::size_t kBlockBins = 512;
  std::vector<std::complex<double>> pulse(kBlockBins);  // one arrival's pulse on one band's bins in the block
  for (std::size_t j0 = 0; j0 < bins; j0 += kBlockBins) {
    const std::size_t j1 = std::min(bins, j0 + kBlockBins);
    for (std::size_t p = 0; p < placed.size(); ++p)
      for (std::size_t b = 0; b < nbands; ++b) {
        const std::complex<double> c = plan.arrival_coefficients[placed[p]][b];
        if (c == std::complex<double>(0.0, 0.0)) continue;
        const BandGains& g = gains[b];
        const std::size_t first = static_cast<std::size_t>(g.first);
        const std::size_t lo = std::max(j0, first), hi = std::min(j1, first + g.w.size());
        if (lo >= hi) continue;
        std::complex<double>& zb = z[p * nbands + b];
        for (std::size_t j = lo; j < hi; ++j, zb *= step[p]) pulse[j - lo] = c * g.w[j - first] * zb;
        for (std::size_t ch = 1; ch < channels; ++ch) {
          std::complex<double>* to = arrivals[ch - 1].data();
          const double yc = y[p * channels + ch];
          for (std::size_t j = lo; j < hi; ++j) to[j] += yc * pulse[j - lo];
        }
      }
  }
  std::vector<std::vector<double>> rest =
      tracedOutputs(response, plan, gains, seed, local, arrivals, AmbisonicRenderer{order});
  for (std::size_t ch = 1; ch < channels; ++ch) out[ch] = std::move(rest[ch - 1]);
  return out;
}

std::vector<std::vector<double>> synthesizeBinaural(const EnergyResponse& response, double sample_rate_hz,
                                                    double length_s, double volume_m3, double speed_of_sound_m_s,
                                                    std::uint64_t seed, const spatial::Hrtf& hrtf,
                                                    const core::Vec3& forward, const core::Vec3& left,
                                                    const core::Vec3& up, Phasing phasing, std::vector<double>* omni) {
  if (hrtf.sampleRateHz() != sample_rate_hz)
    throw core::InputError("--hrtf", "the HRTF set was prepared for " + std::to_string(hrtf.sampleRateHz()) +
                                         " Hz, the response is at " + std::to_string(sample_rate_hz) + " Hz");
  detail::SynthesisPlan plan;
  std::vector<double> w_channel =
      detail::synthesizePlanned(response, sample_rate_hz, length_s, volume_m3, speed_of_sound_m_s, seed, phasing, &plan);
  if (omni) *omni = std::move(w_channel);
  const BandFilter filter(response.bands, sample_rate_hz);
  const int m = plan.fft_size, nb = response.bands.size();
  const std::size_t n = static_cast<std::size_t>(plan.samples), taps = static_cast<std::size_t>(hrtf.taps());
  const std::function<core::Vec3(const core::Vec3&)> local = [&](const core::Vec3& w) { return localOf(w, forward, left, up); };
  std::vector<BandGains> gains;
  for (int b = 0; b < nb; ++b) gains.push_back(filter.gains(b, m));
  // Arrivals: each band's pulse c·W_b·e^{−2πifτ} through the HRIR of the arrival's direction, at the sample
  // nearest its delay: per band and ear, the HRIRs placed with weights Re(c) and Im(c) in two sequences X_R,
  // X_I (one after the other in the FFT's input, zeroed again after use), and the band part W_b·(X_R + i·X_I)
  // (on the positive frequencies, c·H·e^{−2πifτ}). The bands in parallel (each thread with its FFT), added
  // in band order.
  // Each arrival's HRIR pair and sample, once (−1: beyond the response).
  const std::size_t arrivals = std::min(response.arrivals.size(), plan.arrival_coefficients.size());
  std::vector<int> measured(arrivals, 0);
  std::vector<long> sample(arrivals, -1);
  for (std::size_t a = 0; a < arrivals; ++a) {
    const Arrival& arrival = response.arrivals[a];
    measured[a] = hrtf.nearest(arrival.direction.norm() > 0.0 ? local(arrival.direction) : core::Vec3(1, 0, 0));
    const long s = std::lround(arrival.delay_s * sample_rate_hz);
    if (s >= 0 && static_cast<std::size_t>(s) < n) sample[a] = s;
  }
  struct Workspace {
    RealFft fft;
    explicit Workspace(int size) : fft(size) { std::fill(fft.input(), fft.input() + size, 0.0); }
  };
  tbb::enumerable_thread_specific<Workspace> workspaces(m);
  std::vector<std::vector<std::vector<std::complex<double>>>> band_ears(static_cast<std::size_t>(nb));  // [band][side][band bin]
  tbb::parallel_for(0, nb, [&](int b) {
    RealFft& fft = workspaces.local().fft;
    const BandGains& g = gains[static_cast<std::size_t>(b)];
    std::vector<std::complex<double>> spectrum_r(g.w.size()), spectrum_i(g.w.size());
    band_ears[static_cast<std::size_t>(b)].resize(2);
    bool any = false;
    for (std::size_t a = 0; a < arrivals; ++a)
      any = any || (plan.arrival_coefficients[a][static_cast<std::size_t>(b)] != std::complex<double>(0.0, 0.0) && sample[a] >= 0);
    if (!any) return;
    // The band's spectrum of the HRIRs placed with weights part(c) (the real or the imaginary part).
    const auto transform = [&](int side, double (*part)(const std::complex<double>&), std::complex<double>* out) {
      for (std::size_t a = 0; a < arrivals; ++a) {
        const std::complex<double> c = plan.arrival_coefficients[a][static_cast<std::size_t>(b)];
        if (c == std::complex<double>(0.0, 0.0) || sample[a] < 0) continue;
        addHrir(fft.input(), n, sample[a], hrtf.ear(measured[a], side), taps, part(c));
      }
      fft.forwardInput();
      std::fill(fft.input(), fft.input() + n, 0.0);
      std::copy(fft.spectrum() + g.first, fft.spectrum() + g.first + static_cast<long>(g.w.size()), out);
    };
    for (int side = 0; side < 2; ++side) {
      transform(side, [](const std::complex<double>& c) { return c.real(); }, spectrum_r.data());
      transform(side, [](const std::complex<double>& c) { return c.imag(); }, spectrum_i.data());
      auto& part = band_ears[static_cast<std::size_t>(b)][static_cast<std::size_t>(side)];
      part.resize(g.w.size());
      for (std::size_t j = 0; j < g.w.size(); ++j) part[j] = g.w[j] * (spectrum_r[j] + std::complex<double>(0.0, 1.0) * spectrum_i[j]);
    }
  });
  std::vector<std::vector<std::complex<double>>> ears(2, std::vector<std::complex<double>>(static_cast<std::size_t>(m / 2 + 1)));
  for (int b = 0; b < nb; ++b)
    for (std::size_t side = 0; side < 2; ++side) {
      const auto& part = band_ears[static_cast<std::size_t>(b)][side];
      for (std::size_t j = 0; j < part.size(); ++j) ears[side][static_cast<std::size_t>(gains[static_cast<std::size_t>(b)].first) + j] += part[j];
    }
  return tracedOutputs(response, plan, gains, seed, local, ears, BinauralRenderer{hrtf});
}

}  // namespace diffray::ir
