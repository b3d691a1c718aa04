// `diffray wdf KIND`: tabulates the Wigner distribution (the WBSDF table) of a microstructure for one
// wavelength, prints its size and how signed it is, and optionally writes every cell to CSV
// (x, u', W) for plotting. KIND: slit, slits, half-plane, grating, or profile (a CSV file x,amplitude,phase).
#include <algorithm>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "diffray/cli/commands.h"
#include "diffray/core/atomic_file.h"
#include "diffray/core/error.h"
#include "diffray/core/parallel.h"
#include "diffray/core/progress.h"
#include "diffray/wbsdf/microstructure.h"
#include "diffray/wbsdf/profile_csv.h"
#include "diffray/wbsdf/rough_surface.h"
#include "diffray/wbsdf/table.h"

namespace diffray::cli {

namespace {

struct WdfOptions {
  std::string kind;
  std::string profile;
  std::string csv;
  double width_m = 100e-6, spacing_m = 250e-6, period_m = 1.6e-6, modulation = 2.0, extent_m = 0.0;
  double wavelength_m = 500e-9, u_range_per_m = 0.0;
  int count = 2;
  double sigma_h_m = 0.0, corr_length_m = 0.0, cos_incidence = 1.0;
};

std::shared_ptr<const wbsdf::WbsdfTable> makeTable(const WdfOptions& o) {
  core::requirePositive("--wavelength", o.wavelength_m);
  if (!(o.u_range_per_m >= 0.0)) throw core::InputError("--u-range", "must be >= 0 (0 = 2/λ)");
  if (!(o.extent_m >= 0.0)) throw core::InputError("--extent", "must be > 0 (or 0 for 20 λ)");
  const double u_max = o.u_range_per_m > 0 ? std::min(o.u_range_per_m, 2.0 / o.wavelength_m) : 2.0 / o.wavelength_m;
  wbsdf::TableOptions t;
  t.wavelength_m = o.wavelength_m;
  t.u_half_range_per_m = o.u_range_per_m;
  t.max_cells = 4'000'000;  // a table to look at, not to trace with: coarsen u rather than refuse
  t.coarsen_to_fit = true;
  t.on_row = core::progressOfUnknownSize("wdf " + o.kind);
  if (o.kind == "rough") {
    core::requirePositive("--sigma-h", o.sigma_h_m);
    core::requirePositive("--corr-length", o.corr_length_m);
    if (!(o.cos_incidence >= 0.0 && o.cos_incidence <= 1.0))
      throw core::InputError("--cos-incidence", "must lie in [0, 1]");
    return wbsdf::roughSurfaceTable(
        wbsdf::roughSurfaceWdf(o.sigma_h_m, o.corr_length_m, o.wavelength_m, o.cos_incidence, 4096, u_max));
  }
  if (o.kind == "profile") {
    if (o.profile.empty()) throw core::InputError("--profile", "KIND profile needs --profile FILE.csv");
    return wbsdf::profileTable(wbsdf::readProfileCsv(o.profile), o.wavelength_m);
  }
  std::shared_ptr<wbsdf::Microstructure> m;
  if (o.kind == "slit") {
    core::requirePositive("--width", o.width_m);
    m = wbsdf::Openings::slit(o.width_m);
  } else if (o.kind == "slits") {
    core::requirePositive("--width", o.width_m);
    core::requirePositive("--spacing", o.spacing_m);
    if (o.count < 1) throw core::InputError("--count", "must be >= 1");
    m = wbsdf::Openings::slits(o.count, o.width_m, o.spacing_m);
  } else if (o.kind == "half-plane") {
    const double extent = o.extent_m > 0 ? o.extent_m : 20.0 * o.wavelength_m;
    core::requirePositive("--extent", extent);
    m = wbsdf::Openings::halfPlane(extent);
  } else if (o.kind == "grating") {
    core::requirePositive("--period", o.period_m);
    core::requireFinite("--modulation", o.modulation);
    m = std::make_shared<wbsdf::PhaseGrating>(o.period_m, o.modulation);
  } else {
    throw core::InputError("wdf", "unknown microstructure '" + o.kind +
                                      "' (kinds: slit, slits, half-plane, grating, rough, profile)");
  }
  return wbsdf::WbsdfTable::build(*m, t);
}

/// An option that belongs to some kinds only: refused with another (`wdf slit --count 8` would tabulate one slit).
struct KindOption {
  CLI::Option* option;
  std::vector<std::string> kinds;
};

void checkKindOptions(const std::string& kind, const std::vector<KindOption>& specific) {
  const std::vector<std::string> kinds{"slit", "slits", "half-plane", "grating", "rough", "profile"};
  if (std::find(kinds.begin(), kinds.end(), kind) == kinds.end()) return;  // makeTable names the unknown kind
  for (const KindOption& k : specific) {
    if (k.option->count() == 0 || std::find(k.kinds.begin(), k.kinds.end(), kind) != k.kinds.end()) continue;
    std::string list;
    for (std::size_t i = 0; i < k.kinds.size(); ++i)
      list += (i == 0 ? "" : i + 1 == k.kinds.size() ? " and " : ", ") + k.kinds[i];
    throw core::InputError(k.option->get_name(), "applies to " + list + " only, not " + kind);
  }
}

}  // namespace

Runner addWdfCommand(CLI::App& app, CommonOptions& common) {
  auto o = std::make_shared<WdfOptions>();
  CLI::App* sub = app.add_subcommand(
      "wdf", "Tabulate the Wigner distribution (WBSDF) of a microstructure: slit, slits, half-plane, "
             "grating, rough (Gaussian statistics, paper eq:WDF_gamma) or profile (CSV: x [m], amplitude "
             "0..1, phase [rad]).");
  sub->add_option("kind", o->kind, "slit | slits | half-plane | grating | rough | profile")->required();
  sub->add_option("--wavelength", o->wavelength_m, "wavelength (m)")->capture_default_str();
  const std::vector<std::string> openings{"slit", "slits"}, rough{"rough"};
  const std::vector<KindOption> specific = {
      {sub->add_option("--sigma-h", o->sigma_h_m, "rough: height standard deviation (m)"), rough},
      {sub->add_option("--corr-length", o->corr_length_m, "rough: height correlation length (m)"), rough},
      {sub->add_option("--cos-incidence", o->cos_incidence, "rough: cosine of the incidence angle")->capture_default_str(),
       rough},
      {sub->add_option("--width", o->width_m, "slit, slits: slit width (m)")->capture_default_str(), openings},
      {sub->add_option("--spacing", o->spacing_m, "slits: slit spacing, centre to centre (m)")->capture_default_str(),
       {"slits"}},
      {sub->add_option("--count", o->count, "slits: number of slits")
           ->transform(wholeNumberValidator())
           ->capture_default_str(),
       {"slits"}},
      {sub->add_option("--period", o->period_m, "grating: period (m)")->capture_default_str(), {"grating"}},
      {sub->add_option("--modulation", o->modulation,
                       "grating: phase modulation m: order q carries the efficiency J_q(m/2)^2")
           ->capture_default_str(),
       {"grating"}},
      {sub->add_option("--extent", o->extent_m, "half-plane: tabulated distance past the edge (m, > 0; 0 = 20 λ)"),
       {"half-plane"}},
      {sub->add_option("--u-range", o->u_range_per_m,
                       "half-range of tabulated u' (cycles/m; 0 = 2/λ; larger values are clamped to 2/λ, every "
                       "larger shift being evanescent). Not for profile, which always tabulates |u'| < 2/λ"),
       {"slit", "slits", "half-plane", "grating", "rough"}},
      {sub->add_option("--profile", o->profile, "profile: the CSV file")->check(inputPathValidator()), {"profile"}},
  };
  sub->add_option("--csv", o->csv,
                  "write every cell as x_m,u_per_m,w to this CSV file (w = W; for a grating's line spectrum, "
                  "the line weight divided by the line spacing)")->check(outputPathValidator());
  addThreadsOption(sub, common.threads);
  sub->add_flag("--json", common.json, "print a JSON object instead of text");
  return [o, &common, specific]() {
    checkKindOptions(o->kind, specific);
    core::ThreadLimit limit(common.threads);
    if (!o->csv.empty()) checkOutputFiles({o->csv}, {o->profile});  // before the work; never the profile
    const auto table = makeTable(*o);
    const auto& L = table->layout();
    double max_row = 0.0;
    for (int j = 0; j < L.nx; ++j) max_row = std::max(max_row, table->rowAbsMass(j));
    nlohmann::json j{{"kind", o->kind},
                     {"wavelength_m", o->wavelength_m},
                     {"rows", L.nx},
                     {"columns", L.nu},
                     {"dx_m", L.dx_m},
                     {"du_per_m", L.du_per_m},
                     {"x0_m", L.x0_m},
                     {"u0_per_m", L.u0_per_m},
                     {"bytes", table->bytes()},
                     {"negative_fraction", table->negativeFraction()},
                     {"truncated_mass", table->truncatedMass()},
                     {"max_ray_weight", max_row}};
    if (!o->csv.empty())
      core::writeFileAtomically(o->csv, [&](std::ostream& out) {
        out << "x_m,u_per_m,w\n" << std::setprecision(9);
        for (int r = 0; r < L.nx; ++r)
          for (int k = 0; k < L.nu; ++k)
            out << L.x0_m + (r + 0.5) * L.dx_m << ',' << L.u0_per_m + (k + 0.5) * L.du_per_m << ','
                << table->mass(r, k) / L.du_per_m << '\n';
      });
    if (!o->csv.empty()) announceLarge({o->csv});
    if (common.json) {
      std::cout << jsonText(j) << std::endl;
    } else {
      for (auto it = j.begin(); it != j.end(); ++it) std::cout << std::setw(18) << it.key() << "  " << it.value() << "\n";
    }
    return 0;
  };
}

}  // namespace diffray::cli
