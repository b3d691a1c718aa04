// The CIE 1931 table against oracles that share nothing with it: the analytic multi-lobe fit of Wyman,
// Sloan & Shirley 2013 (written out here), the CIE's ∫ȳ dλ, the equal-energy white point, ȳ's peak, and
// the chromaticities of the CIE 1931 RGB primaries.
#include <gtest/gtest.h>

#include <cmath>

#include "diffray/color/cie1931.h"

namespace diffray::color {
namespace {

// Wyman, Sloan & Shirley, "Simple Analytic Approximations to the CIE XYZ Color Matching Functions",
// JCGT 2(2), 2013, Equation 4 (the multi-lobe fit): sums of piecewise Gaussians whose inverse width
// differs either side of the centre.
double lobe(double lambda, double mu, double inv_sigma_below, double inv_sigma_above) {
  const double t = (lambda - mu) * (lambda < mu ? inv_sigma_below : inv_sigma_above);
  return std::exp(-0.5 * t * t);
}
double xFitWss(double l) {
  return 0.362 * lobe(l, 442.0, 0.0624, 0.0374) + 1.056 * lobe(l, 599.8, 0.0264, 0.0323) -
         0.065 * lobe(l, 501.1, 0.0490, 0.0382);
}
double yFitWss(double l) { return 0.821 * lobe(l, 568.8, 0.0213, 0.0247) + 0.286 * lobe(l, 530.9, 0.0613, 0.0322); }
double zFitWss(double l) { return 1.217 * lobe(l, 437.0, 0.0845, 0.0278) + 0.681 * lobe(l, 459.0, 0.0385, 0.0725); }

// Trapezoid rule on a fine grid, our own quadrature of the interpolated table.
Xyz integrate(double lo, double hi, double step) {
  Xyz sum{0, 0, 0};
  const int n = static_cast<int>(std::lround((hi - lo) / step));
  for (int i = 0; i <= n; ++i) {
    const double w = (i == 0 || i == n) ? 0.5 * step : step;
    const Xyz c = cie1931(lo + i * step);
    sum.x += w * c.x;
    sum.y += w * c.y;
    sum.z += w * c.z;
  }
  return sum;
}

TEST(ColorCie1931, AgreesWithWymanSloanShirleyMultiLobeFit) {
  // The brief's acceptance: within a few per cent of each function's peak (x̄ 1.063, ȳ 1, z̄ 1.783).
  const double tol = 0.03;
  double worst[3] = {0, 0, 0};
  for (double l = 360.0; l <= 830.0; l += 0.5) {
    const Xyz c = cie1931(l);
    worst[0] = std::max(worst[0], std::abs(c.x - xFitWss(l)) / 1.0629);
    worst[1] = std::max(worst[1], std::abs(c.y - yFitWss(l)) / 1.0);
    worst[2] = std::max(worst[2], std::abs(c.z - zFitWss(l)) / 1.7830);
  }
  EXPECT_LT(worst[0], tol);
  EXPECT_LT(worst[1], tol);
  EXPECT_LT(worst[2], tol);
  std::printf("max |table - WSS fit| / peak: x %.4f  y %.4f  z %.4f\n", worst[0], worst[1], worst[2]);
}

TEST(ColorCie1931, LuminanceIntegralAndEqualEnergyWhite) {
  // ∫ȳ dλ = 106.857 nm for the CIE 1931 1 nm table (CIE 015:2004; pbrt's CIE_Y_integral = 106.856895).
  const Xyz integral = integrate(360.0, 830.0, 0.25);
  EXPECT_NEAR(integral.y, 106.857, 0.01);
  EXPECT_NEAR(cieYIntegralNm(), integral.y, 1e-6);
  // The equal-energy spectrum (illuminant E) sits at x = y = 1/3 by construction of XYZ.
  const double sum = integral.x + integral.y + integral.z;
  EXPECT_NEAR(integral.x / sum, 1.0 / 3.0, 1e-3);
  EXPECT_NEAR(integral.y / sum, 1.0 / 3.0, 1e-3);
  // And the three integrals are equal to well under a per cent.
  EXPECT_NEAR(integral.x / integral.y, 1.0, 2e-3);
  EXPECT_NEAR(integral.z / integral.y, 1.0, 2e-3);
}

TEST(ColorCie1931, LuminousEfficiencyPeaksAt555nmWithValueOne) {
  EXPECT_DOUBLE_EQ(cie1931(555.0).y, 1.0);
  double best_l = 0.0, best = -1.0;
  for (int i = 0; i <= 4700; ++i) {
    const double l = 360.0 + 0.1 * i;
    const double y = cie1931(l).y;
    if (y > best) best = y, best_l = l;
  }
  EXPECT_NEAR(best_l, 555.0, 0.05);
  EXPECT_DOUBLE_EQ(best, 1.0);
}

TEST(ColorCie1931, MonochromaticPrimariesOfCieRgb) {
  // CIE 1931 RGB primaries (700, 546.1, 435.8 nm) in xy, as published to 3 decimals
  // (e.g. the public-domain Color Machine Library's CML_RGB_CIE entry: 0.734690 0.265310, 0.272958
  // 0.718062, 0.166446 0.008964). Tolerance: the 3-decimal rounding (5e-4) plus linear interpolation.
  struct Case { double l, x, y; };
  for (const Case c : {Case{700.0, 0.735, 0.265}, Case{546.1, 0.273, 0.718}, Case{435.8, 0.166, 0.009}}) {
    const Xyz v = cie1931(c.l);
    const double s = v.x + v.y + v.z;
    EXPECT_NEAR(v.x / s, c.x, 1e-3) << c.l << " nm";
    EXPECT_NEAR(v.y / s, c.y, 1e-3) << c.l << " nm";
  }
}

TEST(ColorCie1931, LinearBetweenKnotsAndZeroOutsideTheTable) {
  const Xyz a = cie1931(600.0), b = cie1931(601.0), m = cie1931(600.25);
  EXPECT_NEAR(m.x, 0.75 * a.x + 0.25 * b.x, 1e-15);
  EXPECT_NEAR(m.y, 0.75 * a.y + 0.25 * b.y, 1e-15);
  EXPECT_NEAR(m.z, 0.75 * a.z + 0.25 * b.z, 1e-15);
  for (double l : {359.999, 830.001, -1.0, 1e9, std::nan("")}) {
    const Xyz c = cie1931(l);
    EXPECT_EQ(c.x, 0.0);
    EXPECT_EQ(c.y, 0.0);
    EXPECT_EQ(c.z, 0.0);
  }
  EXPECT_GT(cie1931(360.0).x, 0.0);  // the table's ends are inside
  EXPECT_GT(cie1931(830.0).y, 0.0);
  EXPECT_EQ(cie1931(700.0).z, 0.0);  // z̄ is exactly 0 from 650 nm on
}

}  // namespace
}  // namespace diffray::color
