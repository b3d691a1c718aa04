#include "diffray/render/film.h"

#include <algorithm>
#include <vector>
#include <ostream>

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

double autoExposure(const image::Image& img) {
  std::vector<double> peak;  // per pixel: its largest linear sRGB component, where positive
  for (std::size_t i = 0; i + 2 < img.rgb.size(); i += 3) {
    const double m = std::max({img.rgb[i], img.rgb[i + 1], img.rgb[i + 2]});
    if (m > 0) peak.push_back(m);
  }
  if (peak.empty()) return 1.0;
  const std::size_t k = std::min(peak.size() - 1, static_cast<std::size_t>(0.99 * static_cast<double>(peak.size())));
  std::nth_element(peak.begin(), peak.begin() + static_cast<std::ptrdiff_t>(k), peak.end());
  return 1.0 / peak[k];
}

void writePixelCsv(std::ostream& out, const RenderResult& r, const image::Image& img) {
  const auto old_precision = out.precision(9);
  out << "ix,iy,radiance_w_m2_sr,std_error_w_m2_sr,X,Y,Z,r,g,b\n";
  for (int iy = 0; iy < r.height; ++iy)
    for (int ix = 0; ix < r.width; ++ix) {
      const std::size_t i = static_cast<std::size_t>(iy) * r.width + ix;
      out << ix << ',' << iy << ',' << r.pixelRadiance(ix, iy) << ',' << r.pixelStdError(ix, iy);
      for (int c = 0; c < 3; ++c) out << ',' << r.xyz[3 * i + c];
      for (int c = 0; c < 3; ++c) out << ',' << img.rgb[3 * i + c];
      out << '\n';
    }
  out.precision(old_precision);
}

}  // namespace diffray::render
