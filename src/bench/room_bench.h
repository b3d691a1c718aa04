#pragma once
// Room benchmarks of diffray_bench (see room_bench.cpp).
#include <cstdint>
#include <string>

#include "diffray/room/room.h"

namespace diffray::bench {

/// Prints {"bench":"room", "room":label, "embree_rays_per_s", "diffray_rays_per_s", "ratio", ...}.
void benchRoom(const room::Room& room, const std::string& label, std::uint64_t rays);

}  // namespace diffray::bench
