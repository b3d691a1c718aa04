#include "render_is_bench.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

#include "diffray/render/light_scene.h"
#include "diffray/render/light_setup.h"
#include "diffray/render/light_tracer.h"
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

namespace {

struct Timed {
  render::RenderResult result;
  double seconds = 0.0;
};

Timed renderTimed(const render::PreparedScene& scene, std::uint64_t photons, std::uint64_t seed, bool uniform) {
  render::RenderOptions o;
  o.photons = photons;
  o.seed = seed;
  o.uniform_shifts = uniform;
  const auto t0 = std::chrono::steady_clock::now();
  Timed t{render::renderLight(scene, o), 0.0};
  t.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return t;
}

/// RMS and max |x − ref| over every pixel's XYZ, as fractions of the reference's largest value.
void errorsAgainst(const render::RenderResult& r, const render::RenderResult& ref, double& rms, double& max) {
  double peak = 0.0, sum = 0.0;
  max = 0.0;
  for (double v : ref.xyz) peak = std::max(peak, std::abs(v));
  for (std::size_t i = 0; i < ref.xyz.size(); ++i) {
    const double d = r.xyz[i] - ref.xyz[i];
    sum += d * d;
    max = std::max(max, std::abs(d));
  }
  rms = std::sqrt(sum / static_cast<double>(ref.xyz.size())) / peak;
  max /= peak;
}

}  // namespace

void benchRenderIsScene(const std::string& scene_path, const std::string& name, std::uint64_t photons_is) {
  const render::LightScene spec = render::loadLightScene(scene_path);
  const auto scene = render::prepareScene(spec);
  const Timed ref = renderTimed(*scene, 8 * photons_is, 11, false);
  const Timed is = renderTimed(*scene, photons_is, 1, false);
  const Timed cal = renderTimed(*scene, std::max<std::uint64_t>(photons_is / 10, 200'000), 2, true);
  const double rate = static_cast<double>(cal.result.photons) / cal.seconds;
  const Timed uni = renderTimed(*scene, std::max<std::uint64_t>(static_cast<std::uint64_t>(rate * is.seconds), 65'536), 3, true);
  double rms_is, max_is, rms_uni, max_uni;
  errorsAgainst(is.result, ref.result, rms_is, max_is);
  errorsAgainst(uni.result, ref.result, rms_uni, max_uni);
  std::printf(
      "{\"bench\":\"render-is\",\"scene\":\"%s\",\"reference\":\"importance-sampled render, %llu photons\","
      "\"error_is\":%.5f,\"error_uniform\":%.5f,\"max_error_is\":%.5f,\"max_error_uniform\":%.5f,"
      "\"photons_is\":%llu,\"photons_uniform\":%llu,\"seconds\":%.2f,\"seconds_uniform\":%.2f,"
      "\"time_factor\":%.2f,\"time_factor_max_error\":%.2f,\"paper_time_factor\":10}\n",
      name.c_str(), static_cast<unsigned long long>(ref.result.photons), rms_is, rms_uni, max_is, max_uni,
      static_cast<unsigned long long>(is.result.photons), static_cast<unsigned long long>(uni.result.photons),
      is.seconds, uni.seconds, std::pow(rms_uni / rms_is, 2), std::pow(max_uni / max_is, 2));
  std::fflush(stdout);
}

}  // namespace diffray::bench
