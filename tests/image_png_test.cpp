// PNG output: read back with libpng's own low-level reader, bytes within 1 of the sRGB encoding computed
// here from the IEC 61966-2-1 formula; exposure, clamping of negatives and its report; atomic failure.
#include <gtest/gtest.h>
#include <png.h>
#include <unistd.h>

#include <cmath>
#include <csetjmp>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "diffray/core/error.h"
#include "diffray/image/png.h"

namespace diffray::image {
namespace {

namespace fs = std::filesystem;

struct TempDir {
  fs::path path = fs::temp_directory_path() / ("diffray_png_test_" + std::to_string(::getpid()));
  TempDir() { fs::create_directories(path); }
  ~TempDir() { fs::remove_all(path); }
  std::string file(const std::string& name) const { return (path / name).string(); }
  int entries() const {
    return static_cast<int>(std::distance(fs::directory_iterator(path), fs::directory_iterator()));
  }
};

struct Decoded {
  bool ok = false;
  png_uint_32 width = 0, height = 0;
  int bit_depth = 0, color_type = 0;
  std::vector<unsigned char> rgb;
};

// Reads an 8-bit RGB PNG with libpng's classic API (no diffray code). Only POD locals live across setjmp.
bool readPngRaw(const char* path, Decoded* out) {
  FILE* f = std::fopen(path, "rb");
  if (!f) return false;
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png_create_info_struct(png);
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_read_struct(&png, &info, nullptr);
    std::fclose(f);
    return false;
  }
  png_init_io(png, f);
  png_read_info(png, info);
  out->width = png_get_image_width(png, info);
  out->height = png_get_image_height(png, info);
  out->bit_depth = png_get_bit_depth(png, info);
  out->color_type = png_get_color_type(png, info);
  out->rgb.resize(3u * out->width * out->height);
  for (png_uint_32 y = 0; y < out->height; ++y) png_read_row(png, out->rgb.data() + 3u * out->width * y, nullptr);
  png_read_end(png, nullptr);
  png_destroy_read_struct(&png, &info, nullptr);
  std::fclose(f);
  out->ok = true;
  return true;
}

// The sRGB encoding written out independently of color::srgbEncode.
int expectedByte(double linear) {
  const double v = std::min(std::max(linear, 0.0), 1.0);
  const double e = v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1.0 / 2.4) - 0.055;
  return static_cast<int>(std::floor(255.0 * e + 0.5));
}

TEST(ImagePng, RoundTripThroughLibpng) {
  TempDir dir;
  Image img = makeImage(7, 5);  // odd sizes: no row padding assumptions
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      float* p = img.at(x, y);
      p[0] = static_cast<float>(x) / 6.0f;         // red ramps left to right
      p[1] = static_cast<float>(y) / 4.0f;         // green ramps top to bottom
      p[2] = 0.001f * static_cast<float>(x + y);   // blue on the linear segment
    }
  const std::string path = dir.file("ramp.png");
  const EncodeStats stats = writePng(path, img);
  EXPECT_EQ(stats.negative_fraction, 0.0);
  Decoded d;
  ASSERT_TRUE(readPngRaw(path.c_str(), &d));
  EXPECT_EQ(d.width, 7u);
  EXPECT_EQ(d.height, 5u);
  EXPECT_EQ(d.bit_depth, 8);
  EXPECT_EQ(d.color_type, PNG_COLOR_TYPE_RGB);
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x)
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(d.rgb[3u * (7u * y + x) + c], expectedByte(img.at(x, y)[c]), 1) << x << "," << y << "," << c;
  EXPECT_EQ(d.rgb[0], 0);                  // (0, 0): black
  EXPECT_EQ(d.rgb[3u * 6u], 255);          // (6, 0): full red
  EXPECT_EQ(d.rgb[3u * (7u * 4u) + 1], 255);  // (0, 4): full green
}

TEST(ImagePng, ExposureScalesAndNegativesClampToZero) {
  TempDir dir;
  Image img = makeImage(4, 1);
  const float values[12] = {0.25f, -0.01f, 0.05f, -1.0f, -2.0f, -3.0f, 0.5f, 0.6f, 0.7f,
                            NAN, 0.1f, 0.2f};
  img.rgb.assign(values, values + 12);
  const std::string path = dir.file("exposed.png");
  const EncodeStats stats = writePng(path, img, 2.0);
  EXPECT_DOUBLE_EQ(stats.negative_fraction, 4.0 / 12.0);
  EXPECT_DOUBLE_EQ(stats.saturated_fraction, 2.0 / 12.0);  // 0.6·2 and 0.7·2
  EXPECT_DOUBLE_EQ(stats.nonfinite_fraction, 1.0 / 12.0);
  Decoded d;
  ASSERT_TRUE(readPngRaw(path.c_str(), &d));
  for (int i = 0; i < 12; ++i) {
    const double v = std::isfinite(values[i]) ? 2.0 * values[i] : 0.0;
    EXPECT_NEAR(d.rgb[i], expectedByte(v), 1) << i;
  }
  EXPECT_EQ(d.rgb[1], 0);
  EXPECT_EQ(d.rgb[6], 255);  // 0.5·2 = 1
}

TEST(ImagePng, FailedWriteThrowsAndLeavesNothing) {
  TempDir dir;
  const Image img = makeImage(2, 2);
  // A directory where the file should go: the temporary is written, the rename fails, it is removed.
  fs::create_directories(dir.path / "taken.png");
  EXPECT_THROW(writePng(dir.file("taken.png"), img), core::InputError);
  EXPECT_EQ(dir.entries(), 1);
  EXPECT_TRUE(fs::is_directory(dir.path / "taken.png"));
  // A missing directory.
  const std::string missing = dir.file("no/such/dir/out.png");
  try {
    writePng(missing, img);
    ADD_FAILURE() << "no error";
  } catch (const core::InputError& e) {
    EXPECT_NE(std::string(e.what()).find(missing), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(missing));
  EXPECT_EQ(dir.entries(), 1);
}

TEST(ImagePng, BadInputIsAnInputErrorBeforeAnyFile) {
  TempDir dir;
  Image bad;
  bad.width = 3, bad.height = 2;
  bad.rgb.assign(17, 0.0f);  // one short
  EXPECT_THROW(writePng(dir.file("a.png"), bad), core::InputError);
  EXPECT_THROW(writePng(dir.file("b.png"), makeImage(1, 1), 0.0), core::InputError);
  EXPECT_THROW(writePng(dir.file("c.png"), makeImage(1, 1), std::nan("")), core::InputError);
  EXPECT_THROW(makeImage(0, 5), core::InputError);
  EXPECT_THROW(makeImage(70000, 1), core::InputError);
  EXPECT_EQ(dir.entries(), 0);
}

}  // namespace
}  // namespace diffray::image
