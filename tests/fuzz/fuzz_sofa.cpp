// libFuzzer harness: the SOFA HRTF reader (spatial::Hrtf::load: libmysofa's parser and check, then diffray's
// own checks, delays, resampling and normalisation), at the MIT KEMAR set's own rate so that a seed is not
// resampled on every run (a mutated rate is).
#include <cstddef>
#include <cstdint>

#include "diffray/core/error.h"
#include "diffray/spatial/hrtf.h"
#include "fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = diffray::fuzz::writeInput(data, size, "hrtf.sofa");
  try {
    diffray::spatial::Hrtf::load(path, 44100.0);
  } catch (const diffray::core::InputError&) {
  }
  return 0;
}
