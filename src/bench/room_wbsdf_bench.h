#pragma once
// The cost of diffraction in a reverberant room (see room_wbsdf_bench.cpp).
#include <cstdint>
#include <string>

namespace diffray::bench {

/// Prints one JSON line per model ("none", "wbsdf") and one with their ratio: the rays and the seconds each
/// needs before every band's EDT, T30, C50 and C80 (from the energy histograms) of every listener of the scene
/// at `room_path` stay within one ISO 3382-1 JND of a run with `reference_rays` rays (the anchor: `none`).
void benchRoomWbsdf(const std::string& room_path, const std::string& label, std::uint64_t reference_rays);

}  // namespace diffray::bench
