#pragma once
// Plots of validation results, drawn by gnuplot (Debian's gnuplot-nox, a command-line program) into a PNG:
// one panel per case, traced values as points and the oracle as a line, against the screen position (for
// 2D screens, the row through the centre; for gratings, sinθ of each order). The PNG is written to a
// temporary file and renamed, so a failed plot leaves nothing behind. Not thread-safe (runs a process).
#include <functional>
#include <string>
#include <vector>

#include "diffray/compare/scene_compare.h"
#include "diffray/room/room.h"

#include "diffray/ir/response.h"
#include "diffray/validate/case.h"

namespace diffray::cli {

/// Runs the gnuplot script `script_for(tmp_png, scratch_dir)` (which must write its PNG to tmp_png; data
/// files go in scratch_dir) and renames the PNG to png_path. Throws core::InputError naming `option` when
/// gnuplot is missing or fails; nothing is left behind then.
void runGnuplot(const std::string& option, const std::string& png_path,
                const std::function<std::string(const std::string&, const std::string&)>& script_for);

/// The checks every `--plot FILE` option makes before its run: nothing when `path` is empty; else throws
/// core::InputError when `path` does not end in .png (gnuplot writes PNG data whatever the name) or when
/// gnuplot is missing.
void checkPlotOption(const std::string& option, const std::string& path);

/// `s` as a gnuplot single-quoted string (quotes doubled), for titles and file names in scripts.
std::string gnuplotQuoted(const std::string& s);

/// Where each listener's sound comes from over time (`diffray ir --plot-directions`): one panel per
/// listener, one point per window of `window_s` from the onset of the 500 Hz – 2 kHz octaves to `span_s`
/// after it, at the azimuth (in the listener's frame, `frames`) of the window's energy vector over those
/// bands (arrivals and traced part), coloured by its level re the loudest window and sized by r_E. Needs
/// responses that recorded directions. Throws core::InputError naming --plot-directions on failure.
void writeDirectionPlot(const std::string& png_path, const std::vector<std::string>& names,
                        const std::vector<ir::EnergyResponse>& responses, const std::vector<room::Listener>& frames,
                        double window_s = 0.002, double span_s = 0.2);

/// Throws core::InputError naming --plot when gnuplot is missing or fails.
void writeValidationPlot(const std::string& png_path, const std::vector<validate::CaseResult>& results);

/// The energy decay (Schroeder) curves of every band, in dB, one panel per listener (`names`), from the
/// responses' total histograms (`diffray ir --plot`). `flags` (optional, [listener][band]: "ok", "noisy",
/// "negative_energy", ir::BandUncertainty::flagName) label marked bands in the key; a curve that rises
/// (negative energy in a signed histogram) is drawn dashed and says so. Throws core::InputError naming
/// --plot on failure.
void writeDecayPlot(const std::string& png_path, const std::vector<std::string>& names,
                    const std::vector<ir::EnergyResponse>& responses,
                    const std::vector<std::vector<std::string>>& flags = {});

/// `diffray compare --plot`: one panel per listener (every one) of level re free field against frequency
/// (UTD and exact on the fine grid as lines, band levels as points), then one panel per band of level against
/// the listeners' angle past the shadow boundary when the scene defines one. Throws core::InputError naming
/// --plot on failure.
void writeComparePlot(const std::string& png_path, const room::Room& room, const compare::SceneComparison& c);

}  // namespace diffray::cli
