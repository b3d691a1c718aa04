#pragma once
// Deterministic parallel Monte Carlo. Work is cut into chunks of nearly equal size (at most `chunk_size`
// items, and at least 32 chunks when there are enough items, so chunk-to-chunk scatter gives a usable
// variance estimate); chunk c always
// gets the random stream Rng(seed, c) and chunk results are combined in a fixed tree that depends only on
// the number of chunks (tbb::parallel_deterministic_reduce with a simple partitioner). So the same seed
// gives bit-identical results for any thread count. Threads: TBB's default (all cores) unless a
// ThreadLimit is alive. orderedReduce is the variant for large accumulators (a full-frame image): the same
// chunks and streams, merged in chunk order through a pipeline, so at most threads + 1 accumulators are alive
// (deterministicReduce keeps about threads × (log2(chunks) + 1)).
#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/parallel_pipeline.h>
#include <tbb/parallel_reduce.h>
#include <tbb/partitioner.h>

#include <algorithm>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>

#include "diffray/core/rng.h"

namespace diffray::core {

/// Limits TBB to `threads` worker threads while alive (0 = leave the default: all cores).
class ThreadLimit {
 public:
  explicit ThreadLimit(int threads);
  static int current();  ///< threads TBB may use now

 private:
  std::unique_ptr<tbb::global_control> control_;
};

/// An on_chunk for deterministicReduce that forwards to an optional progress callback (none: nothing).
inline auto reportProgressTo(const std::function<void(std::uint64_t)>& on_progress) {
  return [&on_progress](std::uint64_t n) {
    if (on_progress) on_progress(n);
  };
}

/// How deterministicReduce and orderedReduce cut `count` items: `chunks` chunks, chunk c = [begin(c), begin(c+1)).
struct ChunkPlan {
  std::uint64_t count, chunks;
  ChunkPlan(std::uint64_t count_, std::uint64_t chunk_size) : count(count_), chunks((count_ + chunk_size - 1) / chunk_size) {
    if (chunks < 32) chunks = count < 32 ? count : 32;
  }
  std::uint64_t begin(std::uint64_t c) const {
    return (count / chunks) * c + (count % chunks) * c / chunks;  // = floor(count·c/chunks), no overflow
  }
};

/// Runs `body(acc, rng, begin, end)` over [0, count) in fixed chunks and merges the per-chunk
/// accumulators with `acc.merge(other)` in a thread-count-independent order. `make()` builds an empty
/// accumulator. `on_chunk(items)` is called after each chunk (e.g. a progress bar); it must be thread-safe.
template <class Acc, class Make, class Body, class OnChunk>
Acc deterministicReduce(std::uint64_t count, std::uint64_t chunk_size, std::uint64_t seed, Make make,
                        Body body, OnChunk on_chunk) {
  const ChunkPlan plan(count, chunk_size);
  if (plan.chunks == 0) return make();
  // TBB's body form, so that no accumulator is ever copied: each body builds its own with make() at its
  // first chunk, and a join merges the right one into the left in place (the lambda form copies the
  // identity at every split, and the value into each call and each join: a megabyte-sized histogram
  // about three times per chunk, 5 % of a room trace). The tree, and so every sum's order, is TBB's
  // deterministic one, as before.
  struct Reducer {
    const ChunkPlan& plan;
    std::uint64_t seed;
    Make& make;
    Body& body;
    OnChunk& on_chunk;
    std::optional<Acc> acc;
    Reducer(const ChunkPlan& p, std::uint64_t s, Make& m, Body& b, OnChunk& o)
        : plan(p), seed(s), make(m), body(b), on_chunk(o) {}
    Reducer(Reducer& other, tbb::split)
        : plan(other.plan), seed(other.seed), make(other.make), body(other.body), on_chunk(other.on_chunk) {}
    void operator()(const tbb::blocked_range<std::uint64_t>& range) {
      if (!acc) acc.emplace(make());
      for (std::uint64_t c = range.begin(); c != range.end(); ++c) {
        Rng rng(seed, c);
        const std::uint64_t begin = plan.begin(c), end = plan.begin(c + 1);
        body(*acc, rng, begin, end);
        on_chunk(end - begin);
      }
    }
    void join(Reducer& right) {
      if (!right.acc) return;
      if (!acc) acc = std::move(right.acc);
      else acc->merge(*right.acc);
    }
  };
  Reducer reducer(plan, seed, make, body, on_chunk);
  tbb::parallel_deterministic_reduce(tbb::blocked_range<std::uint64_t>(0, plan.chunks, 1), reducer,
                                     tbb::simple_partitioner());
  return reducer.acc ? std::move(*reducer.acc) : make();
}

/// deterministicReduce's contract with a different fixed merge order: ((make() ⊕ chunk 0) ⊕ chunk 1) ⊕ …, each
/// chunk traced into its own make() on some thread and merged serially in chunk order. Bit-identical for
/// any thread count; at most `threads` chunk accumulators plus the total are alive at once.
template <class Acc, class Make, class Body, class OnChunk>
Acc orderedReduce(std::uint64_t count, std::uint64_t chunk_size, std::uint64_t seed, Make make, Body body,
                  OnChunk on_chunk) {
  const ChunkPlan plan(count, chunk_size);
  Acc total = make();
  std::uint64_t next = 0;
  using Item = std::shared_ptr<Acc>;  // copyable, as pipeline filters want; null = no chunk
  auto source = [&](tbb::flow_control& fc) -> std::uint64_t {
    if (next == plan.chunks) fc.stop();
    return next++;
  };
  auto trace = [&](std::uint64_t c) -> Item {
    auto acc = std::make_shared<Acc>(make());
    Rng rng(seed, c);
    body(*acc, rng, plan.begin(c), plan.begin(c + 1));
    on_chunk(plan.begin(c + 1) - plan.begin(c));
    return acc;
  };
  auto fold = [&](const Item& acc) { total.merge(*acc); };
  const std::size_t tokens = static_cast<std::size_t>(std::max(1, ThreadLimit::current()));
  tbb::parallel_pipeline(tokens, tbb::make_filter<void, std::uint64_t>(tbb::filter_mode::serial_in_order, source) &
                                     tbb::make_filter<std::uint64_t, Item>(tbb::filter_mode::parallel, trace) &
                                     tbb::make_filter<Item, void>(tbb::filter_mode::serial_in_order, fold));
  return total;
}

}  // namespace diffray::core
