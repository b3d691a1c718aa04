// `diffray ir --plot-directions FILE.png`: where each listener's sound comes from over time (cli/plot.h).
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "diffray/cli/plot.h"
#include "diffray/core/math.h"
#include "diffray/ir/metrics.h"

namespace diffray::cli {

namespace fs = std::filesystem;

void writeDirectionPlot(const std::string& png_path, const std::vector<std::string>& names,
                        const std::vector<ir::EnergyResponse>& responses, const std::vector<room::Listener>& frames,
                        double window_s, double span_s) {
  runGnuplot("--plot-directions", png_path, [&](const std::string& tmp_png, const std::string& dir_name) {
    const fs::path dir(dir_name);
    const int cols = responses.size() > 1 ? 2 : 1;
    const int rows = static_cast<int>((responses.size() + cols - 1) / cols);
    std::ostringstream script;
    script << "set terminal pngcairo size " << 640 * cols << "," << 420 * rows << " font 'sans,9'\n"
           << "set output " << gnuplotQuoted(tmp_png) << "\n"
           << "set grid\nset xrange [0:" << 1000.0 * span_s << "]\nset yrange [-180:180]\nset ytics 45\n"
           << "set cbrange [-40:0]\nset cblabel 'level re the loudest window, dB'\n"
           << "set palette defined (0 '#f7fbff', 0.4 '#6baed6', 0.8 '#08306b', 1 '#000000')\n"
           << "set xlabel 'time after the onset (ms)'\nset ylabel 'azimuth, left of forward (deg)'\n"
           << "set multiplot layout " << rows << "," << cols << " title "
           << gnuplotQuoted("where the sound comes from, 500 Hz - 2 kHz octaves: one point per " +
                            std::to_string(static_cast<int>(std::lround(1000.0 * window_s))) +
                            " ms window (its energy vector; larger: more from one direction)")
           << " font 'sans,9'\n";
    for (std::size_t l = 0; l < responses.size(); ++l) {
      const ir::EnergyResponse& r = responses[l];
      const room::Listener& li = frames[l];
      // The energy vector of each window: arrivals (exact directions) and the traced part, over the bands.
      std::vector<double> all(static_cast<std::size_t>(r.bins()), 0.0);
      std::vector<int> bands;
      for (int b = 0; b < r.bands.size(); ++b)
        if (r.bands.nominalHz(b) >= 500.0 && r.bands.nominalHz(b) <= 2000.0) bands.push_back(b);
      for (int b : bands) {
        const std::vector<double> t = r.total(b);
        for (std::size_t i = 0; i < all.size(); ++i) all[i] += t[i];
      }
      const long onset = ir::onsetBin(all);
      const fs::path data = dir / ("directions" + std::to_string(l) + ".dat");
      std::ofstream out(data);
      if (onset >= 0) {
        const double t0 = static_cast<double>(onset) * r.bin_s;
        const int windows = static_cast<int>(std::ceil(span_s / window_s));
        std::vector<double> energy(static_cast<std::size_t>(windows), 0.0);
        std::vector<core::Vec3> vec(static_cast<std::size_t>(windows), core::Vec3(0, 0, 0));
        const auto slot = [&](double t) { return static_cast<long>(std::floor((t - t0) / window_s)); };
        for (int b : bands) {
          for (std::size_t i = 0; i < r.traced[static_cast<std::size_t>(b)].size(); ++i) {
            const long w = slot(static_cast<double>(i) * r.bin_s);
            if (w < 0 || w >= windows) continue;
            energy[static_cast<std::size_t>(w)] += r.traced[static_cast<std::size_t>(b)][i];
            if (static_cast<std::size_t>(b) < r.directions.size()) vec[static_cast<std::size_t>(w)] += r.directions[static_cast<std::size_t>(b)][i];
          }
          for (const ir::Arrival& a : r.arrivals) {
            const long w = slot(a.delay_s);
            if (w < 0 || w >= windows) continue;
            energy[static_cast<std::size_t>(w)] += a.energy[b];
            vec[static_cast<std::size_t>(w)] += a.energy[b] * a.direction;
          }
        }
        const double loudest = *std::max_element(energy.begin(), energy.end());
        for (int w = 0; w < windows; ++w) {
          const double e = energy[static_cast<std::size_t>(w)], n = vec[static_cast<std::size_t>(w)].norm();
          if (!(e > 0.0) || !(n > 0.0) || !(loudest > 0.0)) continue;
          const core::Vec3 u = li.toLocal(vec[static_cast<std::size_t>(w)] / n);
          out << 1000.0 * (w + 0.5) * window_s << ' ' << std::atan2(u.y(), u.x()) * 180.0 / core::kPi << ' '
              << std::max(-60.0, 10.0 * std::log10(e / loudest)) << ' ' << std::min(1.0, n / e) << '\n';
        }
      }
      script << "set title " << gnuplotQuoted("listener " + names[l]) << "\nplot " << gnuplotQuoted(data.string())
             << " using 1:2:(0.4 + 2.0 * $4):3 with points pt 7 ps variable lc palette notitle\n";
    }
    script << "unset multiplot\n";
    return script.str();
  });
}

}  // namespace diffray::cli
