#include "diffray/color/srgb.h"

#include <cmath>

namespace diffray::color {

namespace {

// IEC 61966-2-1:1999, the matrices as the standard prints them (4 decimals), rows R, G, B and X, Y, Z.
constexpr double kXyzToSrgb[3][3] = {
    {3.2406, -1.5372, -0.4986}, {-0.9689, 1.8758, 0.0415}, {0.0557, -0.2040, 1.0570}};
constexpr double kSrgbToXyz[3][3] = {
    {0.4124, 0.3576, 0.1805}, {0.2126, 0.7152, 0.0722}, {0.0193, 0.1192, 0.9505}};

}  // namespace

std::array<double, 3> xyzToLinearSrgb(const Xyz& c) {
  std::array<double, 3> rgb{};
  for (int r = 0; r < 3; ++r) rgb[r] = kXyzToSrgb[r][0] * c.x + kXyzToSrgb[r][1] * c.y + kXyzToSrgb[r][2] * c.z;
  return rgb;
}

Xyz linearSrgbToXyz(const std::array<double, 3>& rgb) {
  double v[3];
  for (int r = 0; r < 3; ++r) v[r] = kSrgbToXyz[r][0] * rgb[0] + kSrgbToXyz[r][1] * rgb[1] + kSrgbToXyz[r][2] * rgb[2];
  return {v[0], v[1], v[2]};
}

double srgbEncode(double linear) {
  if (linear <= 0.0031308) return 12.92 * linear;
  return 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055;
}

double srgbDecode(double encoded) {
  if (encoded <= 0.04045) return encoded / 12.92;
  return std::pow((encoded + 0.055) / 1.055, 2.4);
}

}  // namespace diffray::color
