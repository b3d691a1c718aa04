#pragma once
// A spectrogram (dsp::Spectrogram) drawn by gnuplot (cli::runGnuplot) as a PNG image: time across, frequency
// up on a log axis from min_freq_hz to fs/2, level in dB as colour over `range_db` below the loudest pixel.
// The data handed to gnuplot is reduced to at most 800 time columns × 400 log-spaced frequency rows (float32
// binary, ≤ 1.3 MB): each pixel shows the loudest frame and bin it covers (so a one-frame click stays
// visible), or the bin nearest its centre where bins are wider than pixels (low frequencies). Optional
// vertical markers (e.g. the door's START and END) are dashed lines labelled at the top. Written to a
// temporary and renamed, as every plot. Not thread-safe (runs a process).
#include <string>
#include <vector>

#include "diffray/dsp/spectrogram.h"

namespace diffray::cli {

struct TimeMarker {
  double time_s = 0.0;
  std::string label;
};

struct SpectrogramPlotOptions {
  std::string title;
  std::vector<TimeMarker> markers;
  double min_freq_hz = 50.0;
  double range_db = 90.0;
  std::string option = "-o";  ///< the option named in errors (gnuplot missing or failing)
};

/// Throws core::InputError naming `o.option` when gnuplot is missing or fails, or when min_freq_hz is not
/// below fs/2.
void writeSpectrogramPlot(const std::string& png_path, const dsp::Spectrogram& s, const SpectrogramPlotOptions& o);

}  // namespace diffray::cli
