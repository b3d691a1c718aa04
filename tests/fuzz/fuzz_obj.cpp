// libFuzzer harness: the OBJ reader (room::parseObj).
#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>

#include "diffray/core/error.h"
#include "diffray/room/obj.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
  try {
    diffray::room::parseObj(in, "fuzz.obj");
  } catch (const diffray::core::InputError&) {
  }
  return 0;
}
