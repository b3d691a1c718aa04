#include "diffray/dsp/resample.h"

#include <samplerate.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "diffray/core/error.h"

namespace diffray::dsp {

std::vector<float> resample(const std::vector<float>& interleaved, int channels, double from_hz, double to_hz) {
  if (channels < 1) throw core::InputError("resample", "needs at least one channel");
  if (interleaved.size() % static_cast<size_t>(channels) != 0)
    throw core::InputError("resample", "the sample count is not a multiple of the channel count");
  core::requirePositive("resample: source rate", from_hz);
  core::requirePositive("resample: target rate", to_hz);
  const double ratio = to_hz / from_hz;
  if (src_is_valid_ratio(ratio) == 0)
    throw core::InputError("resample", "rate ratio " + std::to_string(ratio) + " lies outside libsamplerate's 1/256 … 256");
  if (from_hz == to_hz || interleaved.empty()) return interleaved;

  const long frames = static_cast<long>(interleaved.size()) / channels;
  const long target = std::max(1L, std::lround(static_cast<double>(frames) * ratio));
  // Room for the converter's flush beyond the target; the result is cut (or zero-padded) to `target`.
  const long room = target + 64;
  std::vector<float> out(static_cast<size_t>(room) * static_cast<size_t>(channels), 0.0f);
  SRC_DATA data{};
  data.data_in = interleaved.data();
  data.input_frames = frames;
  data.data_out = out.data();
  data.output_frames = room;
  data.end_of_input = 1;
  data.src_ratio = ratio;
  const int error = src_simple(&data, SRC_SINC_BEST_QUALITY, channels);
  DIFFRAY_CHECK(error == 0);
  out.resize(static_cast<size_t>(target) * static_cast<size_t>(channels), 0.0f);
  return out;
}

std::vector<float> resampleImpulseResponse(const std::vector<float>& interleaved, int channels, double from_hz,
                                           double to_hz) {
  std::vector<float> h = resample(interleaved, channels, from_hz, to_hz);
  const auto scale = static_cast<float>(from_hz / to_hz);
  for (float& s : h) s *= scale;
  return h;
}

}  // namespace diffray::dsp
