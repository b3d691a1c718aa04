#include "diffray/image/pfm.h"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <sstream>

#include "diffray/core/atomic_file.h"
#include "diffray/core/error.h"

namespace diffray::image {

namespace {

void putFloatLittleEndian(std::ostream& out, float v) {
  std::uint32_t bits;
  std::memcpy(&bits, &v, sizeof bits);
  const char bytes[4] = {static_cast<char>(bits & 0xffu), static_cast<char>((bits >> 8) & 0xffu),
                         static_cast<char>((bits >> 16) & 0xffu), static_cast<char>((bits >> 24) & 0xffu)};
  out.write(bytes, 4);
}

float floatFromBytes(const unsigned char* b, bool little_endian) {
  const std::uint32_t bits =
      little_endian ? (std::uint32_t{b[0]} | std::uint32_t{b[1]} << 8 | std::uint32_t{b[2]} << 16 |
                       std::uint32_t{b[3]} << 24)
                    : (std::uint32_t{b[3]} | std::uint32_t{b[2]} << 8 | std::uint32_t{b[1]} << 16 |
                       std::uint32_t{b[0]} << 24);
  float v;
  std::memcpy(&v, &bits, sizeof v);
  return v;
}

}  // namespace

void writePfm(const std::string& path, const Image& linear_rgb) {
  checkImage(path, linear_rgb);
  core::writeFileAtomically(path, [&](std::ostream& out) {
    out << "PF\n" << linear_rgb.width << ' ' << linear_rgb.height << "\n-1.0\n";
    for (int y = linear_rgb.height - 1; y >= 0; --y) {
      const float* row = linear_rgb.at(0, y);
      for (int i = 0; i < 3 * linear_rgb.width; ++i) putFloatLittleEndian(out, row[i]);
    }
  });
}

Image readPfm(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw core::InputError(path, "cannot open");
  std::string magic;
  int width = 0, height = 0;
  double scale = 0.0;
  in >> magic >> width >> height >> scale;
  if (!in || magic != "PF")
    throw core::InputError(path, "not a colour PFM (expected \"PF\", width, height and scale)");
  if (!(scale != 0.0) || !std::isfinite(scale)) throw core::InputError(path, "PFM scale must be non-zero");
  in.get();  // the single whitespace character that ends the header
  Image image;
  try {
    image = makeImage(width, height);
  } catch (const core::InputError& e) {
    throw core::InputError(path, e.what());
  }
  const bool little_endian = scale < 0.0;
  std::vector<unsigned char> row(12 * static_cast<std::size_t>(width));
  for (int y = height - 1; y >= 0; --y) {
    if (!in.read(reinterpret_cast<char*>(row.data()), static_cast<std::streamsize>(row.size())))
      throw core::InputError(path, "PFM pixel data is shorter than " + std::to_string(width) + " x " +
                                       std::to_string(height) + " pixels");
    float* out = image.at(0, y);
    for (int i = 0; i < 3 * width; ++i) out[i] = floatFromBytes(row.data() + 4 * i, little_endian);
  }
  return image;
}

}  // namespace diffray::image
