// The metrics' standard errors and marks (ir/uncertainty.h).
//  - StatIrJackknife: the jackknife standard error of every figure against the brute-force oracle, the
//    spread of the figure over many independent draws of a synthetic signed Monte Carlo histogram (rays of
//    random sign, size and time on an exponential decay, in 16 batches, plus an exact direct sound).
//  - IrUncertainty: the marks of a band whose energy sums negative (flag, warning naming the listener and
//    the band, no number in the table or the JSON), of a noisy band, of a clean one (none), the JSON keys.
//  - RoomUncertainty: the same marks on a traced room (two-rooms, WBSDF diffraction, few rays).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "diffray/core/bands.h"
#include "diffray/ir/metrics.h"
#include "diffray/ir/uncertainty.h"
#include "diffray/room/scene_file.h"
#include "diffray/transport/room_simulation.h"

namespace diffray::ir {
namespace {

constexpr int kBatches = 16;
constexpr double kBinS = 1e-3;

/// One draw of the synthetic response: `rays_per_batch` rays in each of kBatches batches, each a score of
/// s·a·e^{−kt} in the bin of its time t (uniform over [5 ms, length)), a ~ Exp(1), s = +1.5 (p 0.8) or −1
/// (p 0.2): signed like a WBSDF tally, mean 1; in every band alike. Plus the direct sound, exact, at 5 ms
/// (energy `direct`; none for 0).
EnergyResponse drawResponse(std::mt19937_64& rng, const core::Bands& bands, int rays_per_batch, double t60_s,
                            double length_s, double direct = 0.02) {
  EnergyResponse r;
  r.bands = bands;
  r.bin_s = kBinS;
  const auto bins = static_cast<std::size_t>(std::lround(length_s / kBinS));
  const int nb = bands.size();
  r.traced.assign(static_cast<std::size_t>(nb), std::vector<double>(bins, 0.0));
  r.batches.assign(kBatches, r.traced);
  r.batch_weights.assign(kBatches, static_cast<double>(rays_per_batch));
  const double k = 6.0 * std::log(10.0) / t60_s;
  std::uniform_real_distribution<double> time(0.005, length_s), unit(0.0, 1.0);
  std::exponential_distribution<double> size(1.0);
  const double per_ray = 1.0 / (kBatches * rays_per_batch);
  for (int j = 0; j < kBatches; ++j)
    for (int b = 0; b < nb; ++b)
      for (int i = 0; i < rays_per_batch; ++i) {
        const double t = time(rng), s = unit(rng) < 0.8 ? 1.5 : -1.0;
        const auto bin = std::min(bins - 1, static_cast<std::size_t>(t / kBinS));
        const double e = s * size(rng) * std::exp(-k * t) * per_ray;
        r.batches[j][b][bin] += e;
        r.traced[b][bin] += e;
      }
  Arrival a;
  a.delay_s = 0.005;
  a.energy = core::bandFill(direct);
  r.arrivals.push_back(a);
  return r;
}

// The oracle: M independent draws of the response; the sample standard deviation of each figure over them
// is its true standard error (to sampling), against the root mean square of the M jackknife standard errors.
// Tolerance: the ratio of the two variances has a relative standard deviation of about
// sqrt(2/(M − 1) + 2/(M(K − 1))) (the sample variance over M draws, and the mean of M jackknife variances,
// each with relative scatter sqrt(2/(K − 1))): 0.073 for M = 400; the test allows 4 of them.
TEST(StatIrJackknife, StandardErrorMatchesSpreadOverIndependentDraws) {
  const core::Bands band = core::Bands::octave(1000.0, 1000.0);
  constexpr int kDraws = 400;
  std::mt19937_64 rng(20240611);
  std::array<std::vector<double>, 7> value;
  std::array<double, 7> jack_var{};
  std::array<int, 7> jack_n{};
  for (int d = 0; d < kDraws; ++d) {
    const EnergyResponse r = drawResponse(rng, band, 600, 0.8, 1.2);
    std::vector<std::vector<double>> total{r.total(0)};
    const BandMetrics m = metricsFromHistograms(total, kBinS)[0];
    const BandUncertainty u = jackknifeMetrics(r)[0];
    for (Figure f : kAllFigures) {
      const std::size_t i = static_cast<std::size_t>(f);
      ASSERT_TRUE(std::isfinite(m.value(f))) << figureName(f);
      value[i].push_back(m.value(f));
      if (std::isfinite(u.se[i])) jack_var[i] += u.se[i] * u.se[i], ++jack_n[i];
    }
  }
  const double rel_sd = std::sqrt(2.0 / (kDraws - 1) + 2.0 / (kDraws * (kBatches - 1.0)));
  for (Figure f : kAllFigures) {
    const std::size_t i = static_cast<std::size_t>(f);
    double mean = 0.0, ss = 0.0;
    for (double v : value[i]) mean += v;
    mean /= kDraws;
    for (double v : value[i]) ss += (v - mean) * (v - mean);
    const double var = ss / (kDraws - 1);
    ASSERT_EQ(jack_n[i], kDraws) << figureName(f);  // every draw gives a standard error
    const double ratio = jack_var[i] / jack_n[i] / var;
    std::printf("  %-3s: spread %.4g, jackknife %.4g (variance ratio %.3f)\n", figureName(f), std::sqrt(var),
                std::sqrt(jack_var[i] / jack_n[i]), ratio);
    EXPECT_NEAR(ratio, 1.0, 4.0 * rel_sd) << figureName(f);
  }
}

/// A well-sampled response (4000 rays a batch, no direct sound) whose band `negative_band` (−1: none) has
/// every score made negative, so that it sums negative.
EnergyResponse fixedResponse(const core::Bands& bands, int negative_band) {
  std::mt19937_64 rng(7);
  EnergyResponse r = drawResponse(rng, bands, 4000, 1.0, 1.5, 0.0);
  r.arrivals.clear();
  const int nb = bands.size();
  for (int b = 0; b < nb; ++b) {
    if (b != negative_band) continue;
    for (auto& v : r.traced[b]) v = -std::abs(v);
    for (auto& batch : r.batches)
      for (auto& v : batch[b]) v = -std::abs(v);
  }
  return r;
}

// The Monte-Carlo decay range against a brute-force jackknife written here: the replicates (the response
// without batch k, its traced part scaled back to all the rays), their Schroeder levels, the standard error
// of the level at every bin, and the depth of the whole curve before that error first exceeds 1 dB. A sparse
// tail (200 rays per batch on a 0.8 s decay over 1.2 s) puts the limit well above the curve's last energy;
// markMetrics caps the band's decay range there.
TEST(IrUncertainty, MonteCarloDecayRangeIsWhereTheLevelsStandardErrorReachesOneDb) {
  const core::Bands band = core::Bands::octave(1000.0, 1000.0);
  std::mt19937_64 rng(7);
  const EnergyResponse r = drawResponse(rng, band, 200, 0.8, 1.2);
  const std::vector<double> whole = r.total(0);
  const auto levels = [](const std::vector<double>& e) {
    std::vector<double> tail(e.size() + 1, 0.0), out;
    for (std::size_t i = e.size(); i-- > 0;) tail[i] = tail[i + 1] + e[i];
    for (std::size_t i = 0; i < e.size() && tail[i] > 0.0; ++i) out.push_back(10.0 * std::log10(tail[i] / tail[0]));
    return out;  // up to the first bin with nothing positive left
  };
  std::vector<std::vector<double>> rep_levels;
  for (int k = 0; k < kBatches; ++k) {
    std::vector<double> rep = whole;
    for (std::size_t i = 0; i < rep.size(); ++i)
      rep[i] += -r.batches[k][0][i] + (r.traced[0][i] - r.batches[k][0][i]) / (kBatches - 1.0);
    rep_levels.push_back(levels(rep));
  }
  const std::vector<double> w = levels(whole);
  double depth = 0.0;
  for (std::size_t i = 0; i < w.size(); ++i) {
    double mean = 0.0, ss = 0.0;
    bool all = true;
    for (const auto& l : rep_levels) all = all && i < l.size();
    if (!all) break;
    for (const auto& l : rep_levels) mean += l[i] / kBatches;
    for (const auto& l : rep_levels) ss += (l[i] - mean) * (l[i] - mean);
    if (std::sqrt(ss * (kBatches - 1.0) / kBatches) > 1.0) break;
    depth = std::max(depth, -w[i]);
  }
  const BandUncertainty u = jackknifeMetrics(r)[0];
  EXPECT_NEAR(u.monte_carlo_range_db, depth, 1e-9);
  EXPECT_GT(depth, 10.0);
  std::vector<BandMetrics> m = metricsFromHistograms({whole}, kBinS);
  EXPECT_GT(m[0].decay_range_db, depth + 5.0);  // the curve's own depth reaches deeper
  markMetrics(m, {u});
  EXPECT_EQ(m[0].decay_range_db, depth);
}

TEST(IrUncertainty, NegativeBandIsFlaggedWarnedAndHasNoNumber) {
  const core::Bands bands = core::Bands::octave(500.0, 2000.0);
  const EnergyResponse r = fixedResponse(bands, 2);
  std::vector<std::vector<double>> total;
  for (int b = 0; b < bands.size(); ++b) total.push_back(r.total(b));
  std::vector<BandMetrics> m = metricsFromHistograms(total, r.bin_s);
  const auto marks = markMetrics(m, jackknifeMetrics(r));
  ASSERT_EQ(marks.size(), 3u);
  EXPECT_TRUE(marks[2].negative_energy);
  EXPECT_STREQ(marks[2].flagName(), "negative_energy");
  EXPECT_LT(marks[2].energy, 0.0);
  for (Figure f : kAllFigures) {
    EXPECT_FALSE(std::isfinite(m[2].value(f))) << figureName(f);
    EXPECT_TRUE(marks[2].isNegative(f)) << figureName(f);
  }
  EXPECT_STREQ(marks[0].flagName(), "ok");
  EXPECT_STREQ(marks[1].flagName(), "ok");
  // One warning, naming the listener and the band.
  const auto warnings = uncertaintyWarnings("B-hidden", bands, m, marks);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_EQ(warnings[0].rfind("listener B-hidden, 2000 Hz: energy sums negative (", 0), 0u) << warnings[0];
  EXPECT_NE(warnings[0].find("metrics not available"), std::string::npos) << warnings[0];
  // The table: the band's row holds '!' and "neg" and no number but its own centre.
  const std::string table = metricsTable(bands, m, &marks);
  const std::size_t row = table.find("\n   2000 ");
  ASSERT_NE(row, std::string::npos) << table;
  const std::string line = table.substr(row + 1, table.find('\n', row + 1) - row - 1);
  EXPECT_NE(line.find("neg"), std::string::npos) << line;
  EXPECT_EQ(line.find_first_of("0123456789", 7), std::string::npos) << line;
  int bangs = 0;
  for (char c : line) bangs += c == '!';
  EXPECT_EQ(bangs, 7) << line;  // the seven figures; the decay range column shows '-'
  EXPECT_NE(table.find("!: not available"), std::string::npos) << table;
  // JSON: the existing keys stay (null), the new ones are there.
  nlohmann::ordered_json j = metricsJson(bands, m);
  addUncertaintyJson(j, bands, marks);
  for (const char* key : {"t20", "t30", "edt", "c50", "c80", "d50", "ts", "decay_range_db", "se", "flag",
                          "negative_energy_fraction"})
    EXPECT_TRUE(j["2000"].contains(key)) << key;
  EXPECT_TRUE(j["2000"]["c80"].is_null());
  EXPECT_EQ(j["2000"]["flag"], "negative_energy");
  EXPECT_EQ(j["2000"]["negative_energy_fraction"], 1.0);
  EXPECT_EQ(j["2000"]["not_available_negative_energy"].size(), 7u);
  EXPECT_EQ(j["500"]["flag"], "ok");
  EXPECT_EQ(j["500"]["negative_energy_fraction"], 0.0);
  for (Figure f : kAllFigures) EXPECT_TRUE(j["500"]["se"][figureName(f)].is_number()) << figureName(f);
  EXPECT_FALSE(j["500"].contains("noisy"));
}

TEST(IrUncertainty, CleanResponseHasNoMarks) {
  const core::Bands bands = core::Bands::octave(500.0, 2000.0);
  const EnergyResponse r = fixedResponse(bands, -1);  // 4000 rays a batch: every SE far below its JND
  std::vector<std::vector<double>> total;
  for (int b = 0; b < bands.size(); ++b) total.push_back(r.total(b));
  std::vector<BandMetrics> m = metricsFromHistograms(total, r.bin_s);
  const auto marks = markMetrics(m, jackknifeMetrics(r));
  for (int b = 0; b < bands.size(); ++b) {
    EXPECT_STREQ(marks[b].flagName(), "ok") << b;
    for (Figure f : kAllFigures) EXPECT_LT(marks[b].standardError(f), figureJnd(f, m[b].value(f))) << figureName(f);
  }
  EXPECT_TRUE(uncertaintyWarnings("L", bands, m, marks).empty());
  const std::string table = metricsTable(bands, m, &marks);
  EXPECT_EQ(table.substr(0, table.find("\nflag:")).find_first_of("?!"), std::string::npos) << table;
  EXPECT_NE(table.find("    ok\n"), std::string::npos) << table;
}

TEST(IrUncertainty, NoisyFigureIsMarkedWithItsStandardErrorAndJnd) {
  const core::Bands band = core::Bands::octave(1000.0, 1000.0);
  std::mt19937_64 rng(11);
  const EnergyResponse r = drawResponse(rng, band, 10, 1.0, 1.5, 0.0);  // 160 rays: very noisy
  std::vector<std::vector<double>> total{r.total(0)};
  std::vector<BandMetrics> m = metricsFromHistograms(total, r.bin_s);
  const auto marks = markMetrics(m, jackknifeMetrics(r));
  ASSERT_EQ(marks[0].flag(), BandUncertainty::Flag::Noisy);
  const auto warnings = uncertaintyWarnings("A", band, m, marks);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_EQ(warnings[0].rfind("listener A, 1000 Hz: ", 0), 0u) << warnings[0];
  EXPECT_TRUE(warnings[0].find("exceeds its JND") != std::string::npos ||
              warnings[0].find("jackknife replicates") != std::string::npos)
      << warnings[0];
  const std::string table = metricsTable(band, m, &marks);
  EXPECT_NE(table.find('?'), std::string::npos) << table;
  EXPECT_NE(table.find(" noisy\n"), std::string::npos) << table;
  // Every finite figure marked noisy has an SE above its JND or some replicate without it.
  for (Figure f : kAllFigures) {
    const std::size_t i = static_cast<std::size_t>(f);
    if (marks[0].isNoisy(f)) {
      EXPECT_TRUE(marks[0].unmeasurable[i] > 0 || marks[0].se[i] > figureJnd(f, m[0].value(f))) << figureName(f);
    }
  }
}

// An exponential decay (T = 1 s, 60 dB/s, no noise) whose bins after t_flip are negated: its Schroeder
// curve crosses zero where ∫_z^flip p = ∫_flip^∞ p, z = t_flip − ln2/k (k = 6 ln10/T), when the positive
// energy alone has fallen by 10·log10((1 − e^{−k·flip})/e^{−k·flip}) dB: 18 dB for a flip at 0.3 s (T20
// and T30, which need 25 and 35 dB, are blocked by it, EDT and C80 are not), 72 dB at 1.2 s (nothing is).
TEST(IrUncertainty, NegativeTailBlocksOnlyTheFiguresItCuts) {
  const core::Bands band = core::Bands::octave(1000.0, 1000.0);
  const double k = 6.0 * std::log(10.0) / 1.0;
  for (const double flip : {0.3, 1.2}) {
    EnergyResponse r;
    r.bands = band;
    r.bin_s = kBinS;
    r.traced.assign(1, std::vector<double>(1500, 0.0));
    for (std::size_t i = 0; i < 1500; ++i) {
      const double t0 = static_cast<double>(i) * kBinS;
      r.traced[0][i] = (std::exp(-k * t0) - std::exp(-k * (t0 + kBinS))) * (t0 >= flip - 1e-9 ? -1.0 : 1.0);
    }
    std::vector<std::vector<double>> total{r.total(0)};
    std::vector<BandMetrics> m = metricsFromHistograms(total, r.bin_s);
    const auto marks = markMetrics(m, jackknifeMetrics(r));
    const BandUncertainty& u = marks[0];
    const double depth = 10.0 * std::log10((1.0 - std::exp(-k * flip)) / std::exp(-k * flip));
    EXPECT_NEAR(u.schroeder_zero_s, flip - std::log(2.0) / k, 1.5 * kBinS) << flip;
    EXPECT_NEAR(u.depth_before_zero_db, depth, 0.2) << flip;  // to a bin (0.06 dB at 60 dB/s) and rounding
    if (flip < 1.0) {
      EXPECT_TRUE(u.isNegative(Figure::T20) && u.isNegative(Figure::T30));
      EXPECT_FALSE(u.isNegative(Figure::Edt) || u.isNegative(Figure::C80) || u.isNegative(Figure::C50));
      EXPECT_STREQ(u.flagName(), "negative_energy");
      const auto w = uncertaintyWarnings("L", band, m, marks);
      ASSERT_EQ(w.size(), 1u);
      EXPECT_NE(w[0].find("T20, T30 not available"), std::string::npos) << w[0];
    } else {
      EXPECT_NEAR(m[0].t30, 1.0, 0.01);  // cut far below its range: measured as usual
      EXPECT_STREQ(u.flagName(), "ok");
    }
  }
}

TEST(IrUncertainty, WithoutBatchesThereAreNoStandardErrors) {
  const core::Bands band = core::Bands::octave(1000.0, 1000.0);
  EnergyResponse r = fixedResponse(band, -1);
  r.batches.clear();
  r.batch_weights.clear();
  const BandUncertainty u = jackknifeMetrics(r)[0];
  for (Figure f : kAllFigures) EXPECT_TRUE(std::isnan(u.standardError(f)));
  EXPECT_EQ(u.replicates, 0);
}

// A traced room: two-rooms with WBSDF diffraction at 3000 rays per source, where hidden listeners' bands
// often sum negative. Every band that sums negative is flagged, warned about, and has no figure; every
// other band's figures that are given are not marked negative.
TEST(RoomUncertainty, TracedBandsThatSumNegativeAreMarked) {
  const room::Room room = room::loadRoom(std::string(DIFFRAY_SOURCE_DIR) + "/rooms/two-rooms.json");
  int negative_bands = 0;
  for (std::uint64_t seed : {1u, 2u}) {
    transport::RoomSimulationOptions o;
    o.rays = 3000;
    o.seed = seed;
    o.length_s = 0.5;
    o.diffraction = "wbsdf";
    o.portal = false;  // the plain signed estimator: at 3000 rays some of its bands sum negative
    const transport::RoomSimulation sim = transport::simulateRoom(room, o);
    for (std::size_t l = 0; l < sim.listeners.size(); ++l) {
      const EnergyResponse& r = sim.listeners[l];
      ASSERT_EQ(r.batches.size(), static_cast<std::size_t>(kBatches));
      std::vector<std::vector<double>> total;
      for (int b = 0; b < room.bands.size(); ++b) total.push_back(r.total(b));
      std::vector<BandMetrics> m = metricsFromHistograms(total, r.bin_s);
      const auto marks = markMetrics(m, jackknifeMetrics(r));
      const auto warnings = uncertaintyWarnings(room.listeners[l].name, room.bands, m, marks);
      const std::string table = metricsTable(room.bands, m, &marks);
      for (int b = 0; b < room.bands.size(); ++b) {
        double sum = 0.0;
        for (double v : total[b]) sum += v;
        const std::string where = room.listeners[l].name + ", " + room.bands.label(b) + " Hz";
        bool warned = false;
        for (const auto& w : warnings) warned = warned || w.rfind("listener " + where + ": energy sums negative", 0) == 0;
        if (sum < 0.0) {
          ++negative_bands;
          EXPECT_STREQ(marks[b].flagName(), "negative_energy") << where;
          EXPECT_TRUE(warned) << where;
          for (Figure f : kAllFigures) EXPECT_TRUE(std::isnan(m[b].value(f))) << where;
        } else {
          EXPECT_FALSE(warned) << where;
          EXPECT_FALSE(marks[b].negative_energy) << where;
        }
      }
    }
  }
  EXPECT_GT(negative_bands, 0);  // the run did test a band that sums negative
}

}  // namespace
}  // namespace diffray::ir
