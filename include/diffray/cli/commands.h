#pragma once
// Subcommands of the `diffray` program. Each add*Command registers its options on the CLI11 app and
// returns a runner invoked after parsing; runners return the process exit code. Errors in user input
// are thrown as core::InputError and printed by main() as one line.
#include <CLI/CLI.hpp>
#include <functional>

namespace diffray::cli {

using Runner = std::function<int()>;

/// Options every command shares.
struct CommonOptions {
  std::uint64_t seed = 1;
  int threads = 0;
  bool json = false;
};

/// Adds --rays N to `sub`: a whole number >= 1, also written as 2e6, stored in `target`.
void addRaysOption(CLI::App* sub, std::uint64_t& target, const std::string& help);

Runner addValidateCommand(CLI::App& app, CommonOptions& common);
Runner addWdfCommand(CLI::App& app, CommonOptions& common);
Runner addMetricsCommand(CLI::App& app, CommonOptions& common);
Runner addIrCommand(CLI::App& app, CommonOptions& common);
Runner addCompareCommand(CLI::App& app, CommonOptions& common);
Runner addAuralizeCommand(CLI::App& app, CommonOptions& common);
Runner addSignalCommand(CLI::App& app, CommonOptions& common);

}  // namespace diffray::cli
