#include <cmath>
#include <filesystem>

#include "diffray/cli/commands.h"
#include "diffray/core/error.h"

namespace diffray::cli {

std::uint64_t wholeCount(const std::string& option, double v) {
  if (!(v >= 1 && v <= 1e13 && std::floor(v) == v))
    throw core::InputError(option, "must be a whole number >= 1 (e.g. 2000000 or 2e6)");
  return static_cast<std::uint64_t>(v);
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
      ->type_name("N");
}

void addDiffractionOptions(CLI::App* sub, std::string& diffraction, int& order) {
  sub->add_option("--diffraction", diffraction,
                  "none: geometric acoustics (doorways pass rays straight); wbsdf: rays diffract at the room's "
                  "occluders (rooms/README.md); utd: edge-diffraction paths (Kouyoumjian-Pathak) of the mesh's edges "
                  "added to the geometric response")
      ->check(CLI::IsMember({"none", "wbsdf", "utd"}))
      ->capture_default_str();
  sub->add_option("--diffraction-order", order,
                  "wbsdf: occluder scatterings per ray path; later crossings pass straight (each one multiplies "
                  "the noise of the signed weights)")
      ->check(CLI::Range(1, 8))
      ->capture_default_str();
}

void checkOutputFile(const std::string& path, const std::string& ext) {
  namespace fs = std::filesystem;
  if (!ext.empty() && fs::path(path).extension() != ext)
    throw core::InputError(path, "the output must be a " + ext + " file");
  if (!fs::is_directory(fs::absolute(path).parent_path())) throw core::InputError(path, "its folder does not exist");
}

std::string withExtension(const std::string& path, const std::string& ext) {
  return std::filesystem::path(path).replace_extension(ext).string();
}

void checkSynthesis(const room::Room& room, double length_s, double sample_rate_hz, const std::string& rate_field) {
  const std::string where = room.file.empty() ? "room" : room.file;
  const double fs = sample_rate_hz;
  const int top = room.bands.size() - 1;
  if (!(room.bands.upperHz(top) < 0.5 * fs))
    throw core::InputError(rate_field, "the " + room.bands.label(top) + " Hz band reaches past the Nyquist frequency of " +
                                           std::to_string(static_cast<long>(fs)) + " Hz; raise the sample rate");
  if (!(room.volume() > 0.0))
    throw core::InputError(where, "the geometry encloses no volume, which the IR synthesis needs (V in the "
                                  "reflection density 4πc³t²/V)");
  // Longest possible IR: --length, the file's length, or (auto) max_length_s.
  const double longest = length_s > 0 ? length_s : (room.output.ir_length_s > 0 ? room.output.ir_length_s
                                                                                 : room.output.max_length_s);
  constexpr double kMaxFrames = 33554432.0;  // 2^25 frames: ~12 min at 48 kHz, a few GB while synthesizing
  if (longest * fs > kMaxFrames)
    throw core::InputError(where + ": output", "an IR of " + std::to_string(longest) + " s at " +
                                                   std::to_string(static_cast<long>(fs)) +
                                                   " Hz is over 2^25 samples; shorten max_length_s/ir_length_s");
}

}  // namespace diffray::cli
