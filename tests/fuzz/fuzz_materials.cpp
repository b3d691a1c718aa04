// libFuzzer harness: the material library reader (room::loadMaterialLibrary), in octave and third-octave
// bands.
#include <cstddef>
#include <cstdint>

#include "diffray/core/bands.h"
#include "diffray/core/error.h"
#include "diffray/room/materials.h"
#include "fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = diffray::fuzz::writeInput(data, size, "materials.json");
  for (const diffray::core::Bands& bands : {diffray::core::Bands::octave(), diffray::core::Bands::thirdOctave()}) {
    try {
      diffray::room::loadMaterialLibrary(path, bands);
    } catch (const diffray::core::InputError&) {
    }
  }
  return 0;
}
