#include "diffray/audio/wav_float_format.h"

#include <cstring>

namespace diffray::audio {

namespace {

void put16(std::string& out, std::uint32_t v) {
  out.push_back(static_cast<char>(v & 0xFFu));
  out.push_back(static_cast<char>((v >> 8) & 0xFFu));
}
void put32(std::string& out, std::uint64_t v) {
  for (int shift = 0; shift < 32; shift += 8) out.push_back(static_cast<char>((v >> shift) & 0xFFu));
}

// KSDATAFORMAT_SUBTYPE_IEEE_FLOAT, {00000003-0000-0010-8000-00AA00389B71}, as stored (GUID fields little-endian).
constexpr unsigned char kIeeeFloatGuid[16] = {0x03, 0x00, 0x00, 0x00, 0x00, 0x00, 0x10, 0x00,
                                              0x80, 0x00, 0x00, 0xAA, 0x00, 0x38, 0x9B, 0x71};
constexpr std::uint32_t kWaveFormatIeeeFloat = 3;
constexpr std::uint32_t kWaveFormatExtensible = 0xFFFE;

}  // namespace

std::string floatWavHeader(int channels, int sample_rate_hz, std::uint64_t frames) {
  const bool extensible = channels > 2;
  const auto ch = static_cast<std::uint32_t>(channels);
  const std::uint32_t block_align = 4u * ch;
  const std::uint64_t data_bytes = frames * block_align;
  const std::uint32_t fmt_bytes = extensible ? 40u : 18u;
  std::string h;
  h += "RIFF";
  put32(h, 4u + (8u + fmt_bytes) + 12u + 8u + data_bytes);  // everything after this field
  h += "WAVE";
  h += "fmt ";
  put32(h, fmt_bytes);
  put16(h, extensible ? kWaveFormatExtensible : kWaveFormatIeeeFloat);
  put16(h, ch);
  put32(h, static_cast<std::uint32_t>(sample_rate_hz));
  put32(h, static_cast<std::uint64_t>(sample_rate_hz) * block_align);  // average bytes per second
  put16(h, block_align);
  put16(h, 32u);                       // bits per sample
  put16(h, extensible ? 22u : 0u);     // cbSize: bytes of format information that follow
  if (extensible) {
    put16(h, 32u);  // valid bits per sample
    put32(h, 0u);   // channel mask: no loudspeaker positions
    h.append(reinterpret_cast<const char*>(kIeeeFloatGuid), sizeof(kIeeeFloatGuid));
  }
  h += "fact";
  put32(h, 4u);
  put32(h, frames);  // sample frames per channel
  h += "data";
  put32(h, data_bytes);
  return h;
}

void appendFloat32LE(std::string& out, const float* values, std::size_t count) {
  const std::size_t at = out.size();
  out.resize(at + 4 * count);
  for (std::size_t i = 0; i < count; ++i) {
    std::uint32_t bits = 0;
    std::memcpy(&bits, &values[i], 4);
    for (int b = 0; b < 4; ++b) out[at + 4 * i + static_cast<std::size_t>(b)] = static_cast<char>((bits >> (8 * b)) & 0xFFu);
  }
}

}  // namespace diffray::audio
