#include "diffray/ir/metrics.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "diffray/core/error.h"
#include "diffray/ir/band_filter.h"
#include "diffray/ir/filter_limit.h"
#include "diffray/ir/uncertainty.h"

namespace diffray::ir {

namespace {

constexpr double kNaN = BandMetrics::kNaN;
constexpr double kOnsetDb = -20.0;  // ISO 3382-1 A.3.4: the onset lies ≥ 20 dB below the peak
constexpr double kNoiseMarginDb = 10.0;  // ISO 3382-1 §5.3.3: evaluation ranges end this far above the noise

double dB(double ratio) { return 10.0 * std::log10(ratio); }
/// Time of bin edge i (or i bins' duration).
double edgeS(double i, double bin_s) { return i * bin_s; }
double edgeS(long i, double bin_s) { return static_cast<double>(i) * bin_s; }

struct Line {
  double slope = 0.0, intercept = 0.0;  ///< y = slope·t + intercept
  bool ok = false;
};

Line leastSquares(const std::vector<double>& t, const std::vector<double>& y, size_t first, size_t last) {
  Line line;
  const double n = static_cast<double>(last - first + 1);
  if (last < first + 1) return line;  // two points at least
  double mt = 0.0, my = 0.0;
  for (size_t i = first; i <= last; ++i) mt += t[i], my += y[i];
  mt /= n;
  my /= n;
  double stt = 0.0, sty = 0.0;
  for (size_t i = first; i <= last; ++i) stt += (t[i] - mt) * (t[i] - mt), sty += (t[i] - mt) * (y[i] - my);
  if (!(stt > 0.0)) return line;
  line.slope = sty / stt;
  line.intercept = my - line.slope * mt;
  line.ok = std::isfinite(line.slope);
  return line;
}

/// Mean power (energy per second) over intervals of w bins, and the interval centres; in dB (−inf for 0).
struct Smoothed {
  std::vector<double> t_s, level_db;
};

Smoothed smooth(const std::vector<double>& e, long w, double bin_s) {
  Smoothed s;
  const long n = static_cast<long>(e.size());
  for (long j = 0; j + w <= n; j += w) {
    double sum = 0.0;
    for (long i = j; i < j + w; ++i) sum += e[i];
    s.t_s.push_back(edgeS(static_cast<double>(j) + 0.5 * static_cast<double>(w), bin_s));
    s.level_db.push_back(sum > 0.0 ? dB(sum / edgeS(w, bin_s)) : -HUGE_VAL);
  }
  return s;
}

/// The line through the smoothed levels from the first interval (from the peak on) at or below top_db
/// to the last one before the level first drops below bottom_db.
Line fitBetween(const Smoothed& s, double top_db, double bottom_db) {
  const size_t peak = static_cast<size_t>(std::max_element(s.level_db.begin(), s.level_db.end()) - s.level_db.begin());
  size_t first = peak;
  while (first < s.level_db.size() && s.level_db[first] > top_db) ++first;
  size_t last = first;
  while (last + 1 < s.level_db.size() && s.level_db[last + 1] >= bottom_db) ++last;
  if (first >= s.level_db.size() || s.level_db[first] < bottom_db) return Line{};
  return leastSquares(s.t_s, s.level_db, first, last);
}

double meanPower(const std::vector<double>& e, long from, double bin_s) {
  const long n = static_cast<long>(e.size());
  double sum = 0.0;
  for (long i = from; i < n; ++i) sum += e[i];
  return sum / edgeS(n - from, bin_s);
}

/// Where to stop the Schroeder integral, and the energy of the decay's continuation beyond.
struct Truncation {
  long bins = 0;             ///< bins kept, from the onset
  double tail = 0.0;         ///< energy added for the exponential continuation past `bins`
  double tail_rate = 0.0;    ///< its decay rate k: power ∝ e^{−k t}
  bool truncated = false;
  bool noise_floor = false;  ///< the decay meets a noise floor (not merely the response's end)
  double noise_range_db = HUGE_VAL;  ///< peak over noise, when the decay never clears the noise by 10 dB
};

// Lundeby, Vigran, Bietz & Vorländer, "Uncertainties of measurements in room acoustics", Acustica 81
// (1995), the iterative noise truncation ISO 3382-1 §5.3.3 refers to:
//  1. average the power in 10 ms intervals; 2. the noise is the mean power of the last 10 %;
//  3. a line from the peak down to 10 dB above the noise; 4. the crosspoint: where it meets the noise;
//  5. new intervals, 5 per 10 dB of decay; 6. the noise from 5 dB of decay past the crosspoint (at
//  least the last 10 %); 7. the late decay: a line from 25 to 5 dB above the noise; 8. a new crosspoint;
//  repeat 5–8 until it moves by less than an interval (at most 10 times). The integral stops at the
//  crosspoint and the line's exponential continuation (energy P(t_c)/k) stands in for what lies beyond;
//  a response that ends first is integrated to its end and continued from the power it ends with.
// A response whose last 10 % holds no energy has no noise: it is used whole.
Truncation lundeby(const std::vector<double>& e, double bin_s) {
  const long n = static_cast<long>(e.size());
  Truncation none;
  none.bins = n;
  const double t_end = edgeS(n, bin_s);
  double noise = meanPower(e, n - std::max(1L, n / 10), bin_s);
  if (!(noise > 0.0)) return none;
  long w = std::max(1L, std::lround(0.010 / bin_s));
  Smoothed s = smooth(e, w, bin_s);
  if (s.t_s.size() < 3) return none;
  Line line = fitBetween(s, HUGE_VAL, dB(noise) + 10.0);
  if (!line.ok || line.slope >= 0.0) {
    none.noise_range_db = *std::max_element(s.level_db.begin(), s.level_db.end()) - dB(noise);
    none.noise_floor = true;
    return none;
  }
  double tc = (dB(noise) - line.intercept) / line.slope;
  for (int iteration = 0; iteration < 10 && tc < t_end; ++iteration) {
    const double db_per_s = -line.slope;
    w = std::max(1L, std::lround(2.0 / db_per_s / bin_s));  // 5 intervals per 10 dB
    s = smooth(e, w, bin_s);
    if (s.t_s.size() < 3) break;
    const double t_noise = std::min(tc + 5.0 / db_per_s, 0.9 * t_end);
    const double new_noise = meanPower(e, static_cast<long>(t_noise / bin_s), bin_s);
    if (!(new_noise > 0.0)) return none;
    const Line late = fitBetween(s, dB(new_noise) + 25.0, dB(new_noise) + 5.0);
    if (!late.ok || late.slope >= 0.0) break;
    noise = new_noise;
    line = late;
    const double tc_new = (dB(noise) - line.intercept) / line.slope;
    const bool settled = std::abs(tc_new - tc) < edgeS(w, bin_s);
    tc = tc_new;
    if (settled) break;
  }
  if (!(tc > 0.0)) return none;
  Truncation tr;
  tr.truncated = true;
  tr.tail_rate = -line.slope * std::log(10.0) / 10.0;
  if (tc >= t_end) {
    // The response ends before its decay meets the noise (cut short, with little or no noise): the
    // integral runs to the end and an exponential continuation stands in for the rest, as past a
    // crosspoint. Without it the Schroeder curve plunges at the cut: T30 read up to 18 % short, and the
    // decay range counted the plunge (90 dB from a 1 s cut of a 2 s decay). Its power starts from what the
    // last 10 % of the response actually holds (mean P̄ over Δ, at the decay line's rate k:
    // P(end) = P̄·kΔ/(e^{kΔ} − 1)), not from the line, which a sparse or double-sloped tail can sit far
    // above.
    const long last = std::max(1L, n / 10);
    const double k_span = tr.tail_rate * edgeS(last, bin_s);
    const double p_end = meanPower(e, n - last, bin_s) * (k_span > 1e-12 ? k_span / std::expm1(k_span) : 1.0);
    tr.bins = n;
    tr.tail = p_end / tr.tail_rate;
    return tr;
  }
  // A noise floor persists past the crosspoint; a response cut while it still decays (a histogram, a
  // synthesized IR, a recording stopped early) has its "noise", the last 10 %, at the end of the decay, and
  // the line meets it within the last few dB: then there is no floor to keep clear of. Lundeby's step 6
  // reads the noise from 5 dB of decay past the crosspoint; a floor is one that lasts that long.
  tr.noise_floor = (t_end - tc) * -line.slope >= 5.0;
  tr.bins = std::max(1L, static_cast<long>(tc / bin_s));
  tr.tail = std::pow(10.0, (line.slope * edgeS(tr.bins, bin_s) + line.intercept) / 10.0) / tr.tail_rate;
  return tr;
}

/// T from the Schroeder curve (level_db at times t_s): the line from its first reach of top_db to its
/// first reach of bottom_db; NaN if the curve does not get there within the usable range.
double decayTime(const std::vector<double>& t_s, const std::vector<double>& level_db, double top_db,
                 double bottom_db, double range_db) {
  if (range_db < -bottom_db) return kNaN;
  size_t first = 0;
  while (first < level_db.size() && level_db[first] > top_db) ++first;
  size_t last = first;
  while (last < level_db.size() && level_db[last] > bottom_db) ++last;
  if (last >= level_db.size()) return kNaN;
  const Line line = leastSquares(t_s, level_db, first, last);
  return line.ok && line.slope < 0.0 ? -60.0 / line.slope : kNaN;
}

}  // namespace

long onsetBin(const std::vector<double>& energy_per_bin) {
  double peak = 0.0;
  for (double v : energy_per_bin) {
    core::requireFinite("metrics: energy", v);
    peak = std::max(peak, v);
  }
  if (!(peak > 0.0)) return -1;
  const double threshold = peak * std::pow(10.0, kOnsetDb / 10.0);
  return std::find_if(energy_per_bin.begin(), energy_per_bin.end(), [&](double v) { return v > threshold; }) -
         energy_per_bin.begin();
}

BandMetrics metricsFromEnergy(const std::vector<double>& energy_per_bin, double bin_s) {
  return metricsFromEnergy(energy_per_bin, bin_s, onsetBin(energy_per_bin));
}

BandMetrics metricsFromEnergy(const std::vector<double>& energy_per_bin, double bin_s, long onset) {
  core::requirePositive("metrics: bin width", bin_s);
  BandMetrics m;
  for (double v : energy_per_bin) core::requireFinite("metrics: energy", v);
  if (onset < 0 || onset >= static_cast<long>(energy_per_bin.size())) return m;
  // Energy is integrated from the band's own onset when that comes first: a zero-phase band filter
  // spreads an arrival symmetrically about its time, and its first half belongs to it (for Ts the two
  // halves balance about time zero).
  const long own = onsetBin(energy_per_bin);
  const long start = own >= 0 ? std::min(own, onset) : onset;
  const double zero_s = edgeS(onset - start, bin_s);  // time zero inside e
  const std::vector<double> e(energy_per_bin.begin() + start, energy_per_bin.end());

  const Truncation tr = lundeby(e, bin_s);
  const long nc = tr.bins;
  // Schroeder backward integral at bin edges 0 … nc, in long double: it sums up to millions of samples.
  std::vector<double> schroeder(static_cast<size_t>(nc) + 1);
  long double acc = tr.tail;
  schroeder[nc] = static_cast<double>(acc);
  long double moment = 0.0L;  // ∫ t·p² dt with t from time zero, for Ts
  for (long i = nc - 1; i >= 0; --i) {
    acc += e[i];
    moment += static_cast<long double>(e[i]) * (edgeS(static_cast<double>(i) + 0.5, bin_s) - zero_s);
    schroeder[i] = static_cast<double>(acc);
  }
  const double total = schroeder[0];
  if (!(total > 0.0)) return m;
  std::vector<double> t_s(schroeder.size()), level_db(schroeder.size());
  for (size_t i = 0; i < schroeder.size(); ++i) {
    t_s[i] = static_cast<double>(i) * bin_s - zero_s;
    level_db[i] = schroeder[i] > 0.0 ? dB(schroeder[i] / total) : -HUGE_VAL;
  }
  // The usable decay: down to the truncation, or to the last energy of a response without noise.
  double range = 0.0;
  for (double l : level_db)
    if (std::isfinite(l)) range = std::max(range, -l);
  if (tr.truncated) {
    range = -level_db[nc];
    m.truncation_s = edgeS(nc, bin_s) - zero_s;
  }
  range = std::min(range, tr.noise_range_db);
  m.decay_range_db = range;
  // ISO 3382-1 §5.3.3: the bottom of an evaluation range lies at least 10 dB above the noise floor (T20
  // and T30 then need 35 and 45 dB of decay above the noise; EDT 20 dB, by the same rule). A response
  // without noise (a histogram, a synthesized IR) is usable to its end.
  const double usable = tr.noise_floor ? range - kNoiseMarginDb : range;
  m.edt = decayTime(t_s, level_db, 0.0, -10.0, usable);
  m.t20 = decayTime(t_s, level_db, -5.0, -25.0, usable);
  m.t30 = decayTime(t_s, level_db, -5.0, -35.0, usable);

  // E(t) between bin edges: energy uniform inside a bin; past the truncation, the exponential tail.
  const auto energyAfter = [&](double t_from_zero) {
    const double t = t_from_zero + zero_s;
    const double x = t / bin_s;
    const long j = static_cast<long>(std::floor(x));
    if (j < nc) return schroeder[j] - (x - static_cast<double>(j)) * e[j];
    if (tr.truncated) return tr.tail * std::exp(-tr.tail_rate * (t - edgeS(nc, bin_s)));
    return 0.0;
  };
  const auto clarity = [&](double te) {
    const double late = energyAfter(te);
    return late > 0.0 ? dB(total / late - 1.0) : kNaN;
  };
  m.c50 = clarity(0.050);
  m.c80 = clarity(0.080);
  m.d50 = 1.0 - energyAfter(0.050) / total;
  // The tail's first moment: ∫_tc^∞ t·P_c·e^{−k(t−tc)} dt = tail·(tc + 1/k).
  if (tr.truncated) moment += static_cast<long double>(tr.tail) * (edgeS(nc, bin_s) - zero_s + 1.0 / tr.tail_rate);
  m.ts = static_cast<double>(moment) / total;
  // A band that clears its noise floor by less than kNoiseMarginDb holds mostly noise: its energy ratios
  // measure where the file starts and ends, not the room (C50 of a 1 s decay under hum read −5.7 or
  // −11.7 dB with or without 100 ms of pre-delay), so none is given.
  if (tr.noise_floor && !(range >= kNoiseMarginDb)) m.c50 = m.c80 = m.d50 = m.ts = kNaN;
  // A record that ends (untruncated: no tail to extrapolate) within 50 ms of its onset holds no late
  // energy to compare with: D50 would read 1 and Ts the record's own centre, from no data.
  if (!tr.truncated && edgeS(static_cast<double>(e.size()), bin_s) - zero_s < 0.050) m.d50 = m.ts = kNaN;
  return m;
}

std::vector<BandMetrics> metricsFromSignal(const std::vector<double>& p, double sample_rate_hz,
                                           const core::Bands& bands) {
  for (double v : p) core::requireFinite("metrics: signal sample", v);
  const BandFilter filter(bands, sample_rate_hz);
  // The signal is filtered with the filters' ringing time of zeros in front (as if recorded with a
  // pre-delay) and its mean removed. A zero-phase band spreads an arrival symmetrically about its time;
  // a response that starts at sample 0 would otherwise lose the half before it (C50 0.3–1.4 dB low at
  // 63 Hz and Ts long, against the same response with a pre-delay). A DC offset would turn into steps at
  // both ends, whose low-frequency energy reads as a noise floor (a 0.5 % offset cut the 63 Hz decay range
  // from 88 to 56 dB). The lead shifts every time equally; metrics count from the onset.
  const std::vector<double> padded = withLeadAndNoMean(p, filter.ringSamples());
  std::vector<std::vector<double>> energy = filter.split(padded);
  // The onset of the band-summed signal (p inside the bands' range): a band on its own smears the start
  // over ~1/bandwidth (22 ms at 63 Hz), which would move time zero by several ms.
  std::vector<double> broadband(padded.size(), 0.0);
  for (const auto& band : energy)
    for (size_t n = 0; n < padded.size(); ++n) broadband[n] += band[n];
  for (double& v : broadband) v *= v;
  const long onset = onsetBin(broadband);
  // A band is not measured when the file ends less than its filter's ringing time after the onset: the
  // band signal is then cut off while it still holds much of the filter's own response (a 21-sample click
  // read a negative decay range at 63 Hz, a negative Ts at 125 Hz and an EDT of 0.25 s). This is a test of
  // the file's length only: a response that is itself shorter than the filter's ringing but sits in a long
  // enough file is measured, and then reads the filter's decay (and is flagged: FilterLimit).
  const long after_onset = onset < 0 ? 0 : static_cast<long>(padded.size()) - onset;
  const FilterLimit limit(filter);
  std::vector<BandMetrics> out;
  for (int b = 0; b < static_cast<int>(energy.size()); ++b) {
    if (onset >= 0 && after_onset < filter.ringSamples(b)) {
      BandMetrics m;
      m.shorter_than_filter = true;
      out.push_back(m);
      continue;
    }
    std::vector<double>& band = energy[static_cast<size_t>(b)];
    for (double& v : band) v *= v;
    BandMetrics m = metricsFromEnergy(band, 1.0 / sample_rate_hz, onset);
    for (Figure f : kAllFigures) m.filter_limited[static_cast<size_t>(f)] = limit.limited(b, f, m.value(f));
    out.push_back(m);
  }
  return out;
}

std::vector<BandMetrics> metricsFromHistograms(const std::vector<std::vector<double>>& energy_per_band,
                                               double bin_s) {
  std::vector<double> broadband;
  for (const auto& band : energy_per_band) {
    broadband.resize(std::max(broadband.size(), band.size()), 0.0);
    for (size_t i = 0; i < band.size(); ++i) broadband[i] += band[i];
  }
  const long onset = onsetBin(broadband);
  std::vector<BandMetrics> out;
  for (const auto& band : energy_per_band) out.push_back(metricsFromEnergy(band, bin_s, onset));
  return out;
}

const char* figureName(Figure figure) {
  static constexpr const char* kNames[] = {"edt", "t20", "t30", "c50", "c80", "d50", "ts"};
  return kNames[static_cast<int>(figure)];
}

double BandMetrics::value(Figure f) const {
  switch (f) {
    case Figure::Edt: return edt;
    case Figure::T20: return t20;
    case Figure::T30: return t30;
    case Figure::C50: return c50;
    case Figure::C80: return c80;
    case Figure::D50: return d50;
    case Figure::Ts: return ts;
  }
  return kNaN;
}

nlohmann::ordered_json metricsJson(const core::Bands& bands, const std::vector<BandMetrics>& metrics) {
  DIFFRAY_CHECK(static_cast<int>(metrics.size()) == bands.size());
  const auto value = [](double v) {
    return std::isfinite(v) ? nlohmann::ordered_json(v) : nlohmann::ordered_json(nullptr);
  };
  nlohmann::ordered_json j = nlohmann::ordered_json::object();
  for (int b = 0; b < bands.size(); ++b) {
    const BandMetrics& m = metrics[b];
    j[bands.label(b)] = {{"t20", value(m.t20)}, {"t30", value(m.t30)}, {"edt", value(m.edt)},
                         {"c50", value(m.c50)}, {"c80", value(m.c80)}, {"d50", value(m.d50)},
                         {"ts", value(m.ts)},   {"decay_range_db", value(m.decay_range_db)}};
    if (m.shorter_than_filter) j[bands.label(b)]["shorter_than_filter"] = true;
    nlohmann::ordered_json limited = nlohmann::ordered_json::array();
    for (Figure f : kAllFigures)
      if (m.limited(f)) limited.push_back(figureName(f));
    if (!limited.empty()) j[bands.label(b)]["filter_limited"] = limited;
  }
  return j;
}

std::string metricsTable(const core::Bands& bands, const std::vector<BandMetrics>& metrics,
                         const std::vector<BandUncertainty>* uncertainty) {
  DIFFRAY_CHECK(static_cast<int>(metrics.size()) == bands.size());
  DIFFRAY_CHECK(!uncertainty || uncertainty->size() == metrics.size());
  std::string out;
  char line[160];
  std::snprintf(line, sizeof line, "%7s %7s %7s %7s %7s %7s %7s %7s %9s%s\n", "band Hz", "T20 s", "T30 s", "EDT s",
                "C50 dB", "C80 dB", "D50", "Ts ms", "range dB", uncertainty ? "  flag" : "");
  out += line;
  bool missing = false, short_band = false, limited_any = false, noisy_any = false, negative_any = false;
  const auto cell = [&missing](double v, const char* format) {
    char text[32];
    if (!std::isfinite(v)) {
      missing = true;
      return std::string("      -");
    }
    std::snprintf(text, sizeof text, format, v);
    return std::string(text);
  };
  for (int b = 0; b < bands.size(); ++b) {
    const BandMetrics& m = metrics[b];
    const BandUncertainty* u = uncertainty ? &(*uncertainty)[static_cast<std::size_t>(b)] : nullptr;
    short_band |= m.shorter_than_filter;
    // Marks after a figure: '*' within its band filter's reach (BandMetrics::filter_limited), '?' noisier
    // than its JND; '!' alone where negative energy leaves no figure.
    const auto figure = [&](Figure f, double scale, int decimals) {
      const double v = scale * m.value(f);
      if (!std::isfinite(v)) {
        if (u && u->isNegative(f)) {
          negative_any = true;
          return std::string("      !");
        }
        return cell(v, "%7.3f");
      }
      std::string marks;
      if (m.limited(f)) marks += '*', limited_any = true;
      if (u && u->isNoisy(f)) marks += '?', noisy_any = true;
      char format[16];
      std::snprintf(format, sizeof format, "%%%d.%df%s", 7 - static_cast<int>(marks.size()), decimals, marks.c_str());
      return cell(v, format);
    };
    static constexpr const char* kFlags[] = {"    ok", " noisy", "   neg"};
    out += cell(bands.nominalHz(b), "%7g") + " " + figure(Figure::T20, 1.0, 3) + " " + figure(Figure::T30, 1.0, 3) +
           " " + figure(Figure::Edt, 1.0, 3) + " " + figure(Figure::C50, 1.0, 2) + " " + figure(Figure::C80, 1.0, 2) +
           " " + figure(Figure::D50, 1.0, 3) + " " + figure(Figure::Ts, 1e3, 1) + "   " +
           (m.shorter_than_filter ? std::string("  short") : cell(m.decay_range_db, "%7.1f")) +
           (u ? kFlags[static_cast<int>(u->flag())] : "") + "\n";
  }
  if (missing)
    out += "-: not measurable. T20, T30 and EDT need the decay to fall 25, 35 and 10 dB, and 10 dB more when it "
           "meets a noise floor (ISO 3382-1); C50, C80 need energy after 50, 80 ms. range dB: how far it falls "
           "before a noise floor or the end (and, traced, where the rays resolve its level to 1 dB; impulse/README.md).\n";
  if (limited_any)
    out += "*: within the reach of the band's analysis filter: the exponential decay that reads this way has a true "
           "value more than one JND away (ISO 3382-1 Annex A: 5 % for T and EDT, 1 dB for C, 0.05 for D50, 10 ms for "
           "Ts), or cannot be told from a Dirac; the figure measures the filter too.\n";
  if (short_band)
    out += "short: the file ends sooner after the onset than the band's analysis filter rings (0.15-0.4 s for "
           "octave bands, up to 1.2 s for third octaves), so the band is not measured.\n";
  if (noisy_any)
    out += "?: noisy: its standard error (jackknife over the ray batches, in the JSON's \"se\") exceeds its JND "
           "(5 % for T and EDT, 1 dB for C, 0.05 for D50, 10 ms for Ts), or it cannot be measured once a batch "
           "of rays is left out; trace more rays.\n";
  if (negative_any)
    out += "!: not available: the band's energy (signed with WBSDF diffraction) sums negative, or its decay curve "
           "falls to zero or below; trace more rays.\n";
  if (uncertainty)
    out += "flag: ok, noisy (a figure marked ?), or neg (negative energy: a figure marked !).\n";
  return out;
}

}  // namespace diffray::ir
