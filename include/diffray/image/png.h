#pragma once
// 8-bit sRGB PNG output of a linear RGB Image through libpng. Each channel value v becomes
// round(255 · srgbEncode(clamp(exposure · v, 0, 1))): negative values (signed energy leaves some) and
// non-finite ones become 0, values above 1 saturate; writePng returns how many of each it met, as
// fractions of all 3·width·height channel values, for the caller to report. The file is written
// atomically (core::writeFileAtomically): a failed write leaves no file and an existing one untouched.
// Thread-safe for different paths.
#include <cstdint>
#include <string>
#include <vector>

#include "diffray/image/image.h"

namespace diffray::image {

/// What the 8-bit encoding had to clip, as fractions of all channel values.
struct EncodeStats {
  double negative_fraction = 0.0;   ///< exposure · v < 0, written as 0
  double saturated_fraction = 0.0;  ///< exposure · v > 1, written as 255
  double nonfinite_fraction = 0.0;  ///< NaN or ±Inf, written as 0
};

/// The 8-bit sRGB bytes writePng stores (3 per pixel, top row first) and what they clipped.
/// Throws core::InputError("exposure") unless exposure is finite and > 0.
std::vector<std::uint8_t> encodeSrgb8(const Image& linear_rgb, double exposure, EncodeStats* stats = nullptr);

/// Writes `linear_rgb` as an 8-bit RGB PNG with sRGB encoding. Throws core::InputError naming `path` if it
/// cannot be written, and for a malformed image or a bad exposure (nothing is written then).
EncodeStats writePng(const std::string& path, const Image& linear_rgb, double exposure = 1.0);

}  // namespace diffray::image
