// `diffray compare` in room mode: the table, CSV, JSON lines and plot of compare::RoomComparison.
#include "diffray/cli/compare_room.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "diffray/cli/commands.h"
#include "diffray/cli/plot.h"
#include "diffray/core/atomic_file.h"

namespace diffray::cli {

namespace {

using compare::FigureDifference;
using compare::RoomFigures;

// The figures of a row in table, CSV and JSON order, with their names and units.
constexpr int kFigures = 6;
const char* const kFigureKeys[kFigures] = {"g_db", "early_db", "edt_s", "t30_s", "c50_db", "c80_db"};
const char* const kDiffKeys[kFigures] = {"g_db", "early_db", "edt_pct", "t30_pct", "c50_db", "c80_db"};

std::array<double, kFigures> values(const RoomFigures& f) {
  return {f.g_db, f.early_db, f.edt_s, f.t30_s, f.c50_db, f.c80_db};
}
std::array<double, kFigures> values(const FigureDifference& d) {
  return {d.g_db, d.early_db, d.edt_pct, d.t30_pct, d.c50_db, d.c80_db};
}

bool hasWave(const compare::RoomComparison& c) {
  for (const auto& m : c.models)
    if (!m.vs_wave.empty()) return true;
  return false;
}

// A table cell: the number, or "-" when it is missing.
std::string fixed(double v, int width, int decimals) {
  char buf[32];
  if (std::isfinite(v))
    std::snprintf(buf, sizeof buf, "%*.*f", width, decimals, v);
  else
    std::snprintf(buf, sizeof buf, "%*s", width, "-");
  return buf;
}

// A CSV cell: the number, or empty when it is missing.
std::string cell(double v) {
  if (!std::isfinite(v)) return "";
  std::ostringstream s;
  s << v;
  return s.str();
}

nlohmann::ordered_json number(double v) { return std::isfinite(v) ? nlohmann::ordered_json(v) : nlohmann::ordered_json(); }

// What the free-field reference says about listener l: its angle where it applies, else why not.
std::string referenceLine(const compare::RoomComparison& c, std::size_t l) {
  if (c.free_field.empty()) return "";
  const compare::FreeFieldReference& f = c.free_field[l];
  if (!f.applies) return "free-field aperture reference: not shown, " + f.why_not;
  if (f.g_db.empty()) return "free-field aperture reference: none, " + c.free_field_note;
  char buf[96] = "";
  if (f.shadow_angle_deg) std::snprintf(buf, sizeof buf, "; %+.1f deg past the door's shadow boundary", *f.shadow_angle_deg);
  return std::string("free-field aperture reference: shown (row ") + kApertureModel + ")" + buf;
}

}  // namespace

void printRoomComparison(const room::Room& room, const compare::RoomComparison& c) {
  const bool wave = hasWave(c);
  std::printf("%s: room mode: G and early (the 20 ms from the direct sound) in dB re the free field of the same "
              "source at 10 m; EDT, T30 in s; C50, C80 in dB\n",
              room.name.c_str());
  if (!c.free_field.empty()) std::printf("free-field reference: %s\n", c.free_field_note.c_str());
  bool any_reference = false;
  for (std::size_t l = 0; l < room.listeners.size(); ++l) {
    const room::Listener& li = room.listeners[l];
    std::printf("\nlistener %s at (%.2f, %.2f, %.2f) m, direct sound at %.1f ms", li.name.c_str(), li.position_m.x(),
                li.position_m.y(), li.position_m.z(), 1e3 * c.direct_s[l]);
    const std::string ref = referenceLine(c, l);
    if (!ref.empty()) std::printf("\n  %s", ref.c_str());
    std::printf("\n%6s %-20s %8s %8s %7s %7s %7s %7s", "band", "model", "G dB", "early dB", "EDT s", "T30 s", "C50 dB", "C80 dB");
    if (wave) std::printf("   vs wave: %7s %7s %7s %7s %7s %7s", "G dB", "early", "EDT %", "T30 %", "C50 dB", "C80 dB");
    std::printf("\n");
    for (int b = 0; b < room.bands.size(); ++b) {
      bool first = true;
      for (const auto& m : c.models) {
        const auto v = values(m.figures[l][static_cast<std::size_t>(b)]);
        std::printf("%6s %-20s %s %s %s %s %s %s", first ? room.bands.label(b).c_str() : "", m.model.c_str(),
                    fixed(v[0], 8, 2).c_str(), fixed(v[1], 8, 2).c_str(), fixed(v[2], 7, 3).c_str(),
                    fixed(v[3], 7, 3).c_str(), fixed(v[4], 7, 2).c_str(), fixed(v[5], 7, 2).c_str());
        if (!m.vs_wave.empty()) {
          const auto d = values(m.vs_wave[l][static_cast<std::size_t>(b)]);
          std::printf("            %s %s %s %s %s %s", fixed(d[0], 7, 2).c_str(), fixed(d[1], 7, 2).c_str(),
                      fixed(d[2], 7, 1).c_str(), fixed(d[3], 7, 1).c_str(), fixed(d[4], 7, 2).c_str(),
                      fixed(d[5], 7, 2).c_str());
        }
        std::printf("\n");
        first = false;
      }
      if (!c.free_field.empty() && !c.free_field[l].g_db.empty()) {
        std::printf("%6s %-20s %8s %s\n", "", kApertureModel, "-",
                    fixed(c.free_field[l].g_db[static_cast<std::size_t>(b)], 8, 2).c_str());
        any_reference = true;
      }
    }
  }
  if (any_reference)
    std::printf("\n%s: the direct sound through the door in an infinite screen, no room (its level on the G scale, "
                "in the early column): read it beside the models' early energy, not as an error.\n",
                kApertureModel);
  std::string line;
  for (const auto& m : c.models) {
    char buf[96];
    if (m.rays)
      std::snprintf(buf, sizeof buf, "%s%s %llu rays %.2f s", line.empty() ? "" : ", ", m.model.c_str(),
                    static_cast<unsigned long long>(m.rays), m.seconds);
    else
      std::snprintf(buf, sizeof buf, "%s%s %.2f s", line.empty() ? "" : ", ", m.model.c_str(), m.seconds);
    line += buf;
  }
  if (!c.free_field.empty()) {
    char buf[64];
    std::snprintf(buf, sizeof buf, ", %s %.2f s", kApertureModel, c.free_field_seconds);
    line += buf;
  }
  std::printf("\n%s\n", line.c_str());
}

std::string roomComparisonJsonLines(const room::Room& room, const compare::RoomComparison& c) {
  std::string out;
  for (std::size_t l = 0; l < room.listeners.size(); ++l) {
    const std::string& name = room.listeners[l].name;
    for (const auto& m : c.models)
      for (int b = 0; b < room.bands.size(); ++b) {
        const auto bi = static_cast<std::size_t>(b);
        nlohmann::ordered_json j{{"listener", name}, {"model", m.model}, {"band_hz", room.bands.label(b)}};
        const auto v = values(m.figures[l][bi]);
        for (int k = 0; k < kFigures; ++k) j[kFigureKeys[k]] = number(v[static_cast<std::size_t>(k)]);
        if (!m.vs_wave.empty()) {
          nlohmann::ordered_json d;
          const auto dv = values(m.vs_wave[l][bi]);
          for (int k = 0; k < kFigures; ++k) d[kDiffKeys[k]] = number(dv[static_cast<std::size_t>(k)]);
          j["vs_wave"] = d;
        }
        out += jsonText(j) + '\n';
      }
    if (c.free_field.empty()) continue;
    const compare::FreeFieldReference& f = c.free_field[l];
    if (f.g_db.empty()) {
      nlohmann::ordered_json j{{"listener", name}, {"model", kApertureModel}, {"applies", false},
                               {"why_not", f.applies ? c.free_field_note : f.why_not}};
      out += jsonText(j) + '\n';
      continue;
    }
    for (int b = 0; b < room.bands.size(); ++b) {
      nlohmann::ordered_json j{{"listener", name}, {"model", kApertureModel}, {"applies", true},
                               {"band_hz", room.bands.label(b)}, {"early_db", number(f.g_db[static_cast<std::size_t>(b)])}};
      if (f.shadow_angle_deg) j["angle_past_shadow_boundary_deg"] = *f.shadow_angle_deg;
      out += jsonText(j) + '\n';
    }
  }
  return out;
}

void writeRoomCompareCsv(const std::string& path, const room::Room& room, const compare::RoomComparison& c) {
  core::writeFileAtomically(path, [&](std::ostream& out) {
    out << "listener,model,band_hz";
    for (const char* k : kFigureKeys) out << ',' << k;
    for (const char* k : kDiffKeys) out << ",vs_wave_" << k;
    out << ",angle_past_shadow_boundary_deg\n";
    for (std::size_t l = 0; l < room.listeners.size(); ++l) {
      const std::string& name = room.listeners[l].name;
      for (const auto& m : c.models)
        for (int b = 0; b < room.bands.size(); ++b) {
          const auto bi = static_cast<std::size_t>(b);
          out << name << ',' << m.model << ',' << room.bands.label(b);
          for (double v : values(m.figures[l][bi])) out << ',' << cell(v);
          if (m.vs_wave.empty())
            out << std::string(kFigures, ',');
          else
            for (double v : values(m.vs_wave[l][bi])) out << ',' << cell(v);
          out << ",\n";
        }
      if (c.free_field.empty() || c.free_field[l].g_db.empty()) continue;
      const compare::FreeFieldReference& f = c.free_field[l];
      for (int b = 0; b < room.bands.size(); ++b)
        out << name << ',' << kApertureModel << ',' << room.bands.label(b) << ",," << cell(f.g_db[static_cast<std::size_t>(b)])
            << std::string(kFigures - 2 + kFigures, ',') << ',' << (f.shadow_angle_deg ? cell(*f.shadow_angle_deg) : "")
            << '\n';
    }
  });
}

void writeRoomComparePlot(const std::string& png_path, const room::Room& room, const compare::RoomComparison& c) {
  namespace fs = std::filesystem;
  runGnuplot("--plot", png_path, [&](const std::string& tmp_png, const std::string& dir_name) {
    const fs::path dir(dir_name);
    const int nl = static_cast<int>(room.listeners.size()), cols = std::min(3, nl), rows = (nl + cols - 1) / cols;
    static const char* kColours[] = {"#7f7f7f", "#1f77b4", "#d62728", "#000000", "#2ca02c", "#9467bd"};
    std::ostringstream s;
    s << "set terminal pngcairo size " << 520 * cols << "," << 380 * rows << " font 'sans,9'\n"
      << "set output " << gnuplotQuoted(tmp_png) << "\nset multiplot layout " << rows << "," << cols << "\n"
      << "set grid\nset key top right font 'sans,7' samplen 2\nset logscale x\nset xrange [" << 0.7 * room.bands.nominalHz(0)
      << ":" << 1.4 * room.bands.nominalHz(room.bands.size() - 1) << "]\nset xlabel 'octave band (Hz)'\n"
      << "set ylabel 'dB re free field at 10 m'\n";
    for (int l = 0; l < nl; ++l) {
      const auto li = static_cast<std::size_t>(l);
      std::string plots;
      const auto add = [&](const std::string& file, const std::string& style, const std::string& title) {
        plots += (plots.empty() ? "" : ", ") + gnuplotQuoted(file) + " u 1:2 " + style + " title " + gnuplotQuoted(title);
      };
      for (std::size_t m = 0; m < c.models.size(); ++m) {
        const fs::path path = dir / ("l" + std::to_string(l) + "_" + std::to_string(m) + ".dat");
        std::ofstream f(path);
        int n = 0;
        for (int b = 0; b < room.bands.size(); ++b) {
          const RoomFigures& r = c.models[m].figures[li][static_cast<std::size_t>(b)];
          if (std::isfinite(r.g_db)) ++n;
          f << room.bands.nominalHz(b) << ' ' << (std::isfinite(r.g_db) ? cell(r.g_db) : "NaN") << ' '
            << (std::isfinite(r.early_db) ? cell(r.early_db) : "NaN") << '\n';
        }
        if (!n) continue;
        const std::string colour = std::string("lc rgb '") + kColours[m % 6] + "'";
        add(path.string(), "w lp pt 7 ps 0.8 " + colour, "G " + c.models[m].model);
        plots += ", " + gnuplotQuoted(path.string()) + " u 1:3 w lp dt 2 pt 6 ps 0.6 " + colour + " title " +
                 gnuplotQuoted("early " + c.models[m].model);
      }
      if (!c.free_field.empty() && !c.free_field[li].g_db.empty()) {
        const fs::path path = dir / ("l" + std::to_string(l) + "_ref.dat");
        std::ofstream f(path);
        for (int b = 0; b < room.bands.size(); ++b)
          f << room.bands.nominalHz(b) << ' ' << cell(c.free_field[li].g_db[static_cast<std::size_t>(b)]) << '\n';
        add(path.string(), "w p pt 4 ps 1.2 lc rgb '#000000'", "aperture, free field (direct)");
      }
      s << "set title " << gnuplotQuoted(room.listeners[li].name) << "\n"
        << (plots.empty() ? "plot NaN notitle" : "plot " + plots) << "\n";
    }
    s << "unset multiplot\n";
    return s.str();
  });
}

}  // namespace diffray::cli
