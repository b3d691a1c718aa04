#include "diffray/ir/synthesis.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <numeric>
#include <utility>

#include "diffray/core/error.h"
#include "diffray/core/math.h"
#include "diffray/core/rng.h"
#include "diffray/ir/band_filter.h"
#include "synthesis_plan.h"

namespace diffray::ir {

namespace {

constexpr double kMaxDiracRate = 1e4;  // s⁻¹, the cap on the reflection density 4πc³t²/V
// Streams of the seed: one for the Dirac times and signs, one for the Diracs added to empty bins.
constexpr std::uint64_t kStreamPoisson = 0, kStreamFill = 1;
// The window over which a band's energy is matched to the histogram: this many cycles of its bandwidth
// (rounded to whole bins; one bin, i.e. bin by bin, for bands wider than 2 / bin_s). Shorter windows were
// measured worse (1 cycle: 335 of 390 figures of the shipped rooms within one JND, against 360 with 2):
// the band cannot hold the finer envelope and the gains then chase the noise.
// Rounds of the gain correction. Each round's error is what the filter's mixing of neighbouring bins
// leaves of the previous one; six bring a 4 kHz decay's 10 ms windows within 5 % (three left 7 %), and
// the metrics of the shipped rooms no longer move beyond their scatter after three.
constexpr int kGainIterations = 6;
constexpr double kResolutionCycles = 2.0;
// Jacobi rounds of matchAnalysedEnergies (arrivals, turned traced parts): each brings the analysed energies ~30×
// closer (the crossovers' weight against a band's own); eight leave them within ~1e-6.
constexpr int kAnalysedEnergyRounds = 8;

/// Which histogram bin each sample falls in (bin i covers [i·bin_s, (i+1)·bin_s)), as sample ranges.
struct BinSpans {
  std::vector<long> start;  ///< start[i] … start[i+1] − 1 are bin i's samples; size bins + 1
};

BinSpans binSpans(int bins, double bin_s, double fs, long samples) {
  BinSpans s;
  for (int i = 0; i <= bins; ++i) {
    // The first sample at or after the bin's start; the small slack keeps exact multiples exact.
    const double first = std::ceil(i * bin_s * fs - 1e-9);
    s.start.push_back(std::min(samples, static_cast<long>(first)));
  }
  return s;
}

std::vector<double> bandPass(const BandFilter& filter, RealFft& fft, const std::vector<double>& x, int band) {
  std::vector<std::complex<double>> spectrum, band_spectrum(static_cast<size_t>(fft.bins()), {0.0, 0.0});
  fft.forward(x, spectrum);
  const BandGains g = filter.gains(band, fft.size());
  for (size_t j = 0; j < g.w.size(); ++j) band_spectrum[g.first + j] = g.w[j] * spectrum[g.first + j];
  return fft.inverse(band_spectrum, static_cast<long>(x.size()));
}

double binEnergy(const std::vector<double>& x, const BinSpans& spans, int bin) {
  double sum = 0.0;
  for (long s = spans.start[bin]; s < spans.start[bin + 1]; ++s) sum += x[s] * x[s];
  return sum;
}

void checkInputs(const EnergyResponse& r, double fs, double length_s, double volume_m3, double c) {
  core::requirePositive("synthesis: sample rate", fs);
  core::requirePositive("synthesis: length", length_s);
  core::requirePositive("synthesis: room volume", volume_m3);
  core::requirePositive("synthesis: speed of sound", c);
  core::requirePositive("synthesis: histogram bin width", r.bin_s);
  DIFFRAY_CHECK(r.traced.empty() || static_cast<int>(r.traced.size()) == r.bands.size());
  for (const auto& band : r.traced) {
    DIFFRAY_CHECK(band.size() == r.traced[0].size());
    for (double v : band) core::requireFinite("synthesis: traced energy", v);
  }
  for (const Arrival& a : r.arrivals) {
    core::requireFinite("synthesis: arrival delay", a.delay_s);
    if (a.delay_s < 0.0) throw core::InputError("synthesis", "an arrival has a negative delay");
    for (int b = 0; b < r.bands.size(); ++b) core::requireFinite("synthesis: arrival energy", a.energy[b]);
  }
}

/// The first sample of the first histogram bin holding energy in any band (`samples` if none): the
/// traced part is silent before it. Its zero-phase band filters would otherwise ring ahead of a part that
/// starts abruptly, up to a sixth of a low band's energy before the first bin in a decay that starts at
/// once, and the onset would be found milliseconds early (Ts then reads long).
long tracedStartSample(const EnergyResponse& r, double fs, long samples) {
  for (int i = 0; i < r.bins(); ++i)
    for (const auto& band : r.traced)
      if (band[i] > 0.0) return std::min(samples, static_cast<long>(std::ceil(i * r.bin_s * fs - 1e-9)));  // binSpans
  return samples;
}

/// One band's spectrum on that band's bins (BandGains::first on).
using BandSpectrum = std::vector<std::complex<double>>;

/// The traced part, `samples` long: each band part's spectrum on its band's bins (empty if none).
/// `quiet`: the leading samples combine() silences (tracedStartSample); the gains match what is left.
std::vector<BandSpectrum> tracedParts(const EnergyResponse& r, const BandFilter& filter, RealFft& fft, double volume_m3,
                                      double c, std::uint64_t seed, long samples, long quiet,
                                      detail::SynthesisPlan* plan) {
  const double fs = filter.sampleRateHz();
  const long n = samples;
  const int bins = static_cast<int>(std::min<double>(r.bins(), std::ceil(static_cast<double>(n) / (fs * r.bin_s))));
  std::vector<BandSpectrum> parts;
  if (bins <= 0) return parts;
  const BinSpans spans = binSpans(bins, r.bin_s, fs, n);
  std::vector<double> d = poissonDiracs(n, fs, volume_m3, c, seed);
  core::Rng fill(seed, kStreamFill);
  for (int i = 0; i < bins; ++i) {
    const long a = spans.start[i], b = spans.start[i + 1];
    if (b <= a) continue;
    bool energy = false;
    for (int k = 0; k < r.bands.size(); ++k) energy = energy || r.traced[k][i] > 0.0;
    if (!energy || std::any_of(d.begin() + a, d.begin() + b, [](double v) { return v != 0.0; })) continue;
    const long at = std::min(b - 1, a + static_cast<long>(fill.uniform() * static_cast<double>(b - a)));
    d[at] = fill.uniform() < 0.5 ? -1.0 : 1.0;
  }
  // Per band: each Dirac weighted by g(bin), first √(E_b(bin) / Diracs in the bin) (so a sparse early Dirac
  // carries its bin's energy as a whole, unchopped wavelet), band-passed; then g is corrected by the ratio
  // of the histogram's energy to the band signal's over a window of the band's time resolution (see
  // synthesis.h for why not bin by bin) and the Diracs filtered again. The gains act on the Diracs before
  // the filter, never on the filtered signal: a gain that steps from bin to bin multiplies the signal by a
  // staircase whose sidebands (kHz apart at 1 ms bins) spill a slowly decaying band into its neighbours
  // (measured: T30 at 8 kHz read 20 % long in the shoebox, where 4 kHz decays twice as slowly).
  const int nb = r.bands.size();
  if (plan) {
    plan->diracs = d;
    plan->bin_start = spans.start;
  }
  std::vector<int> count(static_cast<size_t>(bins), 0);
  for (int i = 0; i < bins; ++i)
    for (long s = spans.start[i]; s < spans.start[i + 1]; ++s) count[i] += d[s] != 0.0;
  std::vector<double> weighted(static_cast<size_t>(n));
  std::vector<double> x(static_cast<size_t>(bins)), e(static_cast<size_t>(bins)), g(static_cast<size_t>(bins));
  for (int k = 0; k < nb; ++k) {
    for (int i = 0; i < bins; ++i) {
      e[i] = std::max(0.0, r.traced[k][i]);
      g[i] = count[i] > 0 ? std::sqrt(e[i] / count[i]) : 0.0;
    }
    const double bandwidth_hz = r.bands.upperHz(k) - r.bands.lowerHz(k);
    const int half = static_cast<int>(std::lround(0.5 * kResolutionCycles / (bandwidth_hz * r.bin_s)));
    std::vector<double> db;
    for (int it = 0;; ++it) {
      std::fill(weighted.begin(), weighted.end(), 0.0);
      for (int i = 0; i < bins; ++i)
        for (long s = spans.start[i]; s < spans.start[i + 1]; ++s) weighted[s] = g[i] * d[s];
      db = bandPass(filter, fft, weighted, k);
      if (it == kGainIterations) {
        if (plan) {
          std::vector<double> energy(static_cast<size_t>(bins));
          for (int i = 0; i < bins; ++i) {
            double sum = 0.0;
            for (long s = std::max(spans.start[i], quiet); s < spans.start[i + 1]; ++s) sum += db[s] * db[s];
            energy[i] = sum;
          }
          plan->band_energy.push_back(std::move(energy));
        }
        break;
      }
      std::fill(db.begin(), db.begin() + std::min(quiet, n), 0.0);  // silenced in the end (combine)
      for (int i = 0; i < bins; ++i) x[i] = binEnergy(db, spans, i);
      for (int i = 0; i < bins; ++i) {
        if (e[i] == 0.0) continue;
        const int lo = std::max(0, i - half), hi = std::min(bins - 1, i + half);
        double xs = 0.0, es = 0.0;
        for (int j = lo; j <= hi; ++j) xs += x[j], es += e[j];
        if (xs > 0.0) g[i] *= std::sqrt(es / xs);
      }
    }
    if (plan) plan->gains.push_back(g);
    std::vector<std::complex<double>> spectrum;
    fft.forward(db, spectrum);
    const BandGains band = filter.gains(k, fft.size());
    parts.emplace_back(spectrum.begin() + band.first, spectrum.begin() + band.first + static_cast<long>(band.w.size()));
  }
  return parts;
}

/// The rotation e^{−iφ} that makes a band part u orthogonal to a reference: Re(e^{−iφ}·⟨u, ref⟩) = 0,
/// given cross = ⟨u, ref⟩ (1 if it is 0). Of the two such phases, the one nearer 0.
std::complex<double> orthogonalRotation(std::complex<double> cross) {
  if (!(std::abs(cross) > 0.0)) return {1.0, 0.0};
  const double phi1 = std::arg(cross) - 0.5 * core::kPi, phi2 = std::arg(cross) + 0.5 * core::kPi;
  const auto wrapped = [](double x) { return std::abs(std::remainder(x, core::kTwoPi)); };
  return std::polar(1.0, -(wrapped(phi1) <= wrapped(phi2) ? phi1 : phi2));
}

std::complex<double> innerProduct(const BandSpectrum& u, const BandSpectrum& v) {
  std::complex<double> sum(0.0, 0.0);
  for (size_t j = 0; j < u.size(); ++j) sum += u[j] * std::conj(v[j]);
  return sum;
}

/// Scales x_b (updated in place) such that Σ_{k,l ∈ b ± 1} x_k x_l·coupling(b, k, l) = target_b for every
/// band with a positive target: what band b of a sum of band parts holds in an octave analysis, the
/// neighbours' crossovers included. kAnalysedEnergyRounds Jacobi rounds of x_b ← x_b·√(target_b / held_b); the
/// neighbours' share of a band's energy is a few % at most, so each round gains a factor ~30.
template <class Coupling>
void matchAnalysedEnergies(const std::vector<double>& target, std::vector<double>& x, Coupling coupling) {
  const int nb = static_cast<int>(target.size());
  std::vector<double> scale(static_cast<size_t>(nb), 1.0);
  for (int round = 0; round < kAnalysedEnergyRounds; ++round) {
    for (int b = 0; b < nb; ++b) {
      scale[b] = 1.0;
      if (!(target[b] > 0.0)) continue;
      double held = 0.0;
      for (int k = std::max(0, b - 1); k <= std::min(nb - 1, b + 1); ++k)
        for (int l = std::max(0, b - 1); l <= std::min(nb - 1, b + 1); ++l) held += x[k] * x[l] * coupling(b, k, l);
      if (held > 0.0) scale[b] = std::sqrt(target[b] / held);
    }
    for (int b = 0; b < nb; ++b) x[b] *= scale[b];
  }
}

/// Index of the (b, k, l) coupling in a [band][k − b + 1][l − b + 1] table.
size_t couplingIndex(int b, int k, int l) {
  return static_cast<size_t>(b) * 9 + static_cast<size_t>((k - b + 1) * 3 + (l - b + 1));
}

/// C_bkl = (2/m)·Σ_f W_b(f)²·v_k(f)·conj(v_l(f)) for k, l ∈ b ± 1 (indexed by couplingIndex), where v_k is
/// given on band k's bins (BandGains::first on) and is 0 elsewhere: how band b of an octave analysis weighs
/// the products of neighbouring band parts (v = W for a unit pulse, v = the part's spectrum otherwise).
template <class T>
std::vector<std::complex<double>> couplings(const std::vector<BandGains>& gains, int m,
                                            const std::vector<std::vector<T>>& v) {
  const int nb = static_cast<int>(v.size());
  const auto at = [&](int k, int j) {
    if (k < 0 || k >= nb) return std::complex<double>(0.0, 0.0);
    const int i = j - gains[k].first;
    return i >= 0 && i < static_cast<int>(v[k].size()) ? std::complex<double>(v[k][i]) : std::complex<double>(0.0, 0.0);
  };
  std::vector<std::complex<double>> c(static_cast<size_t>(nb) * 9, {0.0, 0.0});
  for (int b = 0; b < nb; ++b)
    for (int k = b - 1; k <= b + 1; ++k)
      for (int l = b - 1; l <= b + 1; ++l) {
        std::complex<double> sum(0.0, 0.0);
        for (size_t i = 0; i < gains[b].w.size(); ++i) {
          const int j = gains[b].first + static_cast<int>(i);
          sum += gains[b].w[i] * gains[b].w[i] * at(k, j) * std::conj(at(l, j));
        }
        c[couplingIndex(b, k, l)] = 2.0 * sum / static_cast<double>(m);
      }
  return c;
}

/// Per band, the factor that gives band b of Σ_k turn_k·s_k·parts_k (W_b applied to it, as the octave
/// analysis sees it) the energy band b of Σ_k parts_k has: the analysed energy is
/// Σ_{k,l} s_k s_l Re(turn_k·conj(turn_l)·C_bkl) (couplings of the parts), solved by Jacobi rounds as for
/// the arrivals. The turns make parts that came from the same Diracs lose (or gain) their coherent cross
/// terms in the crossovers: up to 6–7 % of a low band's analysed energy each, so a band read up to −12 %
/// in a single response without this.
std::vector<double> analysedEnergyScales(const std::vector<BandSpectrum>& parts,
                                         const std::vector<std::complex<double>>& turns,
                                         const std::vector<BandGains>& gains, int m) {
  const int nb = static_cast<int>(parts.size());
  const std::vector<std::complex<double>> c = couplings(gains, m, parts);
  std::vector<double> target(static_cast<size_t>(nb), 0.0);
  for (int b = 0; b < nb; ++b)
    for (int k = std::max(0, b - 1); k <= std::min(nb - 1, b + 1); ++k)
      for (int l = std::max(0, b - 1); l <= std::min(nb - 1, b + 1); ++l) target[b] += std::real(c[couplingIndex(b, k, l)]);
  std::vector<double> s(static_cast<size_t>(nb), 1.0);
  matchAnalysedEnergies(target, s, [&](int b, int k, int l) {
    return std::real(turns[k] * std::conj(turns[l]) * c[couplingIndex(b, k, l)]);
  });
  return s;
}

/// The response: the arrivals, each at its exact delay, and the traced part (tracedParts' band spectra,
/// or empty), phased within each band so that their energies add: the earliest arrival as it is, the
/// traced part rotated to be orthogonal to it, every later arrival orthogonal to all before it.
std::vector<double> combine(const EnergyResponse& r, const BandFilter& filter, RealFft& fft,
                            std::vector<BandSpectrum> traced, long samples, Phasing phasing, long traced_start,
                            detail::SynthesisPlan* plan) {
  const bool orthogonal = phasing == Phasing::Orthogonal;
  const double fs = filter.sampleRateHz();
  const int m = fft.size();
  const double length_s = static_cast<double>(samples) / fs;
  std::vector<BandGains> gains;
  std::vector<double> band_energy;  // Σ_n (band b's impulse response)² = (2/m)·Σ_k W_b(k)² (W = 0 at 0, m/2)
  for (int b = 0; b < r.bands.size(); ++b) {
    gains.push_back(filter.gains(b, m));
    double sum = 0.0;
    for (double w : gains.back().w) sum += w * w;
    band_energy.push_back(2.0 * sum / m);
    DIFFRAY_CHECK(band_energy.back() > 0.0);
  }
  // Each band's part of the arrivals (on that band's bins, built in order of delay), and what an arrival
  // is made orthogonal to: the band's traced part and the arrivals placed so far.
  std::vector<BandSpectrum> part, reference;
  for (size_t b = 0; b < gains.size(); ++b) {
    part.emplace_back(gains[b].w.size(), std::complex<double>(0.0, 0.0));
    reference.push_back(part.back());
    DIFFRAY_CHECK(b >= traced.size() || traced[b].size() == part.back().size());
  }
  std::vector<size_t> order(r.arrivals.size());
  std::iota(order.begin(), order.end(), size_t{0});
  std::stable_sort(order.begin(), order.end(),
                   [&](size_t x, size_t y) { return r.arrivals[x].delay_s < r.arrivals[y].delay_s; });
  // The analysis weights of the arrivals' band parts: band b of a pulse Σ_k c_k·A_k·W_k (c_k its band
  // phases) holds (2/m)·Σ_f W_b²·|Σ_k c_k A_k W_k|² = Σ_{k,l} A_k A_l Re(c_k c̄_l)·M_bkl, with
  // M_bkl = (2/m)·Σ_f W_b² W_k W_l (the couplings of the filters themselves, real).
  const int nb = r.bands.size();
  std::vector<std::vector<double>> filters;
  for (const BandGains& g : gains) filters.push_back(g.w);
  const std::vector<std::complex<double>> weight = couplings(gains, m, filters);
  bool first = true;
  std::vector<BandSpectrum> u(static_cast<size_t>(nb));
  std::vector<double> amplitude(static_cast<size_t>(nb)), target(static_cast<size_t>(nb));
  std::vector<std::complex<double>> rotation(static_cast<size_t>(nb));
  if (plan) {
    plan->traced_turn.assign(static_cast<size_t>(nb), {1.0, 0.0});
    plan->arrival_coefficients.assign(r.arrivals.size(), std::vector<std::complex<double>>(static_cast<size_t>(nb)));
  }
  for (size_t index : order) {
    const Arrival& a = r.arrivals[index];
    if (a.delay_s >= length_s) continue;  // beyond the response: its energy is not in it
    // e^{−2πi·k·τ·fs/m} by recurrence from the band's first bin: accurate to ~k·1e-16, ample here.
    const double phase_step = -core::kTwoPi * a.delay_s * fs / m;
    const std::complex<double> step = std::polar(1.0, phase_step);
    for (int b = 0; b < nb; ++b) {
      target[b] = std::max(0.0, a.energy[b]);
      amplitude[b] = std::sqrt(target[b] / band_energy[b]);  // the part's own energy: a start
      rotation[b] = {1.0, 0.0};
      if (target[b] == 0.0) continue;
      const BandGains& g = gains[b];
      u[b].resize(g.w.size());
      std::complex<double> z = std::polar(1.0, phase_step * g.first);
      for (size_t j = 0; j < g.w.size(); ++j, z *= step) u[b][j] = g.w[j] * z;
      // The phase of the pulse in this band (a rotation e^{−iφ} of its positive-frequency spectrum: the
      // same envelope, carrier shifted) chosen so that it is orthogonal to what the band holds already:
      // Re(e^{−iφ}·⟨u, reference⟩) = 0, so that band energies add as the energy model says (synthesis.h).
      // The earliest arrival (the direct sound, when there is one) meets nothing and keeps phase 0, so
      // its broadband pulse stays sharp: the onset (time zero of every metric) is found on it. (Scaling u
      // later keeps it orthogonal.)
      if (orthogonal) rotation[b] = orthogonalRotation(innerProduct(u[b], reference[b]));
    }
    // The amplitudes that give band b of the whole pulse (W_b of the sum of its parts, what an octave
    // analysis sees) the arrival's energy: a few Jacobi rounds on the weights above. Matching each part's
    // own energy left the lowest band 7 % short (its lower crossover holds its part filtered twice) and
    // bands whose neighbours differ in amplitude off by the crossover's cross terms.
    matchAnalysedEnergies(target, amplitude, [&](int b, int k, int l) {
      return std::real(rotation[k] * std::conj(rotation[l])) * std::real(weight[couplingIndex(b, k, l)]);
    });
    for (int b = 0; b < nb; ++b) {
      if (target[b] == 0.0) continue;
      const std::complex<double> c = rotation[b] * amplitude[b];
      if (plan) plan->arrival_coefficients[index][static_cast<size_t>(b)] = c;
      for (size_t j = 0; j < u[b].size(); ++j) {
        part[b][j] += c * u[b][j];
        reference[b][j] += c * u[b][j];
      }
    }
    if (first && orthogonal) {
      // The traced part (all of its envelope kept: a rotation of the carrier) made orthogonal to it, each
      // band by its own turn, and rescaled so that the octave analysis finds the energies it found before
      // the turns (they change the crossovers' cross terms between neighbouring parts).
      std::vector<std::complex<double>> turns;
      for (size_t b = 0; b < traced.size(); ++b) turns.push_back(orthogonalRotation(innerProduct(traced[b], part[b])));
      const std::vector<double> scales = analysedEnergyScales(traced, turns, gains, m);
      for (size_t b = 0; b < traced.size(); ++b) {
        if (plan) plan->traced_turn[b] = turns[b] * scales[b];
        for (size_t j = 0; j < traced[b].size(); ++j) {
          traced[b][j] *= turns[b] * scales[b];
          reference[b][j] += traced[b][j];
        }
      }
      first = false;
    }
  }
  // The arrivals and the traced part go back to time separately: the traced part is silenced before its
  // first bin (tracedStartSample), the arrivals' pulses are kept whole.
  const auto toTime = [&](const std::vector<BandSpectrum>& parts) {
    std::vector<std::complex<double>> spectrum(static_cast<size_t>(fft.bins()), {0.0, 0.0});
    for (size_t b = 0; b < parts.size(); ++b)
      for (size_t j = 0; j < parts[b].size(); ++j) spectrum[gains[b].first + j] += parts[b][j];
    return fft.inverse(spectrum, samples);
  };
  std::vector<double> p = toTime(part);
  if (!traced.empty()) {
    const std::vector<double> t = toTime(traced);
    for (long s = std::min(traced_start, samples); s < samples; ++s) p[s] += t[s];
  }
  return p;
}

}  // namespace

std::vector<double> poissonDiracs(long samples, double sample_rate_hz, double volume_m3,
                                  double speed_of_sound_m_s, std::uint64_t seed) {
  // Events of the rate μ(t) = min(4πc³t²/V, μmax) by inverting its integral Λ(t) at the partial sums of
  // unit exponentials: Λ = 4πc³t³/(3V) up to t_cap (where μ reaches μmax), then linear.
  const double a = 4.0 * core::kPi * std::pow(speed_of_sound_m_s, 3) / volume_m3;
  if (!(std::isfinite(a) && a > 0.0))  // a volume of ~1e-300 m³ made a infinite and the event loop endless
    throw core::InputError("volume", "the Dirac rate 4πc³/V must be finite and positive (V = " +
                                         std::to_string(volume_m3) + " m³, c = " + std::to_string(speed_of_sound_m_s) +
                                         " m/s)");
  const double t_cap = std::sqrt(kMaxDiracRate / a);
  const double lambda_cap = a * t_cap * t_cap * t_cap / 3.0;
  const double end_s = static_cast<double>(samples) / sample_rate_hz;
  std::vector<double> d(static_cast<size_t>(samples), 0.0);
  core::Rng rng(seed, kStreamPoisson);
  double lambda = 0.0;
  for (;;) {
    lambda += -std::log(1.0 - rng.uniform());
    const double t = lambda <= lambda_cap ? std::cbrt(3.0 * lambda / a) : t_cap + (lambda - lambda_cap) / kMaxDiracRate;
    if (t >= end_s) break;
    const auto s = std::min(samples - 1, static_cast<long>(t * sample_rate_hz));
    d[s] += rng.uniform() < 0.5 ? -1.0 : 1.0;
  }
  return d;
}

std::vector<double> synthesize(const EnergyResponse& response, double sample_rate_hz, double length_s,
                               double volume_m3, double speed_of_sound_m_s, std::uint64_t seed, Phasing phasing) {
  return detail::synthesizePlanned(response, sample_rate_hz, length_s, volume_m3, speed_of_sound_m_s, seed, phasing,
                                   nullptr);
}

namespace detail {

std::vector<double> synthesizePlanned(const EnergyResponse& response, double sample_rate_hz, double length_s,
                                      double volume_m3, double speed_of_sound_m_s, std::uint64_t seed,
                                      Phasing phasing, SynthesisPlan* plan) {
  checkInputs(response, sample_rate_hz, length_s, volume_m3, speed_of_sound_m_s);
  const long n = core::checkedCount("synthesis: samples", length_s * sample_rate_hz, 1u << 30);
  const BandFilter filter(response.bands, sample_rate_hz);
  RealFft fft(filter.fftLengthFor(n));
  const long quiet = tracedStartSample(response, sample_rate_hz, n);
  if (plan) {
    *plan = SynthesisPlan();
    plan->samples = n;
    plan->quiet = quiet;
    plan->fft_size = fft.size();
  }
  std::vector<BandSpectrum> traced;
  if (!response.traced.empty())
    traced = tracedParts(response, filter, fft, volume_m3, speed_of_sound_m_s, seed, n, quiet, plan);
  return combine(response, filter, fft, std::move(traced), n, phasing, quiet, plan);
}

}  // namespace detail

}  // namespace diffray::ir
