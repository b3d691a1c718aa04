// The `diffray` program: parses the command line with CLI11 and dispatches to a subcommand. Any error in
// the user's input ends the program with one line on stderr and exit code 2; no output file is left
// half-written (outputs are written atomically).
#include <iostream>

#include "diffray/cli/commands.h"
#include "diffray/core/error.h"

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
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::cerr << "diffray: error: " << e.what() << " (see diffray --help)\n";
    return 2;
  }
  try {
    if (app.got_subcommand("ir")) return ir();
    if (app.got_subcommand("validate")) return validate();
    if (app.got_subcommand("wdf")) return wdf();
    if (app.got_subcommand("metrics")) return metrics();
    if (app.got_subcommand("compare")) return compare();
    if (app.got_subcommand("auralize")) return auralize();
    if (app.got_subcommand("door")) return door();
    if (app.got_subcommand("spectrogram")) return spectrogram();
    if (app.got_subcommand("signal")) return dry_signal();
    if (app.got_subcommand("render")) return render();
    return 2;
  } catch (const diffray::core::InputError& e) {
    std::cerr << "diffray: error: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "diffray: internal error (please report): " << e.what() << "\n";
    return 3;
  }
}
