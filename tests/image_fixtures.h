#pragma once
// Shared by the image tests: the tests' temporary directory (temp_dir.h) under the image tests' namespace.
#include "temp_dir.h"

namespace diffray::image::test {

using diffray::test::TempDir;

}  // namespace diffray::image::test
