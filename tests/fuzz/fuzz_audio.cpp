// libFuzzer harness: the audio readers (every format libsndfile opens: WAV, AIFF, FLAC, Ogg, …): the whole-
// file reader audio::readAudio and the streaming audio::AudioReader with audio::readChannel. No header's
// length may size a buffer; a file holding more than the reader's cap is refused with core::InputError.
#include <cstddef>
#include <cstdint>

#include "diffray/audio/wav.h"
#include "diffray/core/error.h"
#include "fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = diffray::fuzz::writeInput(data, size, "audio");
  try {
    std::string warning;
    diffray::audio::readAudio(path, &warning);
  } catch (const diffray::core::InputError&) {
  }
  try {
    diffray::audio::AudioReader reader(path);
    diffray::audio::readChannel(reader, -1);
  } catch (const diffray::core::InputError&) {
  }
  return 0;
}
