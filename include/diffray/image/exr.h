#pragma once
// Linear float images as OpenEXR (through Debian's libopenexr): scanline file, three 32-bit FLOAT channels
// "R", "G", "B" (linear, values stored as they are: negatives, NaN and Inf included), ZIP compression,
// rows top to bottom as in the Image. Writes go through core::writeFileAtomically (OpenEXR writes into its
// stream, which seeks back once for the line-offset table), so a failed write leaves no file. Thread-safe
// for different paths.
#include <string>

#include "diffray/image/image.h"

namespace diffray::image {

/// Writes `linear_rgb` as a float RGB OpenEXR file. Throws core::InputError naming `path` if it cannot be
/// written (OpenEXR's reason included) or the image is malformed; nothing is left behind then.
void writeExr(const std::string& path, const Image& linear_rgb);

/// Reads the R, G, B channels of an OpenEXR file (missing channels read as 0) over its data window.
/// Throws core::InputError naming `path` with OpenEXR's reason if it cannot be read.
Image readExr(const std::string& path);

}  // namespace diffray::image
