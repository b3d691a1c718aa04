#pragma once
// The FDTD benchmark of diffray_bench (see fdtd_bench.cpp).
#include <string>

#include "diffray/room/room.h"

namespace diffray::bench {

/// Prints {"bench":"fdtd", "room":label, "cell_updates_per_s", "triad_bytes_per_s", ...}: the SRL update on
/// the room's grid for its 500 Hz octave at 10 points per wavelength, beside a STREAM-like triad measured
/// in the same run.
void benchFdtd(const room::Room& room, const std::string& label, int steps);

}  // namespace diffray::bench
