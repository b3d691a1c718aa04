// Spatial figures per band: J_LF, J_LFC from AmbiX, IACC_E, IACC_L from binaural responses (see the header).
#include "diffray/ir/spatial_metrics.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include "diffray/core/error.h"
#include "diffray/ir/band_filter.h"
#include "diffray/ir/metrics.h"

namespace diffray::ir {
namespace {

constexpr double kNaN = SpatialBandMetrics::kNaN;

// Two channels split into bands on a common time axis, with time zero and each band's start.
struct BandPair {
  std::vector<std::vector<double>> a, b;  ///< [band][sample], after `lead` zeros
  long onset = -1;                        ///< broadband onset (sample), −1 if silent
  std::vector<long> start;                ///< per band: where a window from time zero starts (≤ onset)
  std::vector<bool> measurable;           ///< per band: the record outlasts the band filter's ringing
  double fs = 0.0;
};

// `both_define_onset`: time zero from the energies of a and b summed (binaural), else from a alone (W). The
// two channels are split in parallel.
BandPair splitPair(const std::vector<double>& a, const std::vector<double>& b, double fs, const core::Bands& bands,
                   bool both_define_onset, const char* what) {
  if (a.size() != b.size()) throw core::InputError(what, "its channels differ in length");
  for (const std::vector<double>* x : {&a, &b})  // the message is built only for a sample that fails
    for (double v : *x)
      if (!std::isfinite(v)) core::requireFinite(std::string(what) + ": sample", v);
  const BandFilter filter(bands, fs);
  const long lead = filter.ringSamples();
  BandPair p;
  p.fs = fs;
  tbb::parallel_invoke([&] { p.a = filter.split(withLeadAndNoMean(a, lead)); },
                       [&] { p.b = filter.split(withLeadAndNoMean(b, lead)); });
  const std::size_t n = static_cast<std::size_t>(lead) + a.size();
  // The band-summed signals' energy: a band alone smears the start over ~1/bandwidth (metrics.h).
  std::vector<double> sum_a(n, 0.0), sum_b(n, 0.0), broadband(n, 0.0);
  for (int band = 0; band < bands.size(); ++band)
    for (std::size_t i = 0; i < n; ++i) sum_a[i] += p.a[static_cast<std::size_t>(band)][i], sum_b[i] += p.b[static_cast<std::size_t>(band)][i];
  for (std::size_t i = 0; i < n; ++i) broadband[i] = sum_a[i] * sum_a[i] + (both_define_onset ? sum_b[i] * sum_b[i] : 0.0);
  p.onset = onsetBin(broadband);
  if (p.onset < 0) throw core::InputError(what, "every sample of the reference channel is zero: there is no response");
  for (int band = 0; band < bands.size(); ++band) {
    const auto& xa = p.a[static_cast<std::size_t>(band)];
    const auto& xb = p.b[static_cast<std::size_t>(band)];
    std::vector<double> e(n);
    for (std::size_t i = 0; i < n; ++i) e[i] = xa[i] * xa[i] + (both_define_onset ? xb[i] * xb[i] : 0.0);
    const long own = onsetBin(e);
    p.start.push_back(own >= 0 ? std::min(own, p.onset) : p.onset);
    p.measurable.push_back(static_cast<long>(n) - p.onset >= filter.ringSamples(band));
  }
  return p;
}

long samples(double seconds, double fs) { return std::lround(seconds * fs); }

}  // namespace

std::vector<SpatialBandMetrics> lateralFractions(const std::vector<double>& w, const std::vector<double>& y,
                                                 double sample_rate_hz, const core::Bands& bands, double reference_10m) {
  const BandPair p = splitPair(w, y, sample_rate_hz, bands, false, "AmbiX response");
  std::vector<SpatialBandMetrics> out(static_cast<std::size_t>(bands.size()));
  const long n5 = p.onset + samples(0.005, p.fs), n80 = p.onset + samples(0.080, p.fs);
  for (int b = 0; b < bands.size(); ++b) {
    const auto& pw = p.a[static_cast<std::size_t>(b)];
    const auto& py = p.b[static_cast<std::size_t>(b)];
    if (!p.measurable[static_cast<std::size_t>(b)] || n80 > static_cast<long>(pw.size())) continue;
    double den = 0.0, num = 0.0, numc = 0.0;
    for (long i = p.start[static_cast<std::size_t>(b)]; i < n80; ++i) den += pw[static_cast<std::size_t>(i)] * pw[static_cast<std::size_t>(i)];
    for (long i = n5; i < n80; ++i) {
      num += py[static_cast<std::size_t>(i)] * py[static_cast<std::size_t>(i)];
      numc += std::abs(py[static_cast<std::size_t>(i)] * pw[static_cast<std::size_t>(i)]);
    }
    if (reference_10m > 0.0) {
      double late = 0.0;
      for (std::size_t i = static_cast<std::size_t>(n80); i < py.size(); ++i) late += py[i] * py[i];
      if (late > 0.0) out[static_cast<std::size_t>(b)].lj_db = 10.0 * std::log10(late / reference_10m);
    }
    if (!(den > 0.0)) continue;
    out[static_cast<std::size_t>(b)].jlf = num / den;
    out[static_cast<std::size_t>(b)].jlfc = numc / den;
  }
  return out;
}

std::vector<SpatialBandMetrics> interauralCrossCorrelation(const std::vector<double>& left,
                                                           const std::vector<double>& right,
                                                           double sample_rate_hz, const core::Bands& bands) {
  const BandPair p = splitPair(left, right, sample_rate_hz, bands, true, "binaural response");
  std::vector<SpatialBandMetrics> out(static_cast<std::size_t>(bands.size()));
  const long n80 = p.onset + samples(0.080, p.fs), max_lag = samples(0.001, p.fs);
  tbb::parallel_for(0, bands.size(), [&](int b) {  // each band alone
    const auto& pl = p.a[static_cast<std::size_t>(b)];
    const auto& pr = p.b[static_cast<std::size_t>(b)];
    const long end = static_cast<long>(pl.size());
    if (!p.measurable[static_cast<std::size_t>(b)] || n80 > end) return;
    out[static_cast<std::size_t>(b)].iacc_e = windowIacc(pl, pr, p.start[static_cast<std::size_t>(b)], n80, max_lag);
    const long late_end = std::min(end, p.onset + samples(0.750, p.fs));
    if (late_end - n80 >= samples(0.010, p.fs)) out[static_cast<std::size_t>(b)].iacc_l = windowIacc(pl, pr, n80, late_end, max_lag);
  });
  return out;
}

// The lags go in groups of kLags, each lag's sum in its own accumulator, over i in increasing order as one
// lag alone would sum it: the group's sums run side by side instead of one long chain of dependent adds.
double windowIacc(const std::vector<double>& l, const std::vector<double>& r, long from, long to, long max_lag) {
  DIFFRAY_CHECK(0 <= from && from <= to && static_cast<std::size_t>(to) <= l.size() && l.size() == r.size());
  double el = 0.0, er = 0.0;
  for (long i = from; i < to; ++i) el += l[static_cast<std::size_t>(i)] * l[static_cast<std::size_t>(i)], er += r[static_cast<std::size_t>(i)] * r[static_cast<std::size_t>(i)];
  if (!(el > 0.0 && er > 0.0)) return kNaN;
  constexpr long kLags = 8;
  const long n = static_cast<long>(r.size());
  const double* pl = l.data();
  const double* pr = r.data();
  double best = 0.0;
  for (long tau0 = -max_lag; tau0 <= max_lag; tau0 += kLags) {
    const long lags = std::min(kLags, max_lag - tau0 + 1);
    // Lag tau0 + k sums i ∈ [begin(k), end(k)); every lag of the group holds [mid_lo, mid_hi).
    const auto begin = [&](long k) { return std::max(from, -(tau0 + k)); };
    const auto end = [&](long k) { return std::min(to, n - (tau0 + k)); };
    const long mid_lo = begin(0), mid_hi = std::max(mid_lo, end(lags - 1));
    double c[kLags] = {};
    for (long k = 0; k < lags; ++k)
      for (long i = begin(k); i < std::min(mid_lo, end(k)); ++i) c[k] += pl[i] * pr[i + tau0 + k];
    if (lags == kLags)
      for (long i = mid_lo; i < mid_hi; ++i) {
        const double li = pl[i];
        const double* ri = pr + i + tau0;
        for (long k = 0; k < kLags; ++k) c[k] += li * ri[k];
      }
    else
      for (long i = mid_lo; i < mid_hi; ++i)
        for (long k = 0; k < lags; ++k) c[k] += pl[i] * pr[i + tau0 + k];
    for (long k = 0; k < lags; ++k) {
      for (long i = std::max(mid_hi, begin(k)); i < end(k); ++i) c[k] += pl[i] * pr[i + tau0 + k];
      best = std::max(best, std::abs(c[k]));
    }
  }
  return best / std::sqrt(el * er);
}

double bandAverage(const core::Bands& bands, const std::vector<SpatialBandMetrics>& metrics,
                   double SpatialBandMetrics::*figure, double lo_hz, double hi_hz) {
  double sum = 0.0;
  int count = 0;
  for (int b = 0; b < bands.size(); ++b) {
    const double f = bands.nominalHz(b);
    if (f < lo_hz * 0.99 || f > hi_hz * 1.01) continue;
    sum += metrics[static_cast<std::size_t>(b)].*figure;
    ++count;
  }
  return count > 0 ? sum / count : kNaN;
}

nlohmann::ordered_json spatialJson(const core::Bands& bands, const std::vector<SpatialBandMetrics>& metrics,
                                   bool ambix) {
  const auto value = [](double v) { return std::isfinite(v) ? nlohmann::ordered_json(v) : nlohmann::ordered_json(nullptr); };
  nlohmann::ordered_json j, per_band = nlohmann::ordered_json::object();
  for (int b = 0; b < bands.size(); ++b) {
    const SpatialBandMetrics& m = metrics[static_cast<std::size_t>(b)];
    per_band[bands.label(b)] = ambix ? nlohmann::ordered_json{{"jlf", value(m.jlf)}, {"jlfc", value(m.jlfc)}}
                                     : nlohmann::ordered_json{{"iacc_e", value(m.iacc_e)}, {"iacc_l", value(m.iacc_l)}};
    if (ambix && std::isfinite(m.lj_db)) per_band[bands.label(b)]["lj_db"] = m.lj_db;
  }
  j["bands"] = per_band;
  if (ambix) {
    j["jlf_125_1000"] = value(bandAverage(bands, metrics, &SpatialBandMetrics::jlf, 125.0, 1000.0));
    j["jlfc_125_1000"] = value(bandAverage(bands, metrics, &SpatialBandMetrics::jlfc, 125.0, 1000.0));
    // L_J's single figure: the mean over the 125 Hz – 1 kHz octaves (ISO 3382-1 Table A.1).
    const double lj = bandAverage(bands, metrics, &SpatialBandMetrics::lj_db, 125.0, 1000.0);
    if (std::isfinite(lj)) j["lj_db_125_1000"] = lj;
  } else {
    j["iacc_e3"] = value(bandAverage(bands, metrics, &SpatialBandMetrics::iacc_e, 500.0, 2000.0));
    j["iacc_l3"] = value(bandAverage(bands, metrics, &SpatialBandMetrics::iacc_l, 500.0, 2000.0));
  }
  return j;
}

std::string spatialTable(const core::Bands& bands, const std::vector<SpatialBandMetrics>& metrics, bool ambix) {
  std::string out;
  char line[160];
  bool lj = false;
  for (const SpatialBandMetrics& m : metrics) lj = lj || std::isfinite(m.lj_db);
  std::snprintf(line, sizeof line, "%7s %8s %8s%s\n", "band Hz", ambix ? "J_LF" : "IACC_E", ambix ? "J_LFC" : "IACC_L",
                ambix && lj ? "   L_J dB" : "");
  out += line;
  const auto cell = [](double v) {
    char c[32];
    if (std::isfinite(v)) std::snprintf(c, sizeof c, "%8.3f", v);
    else std::snprintf(c, sizeof c, "%8s", "-");
    return std::string(c);
  };
  for (int b = 0; b < bands.size(); ++b) {
    const SpatialBandMetrics& m = metrics[static_cast<std::size_t>(b)];
    out += std::string(7 - std::min<std::size_t>(7, bands.label(b).size()), ' ') + bands.label(b) + " " +
           cell(ambix ? m.jlf : m.iacc_e) + " " + cell(ambix ? m.jlfc : m.iacc_l) + (ambix && lj ? " " + cell(m.lj_db) : "") +
           "\n";
  }
  if (ambix)
    out += "J_LF (125 Hz - 1 kHz): " + cell(bandAverage(bands, metrics, &SpatialBandMetrics::jlf, 125.0, 1000.0)) +
           "   J_LFC: " + cell(bandAverage(bands, metrics, &SpatialBandMetrics::jlfc, 125.0, 1000.0)) +
           (lj ? "   L_J dB: " + cell(bandAverage(bands, metrics, &SpatialBandMetrics::lj_db, 125.0, 1000.0)) : "") + "\n";
  else
    out += "IACC_E3 (500 Hz - 2 kHz): " + cell(bandAverage(bands, metrics, &SpatialBandMetrics::iacc_e, 500.0, 2000.0)) +
           "   IACC_L3: " + cell(bandAverage(bands, metrics, &SpatialBandMetrics::iacc_l, 500.0, 2000.0)) + "\n";
  return out;
}

}  // namespace diffray::ir
