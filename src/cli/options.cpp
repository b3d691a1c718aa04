#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <limits>

#include "diffray/cli/commands.h"
#include "diffray/room/json_fields.h"
#include "diffray/core/error.h"
#include "diffray/core/parallel.h"

namespace diffray::cli {

std::uint64_t wholeCount(const std::string& option, double v) {
  if (!(v >= 1 && v <= kMaxCount && std::floor(v) == v))
    throw core::InputError(option, "must be a whole number >= 1 (e.g. 2000000 or 2e6)");
  return static_cast<std::uint64_t>(v);
}

void requireDecimalFloats(CLI::App& app) {
  static const CLI::Validator decimal(
      [](const std::string& text) -> std::string {
        return isDecimalNumber(text) ? std::string() : "must be a decimal number, got " + text;
      },
      "", "decimal");
  for (CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; }))
    for (CLI::Option* opt : sub->get_options())
      if (opt->get_type_name().rfind("FLOAT", 0) == 0) opt->check(decimal);  // double targets: "FLOAT..."
}

const CLI::Validator& decimalCountValidator() {
  static const CLI::Validator check(
      [](const std::string& text) -> std::string {
        return isDecimalNumber(text) ? std::string() : "must be a whole number >= 1 (e.g. 2000000 or 2e6), got " + text;
      },
      "N", "count");
  return check;
}

const CLI::Validator& inputPathValidator() {
  static const CLI::Validator check(
      [](const std::string& text) -> std::string {
        return text.empty() ? "an input file name must not be empty" : std::string();
      },
      "", "input path");
  return check;
}

const CLI::Validator& seedValidator() {
  // CLI11 would read "-3" into a std::uint64_t as 2^64 - 3, clamp 99999999999999999999999 to 2^64 - 1, and
  // read "010" as octal 8: a seed is refused unless all digits and at most 2^64 - 1, and it is handed on
  // without leading zeros (so it is read as decimal). Applied with ->transform(), which may rewrite the text.
  static const CLI::Validator check(
      [](std::string& text) -> std::string {
        if (text.empty() || text.find_first_not_of("0123456789") != std::string::npos)
          return "must be a whole number >= 0, got " + text;
        const std::size_t first = std::min(text.find_first_not_of('0'), text.size() - 1);
        const std::string digits = text.substr(first);
        const std::string max = std::to_string(std::numeric_limits<std::uint64_t>::max());
        if (digits.size() > max.size() || (digits.size() == max.size() && digits > max))
          return "must be at most " + max + " (2^64 - 1), got " + text;
        text = digits;
        return {};
      },
      "SEED", "seed");
  return check;
}

CLI::Validator wholeNumberValidator(int lo, int hi) {
  const bool ranged = lo != std::numeric_limits<int>::min() || hi != std::numeric_limits<int>::max();
  return CLI::Validator(
      [lo, hi](std::string& text) -> std::string {
        // Decimal only: C's strtol, which CLI11 uses for integers, reads "010" as 8 and "0x10" as 16.
        double v = 0.0;
        if (!isDecimalNumber(text) || !CLI::detail::lexical_cast(text, v) || (std::isfinite(v) && std::floor(v) != v) ||
            (v == 0.0 && text.substr(0, text.find_first_of("eE")).find_first_of("123456789") != std::string::npos))
          return "must be a whole number (e.g. 8 or 1e3), got " + text;  // the last test: 1e-400 underflows to 0
        if (!(v >= lo && v <= hi))  // 1e400 (infinite as a double) too
          return "must be a whole number from " + std::to_string(lo) + " to " + std::to_string(hi) + ", got " + text;
        text = std::to_string(static_cast<int>(v));  // plain digits for CLI11's integer conversion
        return {};
      },
      ranged ? "INT in [" + std::to_string(lo) + " - " + std::to_string(hi) + "]" : std::string(), "whole");
}

const CLI::Validator& outputPathValidator() {
  static const CLI::Validator check(
      [](const std::string& text) -> std::string {
        return text.empty() ? "an output file name must not be empty" : std::string();
      },
      "", "output path");
  return check;
}

const CLI::Validator& gainDbValidator() {
  static const CLI::Validator check(
      [](const std::string& text) -> std::string {
        double gain_db = 0.0;
        if (!CLI::detail::lexical_cast(text, gain_db) || !std::isfinite(gain_db) || std::abs(gain_db) > kMaxGainDb)
          return "must be a number of dB between -" + std::to_string(static_cast<int>(kMaxGainDb)) + " and " +
                 std::to_string(static_cast<int>(kMaxGainDb)) + ", got " + text;
        return {};
      },
      "DB", "gain");
  return check;
}

void addThreadsOption(CLI::App* sub, int& threads) {
  sub->add_option("--threads", threads, "worker threads (0 = all cores)")
      ->transform(wholeNumberValidator())
      ->capture_default_str();
}

void addRaysOption(CLI::App* sub, std::uint64_t& target, const std::string& help) {
  sub->add_option_function<double>(
         "--rays",
         [&target](double v) {
           try {
             target = wholeCount("--rays", v);
           } catch (const core::InputError&) {
             throw CLI::ValidationError("--rays", "must be a whole number >= 1 (e.g. 2000000 or 2e6)");
           }
         },
         help)
      ->check(decimalCountValidator())
      ->type_name("N");
}

void addDiffractionOptions(CLI::App* sub, std::string& diffraction, int& order) {
  sub->add_option("--diffraction", diffraction,
                  "none: geometric acoustics (doorways pass rays straight); wbsdf: rays diffract at the room's "
                  "occluders (rooms/README.md); utd: edge-diffraction paths (Kouyoumjian-Pathak) of the mesh's edges, "
                  "with first-order reflections before and after them, added to the geometric response")
      ->check(CLI::IsMember({"none", "wbsdf", "utd"}))
      ->capture_default_str();
  sub->add_option("--diffraction-order", order,
                  "wbsdf: occluder scatterings per ray path; later crossings pass straight (each one multiplies "
                  "the noise of the signed weights)")
      ->transform(wholeNumberValidator(1, 8))
      ->capture_default_str();
}

void addContinuationOption(CLI::App* sub, bool& portal) {
  sub->add_option_function<std::string>(
         "--wbsdf-continuation", [&portal](const std::string& v) { portal = v == "portal"; },
         "wbsdf: how a ray goes on past a door, slit or edge once next-event estimation has scored its first "
         "flight. portal: in every band along one direction, across an opening drawn from the whole opening's "
         "far-field pattern (a positive weight; across an edge from its kernel, signed); wigner: in one band, "
         "from the Wigner distribution at the hit point, a signed weight (noisier in reverberant rooms)")
      ->check(CLI::IsMember({"portal", "wigner"}))
      ->default_str(portal ? "portal" : "wigner");
}

void checkOutputFile(const std::string& path, const std::string& ext) {
  namespace fs = std::filesystem;
  if (!ext.empty() && fs::path(path).extension() != ext)
    throw core::InputError(path, "the output must be a " + ext + " file");
  const fs::path folder = fs::absolute(path).parent_path();
  if (!fs::is_directory(folder)) throw core::InputError(path, "its folder does not exist");
  if (fs::is_directory(path)) throw core::InputError(path, "is a folder, not a file");
  // The file is written as a temporary beside it, then renamed (core/atomic_file.h): the folder must be writable.
  if (::access(folder.c_str(), W_OK | X_OK) != 0) throw core::InputError(path, "its folder is not writable");
}

void checkOutputFiles(const std::vector<std::string>& paths, const std::vector<std::string>& inputs) {
  std::error_code ec;
  std::vector<std::filesystem::path> seen;  // outputs so far, as absolute paths without "." or ".."
  for (const std::string& path : paths) {
    if (path.empty()) continue;
    checkOutputFile(path, "");
    for (const std::string& input : inputs)
      if (isAnyOf(path, {input})) throw core::InputError(path, "would overwrite the input " + input);
    // Two outputs in one file (validate or compare with --csv out.png --plot out.png): one would silently
    // replace the other. The files need not exist yet (weakly_canonical).
    const std::filesystem::path p = std::filesystem::weakly_canonical(std::filesystem::absolute(path), ec);
    if (!ec && std::find(seen.begin(), seen.end(), p) != seen.end())
      throw core::InputError(path, "is given for two of this command's outputs, which would overwrite each other");
    if (!ec) seen.push_back(p);
  }
}

std::string reasonOf(const core::InputError& e) {
  const std::string what = e.what();
  return e.where().empty() ? what : what.substr(e.where().size() + 2);
}

void announceLarge(const std::vector<std::string>& paths) {
  for (const std::string& p : paths) {
    std::error_code ec;
    const std::uintmax_t bytes = std::filesystem::file_size(p, ec);
    if (ec || bytes <= 10'000'000) continue;
    std::cerr << "diffray: note: " << core::oneLine(p) << " is " << (bytes + 500'000) / 1'000'000 << " MB\n";
  }
}

void commitAndAnnounce(OutputFiles& outputs) {
  outputs.commit();
  announceLarge(outputs.committed());
}

void warnOf(const std::string& warning) {
  if (!warning.empty()) std::cerr << "diffray: warning: " << core::oneLine(warning) << "\n";
}

double dbfs(double peak) { return peak > 0.0 ? 20.0 * std::log10(peak) : -std::numeric_limits<double>::infinity(); }

void warnIfClips(const std::string& path, double peak, const std::string& remedy) {
  if (!(peak > 1.0)) return;
  std::ostringstream line;
  line << core::oneLine(path) << " peaks at " << std::showpos << std::fixed << std::setprecision(1) << dbfs(peak)
       << " dBFS, above full scale: it will clip when played or converted to fixed point (" << remedy << ")";
  warnOf(line.str());
}

bool isAnyOf(const std::string& path, const std::vector<std::string>& files) {
  std::error_code ec;
  for (const std::string& f : files)
    if (!f.empty() && std::filesystem::equivalent(path, f, ec)) return true;
  return false;
}

std::string withExtension(const std::string& path, const std::string& ext) {
  return std::filesystem::path(path).replace_extension(ext).string();
}

std::vector<std::string> nearestNames(const std::string& word, const std::vector<std::string>& names) {
  std::vector<std::pair<std::size_t, std::string>> near;
  for (const std::string& n : names) {
    const std::size_t d = n.rfind(word, 0) == 0 ? 0 : core::editDistance(word, n);
    if (d <= 2) near.emplace_back(d, n);
  }
  std::sort(near.begin(), near.end());
  std::vector<std::string> out;
  for (const auto& entry : near) out.push_back(entry.second);
  return out;
}

void checkSubcommandName(const CLI::App& app, int argc, const char* const* argv) {
  if (argc < 2 || argv[1][0] == '-') return;
  const std::string word = argv[1];
  std::vector<std::string> names;
  for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; })) {
    if (sub->get_name() == word) return;
    names.push_back(sub->get_name());
  }
  const std::vector<std::string> near = nearestNames(word, names);
  std::string hint;
  for (std::size_t i = 0; i < near.size(); ++i) hint += (i ? " or " : "") + near[i];
  throw core::InputError("diffray " + core::oneLine(word),
                         "no such command" + (hint.empty() ? std::string() : "; did you mean " + hint + "?"));
}

void clampThreads(CommonOptions& common) {
  const int cores = core::ThreadLimit::current();
  if (cores > 0 && common.threads > cores) {
    std::cerr << "diffray: note: --threads " << common.threads << " is more than the " << cores
              << " cores here: using " << cores << "\n";
    common.threads = cores;
  }
}

void addHrtfOption(CLI::App* sub, std::string& path, const std::string& what) {
  sub->add_option("--hrtf", path,
                  "SOFA HRTF set of " + what + " (default: Debian's MIT KEMAR set, " +
                      std::string(spatial::Hrtf::defaultPath()) + ")")
      ->check(inputPathValidator());
}

std::string describeHrtf(const spatial::Hrtf& hrtf) {
  std::string out = hrtf.path() + " (" + std::to_string(hrtf.directions()) + " directions";
  if (hrtf.fileRateHz() != hrtf.sampleRateHz())
    out += ", resampled from " + room::formatNumber(hrtf.fileRateHz()) + " to " + room::formatNumber(hrtf.sampleRateHz()) +
           " Hz";
  return out + ")";
}

}  // namespace diffray::cli
