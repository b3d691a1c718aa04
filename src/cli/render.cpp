// `diffray render SCENE.json -o OUT.png [--photons N | --spp N] [--seed S] [--threads T] [--exposure E]
// [--float pfm|exr] [--csv FILE]`: light-traces a light scene (rooms/light/README.md, render/light_tracer.h)
// and writes OUT.png (sRGB, 8 bit), OUT.pfm or OUT.exr (linear sRGB floats, radiance units), OUT.json
// (photons, seed, seconds, negative-energy fractions, energy balance, the files written; OUT.render.json
// when OUT.json is the scene itself) and, with --csv,
// every pixel's radiance, standard error, XYZ and linear sRGB. Every output is written atomically, and all
// are checked before the render starts; bad input is one line and exit 2.
#include <chrono>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "diffray/cli/commands.h"
#include "diffray/core/atomic_file.h"
#include "diffray/core/error.h"
#include "diffray/core/parallel.h"
#include "diffray/core/progress.h"
#include "diffray/image/exr.h"
#include "diffray/image/pfm.h"
#include "diffray/image/png.h"
#include "diffray/render/film.h"
#include "diffray/render/light_scene.h"
#include "diffray/render/light_setup.h"
#include "diffray/render/light_tracer.h"

namespace diffray::cli {

namespace {

struct RenderCliOptions {
  std::string scene, out, float_format = "pfm", csv;
  double photons = 0, spp = 0, exposure = 0;
  bool seed_given = false;
};

/// The sidecar: OUT.json, or OUT.render.json when OUT.json is the scene itself (-o cd.png beside cd.json).
std::string sidecarOf(const RenderCliOptions& o) {
  const std::string plain = withExtension(o.out, ".json");
  return isAnyOf(plain, {o.scene}) ? withExtension(o.out, ".render.json") : plain;
}

/// Every output (PNG, float image, sidecar, CSV), checked before the scene is even read.
void checkOutput(const RenderCliOptions& o) {
  checkOutputFile(o.out, ".png");
  if (!o.csv.empty()) checkOutputFile(o.csv, ".csv");
  checkOutputFiles({o.out, sidecarOf(o), withExtension(o.out, "." + o.float_format), o.csv}, {o.scene});
  if (sidecarOf(o) != withExtension(o.out, ".json"))
    std::cerr << "diffray: note: " << withExtension(o.out, ".json") << " is the scene, so the sidecar is "
              << sidecarOf(o) << "\n";
}

}  // namespace

Runner addRenderCommand(CLI::App& app, CommonOptions& common) {
  auto o = std::make_shared<RenderCliOptions>();
  CLI::App* sub = app.add_subcommand(
      "render", "Render a light scene (rooms/light/README.md) by spectral light tracing with WBSDF occluders: "
                "writes OUT.png, OUT.pfm or OUT.exr (linear floats) and OUT.json.");
  sub->add_option("scene", o->scene, "light scene file (JSON)")->check(inputPathValidator())->required();
  sub->add_option("-o,--output", o->out, "output PNG (the float image and .json go beside it; the sidecar is OUT.render.json when OUT.json is the scene)")
      ->check(outputPathValidator())
      ->required();
  auto* photons_opt = sub->add_option("--photons", o->photons, "photons to trace (default: the scene's render.photons)")
                          ->check(decimalCountValidator());
  sub->add_option("--spp", o->spp, "photons per pixel (photons = spp × width × height)")
      ->check(decimalCountValidator())
      ->excludes(photons_opt);
  sub->add_option("--seed", common.seed, "random seed (default: the scene's render.seed)")->transform(seedValidator());
  addThreadsOption(sub, common.threads);
  sub->add_option("--exposure", o->exposure, "PNG scale on the linear radiance (default: the scene's, or auto)");
  sub->add_option("--float", o->float_format, "linear float image beside the PNG: pfm (default) or exr (OpenEXR)")
      ->check(CLI::IsMember({"pfm", "exr"}));
  sub->add_option("--csv", o->csv, "also write every pixel (radiance, standard error, XYZ, linear sRGB) to this CSV")
      ->check(outputPathValidator());
  return [o, sub, &common]() {
    checkOutput(*o);
    const render::LightScene scene = render::loadLightScene(o->scene);
    std::uint64_t photons = scene.settings.photons;
    if (sub->count("--photons")) photons = wholeCount("--photons", o->photons);
    if (sub->count("--spp")) photons = render::sppPhotons(wholeCount("--spp", o->spp), scene.camera.width, scene.camera.height);
    if (sub->count("--exposure")) core::requirePositive("--exposure", o->exposure);
    const std::uint64_t seed = sub->count("--seed") ? common.seed : scene.settings.seed;

    core::ThreadLimit limit(common.threads);
    const auto start = std::chrono::steady_clock::now();
    const auto prepared = render::prepareScene(scene, false, core::progressOfUnknownSize);
    render::RenderOptions ropt;
    ropt.photons = photons;
    ropt.seed = seed;
    core::Progress progress("render " + scene.name, photons);
    ropt.on_progress = [&](std::uint64_t n) { progress.add(n); };
    const render::RenderResult r = render::renderLight(*prepared, ropt);
    progress.finish();
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

    const image::Image img = render::linearSrgb(r);
    const double exposure = o->exposure > 0 ? o->exposure
                            : scene.settings.exposure > 0 ? scene.settings.exposure
                                                          : render::autoExposure(img);
    OutputFiles written;
    written.write(o->out, [&](const std::string& f) { image::writePng(f, img, exposure); });
    const std::string float_file = withExtension(o->out, "." + o->float_format);
    written.write(float_file, [&](const std::string& f) {
      if (o->float_format == "exr") image::writeExr(f, img);
      else image::writePfm(f, img);
    });
    if (!o->csv.empty())
      written.write(o->csv, [&](const std::string& f) {
        core::writeFileAtomically(f, [&](std::ostream& out) { render::writePixelCsv(out, r, img); });
      });
    nlohmann::json files{{"png", o->out}, {o->float_format, float_file}};
    if (!o->csv.empty()) files["csv"] = o->csv;
    const double p = r.emitted;
    nlohmann::json side{{"scene", o->scene},
                        {"name", scene.name},
                        {"width", r.width},
                        {"height", r.height},
                        {"photons", r.photons},
                        {"seed", seed},
                        {"threads", core::ThreadLimit::current()},
                        {"seconds", seconds},
                        {"exposure", exposure},
                        {"negative_pixel_fraction", r.negativePixelFraction()},
                        {"negative_score_fraction", r.negativeScoreFraction()},
                        {"camera_scores", r.camera_scores},
                        {"files", files},
                        {"energy",
                         {{"emitted_w", p},
                          {"on_diffuse", r.on_diffuse / p},
                          {"absorbed_occluders", r.absorbed_occluders / p},
                          {"absorbed_diffuse", r.absorbed_diffuse / p},
                          {"evanescent", r.evanescent / p},
                          {"escaped", r.escaped / p},
                          {"bounce_limit", r.bounce_limit / p}}}};
    written.write(sidecarOf(*o), [&](const std::string& f) {
      core::writeFileAtomically(f, [&](std::ostream& out) { out << jsonText(side, 2) << "\n"; });
    });
    commitAndAnnounce(written);
    std::cout << jsonText(side) << std::endl;
    return 0;
  };
}

}  // namespace diffray::cli
