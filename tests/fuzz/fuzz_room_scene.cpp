// libFuzzer harness: the room scene reader (room::parseRoom: materials, geometry, occluders, doors, sources,
// listeners, output), with relative paths (materials_library, OBJ files) resolved in the shipped rooms/
// folder so that the fuzzer can reach them.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "diffray/core/error.h"
#include "diffray/room/scene_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    std::vector<std::string> warnings;
    diffray::room::parseRoom(text, "fuzz.json", DIFFRAY_SOURCE_DIR "/rooms", &warnings);
  } catch (const diffray::core::InputError&) {
  }
  return 0;
}
