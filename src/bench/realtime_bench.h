#pragma once
// The real-time bench (realtime_bench.cpp): the playback callback's cost per block against the block's
// duration.

namespace diffray::bench {

/// Plays `seconds` of stereo noise through a 3 s stereo IR with the test backend (block 256 at 48 kHz) and
/// prints one JSON line: callback median / p99 / max in ms, the block's duration (the anchor), and the
/// same figures for the uniformly partitioned convolver on the same blocks.
void benchRealtime(double seconds);

}  // namespace diffray::bench
