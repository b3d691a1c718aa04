// Ambisonic decoding (spatial/ambisonic_decoder.h). Oracles: first-order SN3D harmonics written out here
// (mode matching must give back the field's harmonics exactly on a layout of full rank); the HRTF set read
// with libmysofa's own API (a decoded plane wave's interaural differences below the order's spatial limit).
#include <gtest/gtest.h>
#include <mysofa.h>

#include <cmath>
#include <complex>
#include <fstream>
#include <vector>

#include "diffray/core/error.h"
#include "diffray/spatial/ambisonic_decoder.h"
#include "diffray/spatial/hrtf.h"
#include "diffray/spatial/spherical_harmonics.h"
#include "response_fixtures.h"

namespace diffray::spatial {
namespace {

using core::Vec3;
constexpr double kPi = 3.14159265358979323846;

TEST(SpatialDecoder, ModeMatchingGivesBackTheFirstOrderHarmonics) {
  // A plane wave from d at order 1: W = 1, Y = y, Z = z, X = x (SN3D, ACN). On the eight corners of a cube
  // (rank 4), the feeds g must satisfy Σ g_j·(1, y_j, z_j, x_j) = (1, d_y, d_z, d_x).
  const Vec3 d = Vec3(0.3, -0.5, 0.4).normalized();
  const std::vector<std::vector<float>> field{{1.0f}, {static_cast<float>(d.y())}, {static_cast<float>(d.z())},
                                              {static_cast<float>(d.x())}};
  std::vector<Vec3> cube;
  for (int i = 0; i < 8; ++i) cube.push_back(Vec3(i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1).normalized());
  const auto g = decodeToLayout(field, cube);
  ASSERT_EQ(g.size(), 8u);
  Vec3 v(0, 0, 0);
  double w = 0.0;
  for (std::size_t j = 0; j < 8; ++j) w += g[j][0], v += static_cast<double>(g[j][0]) * cube[j];
  EXPECT_NEAR(w, 1.0, 1e-6);
  EXPECT_NEAR(v.x(), d.x(), 1e-6);
  EXPECT_NEAR(v.y(), d.y(), 1e-6);
  EXPECT_NEAR(v.z(), d.z(), 1e-6);
}

TEST(SpatialDecoder, LayoutsAndChannelCountsRefusedInOneLine) {
  const auto layout = parseLayout("30:0,-30,110:10", "--decode");
  ASSERT_EQ(layout.size(), 3u);
  EXPECT_NEAR(std::atan2(layout[1].y(), layout[1].x()) * 180.0 / kPi, -30.0, 1e-12);
  EXPECT_NEAR(std::asin(layout[2].z()) * 180.0 / kPi, 10.0, 1e-12);
  for (const std::string bad : {"", "30:0,", "x:0", "30:95", "0x10:0"})
    EXPECT_THROW(parseLayout(bad, "--decode"), core::InputError) << bad;
  EXPECT_EQ(ambisonicOrderOf(16, "ir"), 3);
  EXPECT_THROW(ambisonicOrderOf(5, "ir"), core::InputError);
}


// x through a linear-phase low-pass at `fc` Hz (a Hann-windowed sinc of 257 taps at 48 kHz, written here):
// the interaural time difference is a cue of the low frequencies.
std::vector<double> lowPass(const std::vector<double>& x, double fc) {
  const int half = 128;
  std::vector<double> h(2 * half + 1);
  for (int k = -half; k <= half; ++k) {
    const double t = 2.0 * fc / 48000.0, arg = kPi * t * k;
    h[static_cast<std::size_t>(k + half)] =
        (k == 0 ? t : t * std::sin(arg) / arg) * 0.5 * (1.0 + std::cos(kPi * k / (half + 1)));
  }
  std::vector<double> y(x.size() + h.size() - 1, 0.0);
  for (std::size_t i = 0; i < x.size(); ++i)
    for (std::size_t k = 0; k < h.size(); ++k) y[i + k] += x[i] * h[k];
  return y;
}

// Σ|X(f)|² over the DFT bins of [lo, hi) Hz of x zero-padded to n (direct sum).
double bandEnergy(const std::vector<double>& x, int n, double lo, double hi) {
  double e = 0.0;
  for (int k = static_cast<int>(std::ceil(lo * n / 48000.0)); k < hi * n / 48000.0; ++k) {
    std::complex<double> sum(0.0, 0.0), z(1.0, 0.0);
    const std::complex<double> step = std::polar(1.0, -2.0 * kPi * k / n);
    for (double v : x) sum += v * z, z *= step;
    e += std::norm(sum);
  }
  return e;
}

TEST(SpatialDecoder, BinauralDecodeKeepsTheInterauralDifferencesBelowTheOrdersLimit) {
  // A third-order plane wave (a unit impulse) from 60° left, decoded to the ears, against the HRIR pair of
  // that direction read by libmysofa. Third order holds the field up to k·r = 3 (r = 8.75 cm: 1.9 kHz); the
  // interaural time difference below 1.2 kHz (where it is heard) must match within two samples and the level
  // difference over the 500 Hz – 1.4 kHz octave within 1.5 dB, the order of the level differences listeners
  // tell apart (the octave's top reaches k·r = 2.3, where a third-order field at the ears is no longer
  // exact; measured: equal ITDs, level differences 8.6 dB against 7.5 dB). Above the limit no agreement is
  // claimed.
  const std::string path = Hrtf::defaultPath();
  if (!std::ifstream(path)) GTEST_SKIP() << path << " is not installed (libmysofa1)";
  const Vec3 d(std::cos(kPi / 3), std::sin(kPi / 3), 0.0);
  std::vector<double> y(16);
  realSphericalHarmonicsSn3d(3, d, y.data());
  std::vector<std::vector<float>> field(16, std::vector<float>(64, 0.0f));
  for (int c = 0; c < 16; ++c) field[static_cast<std::size_t>(c)][8] = static_cast<float>(y[static_cast<std::size_t>(c)]);
  const Hrtf hrtf = Hrtf::load("", 48000.0);
  const auto ears = decodeToBinaural(field, hrtf);
  int filter_length = 0, err = 0;
  MYSOFA_EASY* easy = mysofa_open(path.c_str(), 48000.0f, &filter_length, &err);
  ASSERT_NE(easy, nullptr);
  std::vector<float> hl(static_cast<std::size_t>(filter_length)), hr(hl.size());
  float dl = 0, dr = 0;
  mysofa_getfilter_float_nointerp(easy, static_cast<float>(d.x()), static_cast<float>(d.y()), 0.0f, hl.data(), hr.data(), &dl,
                                  &dr);
  mysofa_close(easy);
  const std::vector<double> l(ears[0].begin(), ears[0].end()), r(ears[1].begin(), ears[1].end());
  const std::vector<double> sl(hl.begin(), hl.end()), sr(hr.begin(), hr.end());
  EXPECT_NEAR(test::interauralLagSamples(lowPass(l, 1200), lowPass(r, 1200)),
              test::interauralLagSamples(lowPass(sl, 1200), lowPass(sr, 1200)), 2);
  const int n = 1 << 13;
  const double ild = 10 * std::log10(bandEnergy(l, n, 500, 1414) / bandEnergy(r, n, 500, 1414));
  const double ild_sofa = 10 * std::log10(bandEnergy(sl, n, 500, 1414) / bandEnergy(sr, n, 500, 1414));
  EXPECT_GT(ild_sofa, 3.0);
  EXPECT_NEAR(ild, ild_sofa, 1.5);
}

}  // namespace
}  // namespace diffray::spatial
