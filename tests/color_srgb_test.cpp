// XYZ → sRGB (IEC 61966-2-1): D65 white to (1, 1, 1), the matrix against its published inverse, the
// Rec. 709 primaries' chromaticities, and the transfer function's breakpoint, ends and inverse.
#include <gtest/gtest.h>

#include <cmath>

#include "diffray/color/srgb.h"

namespace diffray::color {
namespace {

TEST(ColorSrgb, D65WhiteMapsToOne) {
  const auto rgb = xyzToLinearSrgb({0.9505, 1.0, 1.089});
  for (double v : rgb) EXPECT_NEAR(v, 1.0, 1e-3);
}

TEST(ColorSrgb, MatrixTimesPublishedInverseIsIdentity) {
  for (int k = 0; k < 3; ++k) {
    std::array<double, 3> e{0, 0, 0};
    e[k] = 1.0;
    const Xyz xyz = linearSrgbToXyz(e);
    const auto back = xyzToLinearSrgb(xyz);
    for (int r = 0; r < 3; ++r) EXPECT_NEAR(back[r], r == k ? 1.0 : 0.0, 1e-3) << k << "," << r;
  }
}

TEST(ColorSrgb, PrimariesAreRec709) {
  // ITU-R BT.709 / sRGB primaries: R (0.64, 0.33), G (0.30, 0.60), B (0.15, 0.06); white D65 (0.3127, 0.3290).
  const double expected[4][2] = {{0.64, 0.33}, {0.30, 0.60}, {0.15, 0.06}, {0.3127, 0.3290}};
  for (int k = 0; k < 4; ++k) {
    std::array<double, 3> rgb{1, 1, 1};
    if (k < 3) rgb = {0, 0, 0}, rgb[k] = 1.0;
    const Xyz c = linearSrgbToXyz(rgb);
    const double s = c.x + c.y + c.z;
    EXPECT_NEAR(c.x / s, expected[k][0], 5e-4) << k;
    EXPECT_NEAR(c.y / s, expected[k][1], 5e-4) << k;
  }
}

TEST(ColorSrgb, TransferFunctionBreakpointsAndContinuity) {
  EXPECT_EQ(srgbEncode(0.0), 0.0);
  EXPECT_NEAR(srgbEncode(1.0), 1.0, 1e-15);
  // The breakpoint: 0.0031308 linear ↔ 0.04045 encoded (IEC 61966-2-1), both branches agree there.
  const double bp = 0.0031308;
  EXPECT_NEAR(srgbEncode(bp), 0.04045, 1e-6);
  EXPECT_NEAR(srgbEncode(std::nextafter(bp, 1.0)), srgbEncode(bp), 1e-7);
  EXPECT_NEAR(1.055 * std::pow(bp, 1.0 / 2.4) - 0.055, 12.92 * bp, 1e-7);
  EXPECT_NEAR(srgbDecode(0.04045), bp, 1e-7);
  EXPECT_NEAR(srgbDecode(std::nextafter(0.04045, 1.0)), srgbDecode(0.04045), 1e-8);
  // Linear segment below, power law above; mid-grey 0.5 encodes to 0.7354 (8-bit 188).
  EXPECT_DOUBLE_EQ(srgbEncode(0.001), 0.01292);
  EXPECT_NEAR(srgbEncode(0.5), 0.7354, 1e-4);
  EXPECT_NEAR(srgbEncode(0.18), 0.4614, 1e-4);  // 18 % grey
  // Monotone, and decode inverts encode.
  double prev = -1.0;
  for (double v = 0.0; v <= 1.0; v += 1e-3) {
    const double e = srgbEncode(v);
    EXPECT_GT(e, prev);
    prev = e;
    EXPECT_NEAR(srgbDecode(e), v, 1e-12);
  }
}

}  // namespace
}  // namespace diffray::color
