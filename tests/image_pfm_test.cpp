// PFM output: header and byte layout checked byte by byte (bottom row first, little-endian float32,
// scale −1.0), signed and non-finite values kept, the reader's round trip, atomic failure.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "diffray/core/error.h"
#include "diffray/image/pfm.h"

namespace diffray::image {
namespace {

namespace fs = std::filesystem;

struct TempDir {
  fs::path path = fs::temp_directory_path() / ("diffray_pfm_test_" + std::to_string(::getpid()));
  TempDir() { fs::create_directories(path); }
  ~TempDir() { fs::remove_all(path); }
  std::string file(const std::string& name) const { return (path / name).string(); }
  int entries() const {
    return static_cast<int>(std::distance(fs::directory_iterator(path), fs::directory_iterator()));
  }
};

std::vector<unsigned char> slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

float leFloat(const unsigned char* b) {
  const std::uint32_t bits = std::uint32_t{b[0]} | std::uint32_t{b[1]} << 8 | std::uint32_t{b[2]} << 16 |
                             std::uint32_t{b[3]} << 24;
  float v;
  std::memcpy(&v, &bits, 4);
  return v;
}

TEST(ImagePfm, HeaderAndBottomToTopLittleEndianLayout) {
  TempDir dir;
  Image img = makeImage(3, 2);
  for (int i = 0; i < 18; ++i) img.rgb[i] = static_cast<float>(i) - 4.5f;  // negatives too
  img.rgb[7] = 1e-30f;
  const std::string path = dir.file("a.pfm");
  writePfm(path, img);
  const auto bytes = slurp(path);
  const std::string header = "PF\n3 2\n-1.0\n";
  ASSERT_EQ(bytes.size(), header.size() + 18 * 4);
  EXPECT_EQ(std::string(bytes.begin(), bytes.begin() + static_cast<long>(header.size())), header);
  const unsigned char* data = bytes.data() + header.size();
  // File row 0 is the image's bottom row (y = 1), then y = 0.
  for (int file_row = 0; file_row < 2; ++file_row) {
    const int y = 1 - file_row;
    for (int i = 0; i < 9; ++i)
      EXPECT_EQ(leFloat(data + 4 * (9 * file_row + i)), img.rgb[9 * y + i]) << file_row << "," << i;
  }
  // Byte order on disk: rgb[0] = −4.5f is 0xc0900000, stored little-endian as 00 00 90 c0.
  const unsigned char* first_of_top_row = data + 4 * 9;  // file row 1 = image row 0, rgb[0]
  EXPECT_EQ(first_of_top_row[0], 0x00);
  EXPECT_EQ(first_of_top_row[1], 0x00);
  EXPECT_EQ(first_of_top_row[2], 0x90);
  EXPECT_EQ(first_of_top_row[3], 0xc0);
}

TEST(ImagePfm, RoundTripKeepsSignedAndNonFiniteValues) {
  TempDir dir;
  Image img = makeImage(5, 4);
  for (std::size_t i = 0; i < img.rgb.size(); ++i) img.rgb[i] = std::sin(static_cast<float>(i)) * 1e3f;
  img.rgb[3] = NAN;
  img.rgb[4] = -INFINITY;
  const std::string path = dir.file("b.pfm");
  writePfm(path, img);
  const Image back = readPfm(path);
  ASSERT_EQ(back.width, 5);
  ASSERT_EQ(back.height, 4);
  for (std::size_t i = 0; i < img.rgb.size(); ++i) {
    if (std::isnan(img.rgb[i]))
      EXPECT_TRUE(std::isnan(back.rgb[i]));
    else
      EXPECT_EQ(back.rgb[i], img.rgb[i]) << i;
  }
}

TEST(ImagePfm, ReadsBigEndianToo) {
  TempDir dir;
  const std::string path = dir.file("be.pfm");
  {
    std::ofstream out(path, std::ios::binary);
    out << "PF\n1 1\n1.0\n";
    const unsigned char px[12] = {0x3f, 0x80, 0, 0, 0x40, 0, 0, 0, 0xc0, 0x40, 0, 0};  // 1, 2, −3
    out.write(reinterpret_cast<const char*>(px), 12);
  }
  const Image img = readPfm(path);
  EXPECT_EQ(img.rgb[0], 1.0f);
  EXPECT_EQ(img.rgb[1], 2.0f);
  EXPECT_EQ(img.rgb[2], -3.0f);
}

TEST(ImagePfm, FailuresAreInputErrorsAndLeaveNothing) {
  TempDir dir;
  fs::create_directories(dir.path / "taken.pfm");
  EXPECT_THROW(writePfm(dir.file("taken.pfm"), makeImage(2, 2)), core::InputError);
  EXPECT_THROW(writePfm(dir.file("no/dir/x.pfm"), makeImage(2, 2)), core::InputError);
  Image bad;
  EXPECT_THROW(writePfm(dir.file("empty.pfm"), bad), core::InputError);
  EXPECT_EQ(dir.entries(), 1);  // only the directory we made
  EXPECT_THROW(readPfm(dir.file("missing.pfm")), core::InputError);
  {
    std::ofstream(dir.file("short.pfm"), std::ios::binary) << "PF\n2 2\n-1.0\n" << "abc";
    std::ofstream(dir.file("grey.pfm"), std::ios::binary) << "Pf\n1 1\n-1.0\n" << "abcd";
  }
  EXPECT_THROW(readPfm(dir.file("short.pfm")), core::InputError);
  EXPECT_THROW(readPfm(dir.file("grey.pfm")), core::InputError);
}

}  // namespace
}  // namespace diffray::image
