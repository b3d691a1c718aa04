// OpenEXR output: the header read back by OpenEXR itself (three FLOAT channels R, G, B, the size), the
// pixel values bit-exact (signed ones included), and failures as one-line InputErrors leaving no file.
#include <gtest/gtest.h>
#include <ImfChannelList.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "diffray/core/error.h"
#include "image_fixtures.h"
#include "diffray/image/exr.h"

namespace diffray::image {
namespace {

namespace fs = std::filesystem;

using test::TempDir;

TEST(ImageExr, FloatChannelsRoundTripBitExact) {
  TempDir dir("exr_test");
  Image img = makeImage(6, 3);
  for (std::size_t i = 0; i < img.rgb.size(); ++i) img.rgb[i] = std::cos(static_cast<float>(i)) * 3.0f;
  img.rgb[5] = -1e-20f;
  img.rgb[6] = 7e30f;
  const std::string path = dir.file("a.exr");
  writeExr(path, img);
  {
    Imf::InputFile file(path.c_str());
    const Imath::Box2i w = file.header().dataWindow();
    EXPECT_EQ(w.max.x - w.min.x + 1, 6);
    EXPECT_EQ(w.max.y - w.min.y + 1, 3);
    int channels = 0;
    for (auto it = file.header().channels().begin(); it != file.header().channels().end(); ++it, ++channels) {
      EXPECT_EQ(it.channel().type, Imf::FLOAT) << it.name();
      EXPECT_TRUE(std::string(it.name()) == "R" || std::string(it.name()) == "G" || std::string(it.name()) == "B");
    }
    EXPECT_EQ(channels, 3);
  }
  const Image back = readExr(path);
  ASSERT_EQ(back.width, 6);
  ASSERT_EQ(back.height, 3);
  for (std::size_t i = 0; i < img.rgb.size(); ++i) EXPECT_EQ(back.rgb[i], img.rgb[i]) << i;
  EXPECT_EQ(dir.entries(), 1);
}

TEST(ImageExr, FailuresAreInputErrorsAndLeaveNothing) {
  TempDir dir("exr_test");
  fs::create_directories(dir.path / "taken.exr");
  EXPECT_THROW(writeExr(dir.file("taken.exr"), makeImage(2, 2)), core::InputError);
  EXPECT_THROW(writeExr(dir.file("no/dir/x.exr"), makeImage(2, 2)), core::InputError);
  EXPECT_THROW(writeExr(dir.file("bad.exr"), Image{}), core::InputError);
  EXPECT_EQ(dir.entries(), 1);
  EXPECT_THROW(readExr(dir.file("missing.exr")), core::InputError);
  std::ofstream(dir.file("junk.exr")) << "not an exr file";
  try {
    readExr(dir.file("junk.exr"));
    ADD_FAILURE() << "no error";
  } catch (const core::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("junk.exr"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace diffray::image
