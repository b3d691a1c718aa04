#pragma once
// Plots of validation results, drawn by gnuplot (Debian's gnuplot-nox, a command-line program) into a PNG:
// one panel per case, traced values as points and the oracle as a line, against the screen position (for
// 2D screens, the row through the centre; for gratings, sinθ of each order). The PNG is written to a
// temporary file and renamed, so a failed plot leaves nothing behind. Not thread-safe (runs a process).
#include <string>
#include <vector>

#include "diffray/validate/case.h"

namespace diffray::cli {

/// Throws core::InputError naming --plot when gnuplot is missing or fails.
void writeValidationPlot(const std::string& png_path, const std::vector<validate::CaseResult>& results);

}  // namespace diffray::cli
