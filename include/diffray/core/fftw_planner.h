#pragma once
// The process-wide mutex that guards FFTW's planner. FFTW's plan creation and destruction (fftw_plan_*,
// fftw_destroy_plan) are not thread-safe; executing plans is. Every module that creates or destroys FFTW
// plans (wbsdf's numeric Wigner distribution, ir's band filters, dsp's convolvers) holds it while doing so.
#include <mutex>

namespace diffray::core {

std::mutex& fftwPlannerMutex();

}  // namespace diffray::core
