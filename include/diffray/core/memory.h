#pragma once
// The machine's memory, for refusing up front work that would not fit (a render's accumulators, the
// analysis of a very long audio file) with one clear line instead of an allocation failure or the OOM
// killer. Thread-safe (sysconf only).

namespace diffray::core {

/// sysconf(_SC_PHYS_PAGES) × sysconf(_SC_PAGE_SIZE), or 0 when unknown.
double physicalMemoryBytes();

}  // namespace diffray::core
