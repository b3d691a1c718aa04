// `diffray auralize --ir IR.wav --in DRY.wav --play [--device N|NAME] [--block FRAMES] [--gain DB]`,
// `diffray door … --play` and `diffray auralize --list-devices`: see include/diffray/cli/play.h. The dry
// file is streamed by a reader thread (audio::DryFileStreamer) into a lock-free ring that the PortAudio
// callback drains through the non-uniform convolver (audio::PlaybackRenderer; for the door, its crossfading
// form); the ring is half filled before the stream starts. The latency added by the convolution is zero;
// the device's buffer adds one block (block / rate seconds) plus whatever the host API adds (printed as
// PortAudio reports it). Ctrl-C sets an atomic flag that the polling loop sees within 20 ms; the stream is
// aborted, the reader stopped, and the exit code is 130.
#include <algorithm>
#include <atomic>
#include <csignal>
#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

#include "diffray/audio/playback.h"
#include "diffray/audio/portaudio_output.h"
#include "diffray/audio/wav.h"
#include "diffray/cli/commands.h"
#include "diffray/cli/play.h"
#include "diffray/core/error.h"

namespace diffray::cli {

namespace {

std::atomic<bool> g_interrupted{false};
static_assert(std::atomic<bool>::is_always_lock_free, "the SIGINT handler stores to an atomic<bool>");

extern "C" void onInterrupt(int /*signal*/) { g_interrupted.store(true); }

/// Installs the SIGINT handler for its lifetime.
struct InterruptGuard {
  using Handler = void (*)(int);
  Handler previous;
  InterruptGuard() : previous(std::signal(SIGINT, onInterrupt)) { g_interrupted.store(false); }
  ~InterruptGuard() { std::signal(SIGINT, previous == SIG_ERR ? SIG_DFL : previous); }
};

}  // namespace

int listAudioDevices() {
  audio::PortAudioHost host;
  const auto devices = host.outputDevices();
  if (devices.empty()) {
    std::cout << "no audio output devices found (PortAudio found none)\n";
    return 0;
  }
  for (const auto& d : devices)
    std::printf("%3d%s %s [%s] %d ch, default %.0f Hz, low latency %.1f ms\n", d.index, d.is_default ? "*" : " ",
                d.name.c_str(), d.host_api.c_str(), d.max_output_channels, d.default_sample_rate_hz,
                1e3 * d.default_low_latency_s);
  std::cout << "(* the default output device)\n";
  return 0;
}

void requireOutputDevice(const std::string& device) {
  audio::PortAudioHost host;
  host.chooseOutputDevice(device);
}

void requireBlockFrames(int block_frames) {
  if (block_frames < kMinBlockFrames || block_frames > kMaxBlockFrames)
    throw core::InputError("--block", "must lie between " + std::to_string(kMinBlockFrames) + " and " +
                                          std::to_string(kMaxBlockFrames) + " frames, got " + std::to_string(block_frames));
}

namespace {

/// Plays `renderer` fed from `dry` on the chosen device until it ends or Ctrl-C; `what` names it in the
/// first line of `status`. Returns the exit code (0, or 130 after Ctrl-C).
int playRenderer(audio::PlaybackRenderer& renderer, audio::AudioReader& dry, audio::PortAudioHost& host,
                 const audio::OutputDevice& device, int block_frames, const std::string& what, std::ostream& status) {
  const double rate = dry.sampleRateHz();
  status << "playing " << what << " on " << device.name << ": " << renderer.outputChannels()
            << " channel(s) at " << rate << " Hz, block " << block_frames << " frames = "
            << 1e3 * block_frames / rate << " ms, " << renderer.irFrames() << " IR frames; Ctrl-C stops" << std::endl;
  InterruptGuard guard;
  audio::DryFileStreamer streamer(dry, renderer);
  streamer.waitForPrefill(renderer.ringFrames() / 2);
  const audio::PlaybackReport report = host.play(renderer, device, rate, g_interrupted);
  streamer.stop();
  streamer.wait();
  status << (report.interrupted ? "interrupted" : "done") << ": " << renderer.framesRendered()
            << " frames, device output latency " << 1e3 * report.output_latency_s << " ms, underruns "
            << renderer.underruns() << " (" << renderer.underrunFrames() << " dry frames missed)\n";
  return report.interrupted ? 130 : 0;
}

audio::PlaybackConfig playbackConfig(int block_frames, double gain_db) {
  audio::PlaybackConfig config;
  config.block_frames = block_frames;
  config.gain_db = gain_db;
  config.ring_frames = std::max<long>(1L << 16, 8L * block_frames);
  return config;
}

}  // namespace

int playAuralization(const PlayOptions& o) {
  core::requireFinite("--gain", o.gain_db);
  requireBlockFrames(o.block_frames);
  audio::AudioReader dry(o.in);
  std::string cut;
  const audio::AudioBuffer ir = audio::readAudio(o.ir, &cut);
  warnOf(dry.warning());
  warnOf(cut);
  const std::vector<std::vector<float>> ir_channels =
      decodedIr(irAtRate(ir, dry.sampleRateHz(), o.ir, o.no_resample), o, dry.sampleRateHz());
  audio::PortAudioHost host;
  const audio::OutputDevice device = host.chooseOutputDevice(o.device);
  audio::PlaybackRenderer renderer(ir_channels, dry.channels(), playbackConfig(o.block_frames, o.gain_db));
  return playRenderer(renderer, dry, host, device, o.block_frames, o.in + " * " + o.ir, std::cout);
}

int playCrossfade(const std::vector<std::vector<std::vector<float>>>& irs, const std::vector<long>& key_frames,
                  const std::string& in, const std::string& device_name, int block_frames, double gain_db,
                  std::ostream& status) {
  core::requireFinite("--gain", gain_db);
  requireBlockFrames(block_frames);
  audio::AudioReader dry(in);
  audio::PortAudioHost host;
  const audio::OutputDevice device = host.chooseOutputDevice(device_name);
  audio::PlaybackRenderer renderer(irs, key_frames, dry.channels(), playbackConfig(block_frames, gain_db));
  return playRenderer(renderer, dry, host, device, block_frames,
                      in + " through the closing door (" + std::to_string(irs.size()) + " crossfaded IRs)", status);
}

}  // namespace diffray::cli
