#include "diffray/cli/spectrogram_plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "diffray/cli/plot.h"
#include "diffray/core/error.h"

namespace diffray::cli {

namespace {

constexpr int kMaxColumns = 800;
constexpr int kRows = 400;

/// The image handed to gnuplot: columns × rows of dB, row-major from the lowest frequency, on a grid
/// uniform in time and in log10(frequency).
struct Image {
  int columns = 0, rows = kRows;
  double x0_s = 0.0, dx_s = 0.0;  ///< centre of column 0, column spacing
  double y0 = 0.0, dy = 0.0;      ///< log10(Hz) at the centre of row 0, row spacing
  std::vector<float> db;
  float top_db = 0.0f;
};

Image reduce(const dsp::Spectrogram& s, double min_freq_hz) {
  Image im;
  const int frames = s.frames();
  im.columns = std::min(frames, kMaxColumns);
  const double per_column = static_cast<double>(frames) / im.columns;
  // Column c covers frames [c·F/C, (c+1)·F/C): its centre, in frame index, is (c + ½)·F/C − ½, and frame
  // i's time is time_s[0] + i·hop/fs (time_s[0] = window/2/fs, or later for folded frames,
  // dsp::spectrogramPeaks), so the column times are evenly spaced.
  im.dx_s = per_column * s.hop / s.sample_rate_hz;
  im.x0_s = s.time_s.front() + (0.5 * per_column - 0.5) * s.hop / s.sample_rate_hz;
  const double lo = std::log10(min_freq_hz), hi = std::log10(0.5 * s.sample_rate_hz);
  im.dy = (hi - lo) / im.rows;
  im.y0 = lo + 0.5 * im.dy;
  const double bin_hz = s.sample_rate_hz / s.window;
  // Bins [k_begin, k_end) of each row; a single nearest bin where a row is narrower than a bin.
  std::vector<int> k_begin(static_cast<size_t>(im.rows)), k_end(static_cast<size_t>(im.rows));
  for (int r = 0; r < im.rows; ++r) {
    const double f_a = std::pow(10.0, lo + r * im.dy), f_b = std::pow(10.0, lo + (r + 1) * im.dy);
    int a = static_cast<int>(std::ceil(f_a / bin_hz)), b = static_cast<int>(std::ceil(f_b / bin_hz));
    if (b <= a) a = static_cast<int>(std::lround(std::pow(10.0, lo + (r + 0.5) * im.dy) / bin_hz)), b = a + 1;
    k_begin[static_cast<size_t>(r)] = std::min(a, s.bins() - 1);
    k_end[static_cast<size_t>(r)] = std::min(b, s.bins());
  }
  im.db.assign(static_cast<size_t>(im.columns) * static_cast<size_t>(im.rows), static_cast<float>(dsp::Spectrogram::kFloorDb));
  im.top_db = static_cast<float>(dsp::Spectrogram::kFloorDb);
  for (int c = 0; c < im.columns; ++c) {
    const int i_begin = static_cast<int>(c * per_column);
    const int i_end = std::max(i_begin + 1, static_cast<int>((c + 1) * per_column));
    for (int r = 0; r < im.rows; ++r) {
      float& pixel = im.db[static_cast<size_t>(r) * static_cast<size_t>(im.columns) + static_cast<size_t>(c)];
      for (int i = i_begin; i < std::min(i_end, frames); ++i)
        for (int k = k_begin[static_cast<size_t>(r)]; k < k_end[static_cast<size_t>(r)]; ++k) pixel = std::max(pixel, s.at(i, k));
      im.top_db = std::max(im.top_db, pixel);
    }
  }
  return im;
}

/// "50", "100", "1k", "20k": labels for the log frequency axis.
std::string hzLabel(double f) {
  std::ostringstream o;
  if (f >= 1000.0) o << f / 1000.0 << "k"; else o << f;
  return o.str();
}

}  // namespace

void writeSpectrogramPlot(const std::string& png_path, const dsp::Spectrogram& s, const SpectrogramPlotOptions& o) {
  if (!(o.min_freq_hz > 0.0 && o.min_freq_hz < 0.5 * s.sample_rate_hz))
    throw core::InputError(o.option, "the spectrogram's lowest frequency must lie between 0 and fs/2");
  core::requirePositive(o.option + " dB range", o.range_db);
  DIFFRAY_CHECK(s.frames() > 0 && s.bins() > 1);
  const Image im = reduce(s, o.min_freq_hz);
  runGnuplot(o.option, png_path, [&](const std::string& tmp_png, const std::string& dir) {
    const std::string data = (std::filesystem::path(dir) / "spectrogram.f32").string();
    {
      std::ofstream out(data, std::ios::binary);
      out.write(reinterpret_cast<const char*>(im.db.data()), static_cast<std::streamsize>(im.db.size() * sizeof(float)));
    }
    const double top = std::ceil(im.top_db);
    std::ostringstream g;
    g.precision(10);
    g << "set terminal pngcairo size 1100,560 font 'sans,10'\nset output " << gnuplotQuoted(tmp_png) << "\n"
      << "set title " << gnuplotQuoted(o.title) << " noenhanced offset 0,1\nset tmargin 4\n"
      << "set xlabel 'time (s)'\nset ylabel 'frequency (Hz)'\nset cblabel 'level (dB re full-scale sine)'\n"
      << "set palette defined (0 '#000004', 1 '#3b0f70', 2 '#8c2981', 3 '#de4968', 4 '#fe9f6d', 5 '#fcfdbf')\n"
      << "set cbrange [" << top - o.range_db << ":" << top << "]\n"
      << "set xrange [" << im.x0_s - 0.5 * im.dx_s << ":" << im.x0_s + (im.columns - 0.5) * im.dx_s << "]\n"
      << "set yrange [" << im.y0 - 0.5 * im.dy << ":" << im.y0 + (im.rows - 0.5) * im.dy << "]\n";
    // Log frequency axis by hand (the image grid is uniform in log10 f): tics at 1, 2, 5 × 10^n.
    g << "set ytics (";
    bool first = true;
    for (double decade = 1.0; decade < s.sample_rate_hz; decade *= 10.0)
      for (double m : {1.0, 2.0, 5.0}) {
        const double f = m * decade;
        if (f < o.min_freq_hz || f > 0.5 * s.sample_rate_hz) continue;
        g << (first ? "" : ", ") << "'" << hzLabel(f) << "' " << std::log10(f);
        first = false;
      }
    g << ")\nset tics out\n";
    int tag = 1;
    for (const TimeMarker& m : o.markers) {
      g << "set arrow " << tag << " from first " << m.time_s << ", graph 0 to first " << m.time_s
        << ", graph 1 nohead front lw 2 dt 2 lc rgb '#40c0ff'\n"
        << "set label " << tag << " " << gnuplotQuoted(m.label) << " at first " << m.time_s
        << ", graph 1.03 center noenhanced textcolor rgb '#0070c0'\n";
      ++tag;
    }
    g << "plot " << gnuplotQuoted(data) << " binary array=(" << im.columns << "," << im.rows
      << ") format='%float' dx=" << im.dx_s << " dy=" << im.dy << " origin=(" << im.x0_s << "," << im.y0
      << ") with image notitle\n";
    return g.str();
  });
}

}  // namespace diffray::cli
