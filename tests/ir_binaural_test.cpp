// Binaural IR synthesis (ir/spatial_synthesis.h) and the SOFA reader (spatial/hrtf.h). Oracle: the HRTF set
// read directly with libmysofa's own API in the test (its own lookup and its own resampler, not
// libsamplerate), against which a single arrival's interaural time and level differences are checked; the
// level differences per octave are computed here by a plain DFT.
#include <gtest/gtest.h>
#include <mysofa.h>

#include <cmath>
#include <complex>
#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <vector>

#include "diffray/core/error.h"
#include "diffray/ir/spatial_synthesis.h"
#include "diffray/ir/synthesis.h"
#include "diffray/spatial/hrtf.h"
#include "response_fixtures.h"
#include "temp_dir.h"

namespace diffray::ir {
namespace {

using core::Vec3;
constexpr double kFs = 48000.0;
constexpr double kDeg = 3.14159265358979323846 / 180.0;

// |X(f)|² at the DFT frequencies k·fs/n for k in [k0, k1) of x zero-padded to n (direct sum).
std::vector<double> powerSpectrum(const std::vector<double>& x, int n, int k0, int k1) {
  std::vector<double> out;
  for (int k = k0; k < k1; ++k) {
    std::complex<double> sum(0.0, 0.0);
    const std::complex<double> step = std::polar(1.0, -2.0 * 3.14159265358979323846 * k / n);
    std::complex<double> z(1.0, 0.0);
    for (std::size_t t = 0; t < x.size(); ++t, z *= step) sum += x[t] * z;
    out.push_back(std::norm(sum));
  }
  return out;
}


TEST(IrBinaural, SingleArrivalCarriesTheHrtfsTimeAndLevelDifferences) {
  // One arrival from azimuth 60° (to the left), elevation 0: a direction of the MIT KEMAR grid, so both
  // readers take the same measurement. The ears' signals are the arrival's pulse (W) through the HRIRs, so
  // per octave their energy ratio is Σ|W|²|H_L|² / Σ|W|²|H_R|² over the octave's DFT bins, with H read here
  // by libmysofa at 48 kHz (its own resampler). Tolerances: the two resamplers' pass bands (both ripple
  // below 0.01 dB) and libmysofa's normalisation (one gain for both ears, it cancels): 0.1 dB; the ITD
  // within one sample (the arrival is placed at the nearest sample, the resamplers align to a fraction of one).
  const std::string path = spatial::Hrtf::defaultPath();
  if (!std::ifstream(path)) GTEST_SKIP() << path << " is not installed (libmysofa1)";
  const Vec3 d(std::cos(60 * kDeg), std::sin(60 * kDeg), 0.0);
  const EnergyResponse r = test::singleArrival(0.02, d);
  const spatial::Hrtf hrtf = spatial::Hrtf::load("", kFs);
  const auto ears = synthesizeBinaural(r, kFs, 0.2, 100.0, 343.0, 1, hrtf, Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1));
  const std::vector<double> w = synthesize(r, kFs, 0.2, 100.0, 343.0, 1);

  int filter_length = 0, err = 0;
  MYSOFA_EASY* easy = mysofa_open(path.c_str(), static_cast<float>(kFs), &filter_length, &err);
  ASSERT_NE(easy, nullptr) << "libmysofa error " << err;
  std::vector<float> hl(static_cast<std::size_t>(filter_length)), hr(hl.size());
  float dl = 0, dr = 0;
  mysofa_getfilter_float_nointerp(easy, static_cast<float>(d.x()), static_cast<float>(d.y()), 0.0f, hl.data(), hr.data(), &dl,
                                  &dr);
  mysofa_close(easy);
  ASSERT_EQ(dl, 0.0f);
  ASSERT_EQ(dr, 0.0f);
  const std::vector<double> hld(hl.begin(), hl.end()), hrd(hr.begin(), hr.end());

  // ITD: the left ear leads for a source on the left.
  const int itd_ours = test::interauralLagSamples(ears[0], ears[1]), itd_sofa = test::interauralLagSamples(hld, hrd);
  EXPECT_LT(itd_sofa, -10);  // ~0.5 ms
  EXPECT_NEAR(itd_ours, itd_sofa, 1);

  // ILD per octave, 250 Hz – 8 kHz.
  const int n = 1 << 14;
  for (double fc : {250.0, 500.0, 1000.0, 2000.0, 4000.0, 8000.0}) {
    const int k0 = static_cast<int>(std::ceil(fc / std::sqrt(2.0) * n / kFs));
    const int k1 = static_cast<int>(std::floor(fc * std::sqrt(2.0) * n / kFs));
    const auto pl = powerSpectrum(ears[0], n, k0, k1), pr = powerSpectrum(ears[1], n, k0, k1);
    const auto pw = powerSpectrum(w, n, k0, k1), ql = powerSpectrum(hld, n, k0, k1), qr = powerSpectrum(hrd, n, k0, k1);
    double el = 0, er = 0, ol = 0, orr = 0;
    for (std::size_t i = 0; i < pl.size(); ++i) el += pl[i], er += pr[i], ol += pw[i] * ql[i], orr += pw[i] * qr[i];
    EXPECT_NEAR(10 * std::log10(el / er), 10 * std::log10(ol / orr), 0.1) << fc << " Hz";
  }
}

TEST(IrBinaural, HrtfSetIsNormalisedToTheDiffuseField) {
  const std::string path = spatial::Hrtf::defaultPath();
  if (!std::ifstream(path)) GTEST_SKIP() << path << " is not installed (libmysofa1)";
  const spatial::Hrtf h = spatial::Hrtf::load("", kFs);
  EXPECT_EQ(h.directions(), 710);  // the MIT KEMAR grid
  EXPECT_EQ(h.fileRateHz(), 44100.0);
  double energy = 0.0;
  for (int i = 0; i < h.directions(); ++i)
    for (int side = 0; side < 2; ++side)
      for (int k = 0; k < h.taps(); ++k) energy += static_cast<double>(h.ear(i, side)[k]) * h.ear(i, side)[k];
  EXPECT_NEAR(energy / (2.0 * h.directions()), 1.0, 1e-4);
  // nearest() against a brute-force search: a grid direction finds itself, and 5000 random directions the
  // measurement of largest cosine.
  for (int i = 0; i < h.directions(); i += 37) EXPECT_EQ(h.nearest(h.direction(i)), i);
  std::mt19937_64 rng(3);
  std::normal_distribution<double> normal;
  for (int t = 0; t < 5000; ++t) {
    const Vec3 d = Vec3(normal(rng), normal(rng), normal(rng)).normalized();
    double best = -2.0;
    for (int i = 0; i < h.directions(); ++i) best = std::max(best, h.direction(i).dot(d));
    ASSERT_DOUBLE_EQ(h.direction(h.nearest(d)).dot(d), best) << t;
  }
}

TEST(IrBinaural, BadSofaFilesRefusedInOneLine) {
  const test::TempDir dir("binaural_bad");
  const auto refuses = [](const std::string& path, const std::string& words) {
    try {
      spatial::Hrtf::load(path, kFs);
      ADD_FAILURE() << path << " was accepted";
    } catch (const core::InputError& e) {
      EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
    }
  };
  refuses(dir.file("missing.sofa"), "cannot read");
  std::ofstream(dir.file("text.sofa")) << "not HDF5 at all\n";
  refuses(dir.file("text.sofa"), "not a SOFA file");
  // A SOFA file of another convention: the KEMAR set with its SOFAConventions attribute renamed in place
  // (same length, so the HDF5 structure stays valid): libmysofa reads it, its check refuses it.
  std::ifstream in(spatial::Hrtf::defaultPath(), std::ios::binary);
  if (!in) GTEST_SKIP() << "the default set is not installed (libmysofa1)";
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string from = "SimpleFreeFieldHRIR", to = "SimpleFreeFieldHRTF";
  const std::size_t at = bytes.find(from);
  ASSERT_NE(at, std::string::npos);
  bytes.replace(at, from.size(), to);
  std::ofstream(dir.file("other.sofa"), std::ios::binary) << bytes;
  refuses(dir.file("other.sofa"), "not an HRTF set");
}

}  // namespace
}  // namespace diffray::ir
