#pragma once
// Linear float images as PFM (Portable Float Map, colour variant): the header "PF\n<width> <height>\n-1.0\n"
// (a negative scale means little-endian), then 3 IEEE-754 binary32 values per pixel, rows from the BOTTOM
// row up, left to right. Values are stored as they are (negatives, NaN and Inf included), so a PFM keeps
// the signed energy a PNG clips. Writes are atomic (core::writeFileAtomically). Thread-safe for different
// paths.
#include <string>

#include "diffray/image/image.h"

namespace diffray::image {

/// Writes `linear_rgb` as a little-endian colour PFM. Throws core::InputError naming `path` if it cannot be
/// written or the image is malformed; nothing is left behind then.
void writePfm(const std::string& path, const Image& linear_rgb);

/// Reads a colour PFM ("PF") of either endianness. Throws core::InputError naming `path` for a missing file,
/// a greyscale ("Pf") or malformed header, or a short pixel block.
Image readPfm(const std::string& path);

}  // namespace diffray::image
