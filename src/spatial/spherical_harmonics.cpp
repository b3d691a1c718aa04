// Real SN3D spherical harmonics in ACN order (see the header).
#include "diffray/spatial/spherical_harmonics.h"

#include <cmath>
#include <complex>
#include <string>

#include "diffray/core/error.h"

namespace diffray::spatial {

void realSphericalHarmonicsSn3d(int order, const core::Vec3& direction, double* out) {
  if (order < 0 || order > kMaxAmbisonicOrder)
    throw core::InputError("Ambisonic order", "must lie in [0, " + std::to_string(kMaxAmbisonicOrder) + "], got " +
                                                  std::to_string(order));
  for (int c = 0; c < 3; ++c) core::requireFinite("direction", direction[c]);
  const double norm = direction.norm();
  if (!(norm > 0.0)) throw core::InputError("direction", "must not be zero");
  const core::Vec3 d = direction / norm;
  const double t = d.z();
  const std::complex<double> e(d.x(), d.y());  // cos θ·e^{iφ}
  std::complex<double> e_m(1.0, 0.0);           // (cos θ·e^{iφ})^m
  double p_mm = 1.0;                            // P_m^m(t)/(1 − t²)^{m/2} = (2m − 1)!!
  double fact_ratio = 1.0;                      // (n − m)!/(n + m)! for n = m: 1/(2m)!
  for (int m = 0; m <= order; ++m) {
    if (m > 0) {
      e_m *= e;
      p_mm *= 2.0 * m - 1.0;
      fact_ratio /= (2.0 * m - 1.0) * (2.0 * m);
    }
    // P_n^m/(1 − t²)^{m/2} for n = m, m + 1, …, order by the recurrence
    // (n − m)·P_n^m = (2n − 1)·t·P_{n−1}^m − (n + m − 1)·P_{n−2}^m.
    double p_prev = 0.0, p = p_mm, ratio = fact_ratio;
    for (int n = m; n <= order; ++n) {
      if (n > m) {
        const double next = ((2.0 * n - 1.0) * t * p - (n + m - 1.0) * p_prev) / (n - m);
        p_prev = p;
        p = next;
        ratio *= static_cast<double>(n - m) / static_cast<double>(n + m);  // (n − m)!/(n + m)!
      }
      const double n_sn3d = std::sqrt((m == 0 ? 1.0 : 2.0) * ratio);
      out[n * n + n + m] = n_sn3d * p * e_m.real();
      if (m > 0) out[n * n + n - m] = n_sn3d * p * e_m.imag();
    }
  }
}

std::vector<double> realSphericalHarmonicsSn3d(int order, const core::Vec3& direction) {
  std::vector<double> out(static_cast<std::size_t>(ambisonicChannels(std::max(order, 0))));
  realSphericalHarmonicsSn3d(order, direction, out.data());
  return out;
}

}  // namespace diffray::spatial
