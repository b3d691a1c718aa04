#pragma once
// The outputs of `diffray compare` in room mode (compare/room_compare.h): a table per listener (rows band ×
// model: G, early energy, EDT, T30, C50, C80, and with a wave model each ray model's difference from it), the
// same as CSV and as JSON lines, and a gnuplot PNG of G (and the early energy) per band, one panel per
// listener. The free-field aperture reference appears only for listeners it describes; for the others the
// table says why, once per listener. Not thread-safe (prints; the plot runs a process).
#include <string>

#include "diffray/compare/room_compare.h"
#include "diffray/room/room.h"

namespace diffray::cli {

/// The name of the free-field aperture reference in every output.
inline constexpr const char* kApertureModel = "aperture-free-field";

void printRoomComparison(const room::Room& room, const compare::RoomComparison& c);
/// One JSON object per line: per listener, model and band; the aperture reference per band where it
/// applies, else one object with "applies": false and "why_not".
std::string roomComparisonJsonLines(const room::Room& room, const compare::RoomComparison& c);
void writeRoomCompareCsv(const std::string& path, const room::Room& room, const compare::RoomComparison& c);
/// Throws core::InputError naming --plot when gnuplot is missing or fails.
void writeRoomComparePlot(const std::string& png_path, const room::Room& room, const compare::RoomComparison& c);

}  // namespace diffray::cli
