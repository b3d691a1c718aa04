#include "diffray/core/fftw_planner.h"

namespace diffray::core {

std::mutex& fftwPlannerMutex() {
  static std::mutex mutex;
  return mutex;
}

}  // namespace diffray::core
