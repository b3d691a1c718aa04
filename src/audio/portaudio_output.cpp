#include "diffray/audio/portaudio_output.h"

#include <fcntl.h>
#include <portaudio.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <thread>

#include "diffray/core/error.h"

namespace diffray::audio {

namespace {

const char* const kNoDevice = "no audio output device (PortAudio found none); write a file with -o instead";

/// Sends fd 2 to /dev/null for its lifetime (PortAudio's host APIs print while probing), unless
/// DIFFRAY_AUDIO_VERBOSE=1.
class QuietStderr {
 public:
  QuietStderr() {
    const char* verbose = std::getenv("DIFFRAY_AUDIO_VERBOSE");
    if (verbose != nullptr && std::strcmp(verbose, "1") == 0) return;
    std::fflush(stderr);
    saved_ = ::dup(2);
    const int null_fd = ::open("/dev/null", O_WRONLY);
    if (saved_ < 0 || null_fd < 0 || ::dup2(null_fd, 2) < 0) {
      if (null_fd >= 0) ::close(null_fd);
      restore();
      return;
    }
    ::close(null_fd);
  }
  ~QuietStderr() { restore(); }
  QuietStderr(const QuietStderr&) = delete;
  QuietStderr& operator=(const QuietStderr&) = delete;

 private:
  void restore() {
    if (saved_ < 0) return;
    std::fflush(stderr);
    ::dup2(saved_, 2);
    ::close(saved_);
    saved_ = -1;
  }
  int saved_ = -1;
};

void check(PaError err, const std::string& what) {
  if (err != paNoError) throw core::InputError("audio", what + ": " + Pa_GetErrorText(err));
}

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

}  // namespace

PortAudioHost::PortAudioHost() {
  PaError err;
  {
    QuietStderr quiet;
    err = Pa_Initialize();
  }
  check(err, "PortAudio could not start");
}

PortAudioHost::~PortAudioHost() {
  QuietStderr quiet;
  Pa_Terminate();
}

std::vector<OutputDevice> PortAudioHost::outputDevices() const {
  std::vector<OutputDevice> devices;
  const PaDeviceIndex count = Pa_GetDeviceCount();  // negative: an error, i.e. none usable
  const PaDeviceIndex default_out = Pa_GetDefaultOutputDevice();
  for (PaDeviceIndex i = 0; i < count; ++i) {
    const PaDeviceInfo* info = Pa_GetDeviceInfo(i);
    if (info == nullptr || info->maxOutputChannels < 1) continue;
    OutputDevice d;
    d.index = i;
    d.name = info->name != nullptr ? info->name : "";
    const PaHostApiInfo* api = Pa_GetHostApiInfo(info->hostApi);
    d.host_api = api != nullptr && api->name != nullptr ? api->name : "";
    d.max_output_channels = info->maxOutputChannels;
    d.default_sample_rate_hz = info->defaultSampleRate;
    d.default_low_latency_s = info->defaultLowOutputLatency;
    d.is_default = i == default_out;
    devices.push_back(d);
  }
  return devices;
}

OutputDevice PortAudioHost::chooseOutputDevice(const std::string& spec) const {
  const std::vector<OutputDevice> devices = outputDevices();
  if (devices.empty()) throw core::InputError("", kNoDevice);
  if (spec.empty()) {
    for (const OutputDevice& d : devices)
      if (d.is_default) return d;
    return devices.front();
  }
  const std::string hint = " (diffray auralize --list-devices lists them)";
  if (std::all_of(spec.begin(), spec.end(), [](unsigned char c) { return std::isdigit(c) != 0; })) {
    for (const OutputDevice& d : devices)
      if (std::to_string(d.index) == spec) return d;
    throw core::InputError("--device", "no output device has index " + spec + hint);
  }
  std::vector<OutputDevice> matches;
  for (const OutputDevice& d : devices)
    if (lower(d.name).find(lower(spec)) != std::string::npos) matches.push_back(d);
  if (matches.size() == 1) return matches.front();
  if (matches.empty()) throw core::InputError("--device", "no output device's name contains \"" + spec + "\"" + hint);
  throw core::InputError("--device", "\"" + spec + "\" matches " + std::to_string(matches.size()) +
                                         " output devices; give its index" + hint);
}

PlaybackReport PortAudioHost::play(PlaybackRenderer& renderer, const OutputDevice& device, double sample_rate_hz,
                                      const std::atomic<bool>& stop) {
  if (renderer.outputChannels() > device.max_output_channels)
    throw core::InputError("--device", device.name + " has " + std::to_string(device.max_output_channels) +
                                           " output channels; the convolution gives " +
                                           std::to_string(renderer.outputChannels()));
  PaStreamParameters out{};
  out.device = device.index;
  out.channelCount = renderer.outputChannels();
  out.sampleFormat = paFloat32;  // interleaved
  out.suggestedLatency = device.default_low_latency_s;
  out.hostApiSpecificStreamInfo = nullptr;
  PaStream* stream = nullptr;
  PaError err;
  {
    QuietStderr quiet;
    err = Pa_OpenStream(&stream, nullptr, &out, sample_rate_hz, static_cast<unsigned long>(renderer.blockFrames()),
                        paClipOff, &playbackCallback, &renderer);
  }
  check(err, "cannot open " + device.name + " at " + std::to_string(static_cast<long>(sample_rate_hz)) + " Hz");
  PlaybackReport report;
  report.device = device.name;
  if (const PaStreamInfo* info = Pa_GetStreamInfo(stream)) report.output_latency_s = info->outputLatency;
  err = Pa_StartStream(stream);
  if (err == paNoError) {
    while (Pa_IsStreamActive(stream) == 1) {
      if (stop.load()) {
        report.interrupted = true;
        break;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    QuietStderr quiet;
    if (report.interrupted) Pa_AbortStream(stream);
    else Pa_StopStream(stream);
  }
  {
    QuietStderr quiet;
    Pa_CloseStream(stream);
  }
  check(err, "cannot start " + device.name);
  return report;
}

}  // namespace diffray::audio
