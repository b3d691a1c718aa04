#include "diffray/audio/speech.h"

#include <fcntl.h>
#include <spawn.h>
#include <stdlib.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <filesystem>
#include <cctype>
#include <fstream>
#include <sstream>
#include <string>

#include "diffray/audio/wav.h"
#include "diffray/core/error.h"
#include "diffray/dsp/resample.h"

extern char** environ;

namespace diffray::audio {

namespace {

constexpr const char* kProgram = "espeak-ng";

/// A private temporary folder (mkdtemp), removed with its contents when it goes out of scope.
struct TempDir {
  std::string path;
  TempDir() {
    std::string pattern = (std::filesystem::temp_directory_path() / "diffray-speech-XXXXXX").string();
    if (::mkdtemp(pattern.data()) == nullptr)
      throw core::InputError("speech", "cannot create a temporary folder in " +
                                           std::filesystem::temp_directory_path().string());
    path = pattern;
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path, ec);
  }
};

/// Runs `argv` (argv[0] looked up on the PATH) with stdout to `stdout_path` (/dev/null when empty) and stderr
/// to /dev/null; returns its exit code, 127 when it could not be started, 128 + signal when killed.
int runQuietly(const std::vector<std::string>& args, const std::string& stdout_path = "") {
  std::vector<char*> argv;
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, stdout_path.empty() ? "/dev/null" : stdout_path.c_str(),
                                   O_WRONLY | O_CREAT | O_TRUNC, 0600);
  posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, "/dev/null", O_WRONLY, 0);
  pid_t pid = 0;
  const int spawned = posix_spawnp(&pid, argv[0], &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (spawned != 0) return 127;
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) return 127;
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  return WIFSIGNALED(status) ? 128 + WTERMSIG(status) : 127;
}

/// Whether espeak-ng knows `voice`: its part before any '+variant' is a language, voice name or voice file of
/// `espeak-ng --voices` (a table: Pty, Language, Age/Gender, VoiceName, File, then "(lang pty)" pairs).
/// espeak-ng itself falls back to its default voice for an unknown name and exits 0, so it cannot tell.
bool espeakKnowsVoice(const std::string& voice, const std::string& folder) {
  const std::string listing = folder + "/voices.txt";
  if (runQuietly({kProgram, "--voices"}, listing) != 0) return true;  // cannot list: leave it to espeak-ng
  const std::string name = voice.substr(0, voice.find('+'));
  const auto lower = [](std::string t) {
    for (char& c : t) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return t;
  };
  std::ifstream in(listing);
  std::string line;
  std::getline(in, line);  // the header
  while (std::getline(in, line)) {
    std::istringstream fields(line);
    std::string field;
    for (int k = 0; fields >> field; ++k) {
      if (k == 0 || k == 2) continue;  // priority, age/gender
      if (!field.empty() && field.front() == '(') field.erase(0, 1);
      if (lower(field) == lower(name)) return true;
    }
  }
  return false;
}

}  // namespace

bool espeakAvailable() { return runQuietly({kProgram, "--version"}) == 0; }

std::vector<float> synthesizeSpeech(const SpeechSpec& spec) {
  if (spec.text.find_first_not_of(" \t\r\n") == std::string::npos)
    throw core::InputError("--text", "is empty: nothing to say");
  if (spec.words_per_minute < 80 || spec.words_per_minute > 450)
    throw core::InputError("--speed", "must lie between 80 and 450 words per minute");
  if (!(spec.amplitude > 0.0 && spec.amplitude <= 1.0))
    throw core::InputError("--level", "the peak must lie in (0, 1] of full scale (at most 0 dBFS)");
  core::requirePositive("--rate", spec.rate_hz);
  if (!espeakAvailable())
    throw core::InputError("speech", "needs espeak-ng; as root: apt-get install espeak-ng");

  TempDir dir;
  if (!espeakKnowsVoice(spec.voice, dir.path))
    throw core::InputError("--voice", "espeak-ng has no voice '" + spec.voice + "' (`espeak-ng --voices` lists them)");
  const std::string text_path = dir.path + "/text.txt", wav_path = dir.path + "/speech.wav";
  {
    std::ofstream text(text_path);
    text << spec.text << "\n";
    if (!text.flush()) throw core::InputError("speech", "cannot write the text to " + text_path);
  }
  const int code = runQuietly({kProgram, "-v", spec.voice, "-s", std::to_string(spec.words_per_minute), "-w",
                               wav_path, "-f", text_path});
  if (code != 0)
    throw core::InputError("speech", "espeak-ng failed (exit code " + std::to_string(code) + "; is '" + spec.voice +
                                         "' a voice from `espeak-ng --voices`?)");
  const AudioBuffer raw = readAudio(wav_path);
  std::vector<float> mono(static_cast<size_t>(raw.frames()));
  for (long f = 0; f < raw.frames(); ++f)  // espeak-ng writes mono; average channels should that change
    for (int c = 0; c < raw.channels; ++c)
      mono[static_cast<size_t>(f)] += static_cast<float>(raw.samples[static_cast<size_t>(f * raw.channels + c)] / raw.channels);
  std::vector<float> out = dsp::resample(mono, 1, raw.sample_rate_hz, spec.rate_hz);
  float peak = 0.0f;
  for (float s : out) peak = std::max(peak, std::abs(s));
  if (peak == 0.0f) throw core::InputError("speech", "espeak-ng produced silence");
  const auto scale = static_cast<float>(spec.amplitude / peak);
  for (float& s : out) s *= scale;
  return out;
}

}  // namespace diffray::audio
