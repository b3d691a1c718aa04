#include "diffray/spatial/ambisonic_decoder.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <complex>
#include <sstream>

#include "diffray/core/error.h"
#include "diffray/core/number.h"
#include "diffray/ir/band_filter.h"
#include "diffray/spatial/hrtf.h"
#include "diffray/spatial/spherical_harmonics.h"

namespace diffray::spatial {

namespace {

// The mode-matching decoder: L × C, rows the loudspeakers.
Eigen::MatrixXd decoder(int order, const std::vector<core::Vec3>& layout) {
  const int c = ambisonicChannels(order);
  Eigen::MatrixXd y(c, static_cast<Eigen::Index>(layout.size()));
  std::vector<double> h(static_cast<std::size_t>(c));
  for (std::size_t j = 0; j < layout.size(); ++j) {
    realSphericalHarmonicsSn3d(order, layout[j], h.data());
    for (int k = 0; k < c; ++k) y(k, static_cast<Eigen::Index>(j)) = h[static_cast<std::size_t>(k)];
  }
  return y.completeOrthogonalDecomposition().pseudoInverse();
}

void checkSignal(const std::vector<std::vector<float>>& ambix) {
  ambisonicOrderOf(static_cast<int>(ambix.size()), "Ambisonic signal");
  for (const auto& ch : ambix)
    if (ch.size() != ambix.front().size()) throw core::InputError("Ambisonic signal", "its channels differ in length");
}

}  // namespace

std::vector<core::Vec3> parseLayout(const std::string& text, const std::string& option) {
  std::vector<core::Vec3> out;
  std::stringstream list(text);
  std::string item;
  while (std::getline(list, item, ',')) {
    const auto colon = item.find(':');
    double az = 0.0, el = 0.0;
    const bool ok = core::parseDecimal(item.substr(0, colon), az) &&
                    (colon == std::string::npos || core::parseDecimal(item.substr(colon + 1), el));
    if (!ok) throw core::InputError(option, "\"" + item + "\" is not AZ:EL in degrees (e.g. 30:0)");
    if (std::abs(az) > 360.0 || std::abs(el) > 90.0)
      throw core::InputError(option, "\"" + item + "\": the azimuth must lie in [-360, 360] and the elevation in [-90, 90]");
    const double a = az * core::kPi / 180.0, e = el * core::kPi / 180.0;
    out.emplace_back(std::cos(a) * std::cos(e), std::sin(a) * std::cos(e), std::sin(e));
  }
  if (out.empty() || text.empty() || text.back() == ',')
    throw core::InputError(option, "needs loudspeaker directions AZ:EL,AZ:EL,… in degrees");
  return out;
}

int ambisonicOrderOf(int channels, const std::string& what) {
  for (int order = 1; order <= 3; ++order)
    if (channels == ambisonicChannels(order)) return order;
  throw core::InputError(what, "has " + std::to_string(channels) +
                                   " channels: an AmbiX signal of order 1, 2 or 3 has 4, 9 or 16");
}

std::vector<std::vector<float>> decodeToLayout(const std::vector<std::vector<float>>& ambix,
                                               const std::vector<core::Vec3>& layout) {
  checkSignal(ambix);
  const int order = ambisonicOrderOf(static_cast<int>(ambix.size()), "Ambisonic signal");
  const Eigen::MatrixXd d = decoder(order, layout);
  const std::size_t n = ambix.front().size();
  std::vector<std::vector<float>> out(layout.size(), std::vector<float>(n, 0.0f));
  for (std::size_t j = 0; j < layout.size(); ++j)
    for (std::size_t c = 0; c < ambix.size(); ++c) {
      const auto g = static_cast<float>(d(static_cast<Eigen::Index>(j), static_cast<Eigen::Index>(c)));
      if (g == 0.0f) continue;
      for (std::size_t s = 0; s < n; ++s) out[j][s] += g * ambix[c][s];
    }
  return out;
}

std::vector<std::vector<float>> decodeToBinaural(const std::vector<std::vector<float>>& ambix, const Hrtf& hrtf) {
  checkSignal(ambix);
  const int order = ambisonicOrderOf(static_cast<int>(ambix.size()), "Ambisonic signal");
  // 2(N+1)² virtual loudspeakers on a Fibonacci lattice, each at the nearest measured HRTF direction.
  const int count = 2 * ambisonicChannels(order);
  std::vector<core::Vec3> layout;
  std::vector<int> measured;
  const double golden = core::kPi * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < count; ++i) {
    const double z = 1.0 - (2.0 * i + 1.0) / count, r = std::sqrt(std::max(0.0, 1.0 - z * z));
    const int m = hrtf.nearest(core::Vec3(r * std::cos(golden * i), r * std::sin(golden * i), z));
    if (std::find(measured.begin(), measured.end(), m) != measured.end()) continue;
    measured.push_back(m);
    layout.push_back(hrtf.direction(m));
  }
  const std::vector<std::vector<float>> feeds = decodeToLayout(ambix, layout);
  // Convolution by FFT: each feed's spectrum times its HRIRs' spectra, summed per ear.
  const std::size_t n = ambix.front().size(), taps = static_cast<std::size_t>(hrtf.taps()), length = n + taps - 1;
  int size = 1;
  while (static_cast<std::size_t>(size) < length) size *= 2;
  ir::RealFft fft(size);
  std::vector<std::vector<std::complex<double>>> ears(2, std::vector<std::complex<double>>(static_cast<std::size_t>(fft.bins())));
  std::vector<std::complex<double>> feed_spectrum, h_spectrum;
  std::vector<double> x(n), h(taps);
  for (std::size_t j = 0; j < layout.size(); ++j) {
    for (std::size_t s = 0; s < n; ++s) x[s] = feeds[j][s];
    fft.forward(x, feed_spectrum);
    for (int side = 0; side < 2; ++side) {
      const float* hrir = hrtf.ear(measured[j], side);
      for (std::size_t k = 0; k < taps; ++k) h[k] = hrir[k];
      fft.forward(h, h_spectrum);
      for (std::size_t k = 0; k < feed_spectrum.size(); ++k) ears[static_cast<std::size_t>(side)][k] += feed_spectrum[k] * h_spectrum[k];
    }
  }
  std::vector<std::vector<float>> out(2);
  for (std::size_t side = 0; side < 2; ++side) {
    const std::vector<double> y = fft.inverse(ears[side], static_cast<long>(length));
    out[side].assign(y.begin(), y.end());
  }
  return out;
}

}  // namespace diffray::spatial
