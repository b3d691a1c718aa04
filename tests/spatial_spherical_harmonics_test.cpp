// Real SN3D spherical harmonics in ACN order (spatial/spherical_harmonics.h) against:
// - the closed forms of orders 0–3 in Cartesian components, written out here from the AmbiX definition
//   (N_n^|m| P_n^|m| with the factorials worked by hand): e.g. ACN 4 = √3·x·y, ACN 12 = z(5z² − 3)/2;
// - orthonormality to order 7 by quadrature over the sphere written here (Gauss–Legendre in z = sin θ,
//   24 nodes by Newton's method on P_24 in tests/quadrature_rules.h, and the equally spaced rule in φ: both exact for the
//   polynomial and trigonometric degrees involved):
//   ∫ Y_i·Y_j dΩ = 4π/(2n + 1)·δ_ij under SN3D;
// - invariance under the direction's length, and bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "diffray/core/error.h"
#include "diffray/spatial/spherical_harmonics.h"
#include "quadrature_rules.h"

namespace {

namespace sp = diffray::spatial;
using diffray::core::Vec3;
constexpr double kPi = 3.14159265358979323846;

std::vector<double> closedForms(const Vec3& d) {
  const double x = d.x(), y = d.y(), z = d.z(), s3 = std::sqrt(3.0), s15 = std::sqrt(15.0);
  return {1.0,
          y, z, x,
          s3 * x * y, s3 * y * z, 0.5 * (3.0 * z * z - 1.0), s3 * x * z, 0.5 * s3 * (x * x - y * y),
          std::sqrt(5.0 / 8.0) * y * (3.0 * x * x - y * y), s15 * x * y * z, std::sqrt(3.0 / 8.0) * y * (5.0 * z * z - 1.0),
          0.5 * z * (5.0 * z * z - 3.0), std::sqrt(3.0 / 8.0) * x * (5.0 * z * z - 1.0), 0.5 * s15 * z * (x * x - y * y),
          std::sqrt(5.0 / 8.0) * x * (x * x - 3.0 * y * y)};
}

TEST(SpatialSphericalHarmonics, OrdersZeroToThreeMatchTheirClosedForms) {
  std::mt19937_64 rng(3);
  std::normal_distribution<double> g;
  std::vector<Vec3> dirs = {Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1), Vec3(0, 0, -1), Vec3(-1, -1, 0.3)};
  for (int i = 0; i < 200; ++i) dirs.emplace_back(g(rng), g(rng), g(rng));
  for (const Vec3& raw : dirs) {
    const Vec3 d = raw.normalized();
    const std::vector<double> y = sp::realSphericalHarmonicsSn3d(3, 2.5 * raw);  // the length does not matter
    const std::vector<double> want = closedForms(d);
    ASSERT_EQ(y.size(), 16u);
    for (std::size_t c = 0; c < 16; ++c) EXPECT_NEAR(y[c], want[c], 1e-13) << "ACN " << c << " at " << d.transpose();
  }
}

TEST(SpatialSphericalHarmonics, OrthogonalWithSn3dNormsToOrderSeven) {
  const int order = 7, nc = sp::ambisonicChannels(order);
  const int nphi = 64;  // products of order ≤ 7 harmonics: degree ≤ 14 in z and in φ; 24 nodes, 64 angles
  const diffray::testing::Rule gl = diffray::testing::gaussRule(24);
  const std::vector<double>&zs = gl.nodes, &ws = gl.weights;
  std::vector<std::vector<double>> gram(nc, std::vector<double>(nc, 0.0));
  std::vector<double> y(nc);
  for (std::size_t i = 0; i < zs.size(); ++i) {
    const double z = zs[i], rxy = std::sqrt(std::max(0.0, 1.0 - z * z));
    for (int k = 0; k < nphi; ++k) {
      const double phi = 2.0 * kPi * k / nphi, w = ws[i] * 2.0 * kPi / nphi;
      sp::realSphericalHarmonicsSn3d(order, Vec3(rxy * std::cos(phi), rxy * std::sin(phi), z), y.data());
      for (int a = 0; a < nc; ++a)
        for (int b = 0; b < nc; ++b) gram[a][b] += w * y[a] * y[b];
    }
  }
  for (int a = 0; a < nc; ++a) {
    const int n = static_cast<int>(std::floor(std::sqrt(static_cast<double>(a))));
    for (int b = 0; b < nc; ++b)
      EXPECT_NEAR(gram[a][b], a == b ? 4.0 * kPi / (2.0 * n + 1.0) : 0.0, 1e-12) << a << "," << b;
  }
}

TEST(SpatialSphericalHarmonics, RefusesBadInput) {
  EXPECT_THROW(sp::realSphericalHarmonicsSn3d(8, Vec3(1, 0, 0)), diffray::core::InputError);
  EXPECT_THROW(sp::realSphericalHarmonicsSn3d(-1, Vec3(1, 0, 0)), diffray::core::InputError);
  EXPECT_THROW(sp::realSphericalHarmonicsSn3d(1, Vec3(0, 0, 0)), diffray::core::InputError);
  EXPECT_THROW(sp::realSphericalHarmonicsSn3d(1, Vec3(NAN, 0, 0)), diffray::core::InputError);
}

}  // namespace
