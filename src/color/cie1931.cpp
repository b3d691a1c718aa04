#include "diffray/color/cie1931.h"

#include <cmath>

namespace diffray::color {

Xyz cie1931(double wavelength_nm) {
  // NaN fails both comparisons and lands here too.
  if (!(wavelength_nm >= kCieFirstNm && wavelength_nm <= kCieLastNm)) return {0.0, 0.0, 0.0};
  const double offset = wavelength_nm - kCieFirstNm;
  int i = static_cast<int>(offset);
  if (i >= kCieSamples - 1) i = kCieSamples - 2;  // λ = 830 exactly: the last segment at t = 1
  const double t = offset - i;
  auto lerp = [i, t](const double* v) { return v[i] + t * (v[i + 1] - v[i]); };
  return {lerp(detail::kCieX), lerp(detail::kCieY), lerp(detail::kCieZ)};
}

double cieYIntegralNm() {
  double sum = 0.0;
  for (int i = 0; i + 1 < kCieSamples; ++i) sum += 0.5 * (detail::kCieY[i] + detail::kCieY[i + 1]);
  return sum;  // knots are 1 nm apart
}

}  // namespace diffray::color
