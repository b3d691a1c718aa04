#pragma once
// Small math functions and constants shared by every module. Vectors are Eigen's double vectors; all
// geometry in diffray is computed in double (Embree's float hits are refined in double).
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>
#include <vector>

namespace diffray::core {

using Vec3 = Eigen::Vector3d;
using Vec2 = Eigen::Vector2d;

inline constexpr double kPi = 3.14159265358979323846;
inline constexpr double kTwoPi = 2.0 * kPi;

/// Normalised sinc: sin(pi z)/(pi z), 1 at z = 0.
inline double sinc(double z) {
  const double pz = kPi * z;
  if (std::abs(pz) < 1e-4) return 1.0 - pz * pz / 6.0;
  return std::sin(pz) / pz;
}

/// Speed of sound in air at temperature `celsius`: 331.3·sqrt(1 + T/273.15) m/s (ideal gas, c ∝ √T_abs).
inline double speedOfSound(double celsius = 20.0) { return 331.3 * std::sqrt(1.0 + celsius / 273.15); }

/// Gauss–Legendre rule on [-1, 1] with n nodes, computed by Golub–Welsch with Eigen's symmetric
/// eigensolver. Exact for polynomials of degree 2n-1. Results are cached per n (thread-safe).
struct GaussLegendre {
  std::vector<double> nodes;
  std::vector<double> weights;
};
const GaussLegendre& gaussLegendre(int n);

/// Integral of f over [a, b] by composite Gauss–Legendre: `panels` panels of `order` nodes each.
template <class F>
double integrate(F&& f, double a, double b, int panels, int order = 8) {
  const GaussLegendre& gl = gaussLegendre(order);
  const double h = (b - a) / panels;
  double sum = 0.0;
  for (int p = 0; p < panels; ++p) {
    const double mid = a + (p + 0.5) * h;
    for (int i = 0; i < order; ++i) sum += gl.weights[i] * f(mid + 0.5 * h * gl.nodes[i]);
  }
  return 0.5 * h * sum;
}

}  // namespace diffray::core
