#include "diffray/image/image.h"

#include "diffray/core/error.h"

namespace diffray::image {

namespace {
constexpr int kMaxSide = 65535;
bool sideOk(int n) { return n >= 1 && n <= kMaxSide; }
}  // namespace

Image makeImage(int width, int height) {
  if (!sideOk(width) || !sideOk(height))
    throw core::InputError("image size", std::to_string(width) + " x " + std::to_string(height) +
                                             ": each side must be 1 to " + std::to_string(kMaxSide) + " pixels");
  Image image;
  image.width = width;
  image.height = height;
  image.rgb.assign(3 * static_cast<std::size_t>(width) * static_cast<std::size_t>(height), 0.0f);
  return image;
}

void checkImage(const std::string& where, const Image& image) {
  if (!sideOk(image.width) || !sideOk(image.height))
    throw core::InputError(where, "image is " + std::to_string(image.width) + " x " +
                                      std::to_string(image.height) + " pixels: each side must be 1 to " +
                                      std::to_string(kMaxSide));
  const std::size_t expected = 3 * static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height);
  if (image.rgb.size() != expected)
    throw core::InputError(where, "image has " + std::to_string(image.rgb.size()) + " values, expected 3 x " +
                                      std::to_string(image.width) + " x " + std::to_string(image.height));
}

}  // namespace diffray::image
