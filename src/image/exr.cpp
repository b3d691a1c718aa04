#include "diffray/image/exr.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfIO.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <Iex.h>

#include <cstdint>
#include <ostream>

#include "diffray/core/atomic_file.h"
#include "diffray/core/error.h"

namespace diffray::image {

namespace {

/// OpenEXR's output stream interface over the std::ostream that writeFileAtomically hands out.
class StdOStreamAdapter : public Imf::OStream {
 public:
  StdOStreamAdapter(std::ostream& out, const std::string& name) : Imf::OStream(name.c_str()), out_(out) {}
  void write(const char c[], int n) override {
    out_.write(c, n);
    if (!out_) throw Iex::IoExc("write failed");
  }
  uint64_t tellp() override { return static_cast<uint64_t>(out_.tellp()); }
  void seekp(uint64_t pos) override {
    out_.seekp(static_cast<std::streamoff>(pos));
    if (!out_) throw Iex::IoExc("seek failed");
  }

 private:
  std::ostream& out_;
};

Imf::Slice floatSlice(float* base, int width) {
  return Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(base), 3 * sizeof(float),
                    3 * sizeof(float) * static_cast<std::size_t>(width));
}

}  // namespace

void writeExr(const std::string& path, const Image& linear_rgb) {
  checkImage(path, linear_rgb);
  Imf::Header header(linear_rgb.width, linear_rgb.height);
  header.compression() = Imf::ZIP_COMPRESSION;
  for (const char* name : {"R", "G", "B"}) header.channels().insert(name, Imf::Channel(Imf::FLOAT));
  // OpenEXR takes non-const slice pointers for reading and writing alike; it only reads them here.
  float* base = const_cast<float*>(linear_rgb.rgb.data());
  Imf::FrameBuffer frame;
  frame.insert("R", floatSlice(base + 0, linear_rgb.width));
  frame.insert("G", floatSlice(base + 1, linear_rgb.width));
  frame.insert("B", floatSlice(base + 2, linear_rgb.width));
  try {
    core::writeFileAtomically(path, [&](std::ostream& out) {
      StdOStreamAdapter stream(out, path);
      Imf::OutputFile file(stream, header);
      file.setFrameBuffer(frame);
      file.writePixels(linear_rgb.height);
    });
  } catch (const Iex::BaseExc& e) {
    throw core::InputError(path, std::string("OpenEXR: ") + e.what());
  }
}

Image readExr(const std::string& path) {
  try {
    Imf::InputFile file(path.c_str());
    const Imath::Box2i window = file.header().dataWindow();
    const int width = window.max.x - window.min.x + 1, height = window.max.y - window.min.y + 1;
    Image image;
    try {
      image = makeImage(width, height);
    } catch (const core::InputError& e) {
      throw core::InputError(path, e.what());
    }
    // The frame buffer is addressed in data-window coordinates: shift the base so (min.x, min.y) is pixel 0.
    float* origin = image.rgb.data() - 3 * (static_cast<std::ptrdiff_t>(window.min.y) * width + window.min.x);
    Imf::FrameBuffer frame;
    const char* names[3] = {"R", "G", "B"};
    for (int c = 0; c < 3; ++c) frame.insert(names[c], floatSlice(origin + c, width));
    file.setFrameBuffer(frame);
    file.readPixels(window.min.y, window.max.y);
    return image;
  } catch (const Iex::BaseExc& e) {
    throw core::InputError(path, std::string("OpenEXR: ") + e.what());
  }
}

}  // namespace diffray::image
