#include "diffray/render/film.h"

#include <algorithm>
#include <vector>

#include "diffray/color/srgb.h"

namespace diffray::render {

image::Image linearSrgb(const RenderResult& r) {
  image::Image img;
  img.width = r.width;
  img.height = r.height;
  const std::size_t n = static_cast<std::size_t>(r.width) * r.height;
  img.rgb.resize(3 * n);
  for (std::size_t i = 0; i < n; ++i) {
    const std::array<double, 3> rgb = color::xyzToLinearSrgb({r.xyz[3 * i], r.xyz[3 * i + 1], r.xyz[3 * i + 2]});
    for (int c = 0; c < 3; ++c) img.rgb[3 * i + c] = static_cast<float>(rgb[c]);
  }
  return img;
}

double autoExposure(const RenderResult& r) {
  std::vector<double> y;
  for (std::size_t i = 1; i < r.xyz.size(); i += 3)
    if (r.xyz[i] > 0) y.push_back(r.xyz[i]);
  if (y.empty()) return 1.0;
  const std::size_t k = std::min(y.size() - 1, static_cast<std::size_t>(0.99 * static_cast<double>(y.size())));
  std::nth_element(y.begin(), y.begin() + static_cast<std::ptrdiff_t>(k), y.end());
  return 1.0 / y[k];
}

}  // namespace diffray::render
