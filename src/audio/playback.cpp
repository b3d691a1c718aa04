#include "diffray/audio/playback.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>

#include "diffray/core/error.h"

namespace diffray::audio {

namespace {

void requireConfig(const PlaybackConfig& config) {
  core::requireFinite("gain", config.gain_db);
  if (config.max_callback_frames < 1 || config.ring_frames < 1)
    throw core::InputError("playback", "the ring and the callback scratch need at least one frame");
}

}  // namespace

PlaybackRenderer::PlaybackRenderer(const std::vector<std::vector<float>>& ir, int input_channels,
                                   const PlaybackConfig& config)
    : config_(config),
      gain_(static_cast<float>(std::pow(10.0, config.gain_db / 20.0))),
      input_channels_(input_channels),
      ring_(config.ring_frames, std::max(1, input_channels)) {
  requireConfig(config);
  conv_.init(config.block_frames, ir, input_channels);
  dry_.assign(static_cast<size_t>(config.max_callback_frames) * static_cast<size_t>(input_channels), 0.0f);
  ir_frames_ = conv_.irLength();
  tail_left_ = ir_frames_ - 1;
}

PlaybackRenderer::PlaybackRenderer(const std::vector<std::vector<std::vector<float>>>& irs,
                                   const std::vector<long>& key_frames, int input_channels,
                                   const PlaybackConfig& config)
    : config_(config),
      gain_(static_cast<float>(std::pow(10.0, config.gain_db / 20.0))),
      input_channels_(input_channels),
      fade_(std::make_unique<dsp::NonUniformCrossfadeConvolver>()),
      ring_(config.ring_frames, std::max(1, input_channels)) {
  requireConfig(config);
  if (input_channels < 1) throw core::InputError("playback", "the dry input needs at least one channel");
  fade_->init(config.block_frames, irs, 1, key_frames);
  dry_.assign(static_cast<size_t>(config.max_callback_frames) * static_cast<size_t>(input_channels), 0.0f);
  mono_.assign(static_cast<size_t>(config.max_callback_frames), 0.0f);
  for (const auto& ir : irs) ir_frames_ = std::max(ir_frames_, static_cast<long>(ir.front().size()));
  tail_left_ = ir_frames_ - 1;  // at least the crossfade's own tailFrames() wherever the input ends
}

bool PlaybackRenderer::render(float* out, long frames) {
  const long cin = inputChannels(), cout = outputChannels();
  if (finished_.load(std::memory_order_relaxed)) {
    std::fill(out, out + frames * cout, 0.0f);
    return false;
  }
  bool short_of_input = false;
  for (long done = 0; done < frames;) {
    const long n = std::min(frames - done, config_.max_callback_frames);
    long got = ring_.pop(dry_.data(), n);
    if (got < n) {
      // The producer pushes its last frames before it sets input_ended_ (release): pop once more after
      // seeing the flag (acquire) to take them.
      const bool ended = input_ended_.load(std::memory_order_acquire);
      if (ended) got += ring_.pop(dry_.data() + got * cin, n - got);
      std::fill(dry_.begin() + got * cin, dry_.begin() + n * cin, 0.0f);
      if (!ended) {
        short_of_input = true;
        underrun_frames_.fetch_add(n - got, std::memory_order_relaxed);
      } else {
        tail_left_ -= n - got;  // zeros fed after the end let the tail ring out
      }
    }
    float* o = out + done * cout;
    if (fade_) {
      for (long f = 0; f < n; ++f) {
        float sum = 0.0f;
        for (long c = 0; c < cin; ++c) sum += dry_[static_cast<size_t>(f * cin + c)];
        mono_[static_cast<size_t>(f)] = sum / static_cast<float>(cin);
      }
      fade_->process(mono_.data(), o, n);
    } else {
      conv_.process(dry_.data(), o, n);
    }
    for (long i = 0; i < n * cout; ++i) o[i] *= gain_;
    done += n;
  }
  if (short_of_input) underruns_.fetch_add(1, std::memory_order_relaxed);
  rendered_.fetch_add(frames, std::memory_order_relaxed);
  if (tail_left_ <= 0 && input_ended_.load(std::memory_order_acquire) && ring_.available() == 0) {
    finished_.store(true, std::memory_order_release);
    return false;
  }
  return true;
}

int playbackCallback(const void* /*input*/, void* output, unsigned long frames,
                     const PaStreamCallbackTimeInfo* /*time*/, unsigned long /*status_flags*/, void* user) {
  auto* renderer = static_cast<PlaybackRenderer*>(user);
  const bool more = renderer->render(static_cast<float*>(output), static_cast<long>(frames));
  return more ? 0 : 1;  // paContinue : paComplete
}

DryFileStreamer::DryFileStreamer(AudioReader& reader, PlaybackRenderer& renderer)
    : reader_(reader), renderer_(renderer) {
  if (reader.channels() != renderer.inputChannels())
    throw core::InputError("playback", "the dry file has " + std::to_string(reader.channels()) +
                                           " channels, the renderer expects " +
                                           std::to_string(renderer.inputChannels()));
  thread_ = std::thread([this] { run(); });
}

DryFileStreamer::~DryFileStreamer() {
  stop();
  if (thread_.joinable()) thread_.join();
}

void DryFileStreamer::run() {
  constexpr long kChunk = 4096;
  try {
    std::vector<float> chunk(static_cast<size_t>(kChunk) * static_cast<size_t>(reader_.channels()));
    while (!stop_.load(std::memory_order_relaxed)) {
      const long frames = reader_.read(chunk.data(), kChunk);
      if (frames == 0) break;
      for (long pushed = 0; pushed < frames && !stop_.load(std::memory_order_relaxed);) {
        const long n = renderer_.pushDry(chunk.data() + pushed * reader_.channels(), frames - pushed);
        pushed += n;
        if (n == 0) std::this_thread::sleep_for(std::chrono::milliseconds(2));  // the ring is full
      }
    }
  } catch (...) {
    error_ = std::current_exception();
  }
  renderer_.endInput();
}

void DryFileStreamer::waitForPrefill(long frames) const {
  const long target = std::min(frames, renderer_.ringFrames());
  while (!renderer_.inputEnded() && renderer_.bufferedFrames() < target)
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
}

void DryFileStreamer::wait() {
  if (thread_.joinable()) thread_.join();
  if (error_) std::rethrow_exception(error_);
}

}  // namespace diffray::audio
