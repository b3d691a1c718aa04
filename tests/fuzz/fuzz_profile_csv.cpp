// libFuzzer harness: the WBSDF profile CSV reader (wbsdf::readProfileCsv), then the table it feeds at a
// wavelength long enough to keep the table small (a profile the reader accepts must never crash
// profileTable: it refuses what is too long with core::InputError).
#include <cstddef>
#include <cstdint>

#include "diffray/core/error.h"
#include "diffray/wbsdf/profile_csv.h"
#include "fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = diffray::fuzz::writeInput(data, size, "profile.csv");
  try {
    const diffray::wbsdf::ProfilePoints points = diffray::wbsdf::readProfileCsv(path);
    diffray::wbsdf::profileTable(points, 1e-3, 200'000);
  } catch (const diffray::core::InputError&) {
  }
  return 0;
}
