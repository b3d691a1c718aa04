#include "diffray/ir/spatial_synthesis.h"

#include <algorithm>
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

/// One band of the traced part as the spatial syntheses render it: each of W's Diracs (its sample) with a
/// direction in the listener's frame and an amplitude.
struct BandDiracs {
  std::vector<long> at;
  std::vector<core::Vec3> dir;
  std::vector<double> amp;
};

/// Writes the weighted sequences (the response's length, zero on entry) of every output for one band: it
/// may assign or add samples.
using RenderBand = std::function<void(const BandDiracs&, std::vector<std::vector<double>>&)>;

/// The `outputs` signals, each the inverse of its spectrum `direct[o]` (all bins; the arrivals, kept whole)
/// plus its traced part, silent before plan.quiet like W's. The traced part: per band (in parallel, each
/// with its thread's FFT and buffers; summed in band order, so the same samples for any thread count), W's
/// Diracs with their directions and amplitudes (below), rendered by `render` into one sequence per output,
/// each made into a band part as synthesis.cpp makes W's (filtered, back to the response's length, its
/// spectrum on the band's bins: the last two steps by band_refilter.h) and turned as W's traced part was.
/// The outputs go back to time in parallel, each alone.
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
std::vector<std::vector<double>> tracedOutputs(const EnergyResponse& response, const detail::SynthesisPlan& plan,
                                               const std::vector<BandGains>& gains, std::uint64_t seed,
                                               const std::function<core::Vec3(const core::Vec3&)>& local,
                                               const std::vector<std::vector<std::complex<double>>>& direct,
                                               const RenderBand& render) {
  const std::size_t n = static_cast<std::size_t>(plan.samples), outputs = direct.size();
  // Per thread: an FFT of the plan's length and one sequence per output, zeroed again after each use.
  struct Workspace {
    RealFft fft;
    std::vector<std::vector<double>> sequences;
    Workspace(int m, std::size_t count, std::size_t samples) : fft(m), sequences(count, std::vector<double>(samples, 0.0)) {}
  };
  tbb::enumerable_thread_specific<Workspace> workspaces(plan.fft_size, plan.gains.empty() ? std::size_t{0} : outputs, n);
  const std::size_t nbands = std::min(static_cast<std::size_t>(response.bands.size()), plan.gains.size());
  std::vector<std::vector<std::vector<std::complex<double>>>> parts(nbands);  // [band][output][band bin]
  if (nbands > 0) {
    std::vector<long> at;
    std::vector<std::size_t> bin_of;
    const std::size_t bins = plan.bin_start.size() - 1;
    for (std::size_t i = 0; i < bins; ++i)
      for (long s = plan.bin_start[i]; s < plan.bin_start[i + 1]; ++s)
        if (plan.diracs[static_cast<std::size_t>(s)] != 0.0) at.push_back(s), bin_of.push_back(i);
    core::Rng rng(seed, kStreamDirections);
    std::vector<double> pick(at.size());
    std::vector<core::Vec3> diffuse(at.size());
    for (std::size_t q = 0; q < at.size(); ++q) pick[q] = rng.uniform(), diffuse[q] = uniformDirection(rng);
    const std::vector<std::complex<double>> window = detail::truncationWindowSpectrum(plan.fft_size, plan.samples);
    DIFFRAY_CHECK(plan.band_energy.size() >= nbands);
    tbb::parallel_for(std::size_t{0}, nbands, [&](std::size_t band) {
      Workspace& ws = workspaces.local();
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
      unit *= 2.0 / ws.fft.size();
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
      BandDiracs d;
      d.at = at;
      d.dir.resize(at.size());
      d.amp.resize(at.size());
      for (std::size_t q = 0; q < at.size(); ++q) {
        const std::size_t i = bin_of[q];
        const bool directional = pick[q] < dirs.r[i];
        d.dir[q] = local(directional ? dirs.u[i] : diffuse[q]);
        d.amp[q] = (directional ? g[i] * f_directional[i] : h_diffuse[i]) * plan.diracs[static_cast<std::size_t>(at[q])];
      }
      render(d, ws.sequences);
      // Each output's band spectrum, made a band part as W's was (back to the response's length, forward
      // again) on the band's bins alone (band_refilter.h: the same spectrum to rounding).
      const int len = static_cast<int>(bg.w.size());
      detail::BandRefilter refilter(window, ws.fft.size(), bg.first, len);
      std::vector<std::complex<double>> spectrum(bg.w.size());
      parts[band].assign(outputs, std::vector<std::complex<double>>(bg.w.size()));
      for (std::size_t o = 0; o < outputs; ++o) {
        std::vector<double>& x = ws.sequences[o];
        ws.fft.forwardBins(x.data(), x.size(), bg.first, len, spectrum.data());
        std::fill(x.begin(), x.end(), 0.0);
        for (std::size_t j = 0; j < bg.w.size(); ++j) spectrum[j] = bg.w[j] * spectrum[j];
        refilter.apply(spectrum.data(), parts[band][o].data());
      }
    });
  }
  std::vector<std::vector<double>> out(outputs);
  tbb::parallel_for(std::size_t{0}, outputs, [&](std::size_t o) {
    RealFft& fft = workspaces.local().fft;
    fft.inverse(direct[o], plan.samples, out[o]);
    if (nbands == 0) return;
    std::vector<std::complex<double>> sum(static_cast<std::size_t>(fft.bins()), {0.0, 0.0});
    for (std::size_t b = 0; b < nbands; ++b) {
      const std::complex<double> turn = b < plan.traced_turn.size() ? plan.traced_turn[b] : std::complex<double>(1.0, 0.0);
      for (std::size_t j = 0; j < parts[b][o].size(); ++j) sum[static_cast<std::size_t>(gains[b].first) + j] += turn * parts[b][o][j];
    }
    std::vector<double> traced;
    fft.inverse(sum, plan.samples, traced);
    std::fill(traced.begin(), traced.begin() + std::min(plan.quiet, plan.samples), 0.0);
    for (std::size_t s = 0; s < n; ++s) out[o][s] += traced[s];
  });
  return out;
}

core::Vec3 localOf(const core::Vec3& w, const core::Vec3& forward, const core::Vec3& left, const core::Vec3& up) {
  return {w.dot(forward), w.dot(left), w.dot(up)};
}

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
  // Arrivals: Y_c(d) times the arrival's pulse in W (its band coefficients on W_b·e^{−2πifτ}). The channels
  // in one contiguous block per thread, each block summing its channels in arrival order as one thread
  // would: the same spectra for any thread count.
  std::vector<std::vector<std::complex<double>>> arrivals(channels - 1, std::vector<std::complex<double>>(static_cast<std::size_t>(m / 2 + 1)));  // [channel − 1][bin]
  const std::size_t blocks = std::min(channels - 1, static_cast<std::size_t>(std::max(1, core::ThreadLimit::current())));
  tbb::parallel_for(std::size_t{0}, blocks, [&](std::size_t block) {
    const std::size_t ch_begin = 1 + block * (channels - 1) / blocks, ch_end = 1 + (block + 1) * (channels - 1) / blocks;
    std::vector<double> y(channels);
    std::vector<std::complex<double>> pulse;  // the arrival's pulse on one band's bins
    for (std::size_t a = 0; a < response.arrivals.size() && a < plan.arrival_coefficients.size(); ++a) {
      const Arrival& arrival = response.arrivals[a];
      if (!(arrival.direction.norm() > 0.0)) continue;
      spatial::realSphericalHarmonicsSn3d(order, local(arrival.direction), y.data());
      const double phase_step = -core::kTwoPi * arrival.delay_s * sample_rate_hz / m;
      const std::complex<double> step = std::polar(1.0, phase_step);
      for (int b = 0; b < nb; ++b) {
        const std::complex<double> c = plan.arrival_coefficients[a][static_cast<std::size_t>(b)];
        if (c == std::complex<double>(0.0, 0.0)) continue;
        const BandGains& g = gains[static_cast<std::size_t>(b)];
        pulse.resize(g.w.size());
        std::complex<double> z = std::polar(1.0, phase_step * g.first);
        for (std::size_t j = 0; j < g.w.size(); ++j, z *= step) pulse[j] = c * g.w[j] * z;
        for (std::size_t ch = ch_begin; ch < ch_end; ++ch) {
          std::complex<double>* to = arrivals[ch - 1].data() + g.first;
          for (std::size_t j = 0; j < g.w.size(); ++j) to[j] += y[ch] * pulse[j];
        }
      }
    }
  });
  std::vector<std::vector<double>> rest =
      tracedOutputs(response, plan, gains, seed, local, arrivals, [&](const BandDiracs& d, std::vector<std::vector<double>>& seq) {
        std::vector<double> ys(channels);
        for (std::size_t q = 0; q < d.at.size(); ++q) {
          spatial::realSphericalHarmonicsSn3d(order, d.dir[q], ys.data());
          for (std::size_t ch = 1; ch < channels; ++ch) seq[ch - 1][static_cast<std::size_t>(d.at[q])] = d.amp[q] * ys[ch];
        }
      });
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
  // Adds h (the HRIR) at sample s, scaled, into x (cut at the response's end).
  const auto place = [&](std::vector<double>& x, long s, const float* h, double scale) {
    const std::size_t from = static_cast<std::size_t>(s), count = std::min(taps, n - from);
    double* to = x.data() + from;
    for (std::size_t k = 0; k < count; ++k) to[k] += scale * static_cast<double>(h[k]);
  };
  // Arrivals: each band's pulse c·W_b·e^{−2πifτ} through the HRIR of the arrival's direction, at the sample
  // nearest its delay: per band and ear, the HRIRs placed with weights Re(c) and Im(c) in two sequences X_R,
  // X_I, and the band part W_b·(X_R + i·X_I) (on the positive frequencies, c·H·e^{−2πifτ}). The bands in
  // parallel (each thread with its FFT and two sequences, zeroed again after use), added in band order.
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
    std::vector<double> xr, xi;
    Workspace(int size, std::size_t samples) : fft(size), xr(samples, 0.0), xi(samples, 0.0) {}
  };
  tbb::enumerable_thread_specific<Workspace> workspaces(m, n);
  std::vector<std::vector<std::vector<std::complex<double>>>> band_ears(static_cast<std::size_t>(nb));  // [band][side][band bin]
  tbb::parallel_for(0, nb, [&](int b) {
    Workspace& ws = workspaces.local();
    const BandGains& g = gains[static_cast<std::size_t>(b)];
    const int len = static_cast<int>(g.w.size());
    std::vector<std::complex<double>> spectrum_r(g.w.size()), spectrum_i(g.w.size());
    band_ears[static_cast<std::size_t>(b)].resize(2);
    for (int side = 0; side < 2; ++side) {
      bool any = false;
      for (std::size_t a = 0; a < arrivals; ++a) {
        const std::complex<double> c = plan.arrival_coefficients[a][static_cast<std::size_t>(b)];
        if (c == std::complex<double>(0.0, 0.0) || sample[a] < 0) continue;
        const float* h = hrtf.ear(measured[a], side);
        place(ws.xr, sample[a], h, c.real());
        place(ws.xi, sample[a], h, c.imag());
        any = true;
      }
      if (!any) continue;
      ws.fft.forwardBins(ws.xr.data(), n, g.first, len, spectrum_r.data());
      ws.fft.forwardBins(ws.xi.data(), n, g.first, len, spectrum_i.data());
      std::fill(ws.xr.begin(), ws.xr.end(), 0.0);
      std::fill(ws.xi.begin(), ws.xi.end(), 0.0);
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
  return tracedOutputs(response, plan, gains, seed, local, ears, [&](const BandDiracs& d, std::vector<std::vector<double>>& seq) {
    for (std::size_t q = 0; q < d.at.size(); ++q) {
      const int i = hrtf.nearest(d.dir[q]);
      for (int side = 0; side < 2; ++side) place(seq[static_cast<std::size_t>(side)], d.at[q], hrtf.ear(i, side), d.amp[q]);
    }
  });
}

}  // namespace diffray::ir
