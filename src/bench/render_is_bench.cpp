#include "render_is_bench.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "diffray/validate/image_setup.h"

namespace diffray::bench {

void benchRenderIs(std::uint64_t photons_is) {
  const validate::DoubleSlitImageSetup setup;  // rooms/light/double-slit.json
  validate::ImageRunOptions o;
  o.photons = photons_is;
  o.seed = 1;
  const validate::CaseResult is = validate::runImageDoubleSlit(setup, o);
  const double seconds = is.extra.at("seconds_render");
  // Uniform: the photon rate from a short run, then as many photons as fit in the same render time.
  o.uniform_shifts = true;
  o.photons = std::max<std::uint64_t>(photons_is / 10, 200'000);
  o.seed = 2;
  const validate::CaseResult cal = validate::runImageDoubleSlit(setup, o);
  const double rate = static_cast<double>(cal.rays) / cal.extra.at("seconds_render");
  o.photons = std::max<std::uint64_t>(static_cast<std::uint64_t>(rate * seconds), 65'536);
  o.seed = 3;
  const validate::CaseResult uni = validate::runImageDoubleSlit(setup, o);
  const double ratio = uni.rms_error_rel_peak / is.rms_error_rel_peak;
  std::printf(
      "{\"bench\":\"render-is\",\"scene\":\"double-slit\",\"reference\":\"fraunhofer (absolute)\","
      "\"error_is\":%.5f,\"error_uniform\":%.5f,\"max_error_is\":%.5f,\"max_error_uniform\":%.5f,"
      "\"photons_is\":%llu,\"photons_uniform\":%llu,\"seconds\":%.2f,\"seconds_uniform\":%.2f,"
      "\"time_factor\":%.2f,\"time_factor_max_error\":%.2f,\"paper_time_factor\":10}\n",
      is.rms_error_rel_peak, uni.rms_error_rel_peak, is.max_abs_error_rel_peak, uni.max_abs_error_rel_peak,
      static_cast<unsigned long long>(is.rays), static_cast<unsigned long long>(uni.rays), seconds,
      uni.extra.at("seconds_render"), ratio * ratio,
      std::pow(uni.max_abs_error_rel_peak / is.max_abs_error_rel_peak, 2));
  std::fflush(stdout);
}

}  // namespace diffray::bench
