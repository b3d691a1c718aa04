#pragma once
// A floating-point image of linear RGB (for rendered light: linear sRGB primaries, any radiometric scale;
// signed-energy transport can leave small negative values, which the Image keeps as they are). Pixel (x, y)
// has x rightwards and y downwards from the top-left corner, stored row-major, top row first, three floats
// per pixel. A plain aggregate; not synchronised (concurrent writers must touch different pixels).
#include <cstddef>
#include <string>
#include <vector>

namespace diffray::image {

struct Image {
  int width = 0, height = 0;
  std::vector<float> rgb;  ///< 3 floats per pixel, row-major, top row first: size 3·width·height

  std::size_t index(int x, int y) const {
    return 3 * (static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x));
  }
  float* at(int x, int y) { return rgb.data() + index(x, y); }
  const float* at(int x, int y) const { return rgb.data() + index(x, y); }
};

/// A width × height image of zeros. Throws core::InputError("image size") unless both are in 1..65535
/// (PNG's and most viewers' practical limit; also keeps 3·width·height far from overflow).
Image makeImage(int width, int height);

/// Throws core::InputError naming `where` unless width and height are in 1..65535 and rgb has
/// 3·width·height entries.
void checkImage(const std::string& where, const Image& image);

}  // namespace diffray::image
