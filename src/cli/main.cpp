// The `diffray` program: parses the command line with CLI11 and dispatches to a subcommand. Any error in
// the user's input ends the program with one line on stderr and exit code 2; no output file is left
// half-written (outputs are written atomically).
#include <cstdio>
#include <iostream>
#include <new>
#include <string>

#include "diffray/cli/commands.h"
#include "diffray/core/error.h"

namespace {

// Runs a subcommand; a result it could not write to stdout (a full disk, a closed pipe) is an error too.
int finish(int code) {
  std::cout.flush();
  if (std::fflush(stdout) != 0 || std::ferror(stdout) || !std::cout) {
    std::cerr << "diffray: error: cannot write the results to standard output\n";
    return code != 0 ? code : 2;
  }
  return code;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"diffray: ray tracing that hears and sees diffraction, with the Wave BSDF (WBSDF)"};
  app.set_version_flag("--version", std::string("diffray ") + DIFFRAY_VERSION);
  app.require_subcommand(1);
  diffray::cli::CommonOptions common;
  diffray::cli::Runner ir = diffray::cli::addIrCommand(app, common);
  diffray::cli::Runner validate = diffray::cli::addValidateCommand(app, common);
  diffray::cli::Runner wdf = diffray::cli::addWdfCommand(app, common);
  diffray::cli::Runner metrics = diffray::cli::addMetricsCommand(app, common);
  diffray::cli::Runner compare = diffray::cli::addCompareCommand(app, common);
  diffray::cli::Runner auralize = diffray::cli::addAuralizeCommand(app, common);
  diffray::cli::Runner door = diffray::cli::addDoorCommand(app, common);
  diffray::cli::Runner spectrogram = diffray::cli::addSpectrogramCommand(app, common);
  diffray::cli::Runner dry_signal = diffray::cli::addSignalCommand(app, common);
  diffray::cli::Runner render = diffray::cli::addRenderCommand(app, common);
  diffray::cli::Runner wave = diffray::cli::addWaveCommand(app, common);
  diffray::cli::requireDecimalFloats(app);
  try {
    diffray::cli::checkSubcommandName(app, argc, argv);
  } catch (const diffray::core::InputError& e) {
    std::cerr << "diffray: error: " << diffray::core::oneLine(e.what()) << " (see diffray --help)\n";
    return 2;
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::cerr << "diffray: error: " << diffray::core::oneLine(e.what()) << " (see diffray --help)\n";
    return 2;
  }
  diffray::cli::clampThreads(common);
  try {
    if (app.got_subcommand("ir")) return finish(ir());
    if (app.got_subcommand("validate")) return finish(validate());
    if (app.got_subcommand("wdf")) return finish(wdf());
    if (app.got_subcommand("metrics")) return finish(metrics());
    if (app.got_subcommand("compare")) return finish(compare());
    if (app.got_subcommand("auralize")) return finish(auralize());
    if (app.got_subcommand("door")) return finish(door());
    if (app.got_subcommand("spectrogram")) return finish(spectrogram());
    if (app.got_subcommand("signal")) return finish(dry_signal());
    if (app.got_subcommand("render")) return finish(render());
    if (app.got_subcommand("wave")) return finish(wave());
    return 2;
  } catch (const diffray::core::InputError& e) {
    std::cerr << "diffray: error: " << diffray::core::oneLine(e.what()) << "\n";
    return 2;
  } catch (const std::bad_alloc&) {
    // The last resort: work whose memory grows with the input is estimated and refused before it starts,
    // but the memory actually available (other programs, ulimit, containers) can still fall short.
    std::cerr << "diffray: error: out of memory: this run needs more memory than the machine gives it (ask for "
                 "less: fewer rays or pixels, a shorter length, a coarser grid, a shorter file)\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "diffray: internal error (please report): " << diffray::core::oneLine(e.what()) << "\n";
    return 3;
  }
}
