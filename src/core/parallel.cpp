#include "diffray/core/parallel.h"

#include "diffray/core/error.h"

namespace diffray::core {

ThreadLimit::ThreadLimit(int threads) {
  if (threads < 0) throw InputError("--threads", "must be >= 0 (0 = all cores)");
  if (threads > 0)
    control_ = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                     static_cast<std::size_t>(threads));
}

int ThreadLimit::current() {
  return static_cast<int>(tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism));
}

}  // namespace diffray::core
