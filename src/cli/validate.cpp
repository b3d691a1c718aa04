// `diffray validate CASE|all`: runs validation cases and prints a table (or JSON lines), optionally a CSV
// with one row per receiver bin. Exit code 0 when every case meets its target, 1 when one misses it.
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <cstdio>
#include <iomanip>
#include <iostream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>

#include "diffray/cli/commands.h"
#include "diffray/cli/plot.h"
#include "diffray/core/atomic_file.h"
#include "diffray/core/error.h"
#include "diffray/core/parallel.h"
#include "diffray/core/progress.h"
#include "diffray/validate/case.h"

namespace diffray::cli {

namespace {

struct ValidateOptions {
  std::string case_name;
  std::uint64_t rays = 0;
  std::string csv;
  std::string plot;
  bool verbose = false;
  std::string sampler = "qmc";
  std::string model = "wigner";
  std::map<std::string, std::vector<double>> values;  ///< every case parameter the user set
};

/// The values given to --NAME, each argument a comma-separated list ("125,250", or "125 250"). Splitting here
/// rather than with CLI11's delimiter, which drops empty entries: "125,,250", "125," and "" are refused, not
/// read as 125,250. Decimal only (strtod would read 0x10 as 16). Whether the parameter takes several values
/// or whole numbers only is the case's to say (validate::resolveParams).
std::vector<double> parseValues(const std::string& name, const std::vector<std::string>& args) {
  std::vector<double> values;
  for (const std::string& arg : args)
    for (std::size_t start = 0;;) {
      const std::size_t comma = arg.find(',', start);
      const std::string item = arg.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
      double v = 0.0;
      if (item.empty())
        throw CLI::ValidationError("--" + name, "empty entry in \"" + arg + "\" (a comma-separated list of numbers)");
      if (!isDecimalNumber(item) || !CLI::detail::lexical_cast(item, v))
        throw CLI::ValidationError("--" + name, "must be a number, got \"" + item + "\"");
      values.push_back(v);
      if (comma == std::string::npos) break;
      start = comma + 1;
    }
  return values;
}

nlohmann::json toJson(const validate::CaseResult& r) {
  nlohmann::json j;
  j["case"] = r.name;
  j["rays"] = r.rays;
  j["seconds"] = r.seconds;
  if (r.errors_in_db) {  // level differences: the "rel_peak" figures do not apply
    j["max_abs_error_db"] = r.max_abs_error_rel_peak;
    j["rms_error_db"] = r.rms_error_rel_peak;
    j["max_std_error_db"] = r.max_std_error_rel_peak;
    j["target_db"] = r.target_rel_peak;
  } else {
    j["max_abs_error_rel_peak"] = r.max_abs_error_rel_peak;
    j["rms_error_rel_peak"] = r.rms_error_rel_peak;
    j["max_std_error_rel_peak"] = r.max_std_error_rel_peak;
  }
  j["negative_energy_fraction"] = r.negative_energy_fraction;
  if (!r.errors_in_db) j["target_rel_peak"] = r.target_rel_peak;
  j["passed"] = r.passed;
  if (!r.detail.empty()) j["detail"] = r.detail;
  for (const auto& [k, v] : r.extra) j["extra"][k] = v;
  return j;
}

void writeCsv(const std::string& path, const std::vector<validate::CaseResult>& results) {
  core::writeFileAtomically(path, [&](std::ostream& out) {
    out << "case,label,x_m,y_m,traced,reference,std_error,alt_reference\n" << std::setprecision(10);
    for (const auto& r : results)
      for (const auto& row : r.rows)
        out << r.name << ',' << row.label << ',' << row.x_m << ',' << row.y_m << ',' << row.traced << ','
            << row.reference << ',' << row.std_error << ',' << row.alt_reference << '\n';
  });
}

void printTable(const std::vector<validate::CaseResult>& results, bool verbose) {
  std::printf("%-16s %10s %8s %12s %12s %12s %10s  %s\n", "case", "rays", "seconds", "max err",
              "rms err", "noise", "neg. frac", "result");
  for (const auto& r : results) {
    // Errors in % of the pattern's peak, or level differences in dB for the diffraction cases.
    const double scale = r.errors_in_db ? 1.0 : 100.0;
    const char* unit = r.errors_in_db ? "dB" : " %";
    std::printf("%-16s %10llu %8.2f %10.3f%s %10.3f%s %10.3f%s %10.4f  %s\n", r.name.c_str(),
                static_cast<unsigned long long>(r.rays), r.seconds, scale * r.max_abs_error_rel_peak, unit,
                scale * r.rms_error_rel_peak, unit, scale * r.max_std_error_rel_peak, unit, r.negative_energy_fraction,
                r.passed ? "pass" : "MISSED target");
  }
  for (const auto& r : results)
    if (!r.detail.empty()) std::printf("%s: %s\n", r.name.c_str(), r.detail.c_str());
  for (const auto& r : results)
    if (verbose && r.extra.size()) {
      std::printf("%s:", r.name.c_str());
      for (const auto& [k, v] : r.extra) std::printf(" %s=%.4g", k.c_str(), v);
      std::printf("\n");
    }
}

}  // namespace

Runner addValidateCommand(CLI::App& app, CommonOptions& common) {
  auto opts = std::make_shared<ValidateOptions>();
  std::string case_list;
  for (const auto& c : validate::cases()) case_list += "\n  " + c.name + ": " + c.summary;
  CLI::App* sub = app.add_subcommand(
      "validate", "Compare traced diffraction with closed-form and quadrature references." + case_list +
                      "\n  all: every case, as a table");
  sub->add_option("case", opts->case_name, "case name, or all")->required();
  addRaysOption(sub, opts->rays, "rays per case (default: the case's own; 2e6 is accepted)");
  sub->add_option("--seed", common.seed, "random seed; the same seed gives the same result")
      ->transform(seedValidator())
      ->capture_default_str();
  addThreadsOption(sub, common.threads);
  sub->add_flag("--json", common.json, "print one JSON object per case instead of a table");
  sub->add_flag("--verbose", opts->verbose,
                "also print each case's extra figures (energy balance, per-frequency errors, table sizes)");
  sub->add_option("--csv", opts->csv, "write one row per receiver bin to this CSV file")->check(outputPathValidator());
  sub->add_option("--plot", opts->plot, "draw traced vs reference into this PNG (needs gnuplot)")
      ->check(outputPathValidator());
  sub->add_option("--sampler", opts->sampler, "qmc: randomised quasi-Monte Carlo; mc: plain Monte Carlo")
      ->check(CLI::IsMember({"qmc", "mc"}))
      ->capture_default_str();
  sub->add_option("--model", opts->model,
                  "wigner: the paper's WBSDF; angle-impact: exact 2D straight-ray transport (2D aperture cases)")
      ->check(CLI::IsMember({"wigner", "angle-impact"}))
      ->capture_default_str();
  // The union of every case's physical parameters; each case rejects the ones it does not take.
  std::map<std::string, std::string> help;
  for (const auto& c : validate::cases())
    for (const auto& p : c.params) {
      std::ostringstream d;
      for (std::size_t i = 0; i < p.defaults.size(); ++i) d << (i ? "," : "") << p.defaults[i];
      std::string& h = help[p.name];
      h += (h.empty() ? "" : "; ") + c.name + ": " + p.help + " [" + d.str() + "]";
    }
  for (const auto& [name, text] : help) {
    auto* o = sub->add_option_function<std::vector<std::string>>(
        "--" + name, [opts, n = name](const std::vector<std::string>& v) { opts->values[n] = parseValues(n, v); },
        text);
    o->type_name("X");
  }

  return [opts, &common]() {
    core::ThreadLimit limit(common.threads);
    std::vector<const validate::CaseInfo*> chosen;
    if (opts->case_name == "all") {
      for (const auto& c : validate::cases()) {
        if (opts->model == "angle-impact" && !c.angle_impact) {
          std::cerr << "diffray: note: skipping " << c.name << " (the angle-impact model is for 2D apertures)\n";
          continue;
        }
        chosen.push_back(&c);
      }
    } else if (const auto* c = validate::findCase(opts->case_name)) {
      chosen.push_back(c);
    } else {
      std::string names;
      for (const auto& info : validate::cases()) names += info.name + ", ";
      throw core::InputError("validate", "unknown case '" + opts->case_name + "' (cases: " + names + "all)");
    }
    // Resolve every case's parameters before running anything: a bad option fails at once.
    std::vector<validate::Params> params;
    for (const auto* c : chosen) {
      validate::Params given;
      for (const auto& kv : opts->values) {  // not a structured binding: C++17 lambdas cannot capture one
        const std::string& k = kv.first;
        const bool takes = std::any_of(c->params.begin(), c->params.end(), [&](const auto& p) { return p.name == k; });
        if (takes || chosen.size() == 1) given[k] = kv.second;
      }
      params.push_back(validate::resolveParams(*c, given));
    }
    // Outputs are checked before the (possibly long) run: a missing folder or gnuplot fails at once.
    checkOutputFiles({opts->csv, opts->plot});
    checkPlotOption("--plot", opts->plot);
    std::vector<validate::CaseResult> results;
    bool all_passed = true;
    for (std::size_t i = 0; i < chosen.size(); ++i) {
      const auto* c = chosen[i];
      const std::uint64_t rays = opts->rays ? opts->rays : c->default_rays;
      core::Progress progress(c->name, rays);
      validate::RunOptions ro;
      ro.rays = opts->rays;
      ro.seed = common.seed;
      ro.qmc = opts->sampler == "qmc";
      ro.model = opts->model;
      ro.on_progress = [&progress](std::uint64_t n) { progress.add(n); };
      results.push_back(c->run(params[i], ro));
      progress.finish();
      all_passed = all_passed && results.back().passed;
      if (common.json) std::cout << jsonText(toJson(results.back())) << std::endl;
    }
    OutputFiles written;  // replaced together: a later failure leaves the previous files
    if (!opts->plot.empty())  // first: the likelier to fail
      written.write(opts->plot, [&](const std::string& f) { writeValidationPlot(f, results); });
    if (!opts->csv.empty()) written.write(opts->csv, [&](const std::string& f) { writeCsv(f, results); });
    commitAndAnnounce(written);
    if (!common.json) printTable(results, opts->verbose);
    return all_passed ? 0 : 1;
  };
}

}  // namespace diffray::cli
