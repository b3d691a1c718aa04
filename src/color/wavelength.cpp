#include "diffray/color/wavelength.h"

#include <algorithm>
#include <cmath>

#include "diffray/color/cie1931.h"
#include "diffray/core/error.h"

namespace diffray::color {

namespace {

double cmfSum(double wavelength_nm) {
  const Xyz c = cie1931(wavelength_nm);
  return c.x + c.y + c.z;
}

}  // namespace

WavelengthSampler::WavelengthSampler(double lo_nm, double hi_nm) {
  if (!(lo_nm >= kCieFirstNm && hi_nm <= kCieLastNm && lo_nm < hi_nm))
    throw core::InputError("wavelength range", "needs " + std::to_string(kCieFirstNm) +
                                                   " <= lo < hi <= " + std::to_string(kCieLastNm) + " nm");
  // Knots: lo, every integer nm strictly inside, hi. The CMF interpolant is linear between them.
  knots_nm_.push_back(lo_nm);
  for (double k = std::floor(lo_nm) + 1.0; k < hi_nm; k += 1.0) knots_nm_.push_back(k);
  knots_nm_.push_back(hi_nm);
  double peak = 0.0;
  for (double k : knots_nm_) peak = std::max(peak, cmfSum(k));
  const double floor_value = kWavelengthPdfFloor * peak;
  g_.reserve(knots_nm_.size());
  for (double k : knots_nm_) g_.push_back(std::max(cmfSum(k), floor_value));
  cdf_.assign(knots_nm_.size(), 0.0);
  for (std::size_t i = 1; i < knots_nm_.size(); ++i)
    cdf_[i] = cdf_[i - 1] + 0.5 * (g_[i - 1] + g_[i]) * (knots_nm_[i] - knots_nm_[i - 1]);
  DIFFRAY_CHECK(cdf_.back() > 0.0);
}

double WavelengthSampler::pdf(double wavelength_nm) const {
  if (!(wavelength_nm >= knots_nm_.front() && wavelength_nm <= knots_nm_.back())) return 0.0;
  std::size_t i = static_cast<std::size_t>(
      std::upper_bound(knots_nm_.begin(), knots_nm_.end(), wavelength_nm) - knots_nm_.begin());
  i = std::clamp<std::size_t>(i, 1, knots_nm_.size() - 1) - 1;  // segment [i, i + 1]
  const double t = (wavelength_nm - knots_nm_[i]) / (knots_nm_[i + 1] - knots_nm_[i]);
  return (g_[i] + t * (g_[i + 1] - g_[i])) / cdf_.back();
}

WavelengthSample WavelengthSampler::sample(double u) const {
  u = std::clamp(u, 0.0, std::nextafter(1.0, 0.0));
  const double target = u * cdf_.back();
  // Segment i with cdf_[i] <= target < cdf_[i + 1].
  std::size_t i = static_cast<std::size_t>(std::upper_bound(cdf_.begin(), cdf_.end(), target) - cdf_.begin());
  i = std::clamp<std::size_t>(i, 1, cdf_.size() - 1) - 1;
  const double h = knots_nm_[i + 1] - knots_nm_[i];
  const double a = g_[i], b = g_[i + 1];
  const double area = target - cdf_[i];  // ∫_0^s (a + (b − a) x/h) dx = a s + (b − a) s²/(2h)
  double s;
  const double slope = (b - a) / h;
  if (std::abs(slope) * h < 1e-12 * std::max(a, b)) {
    s = area / a;
  } else {
    // s = (−a + √(a² + 2·slope·area)) / slope, written without cancellation.
    const double disc = std::max(a * a + 2.0 * slope * area, 0.0);
    s = 2.0 * area / (a + std::sqrt(disc));
  }
  const double lambda = std::clamp(knots_nm_[i] + s, knots_nm_[i], knots_nm_[i + 1]);
  const double t = (lambda - knots_nm_[i]) / h;
  return {lambda, (a + t * (b - a)) / cdf_.back()};
}

namespace {

const WavelengthSampler& defaultSampler() {
  static const WavelengthSampler sampler(380.0, 780.0);  // thread-safe initialisation (C++11)
  return sampler;
}

bool isDefaultRange(double lo_nm, double hi_nm) { return lo_nm == 380.0 && hi_nm == 780.0; }

}  // namespace

WavelengthSample sampleWavelength(double u, double lo_nm, double hi_nm) {
  if (isDefaultRange(lo_nm, hi_nm)) return defaultSampler().sample(u);
  return WavelengthSampler(lo_nm, hi_nm).sample(u);
}

double wavelengthPdf(double wavelength_nm, double lo_nm, double hi_nm) {
  if (isDefaultRange(lo_nm, hi_nm)) return defaultSampler().pdf(wavelength_nm);
  return WavelengthSampler(lo_nm, hi_nm).pdf(wavelength_nm);
}

}  // namespace diffray::color
