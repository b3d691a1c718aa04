// libFuzzer harness: the light scene reader (render::parseLightScene). The set-up that follows in `render`
// (render::prepareScene, the occluders' WBSDF tables) is not run here: its work legitimately grows with the
// scene (a shipped white-light lens scene takes over 10 s under AddressSanitizer), beyond a fuzzer's time
// limit per input.
#include <cstddef>
#include <cstdint>
#include <string>

#include "diffray/core/error.h"
#include "diffray/render/light_scene.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    diffray::render::parseLightScene(text, "fuzz.json");
  } catch (const diffray::core::InputError&) {
  }
  return 0;
}
