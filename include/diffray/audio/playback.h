#pragma once
// Real-time playback, independent of any audio API.
// PlaybackRenderer is what an audio callback runs: it pops dry frames from a lock-free SPSC ring
// (SpscFrameRing), convolves them with dsp::NonUniformMultichannelConvolver (head block = the callback's
// block, zero latency), applies the gain and writes interleaved float output. Once the dry input has ended
// it feeds zeros until the IR's tail has rung out (IR frames − 1), then reports itself finished and writes
// silence. If the ring runs dry before the input has ended (an underrun: the reader fell behind), the
// missing dry frames are taken as silence (the reverberant tail keeps going) and the underrun is counted;
// the callback never waits. The closing door (`diffray door --play`) is the same with IRs crossfaded over
// time (dsp::NonUniformCrossfadeConvolver, each IR's convolver on the non-uniform engine), the dry input
// mixed to one channel first, as `door` mixes it offline.
// Threads: pushDry()/endInput() from one producer thread (DryFileStreamer); render() from one consumer
// thread (the audio callback); the counters and finished() from anywhere. render() allocates nothing,
// locks nothing and does no I/O (std::atomic loads/stores only; the convolver's process()).
// DryFileStreamer is the producer: a thread that streams a file through audio::AudioReader into the
// renderer, sleeping a little while the ring is full.
// playbackCallback() has PortAudio's PaStreamCallback signature: the PortAudio backend hands it to
// Pa_OpenStream and the test backend (audio/test_backend.h) calls it from an ordinary thread.
#include <atomic>
#include <exception>
#include <memory>
#include <thread>
#include <vector>

#include "diffray/audio/spsc_ring.h"
#include "diffray/audio/wav.h"
#include "diffray/dsp/crossfade_convolver.h"
#include "diffray/dsp/multichannel_convolver.h"

struct PaStreamCallbackTimeInfo;  // portaudio.h; the callback below never reads it

namespace diffray::audio {

struct PlaybackConfig {
  int block_frames = 256;          ///< the convolver's head block: the audio callback's buffer size
  double gain_db = 0.0;            ///< output gain, 10^(dB/20)
  long ring_frames = 1 << 16;      ///< dry frames buffered between the reader thread and the callback
  long max_callback_frames = 8192; ///< scratch size; longer callbacks are processed in pieces
};

class PlaybackRenderer {
 public:
  /// `ir[m]` is IR channel m (channel pairing as in dsp/multichannel_convolver.h). Throws core::InputError
  /// for a bad pairing, IR or block size. Allocates everything render() will use.
  PlaybackRenderer(const std::vector<std::vector<float>>& ir, int input_channels, const PlaybackConfig& config);
  /// The crossfading renderer: `irs[k][m]` is channel m of IR k, heard alone at input frame key_frames[k]
  /// (counted from the first dry frame; dsp/crossfade_convolver.h); the `input_channels` dry channels are
  /// averaged into one before the convolution. Throws core::InputError as CrossfadeConvolver::init does.
  PlaybackRenderer(const std::vector<std::vector<std::vector<float>>>& irs, const std::vector<long>& key_frames,
                   int input_channels, const PlaybackConfig& config);

  int inputChannels() const { return input_channels_; }
  int outputChannels() const { return fade_ ? fade_->outputChannels() : conv_.outputChannels(); }
  int blockFrames() const { return config_.block_frames; }
  /// The IR's frames (the crossfading renderer: the longest IR's).
  long irFrames() const { return ir_frames_; }
  bool crossfading() const { return fade_ != nullptr; }
  /// Tail stages' block sizes after the head (for reporting); see dsp/non_uniform_convolver.h. Not
  /// initialised in the crossfading renderer.
  const dsp::NonUniformMultichannelConvolver& convolver() const { return conv_; }

  // Producer side (one thread).
  /// Queues up to `frames` interleaved dry frames; returns how many fitted (0 when the ring is full).
  long pushDry(const float* frames, long count) { return ring_.push(frames, count); }
  /// No more dry frames will come.
  void endInput() { input_ended_.store(true, std::memory_order_release); }

  // Consumer side: the audio callback.
  /// Writes `frames` interleaved output frames; returns false once the IR's tail has rung out (the rest is
  /// silence). Allocation-, lock- and I/O-free.
  bool render(float* out, long frames);

  // Any thread.
  long bufferedFrames() const { return ring_.available(); }
  long ringFrames() const { return ring_.capacity(); }
  bool inputEnded() const { return input_ended_.load(std::memory_order_acquire); }
  bool finished() const { return finished_.load(std::memory_order_acquire); }
  long underruns() const { return underruns_.load(std::memory_order_relaxed); }          ///< callbacks short of input
  long underrunFrames() const { return underrun_frames_.load(std::memory_order_relaxed); } ///< dry frames replaced by silence
  long framesRendered() const { return rendered_.load(std::memory_order_relaxed); }

 private:
  PlaybackConfig config_;
  float gain_ = 1.0f;
  int input_channels_ = 1;
  long ir_frames_ = 0;
  dsp::NonUniformMultichannelConvolver conv_;
  std::unique_ptr<dsp::NonUniformCrossfadeConvolver> fade_;  ///< the crossfading renderer's, else null
  SpscFrameRing ring_;
  std::vector<float> dry_;   ///< max_callback_frames × input channels
  std::vector<float> mono_;  ///< the crossfading renderer: max_callback_frames, the dry channels' mean
  long tail_left_ = 0;      ///< zero frames still to feed after the input ended (callback thread only)
  std::atomic<bool> input_ended_{false};
  std::atomic<bool> finished_{false};
  std::atomic<long> underruns_{0};
  std::atomic<long> underrun_frames_{0};
  std::atomic<long> rendered_{0};
};

/// PortAudio's stream callback signature; `user` is the PlaybackRenderer. Writes `frames` float frames
/// to `output` and returns paContinue (0) or, once the renderer has finished, paComplete (1).
int playbackCallback(const void* input, void* output, unsigned long frames, const PaStreamCallbackTimeInfo* time,
                     unsigned long status_flags, void* user);

/// Streams `reader` into `renderer` from its own thread, then calls renderer.endInput() (also on a read
/// error, which wait() rethrows). The reader and renderer must outlive this object.
class DryFileStreamer {
 public:
  DryFileStreamer(AudioReader& reader, PlaybackRenderer& renderer);
  ~DryFileStreamer();  ///< stops and joins
  DryFileStreamer(const DryFileStreamer&) = delete;
  DryFileStreamer& operator=(const DryFileStreamer&) = delete;

  /// Returns once the ring holds `frames` frames (capped at its capacity) or the input has ended.
  void waitForPrefill(long frames) const;
  /// Asks the thread to stop early (Ctrl-C); the renderer then sees the input end.
  void stop() { stop_.store(true, std::memory_order_relaxed); }
  /// Joins the thread and rethrows a read error, if any.
  void wait();

 private:
  void run();

  AudioReader& reader_;
  PlaybackRenderer& renderer_;
  std::atomic<bool> stop_{false};
  std::exception_ptr error_;
  std::thread thread_;
};

}  // namespace diffray::audio
