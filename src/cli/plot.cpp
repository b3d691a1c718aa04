#include "diffray/cli/plot.h"

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <algorithm>
#include <sstream>

#include "diffray/core/error.h"
#include "diffray/core/temp_files.h"

namespace diffray::cli {

namespace {

namespace fs = std::filesystem;

// Rows worth drawing: all of a 1D screen; the centre row of a 2D one (the y closest to 0).
std::vector<const validate::Row*> plottedRows(const validate::CaseResult& r) {
  double y_min = INFINITY;
  for (const auto& row : r.rows) y_min = std::min(y_min, std::abs(row.y_m));
  std::vector<const validate::Row*> out;
  for (const auto& row : r.rows)
    if (std::abs(std::abs(row.y_m) - y_min) < 1e-15 && row.y_m <= 0) out.push_back(&row);
  return out;
}

// A gnuplot single-quoted string ('' for a quote). A control character would end gnuplot's command there
// (a newline) and let the rest run as commands of its own: each becomes a space.
std::string quoted(const std::string& s) {
  std::string q = "'";
  for (char c : s) {
    if (c == '\'') q += "''";
    else if (core::isControlCharacter(c)) q += ' ';
    else q += c;
  }
  return q + "'";
}

// Plot files are named in the gnuplot script: a name with a control character cannot be written as given.
void refuseControlCharacters(const std::string& option, const std::string& path) {
  for (char c : path)
    if (core::isControlCharacter(c))
      throw core::InputError(option, "the plot's file name contains a control character (a newline, a tab…): "
                                     "choose a plain name");
}

}  // namespace

void runGnuplot(const std::string& option, const std::string& png_path,
                const std::function<std::string(const std::string&, const std::string&)>& script_for) {
  refuseControlCharacters(option, png_path);
  if (std::system("command -v gnuplot >/dev/null 2>&1") != 0)
    throw core::InputError(option, "needs gnuplot (Debian: apt-get install gnuplot-nox)");
  // A fresh private folder (mkdtemp: mode 0700, never one that someone else made in a shared /tmp, where a
  // planted plot.gp would run as this user).
  std::string dir_template = (fs::temp_directory_path() / "diffray-plot-XXXXXX").string();
  if (::mkdtemp(dir_template.data()) == nullptr)
    throw core::InputError(option, "cannot create a temporary folder for gnuplot in " + fs::temp_directory_path().string());
  const fs::path dir(dir_template);
  const std::string tmp_png = png_path + ".tmp." + std::to_string(::getpid());
  const core::TempRegistration registered(tmp_png);  // deleted if the program is interrupted meanwhile
  const fs::path script_path = dir / "plot.gp";
  std::ofstream(script_path) << script_for(tmp_png, dir.string());
  const std::string cmd = "gnuplot " + quoted(script_path.string()) + " 2>" + quoted((dir / "err.txt").string());
  const int status = std::system(cmd.c_str());
  std::string err;
  {
    std::ifstream e(dir / "err.txt");
    std::getline(e, err);
  }
  fs::remove_all(dir);
  if (status != 0 || !fs::exists(tmp_png)) {
    std::remove(tmp_png.c_str());
    throw core::InputError(option, "gnuplot failed" + (err.empty() ? std::string() : ": " + err));
  }
  if (std::rename(tmp_png.c_str(), png_path.c_str()) != 0) {
    std::remove(tmp_png.c_str());
    throw core::InputError(png_path, "cannot write the plot");
  }
}

std::string gnuplotQuoted(const std::string& s) { return quoted(s); }

void checkPlotOption(const std::string& option, const std::string& path) {
  if (path.empty()) return;
  refuseControlCharacters(option, path);
  if (fs::path(path).extension() != ".png")
    throw core::InputError(option, path + ": the plot is a PNG image: give a file name ending in .png");
  if (std::system("command -v gnuplot >/dev/null 2>&1") != 0)
    throw core::InputError(option, "needs gnuplot (Debian: apt-get install gnuplot-nox)");
}

void writeValidationPlot(const std::string& png_path, const std::vector<validate::CaseResult>& results) {
  runGnuplot("--plot", png_path, [&](const std::string& tmp_png, const std::string& dir_name) {
  const fs::path dir(dir_name);
  std::ostringstream script;
  const int cols = results.size() > 1 ? 2 : 1;
  const int rows = static_cast<int>((results.size() + cols - 1) / cols);
  script << "set terminal pngcairo size " << 640 * cols << "," << 400 * rows << " font 'sans,9'\n"
         << "set output " << quoted(tmp_png) << "\n"
         << "set multiplot layout " << rows << "," << cols << "\n"
         << "set key top right font 'sans,8'\nset grid\n";
  for (std::size_t c = 0; c < results.size(); ++c) {
    const auto& r = results[c];
    // One data block per label (frequency), blocks separated by two blank lines for gnuplot's `index`.
    // Patterns in the order the case produced them (door-rs: the frequencies as given).
    std::vector<std::pair<std::string, std::vector<const validate::Row*>>> by_label;
    for (const auto* row : plottedRows(r)) {
      if (by_label.empty() || by_label.back().first != row->label) by_label.push_back({row->label, {}});
      by_label.back().second.push_back(row);
    }
    const fs::path data = dir / ("case" + std::to_string(c) + ".dat");
    std::ofstream out(data);
    for (const auto& [label, rows_of] : by_label) {
      for (const auto* row : rows_of) out << row->x_m << ' ' << row->traced << ' ' << row->reference << '\n';
      out << "\n\n";
    }
    out.close();
    std::ostringstream title;
    title << r.name << ": max |error| " << std::round(1000.0 * r.max_abs_error_rel_peak * 100.0) / 1000.0
          << " % of peak" << (r.passed ? "" : " (target missed)");
    const bool orders = r.name == "grating-orders";
    script << "set title " << quoted(title.str()) << "\n"
           << "set xlabel " << quoted(orders ? "sin(theta) of the order" : "screen position (m)") << "\n"
           << "set ylabel " << quoted(orders ? "energy fraction" : "intensity / incident") << "\n"
           << "plot ";
    int block = 0;
    for (const auto& [label, rows_of] : by_label) {
      const std::string name = label.empty() ? std::string() : label + " ";
      script << (block ? ", " : "") << quoted(data.string()) << " index " << block << " using 1:3 with "
             << (orders ? "impulses" : "lines") << " lw 2 title " << quoted(name + "reference") << ", "
             << quoted(data.string()) << " index " << block << " using 1:2 with points pt 7 ps 0.5 title "
             << quoted(name + "traced");
      ++block;
    }
    script << "\n";
  }
  script << "unset multiplot\n";
  return script.str();
  });
}

void writeDecayPlot(const std::string& png_path, const std::vector<std::string>& names,
                    const std::vector<ir::EnergyResponse>& responses,
                    const std::vector<std::vector<std::string>>& flags) {
  runGnuplot("--plot", png_path, [&](const std::string& tmp_png, const std::string& dir_name) {
    const fs::path dir(dir_name);
    const int cols = responses.size() > 1 ? 2 : 1;
    const int rows = static_cast<int>((responses.size() + cols - 1) / cols);
    std::ostringstream script;
    script << "set terminal pngcairo size " << 640 * cols << "," << 420 * rows << " font 'sans,9'\n"
           << "set output " << quoted(tmp_png) << "\n"
           << "set key top right font 'sans,8'\nset grid\nset yrange [-70:2]\n"
           << "set xlabel 'time after emission (s)'\nset ylabel 'energy decay (Schroeder), dB'\n";
    bool marked = false;
    std::ostringstream panels;
    for (std::size_t l = 0; l < responses.size(); ++l) {
      const auto& r = responses[l];
      const fs::path data = dir / ("listener" + std::to_string(l) + ".dat");
      std::ofstream out(data);
      std::vector<std::string> titles;
      std::vector<bool> rises;
      for (int b = 0; b < r.bands.size(); ++b) {
        // Backward integral of the band's whole histogram, in dB of its total, at each bin's start.
        const std::vector<double> e = r.total(b);
        std::vector<double> tail(e.size() + 1, 0.0);
        for (std::size_t k = e.size(); k-- > 0;) tail[k] = tail[k + 1] + e[k];
        // A true decay curve never rises; a signed (WBSDF) histogram's can: by more than 1 dB (visible
        // on the plot's scale), it is drawn dashed and labelled.
        double lowest = HUGE_VAL;
        bool up = false;
        std::size_t points = 0;
        for (std::size_t k = 0; k < e.size(); ++k) {
          if (!(tail[k] > 0.0 && tail[0] > 0.0)) break;
          const double level = 10.0 * std::log10(tail[k] / tail[0]);
          up = up || level > lowest + 1.0;
          lowest = std::min(lowest, level);
          out << static_cast<double>(k) * r.bin_s << ' ' << level << '\n';
          ++points;
        }
        out << "\n\n";
        const std::string flag = l < flags.size() && static_cast<std::size_t>(b) < flags[l].size() ? flags[l][b] : "ok";
        std::string title = r.bands.label(b) + " Hz";
        if (flag == "noisy") title += " NOISY (SE > JND)";
        if (flag == "negative_energy") title += tail[0] > 0.0 ? " NEGATIVE ENERGY" : " NEGATIVE ENERGY (not drawn)";
        if (up) title += ", rises: negative energy";
        marked = marked || up || flag != "ok";
        titles.push_back(title);
        rises.push_back(up && points > 0);
      }
      panels << "set title " << quoted("listener " + names[l]) << "\nplot ";
      for (int b = 0; b < r.bands.size(); ++b)
        panels << (b ? ", " : "") << quoted(data.string()) << " index " << b << " using 1:2 with lines lw 2 "
               << (rises[b] ? "dt 2 " : "") << "lc " << (b + 1) << " title " << quoted(titles[b]);
      panels << "\n";
    }
    script << "set multiplot layout " << rows << "," << cols;
    if (marked)  // the legend of the marks, as the figure's title
      script << " title "
             << quoted("dashed: the decay curve rises by more than 1 dB (negative energy); NOISY: a metric's standard "
                       "error exceeds its JND; NEGATIVE ENERGY: no metric; trace more rays")
             << " font 'sans,9'";
    script << "\n" << panels.str() << "unset multiplot\n";
    return script.str();
  });
}

}  // namespace diffray::cli

namespace diffray::cli {

void writeComparePlot(const std::string& png_path, const room::Room& room, const compare::SceneComparison& c) {
  runGnuplot("--plot", png_path, [&](const std::string& tmp_png, const std::string& dir_name) {
    const fs::path dir(dir_name);
    const int nl = static_cast<int>(room.listeners.size());
    bool angles = room.listeners.size() > 1;
    for (const auto& a : c.shadow_angle_deg) angles = angles && a.has_value();
    const int nb = room.bands.size();
    const int panels = nl + (angles ? nb : 0), cols = std::min(3, panels), rows = (panels + cols - 1) / cols;
    static const char* kModels[] = {"exact", "exact-incoherent-floor", "utd", "wbsdf"};
    static const char* kColours[] = {"#000000", "#777777", "#1f77b4", "#d62728"};
    std::ostringstream s;
    s << "set terminal pngcairo size " << 520 * cols << "," << 360 * rows << " font 'sans,9'\n"
      << "set output " << quoted(tmp_png) << "\nset multiplot layout " << rows << "," << cols << "\n"
      << "set grid\nset key bottom left font 'sans,8'\nset ylabel 'level re free field (dB)'\n";
    // Level against frequency, per listener: fine-grid lines and band points per model.
    for (int l = 0; l < nl; ++l) {
      std::string plots;
      for (int m = 0; m < 4; ++m) {
        const fs::path fine = dir / ("f" + std::to_string(l) + "_" + std::to_string(m) + ".dat");
        const fs::path band = dir / ("b" + std::to_string(l) + "_" + std::to_string(m) + ".dat");
        std::ofstream ff(fine), fb(band);
        int n_fine = 0, n_band = 0;
        for (const auto& r : c.rows) {
          if (r.listener != l || r.model != kModels[m] || !std::isfinite(r.level_db)) continue;
          (r.band ? fb : ff) << r.freq_hz << ' ' << r.level_db << ' ' << (std::isfinite(r.std_error_db) ? r.std_error_db : 0.0) << '\n';
          ++(r.band ? n_band : n_fine);
        }
        const std::string colour = std::string("lc rgb '") + kColours[m] + "'";
        if (n_fine) plots += (plots.empty() ? "" : ", ") + quoted(fine.string()) + " u 1:2 w l " + colour + " title '" + kModels[m] + "'";
        if (n_band)
          plots += (plots.empty() ? "" : ", ") + quoted(band.string()) + (m == 3 ? " u 1:2:3 w yerrorbars pt 7 ps 0.8 " : " u 1:2 w p pt 6 ps 1.2 ") +
                   colour + " title '" + kModels[m] + " (band)'";
      }
      std::ostringstream title;
      title << room.listeners[l].name;
      if (c.shadow_angle_deg[l]) title << ", " << std::lround(*c.shadow_angle_deg[l]) << " deg past the shadow boundary";
      s << "set logscale x\nset xrange [" << room.bands.lowerHz(0) << ":" << room.bands.upperHz(nb - 1)
        << "]\nset xlabel 'frequency (Hz)'\nset title " << quoted(title.str()) << "\n"
        << (plots.empty() ? "plot NaN notitle" : "plot " + plots) << "\nunset logscale x\nset autoscale x\n";
    }
    // Level against angle past the shadow boundary, per band: joined by lines, unless two listeners share
    // an angle (listeners round different edges, as in rooms/plate-zones.json), where points only.
    if (angles) {
      std::vector<double> seen;
      for (const auto& a : c.shadow_angle_deg)
        if (a) seen.push_back(*a);
      std::sort(seen.begin(), seen.end());
      bool join = true;
      for (std::size_t i = 1; i < seen.size(); ++i) join = join && seen[i] - seen[i - 1] > 0.5;
      for (int b = 0; b < nb; ++b) {
        std::string plots;
        for (int m = 0; m < 4; ++m) {
          const fs::path path = dir / ("a" + std::to_string(b) + "_" + std::to_string(m) + ".dat");
          std::ofstream f(path);
          std::vector<std::pair<double, const compare::LevelRow*>> pts;
          for (const auto& r : c.rows)
            if (r.band && r.model == kModels[m] && r.band_label == room.bands.label(b) && std::isfinite(r.level_db))
              pts.push_back({*c.shadow_angle_deg[r.listener], &r});
          std::sort(pts.begin(), pts.end(), [](const auto& a, const auto& z) { return a.first < z.first; });
          for (const auto& [a, r] : pts) f << a << ' ' << r->level_db << ' ' << (std::isfinite(r->std_error_db) ? r->std_error_db : 0.0) << '\n';
          if (pts.empty()) continue;
          const std::string colour = std::string("lc rgb '") + kColours[m] + "'";
          plots += (plots.empty() ? "" : ", ") + quoted(path.string()) +
                   (m == 3 ? (join ? " u 1:2:3 w yerrorlines pt 7 ps 0.6 " : " u 1:2:3 w yerrorbars pt 7 ps 0.8 ")
                           : (join ? " u 1:2 w lp pt 6 ps 0.6 " : " u 1:2 w p pt 6 ps 1.2 ")) +
                   colour + " title '" + kModels[m] + "'";
        }
        s << "set xlabel 'angle past the shadow boundary (deg)'\nset title " << quoted(room.bands.label(b) + " Hz band") << "\n"
          << (plots.empty() ? "plot NaN notitle" : "plot " + plots) << "\n";
      }
    }
    s << "unset multiplot\n";
    return s.str();
  });
}

}  // namespace diffray::cli
