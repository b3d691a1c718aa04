#include "diffray/transport/opening_transmission.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "diffray/core/error.h"
#include "diffray/wbsdf/far_field.h"

namespace diffray::transport {

namespace {

constexpr int kFrequenciesPerBand = 4;
constexpr double kNodesPerUnitW = 8.0;
constexpr double kPi = 3.14159265358979323846;

}  // namespace

double OpeningTransmission::exact(double length_x_m, double length_y_m, double lambda_m, double alpha, double beta) {
  // The outer integral along the shorter axis; a uniform axis has length 0 and is handled in closed form.
  if (length_y_m > 0.0 && (length_x_m <= 0.0 || length_y_m < length_x_m)) {
    std::swap(length_x_m, length_y_m);
    std::swap(alpha, beta);
  }
  const double sx = length_x_m / lambda_m;
  if (length_y_m <= 0.0) {  // y uniform: β' = β, α' within ±√(1 − β²)
    const double c = std::sqrt(std::max(0.0, 1.0 - beta * beta));
    return wbsdf::farFieldMass((-c - alpha) * sx, (c - alpha) * sx);
  }
  // The outer integral in φ, α' = sin φ (so √(1 − α'²) = cos φ: the integrand is smooth up to the rim), by
  // composite Simpson with at least kNodesPerUnitW nodes per unit of w = (α' − α)L/λ (dw/dφ ≤ L/λ).
  const double sy = length_y_m / lambda_m, half_pi = 0.5 * kPi;
  int m = static_cast<int>(std::ceil(kNodesPerUnitW * sx * 2.0 * half_pi));
  m = std::max(64, m + (m & 1));
  const double h = 2.0 * half_pi / m;
  double sum = 0.0;
  for (int i = 0; i <= m; ++i) {
    const double phi = -half_pi + i * h, a = std::sin(phi), r = std::cos(phi);
    const double inner = wbsdf::farFieldMass((-r - beta) * sy, (r - beta) * sy);
    const double weight = (i == 0 || i == m) ? 1.0 : (i & 1 ? 4.0 : 2.0);
    sum += weight * sx * wbsdf::farFieldEval((a - alpha) * sx) * inner * r;
  }
  return sum * h / 3.0;
}

OpeningTransmission::OpeningTransmission(double length_x_m, double length_y_m, const core::Bands& bands, double c) {
  DIFFRAY_CHECK(length_x_m > 0.0 || length_y_m > 0.0);
  const int nb = bands.size(), n = kNodes;
  table_.assign(static_cast<std::size_t>(nb) * n * n, 0.0);
  tbb::parallel_for(0, nb * n, [&](int row) {
    const int b = row / n, i = row % n;
    const double t = static_cast<double>(i) / (n - 1), gamma = t * t, rho = std::sqrt(1.0 - gamma * gamma);
    for (int j = 0; j < n; ++j) {
      const double psi = 0.5 * kPi * j / (n - 1), a = rho * std::cos(psi), be = rho * std::sin(psi);
      double tau = 0.0;
      for (int q = 0; q < kFrequenciesPerBand; ++q) {
        const double f = bands.lowerHz(b) + (q + 0.5) / kFrequenciesPerBand * (bands.upperHz(b) - bands.lowerHz(b));
        tau += exact(length_x_m, length_y_m, c / f, a, be);
      }
      table_[(static_cast<std::size_t>(b) * n + i) * n + j] = tau / kFrequenciesPerBand;
    }
  });
}

double OpeningTransmission::at(int band, double alpha, double beta) const {
  const int n = kNodes;
  const double rho2 = std::min(1.0, alpha * alpha + beta * beta);
  const double x = std::sqrt(std::sqrt(1.0 - rho2)) * (n - 1);
  const double y = (rho2 > 0.0 ? std::atan2(std::abs(beta), std::abs(alpha)) / (0.5 * kPi) : 0.0) * (n - 1);
  const int i = std::min(n - 2, static_cast<int>(x)), j = std::min(n - 2, static_cast<int>(y));
  const double fx = x - i, fy = y - j;
  const double* t = &table_[static_cast<std::size_t>(band) * n * n];
  return (1.0 - fx) * ((1.0 - fy) * t[i * n + j] + fy * t[i * n + j + 1]) +
         fx * ((1.0 - fy) * t[(i + 1) * n + j] + fy * t[(i + 1) * n + j + 1]);
}

}  // namespace diffray::transport
