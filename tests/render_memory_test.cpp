// The render's memory guard and photon cap (render/light_tracer.h), against hand computations, and
// core::orderedReduce's contract: chunks merged in chunk order whatever the thread count, with at most
// threads + 1 accumulators alive.
#include <gtest/gtest.h>

#include <atomic>
#include <vector>

#include "diffray/core/error.h"
#include "diffray/core/parallel.h"
#include "diffray/core/memory.h"
#include "diffray/render/light_tracer.h"

namespace {

namespace dr = diffray::render;
using diffray::core::InputError;

TEST(RenderMemory, PeakEstimateByHand) {
  // 2048 × 2048 = 4 194 304 pixels on 2 threads: 3 accumulators of 5 doubles (40 B) + 2 scratch doubles (16 B)
  // = 136 B per pixel = 570 425 344 B.
  EXPECT_DOUBLE_EQ(dr::renderPeakBytes(2048, 2048, 2), 570425344.0);
  // 1 thread: 2 × 40 + 8 = 88 B per pixel on 10 × 10.
  EXPECT_DOUBLE_EQ(dr::renderPeakBytes(10, 10, 1), 8800.0);
}

TEST(RenderMemory, RefusesWhatDoesNotFitInHalfTheMemory) {
  const double gb24 = 24e9;
  // 4K on 2 threads: 3840 × 2160 × 136 B = 1.13 GB, well under 12 GB.
  EXPECT_NO_THROW(dr::checkRenderMemory(3840, 2160, 2, gb24));
  // 16384² on 2 threads: 268 435 456 × 136 B = 36.5 GB > 12 GB.
  EXPECT_THROW(dr::checkRenderMemory(16384, 16384, 2, gb24), InputError);
  // Just over half: 1000 × 1000 × 136 B = 136 MB against 270 MB of memory (half = 135 MB).
  EXPECT_THROW(dr::checkRenderMemory(1000, 1000, 2, 270e6), InputError);
  EXPECT_NO_THROW(dr::checkRenderMemory(1000, 1000, 2, 273e6));
  EXPECT_NO_THROW(dr::checkRenderMemory(16384, 16384, 64, 0.0));  // unknown memory: not refused
  EXPECT_GT(diffray::core::physicalMemoryBytes(), 0.0);
}

TEST(RenderMemory, SppCapInDouble) {
  EXPECT_EQ(dr::sppPhotons(4, 640, 480), 4u * 640u * 480u);
  EXPECT_EQ(dr::sppPhotons(10000000, 1000, 1000), 10000000000000u);  // exactly 1e13: allowed
  EXPECT_THROW(dr::sppPhotons(10000001, 1000, 1000), InputError);
  // 1e13 × 8 × 8 would wrap a uint64 were it multiplied there (1e13 × 16384² ≈ 2.7e21 > 1.8e19).
  EXPECT_THROW(dr::sppPhotons(10000000000000u, 8, 8), InputError);
  EXPECT_THROW(dr::sppPhotons(10000000000000u, 16384, 16384), InputError);
}

// An accumulator that records the chunks it holds, in merge order, and counts how many exist at once.
std::atomic<int> g_alive{0}, g_peak{0};
struct Trail {
  std::vector<std::uint64_t> begins;
  Trail() { note(); }
  Trail(const Trail& o) : begins(o.begins) { note(); }
  ~Trail() { --g_alive; }
  static void note() {
    const int now = ++g_alive;
    int peak = g_peak.load();
    while (now > peak && !g_peak.compare_exchange_weak(peak, now)) {
    }
  }
  void merge(const Trail& o) { begins.insert(begins.end(), o.begins.begin(), o.begins.end()); }
};

TEST(OrderedReduce, ChunkOrderAndBoundedAccumulators) {
  for (int threads : {1, 2, 4}) {
    diffray::core::ThreadLimit limit(threads);
    g_alive = 0;
    g_peak = 0;
    const std::uint64_t count = 1000;  // 32 chunks (the minimum) of 31 or 32 items
    const Trail t = diffray::core::orderedReduce<Trail>(
        count, 100, 7, [] { return Trail(); },
        [](Trail& acc, diffray::core::Rng&, std::uint64_t begin, std::uint64_t) { acc.begins.push_back(begin); },
        [](std::uint64_t) {});
    const diffray::core::ChunkPlan plan(count, 100);
    ASSERT_EQ(t.begins.size(), 32u);
    for (std::uint64_t c = 0; c < 32; ++c) EXPECT_EQ(t.begins[c], plan.begin(c)) << "threads " << threads;
    // The total and one per token (= threads) — each briefly twice while make()'s result is copied into its
    // shared_ptr (Trail has no move constructor), and the returned copy: 2·threads + 2 at most, where
    // deterministicReduce's tree would keep about threads × (log2(32) + 1) = 6·threads.
    EXPECT_LE(g_peak.load(), 2 * threads + 2) << "threads " << threads;
  }
}

}  // namespace
