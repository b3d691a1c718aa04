#include "diffray/image/png.h"

#include <png.h>

#include <algorithm>
#include <cmath>
#include <cstring>

#include "diffray/color/srgb.h"
#include "diffray/core/atomic_file.h"
#include "diffray/core/error.h"

namespace diffray::image {

std::vector<std::uint8_t> encodeSrgb8(const Image& linear_rgb, double exposure, EncodeStats* stats) {
  checkImage("image", linear_rgb);
  core::requirePositive("exposure", exposure);
  std::vector<std::uint8_t> bytes(linear_rgb.rgb.size());
  std::size_t negative = 0, saturated = 0, nonfinite = 0;
  for (std::size_t i = 0; i < bytes.size(); ++i) {
    double v = exposure * static_cast<double>(linear_rgb.rgb[i]);
    if (!std::isfinite(v)) {
      ++nonfinite;
      v = 0.0;
    } else if (v < 0.0) {
      ++negative;
      v = 0.0;
    } else if (v > 1.0) {
      ++saturated;
      v = 1.0;
    }
    bytes[i] = static_cast<std::uint8_t>(std::lround(255.0 * std::clamp(color::srgbEncode(v), 0.0, 1.0)));
  }
  if (stats) {
    const double n = static_cast<double>(bytes.size());
    stats->negative_fraction = static_cast<double>(negative) / n;
    stats->saturated_fraction = static_cast<double>(saturated) / n;
    stats->nonfinite_fraction = static_cast<double>(nonfinite) / n;
  }
  return bytes;
}

EncodeStats writePng(const std::string& path, const Image& linear_rgb, double exposure) {
  EncodeStats stats;
  const std::vector<std::uint8_t> pixels = encodeSrgb8(linear_rgb, exposure, &stats);

  // libpng's simplified API (1.6): compress to memory first, so that no libpng error can leave a partial
  // file and no longjmp crosses C++ frames. 8-bit data in PNG_FORMAT_RGB is written as sRGB.
  png_image png;
  std::memset(&png, 0, sizeof png);
  png.version = PNG_IMAGE_VERSION;
  png.width = static_cast<png_uint_32>(linear_rgb.width);
  png.height = static_cast<png_uint_32>(linear_rgb.height);
  png.format = PNG_FORMAT_RGB;
  const auto stride = static_cast<png_int_32>(3 * linear_rgb.width);
  png_alloc_size_t size = 0;
  if (!png_image_write_get_memory_size(png, size, 0, pixels.data(), stride, nullptr))
    throw core::InputError(path, std::string("PNG encoding failed: ") + png.message);
  std::vector<std::uint8_t> encoded(size);
  if (!png_image_write_to_memory(&png, encoded.data(), &size, 0, pixels.data(), stride, nullptr))
    throw core::InputError(path, std::string("PNG encoding failed: ") + png.message);
  encoded.resize(size);

  core::writeFileAtomically(path, [&](std::ostream& out) {
    out.write(reinterpret_cast<const char*>(encoded.data()), static_cast<std::streamsize>(encoded.size()));
  });
  return stats;
}

}  // namespace diffray::image
