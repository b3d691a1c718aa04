#include "diffray/ir/ambisonic_synthesis.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <functional>

#include <tbb/parallel_for.h>

#include "diffray/core/error.h"
#include "diffray/core/rng.h"
#include "diffray/ir/band_filter.h"
#include "diffray/spatial/spherical_harmonics.h"
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

/// One band's share of the Ambisonic channels 1 … C−1 of the traced part: the Diracs of W weighted by the
/// harmonics of their directions, each channel's energy per window matched to its expected share of W's band
/// part (W's gains cancel W's own chance interference between overlapping Diracs, synthesis.cpp; a
/// channel's Diracs interfere otherwise), then made into a band part as synthesis.cpp makes W's. Owns its
/// FFT: one per thread.
struct BandChannels {
  const EnergyResponse& response;
  const detail::SynthesisPlan& plan;
  const BandGains& bg;
  int band;
  int order;
  const std::vector<long>& at;
  const std::vector<std::size_t>& bin_of;
  std::size_t bins;

  std::vector<std::vector<std::complex<double>>> run(const std::vector<double>& pick, const std::vector<core::Vec3>& diffuse,
                                                     const std::function<core::Vec3(const core::Vec3&)>& local) {
    const std::size_t channels = static_cast<std::size_t>(spatial::ambisonicChannels(order));
    const std::size_t n = static_cast<std::size_t>(plan.samples);
    RealFft fft(plan.fft_size);
    const BandDirections dirs = bandDirections(response, band, static_cast<int>(bins));
    std::vector<double> ys(at.size() * channels);
    std::vector<char> directional(at.size());
    for (std::size_t q = 0; q < at.size(); ++q) {
      const std::size_t i = bin_of[q];
      directional[q] = pick[q] < dirs.r[i];
      const core::Vec3 d = directional[q] ? dirs.u[i] : diffuse[q];
      spatial::realSphericalHarmonicsSn3d(order, local(d), &ys[q * channels]);
    }
    const std::vector<double>& g = plan.gains[static_cast<std::size_t>(band)];
    const double bandwidth_hz = response.bands.upperHz(band) - response.bands.lowerHz(band);
    const auto half = static_cast<std::size_t>(std::lround(0.5 * kResolutionCycles / (bandwidth_hz * response.bin_s)));
    std::vector<double> weighted(n), w_energy(bins), diag(bins, 0.0);
    std::vector<std::complex<double>> spectrum, band_spectrum(static_cast<std::size_t>(fft.bins()));
    // The band part of `weighted`, as synthesis.cpp makes one: filtered, back to the response's length (the
    // filter's ringing beyond either end dropped), and its spectrum on the band's bins.
    const auto bandPart = [&]() {
      fft.forward(weighted, spectrum);
      std::fill(band_spectrum.begin(), band_spectrum.end(), std::complex<double>(0.0, 0.0));
      for (std::size_t j = 0; j < bg.w.size(); ++j)
        band_spectrum[static_cast<std::size_t>(bg.first) + j] = bg.w[j] * spectrum[static_cast<std::size_t>(bg.first) + j];
      return fft.inverse(band_spectrum, plan.samples);
    };
    // W's band part and its energy per bin; the same Diracs' energy without their cross terms (each Dirac's
    // energy through the band filter, (2/m)·Σ W_b² per unit Dirac).
    std::fill(weighted.begin(), weighted.end(), 0.0);
    for (std::size_t q = 0; q < at.size(); ++q)
      weighted[static_cast<std::size_t>(at[q])] = g[bin_of[q]] * plan.diracs[static_cast<std::size_t>(at[q])];
    const std::vector<double> w_part = bandPart();
    for (std::size_t i = 0; i < bins; ++i) {
      double sum = 0.0;
      for (long s = std::max(plan.bin_start[i], plan.quiet); s < plan.bin_start[i + 1]; ++s)
        sum += w_part[static_cast<std::size_t>(s)] * w_part[static_cast<std::size_t>(s)];
      w_energy[i] = sum;
    }
    double unit = 0.0;  // the energy of a unit Dirac through the band filter, (2/m)·Σ W_b²
    for (double w : bg.w) unit += w * w;
    unit *= 2.0 / fft.size();
    std::vector<double> count(bins, 0.0);  // Σ d² per bin: the Diracs' energy at unit gain
    for (std::size_t q = 0; q < at.size(); ++q)
      if (at[q] >= plan.quiet) {
        const double d = plan.diracs[static_cast<std::size_t>(at[q])], a = g[bin_of[q]] * d;
        diag[bin_of[q]] += a * a * unit;
        count[bin_of[q]] += d * d * unit;
      }
    // W's gains were solved so that W's band part holds the histogram's energy over each window, its chance
    // interference between overlapping Diracs included (synthesis.cpp): they undo that interference, and
    // take a heavy tail doing so (where the interference happened to cancel, a few Diracs get large gains).
    // A channel's Diracs interfere otherwise. The directional Diracs (a share r, all from u) keep W's gains,
    // rescaled per window so that on average they hold the share r of W's energy: a share r of W's cross
    // terms remains over them, r·diag + r²·(W − diag) at W's gains, hence the factor √(W/(diag + r·(W −
    // diag))) (1 when r = 1: the channel is then Y(u)·W). The diffuse Diracs (directions independent, E[Y] =
    // 0, no cross terms on average) take one gain per window, √(W/Σ d²·unit), so that they hold W's energy
    // on average without W's tail.
    std::vector<double> f_directional(bins, 1.0), h_diffuse(bins, 0.0);
    for (std::size_t i = 0; i < bins; ++i) {
      const std::size_t lo = i > half ? i - half : 0, hi = std::min(bins - 1, i + half);
      double ws = 0.0, ds = 0.0, cs = 0.0;
      for (std::size_t j = lo; j <= hi; ++j) ws += w_energy[j], ds += diag[j], cs += count[j];
      if (!(ws > 0.0)) continue;
      if (cs > 0.0) h_diffuse[i] = std::sqrt(ws / cs);
      const double mixed = ds + dirs.r[i] * (ws - ds);
      if (mixed > 0.0) f_directional[i] = std::sqrt(ws / mixed);
    }
    std::vector<std::vector<std::complex<double>>> out(channels);
    for (std::size_t ch = 1; ch < channels; ++ch) {
      std::fill(weighted.begin(), weighted.end(), 0.0);
      for (std::size_t q = 0; q < at.size(); ++q) {
        const std::size_t i = bin_of[q];
        const double gain = directional[q] ? g[i] * f_directional[i] : h_diffuse[i];
        weighted[static_cast<std::size_t>(at[q])] = gain * plan.diracs[static_cast<std::size_t>(at[q])] * ys[q * channels + ch];
      }
      fft.forward(bandPart(), spectrum);
      out[ch].assign(spectrum.begin() + bg.first, spectrum.begin() + bg.first + static_cast<long>(bg.w.size()));
    }
    return out;
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
  const int channels = spatial::ambisonicChannels(order);
  std::vector<std::vector<double>> out(static_cast<std::size_t>(channels));
  out[0] = detail::synthesizePlanned(response, sample_rate_hz, length_s, volume_m3, speed_of_sound_m_s, seed,
                                     Phasing::Orthogonal, &plan);
  const long n = plan.samples;
  const BandFilter filter(response.bands, sample_rate_hz);
  RealFft fft(plan.fft_size);
  const int m = fft.size(), nb = response.bands.size();
  const std::function<core::Vec3(const core::Vec3&)> local = [&](const core::Vec3& w) {
    return core::Vec3(w.dot(forward), w.dot(left), w.dot(up));
  };
  std::vector<double> y(static_cast<std::size_t>(channels));
  // Spectra of channels 1 … C−1: the arrivals' and the traced part's apart (the traced part is silenced
  // before plan.quiet in the time domain, as in W).
  std::vector<std::vector<std::complex<double>>> arrivals(
      static_cast<std::size_t>(channels), std::vector<std::complex<double>>(static_cast<std::size_t>(fft.bins())));
  std::vector<std::vector<std::complex<double>>> traced = arrivals;
  std::vector<BandGains> gains;
  for (int b = 0; b < nb; ++b) gains.push_back(filter.gains(b, m));
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
      std::complex<double> z = std::polar(1.0, phase_step * g.first);
      for (std::size_t j = 0; j < g.w.size(); ++j, z *= step) {
        const std::complex<double> pulse = c * g.w[j] * z;
        for (int ch = 1; ch < channels; ++ch) arrivals[static_cast<std::size_t>(ch)][g.first + j] += y[static_cast<std::size_t>(ch)] * pulse;
      }
    }
  }
  if (!plan.gains.empty()) {
    // The Diracs W is made of, one uniform (directional or diffuse?) and one diffuse direction each, shared
    // by the bands: where the bands' fields agree a Dirac keeps one direction across them, and its band
    // parts stay coherent in the crossovers as in W.
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
    // The bands in parallel (each its own FFT), their channel spectra on the band's bins summed in band
    // order afterwards: the same samples for any thread count.
    const std::size_t nbands = std::min(static_cast<std::size_t>(nb), plan.gains.size());
    std::vector<std::vector<std::vector<std::complex<double>>>> parts(nbands);  // [band][channel][band bin]
    tbb::parallel_for(std::size_t{0}, nbands, [&](std::size_t b) {
      BandChannels job{response, plan, gains[b], static_cast<int>(b), order, at, bin_of, bins};
      parts[b] = job.run(pick, diffuse, local);
    });
    for (std::size_t b = 0; b < nbands; ++b) {
      const std::complex<double> turn = b < plan.traced_turn.size() ? plan.traced_turn[b] : std::complex<double>(1.0, 0.0);
      for (int ch = 1; ch < channels; ++ch) {
        const auto& from = parts[b][static_cast<std::size_t>(ch)];
        auto& to = traced[static_cast<std::size_t>(ch)];
        for (std::size_t j = 0; j < from.size(); ++j) to[static_cast<std::size_t>(gains[b].first) + j] += turn * from[j];
      }
    }
  }
  for (int ch = 1; ch < channels; ++ch) {
    out[static_cast<std::size_t>(ch)] = fft.inverse(arrivals[static_cast<std::size_t>(ch)], n);
    if (plan.gains.empty()) continue;
    const std::vector<double> t = fft.inverse(traced[static_cast<std::size_t>(ch)], n);
    for (long s = std::min(plan.quiet, n); s < n; ++s) out[static_cast<std::size_t>(ch)][static_cast<std::size_t>(s)] += t[static_cast<std::size_t>(s)];
  }
  return out;
}

}  // namespace diffray::ir
