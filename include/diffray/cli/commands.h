#pragma once
// Subcommands of the `diffray` program. Each add*Command registers its options on the CLI11 app and
// returns a runner invoked after parsing; runners return the process exit code. Errors in user input
// are thrown as core::InputError and printed by main() as one line.
#include <CLI/CLI.hpp>
#include <functional>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "diffray/core/atomic_file.h"
#include "diffray/core/error.h"
#include "diffray/core/number.h"
#include "diffray/room/room.h"
#include "diffray/spatial/hrtf.h"

namespace diffray::reference {
struct WavePlan;
}

namespace diffray::cli {

using Runner = std::function<int()>;

/// Options every command shares.
struct CommonOptions {
  std::uint64_t seed = 1;
  int threads = 0;
  bool json = false;
};

/// The names among `names` nearest to `word` by edit distance (Levenshtein), at most 2 edits away (or those
/// `word` is a prefix of), best first; empty when none is near.
std::vector<std::string> nearestNames(const std::string& word, const std::vector<std::string>& names);

/// Before parsing: a first argument that is neither an option nor one of `app`'s subcommands is refused
/// (core::InputError) naming the nearest commands; CLI11 would say only that a subcommand is required.
void checkSubcommandName(const CLI::App& app, int argc, const char* const* argv);

/// After parsing: --threads above the cores TBB may use is lowered to them, with a note on stderr.
void clampThreads(CommonOptions& common);

/// The largest photon or ray count a command accepts.
inline constexpr double kMaxCount = 1e13;
/// A count given as a double (2e6 accepted): a whole number in [1, kMaxCount], else core::InputError naming `option`.
std::uint64_t wholeCount(const std::string& option, double v);
/// The transform every --seed option carries (->transform, not ->check: it rewrites the text): digits only
/// (a negative seed would wrap around in a std::uint64_t), at most 2^64 - 1 (CLI11 would clamp a larger one),
/// leading zeros dropped (CLI11 would read "010" as octal).
const CLI::Validator& seedValidator();
/// The transform every integer option carries (->transform): a whole number, also written as 1e3 or 8.0 like
/// --rays, within [lo, hi] (by default the int range); "2.5", "0x10" and "nan" are refused with one line naming
/// the option, where CLI11 alone would say "Could not convert" (or, under CLI::Range, "not in range") and would
/// read "010" as octal.
CLI::Validator wholeNumberValidator(int lo = std::numeric_limits<int>::min(), int hi = std::numeric_limits<int>::max());
/// Whether `text` is a decimal number (core/number.h: not hex, which strtod and CLI11 read as 16 for 0x10,
/// not "nan" or "inf"): the syntax of every number diffray reads.
using core::isDecimalNumber;
/// Adds a decimal-number check to every floating-point option of every subcommand of `app` (CLI11 would
/// read --gain 0x10 as 16 dB, as C's strtod does). Call once all subcommands are added.
void requireDecimalFloats(CLI::App& app);
/// The check every count option carries (--rays, --photons, --spp): a decimal number, so that 0x10 is refused
/// rather than read as 16 (the count's range is checked where it is read, wholeCount).
const CLI::Validator& decimalCountValidator();
/// The check every input-file option carries (a scene, a WAV, a profile): a name given must not be empty
/// (`metrics ""` would otherwise fail with the reader's own, less clear message).
const CLI::Validator& inputPathValidator();
/// The check every output-file option carries (-o, --csv, --plot, --spectrogram): a name given must not be empty
/// (`--csv ""` would otherwise mean "no CSV", or the default name).
const CLI::Validator& outputPathValidator();

/// The largest output gain in dB, either way, a command accepts (door and auralize --gain): ±120 dB spans
/// float32's useful range many times over; beyond it an output is all zeros or all overflow.
inline constexpr double kMaxGainDb = 120.0;
/// The check every --gain option carries, at parse time (before any work): a finite number of dB within
/// ±kMaxGainDb.
const CLI::Validator& gainDbValidator();

/// Adds --rays N to `sub`: a whole number >= 1, also written as 2e6, stored in `target`.
void addRaysOption(CLI::App* sub, std::uint64_t& target, const std::string& help);

/// Adds --threads N to `sub` (worker threads, 0 = all cores; a whole number, read as decimal).
void addThreadsOption(CLI::App* sub, int& threads);

/// Adds --diffraction none|wbsdf|utd and --diffraction-order N (1–8) to `sub`.
void addDiffractionOptions(CLI::App* sub, std::string& diffraction, int& order);
/// `--wbsdf-continuation portal|wigner`: how a ray goes on past an opening (RoomSimulationOptions::portal).
void addContinuationOption(CLI::App* sub, bool& portal);
/// `--hrtf FILE.sofa`: the SOFA set of a binaural output (`what`: the option that asks for one), an existing
/// file; empty selects Debian's MIT KEMAR set (spatial::Hrtf::defaultPath).
void addHrtfOption(CLI::App* sub, std::string& path, const std::string& what);
/// "PATH (N directions)" or "PATH (N directions, resampled from A to B Hz)": the HRTF set a run uses, for
/// its one info line.
std::string describeHrtf(const spatial::Hrtf& hrtf);

/// Checks an output path before any work: its extension is `ext` (".wav"; not checked when empty) and its folder
/// exists and is writable, and the path is not a folder. Throws core::InputError naming the path.
void checkOutputFile(const std::string& path, const std::string& ext);
/// checkOutputFile(path, "") for every non-empty path (extensions are the caller's), none of them is one
/// of the (non-empty) `inputs`, and no two are the same file: all of a command's outputs checked before any
/// work.
void checkOutputFiles(const std::vector<std::string>& paths, const std::vector<std::string>& inputs = {});

/// A command's set of output files, replaced together on commit() (core/atomic_file.h).
using core::OutputFiles;

/// The message of `e` without its leading "where: ", to rethrow it naming what the user gave (a file, an option)
/// instead of an internal name (a temporary file, "resample").
std::string reasonOf(const core::InputError& e);

/// Prints one note on stderr for each of `paths` larger than 10 MB, with its size ("out.csv is 151 MB"): a
/// table written cell by cell can be far larger than a user expects.
void announceLarge(const std::vector<std::string>& paths);
/// outputs.commit(), then announceLarge of what it put in place.
void commitAndAnnounce(OutputFiles& outputs);

/// Prints "diffray: warning: W" on stderr (one line) unless `warning` is empty.
void warnOf(const std::string& warning);
/// Peak level in dBFS of a linear `peak` (full scale 1), -inf for silence.
double dbfs(double peak);
/// A float WAV keeps samples above full scale, but players and fixed-point conversions clip them: when `peak`
/// (linear) exceeds 1, one warning naming `path`, the peak in dBFS and `remedy` (what lowers it).
void warnIfClips(const std::string& path, double peak, const std::string& remedy);

/// `path` with its extension replaced by `ext` (".json").
/// Whether `path` names the same file as one of `files` (files that do not exist match nothing).
bool isAnyOf(const std::string& path, const std::vector<std::string>& files);
std::string withExtension(const std::string& path, const std::string& ext);

Runner addValidateCommand(CLI::App& app, CommonOptions& common);
Runner addWdfCommand(CLI::App& app, CommonOptions& common);
Runner addMetricsCommand(CLI::App& app, CommonOptions& common);
Runner addIrCommand(CLI::App& app, CommonOptions& common);
Runner addCompareCommand(CLI::App& app, CommonOptions& common);
Runner addAuralizeCommand(CLI::App& app, CommonOptions& common);
Runner addDoorCommand(CLI::App& app, CommonOptions& common);
Runner addSpectrogramCommand(CLI::App& app, CommonOptions& common);
Runner addSignalCommand(CLI::App& app, CommonOptions& common);
Runner addRenderCommand(CLI::App& app, CommonOptions& common);
Runner addWaveCommand(CLI::App& app, CommonOptions& common);

/// JSON text for stdout and sidecars. File names may hold any bytes: a string that is not UTF-8 gets U+FFFD
/// where it breaks, instead of an exception after the work is done.
/// A template, so that an ordered_json keeps its key order (band keys 63, 125, …, not sorted as text).
template <class Json>
std::string jsonText(const Json& j, int indent = -1) {
  return j.dump(indent, ' ', false, Json::error_handler_t::replace);
}

/// `diffray wave`'s statement of a run's plan on stderr (grid, memory, steps per band), before any work.
void printWavePlan(const room::Room& room, const reference::WavePlan& plan);

}  // namespace diffray::cli
