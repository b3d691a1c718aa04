#pragma once
// Output files are written whole or not at all: content goes to a temporary file beside the target,
// which is renamed over the target only when complete. A failed write leaves no file behind.
#include <functional>
#include <ostream>
#include <string>

namespace diffray::core {

/// Calls `write(stream)` on a temporary file next to `path`, then renames it to `path`.
/// Throws InputError (naming `path`) if the file cannot be written; nothing is left behind then.
void writeFileAtomically(const std::string& path, const std::function<void(std::ostream&)>& write);

}  // namespace diffray::core
