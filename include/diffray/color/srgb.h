#pragma once
// CIE XYZ to sRGB (IEC 61966-2-1:1999): the standard's 4-decimal matrix from XYZ (D65 white, Y = 1 for
// white) to linear sRGB, and the piecewise transfer function between linear and encoded values. No gamut
// mapping: out-of-gamut colours (every monochromatic one) come out with negative components, left to the
// caller (image::writePng clamps at 0). Pure functions: thread-safe.
#include <array>

#include "diffray/color/cie1931.h"

namespace diffray::color {

/// Linear sRGB (R, G, B) of XYZ by the IEC 61966-2-1 matrix; white (0.9505, 1, 1.089) maps to ≈ (1, 1, 1).
std::array<double, 3> xyzToLinearSrgb(const Xyz& xyz);
/// XYZ of linear sRGB by the standard's published inverse matrix (the round trip is identity to ≈ 1e-4,
/// the 4-decimal rounding of both matrices).
Xyz linearSrgbToXyz(const std::array<double, 3>& rgb);

/// The sRGB encoding (opto-electronic transfer): 12.92·v for v ≤ 0.0031308, else 1.055·v^(1/2.4) − 0.055.
/// Defined for all v: negative v stays on the linear branch (negative output), v > 1 exceeds 1.
double srgbEncode(double linear);
/// Its inverse: e/12.92 for e ≤ 0.04045, else ((e + 0.055)/1.055)^2.4.
double srgbDecode(double encoded);

}  // namespace diffray::color
