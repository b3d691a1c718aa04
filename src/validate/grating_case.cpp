// `diffray validate grating-orders`: a sinusoidal phase grating under a plane wave; the energy in each
// diffraction order against J_q(m/2)² (Cuypers et al. 2012, eq. 14–15), and the
// orders' directions against the grating equation sinθ_q = qλ/Λ.
#include <chrono>
#include <cmath>

#include "diffray/core/error.h"
#include "diffray/reference/fraunhofer.h"
#include "diffray/transport/tracer.h"
#include "diffray/validate/case.h"

namespace diffray::validate {

CaseInfo gratingOrdersCase() {
  CaseInfo c{"grating-orders", "sinusoidal phase grating: energy per order vs J_q(m/2)²", {}, 4'000'000, {}};
  c.params = {{"period", {1.6e-6}, "grating period Λ (m); a CD's track pitch is 1.6 µm"},
              {"modulation", {2.0}, "phase modulation m: t = exp(i(m/2)·sin(2πx/Λ))", -1000.0, true, 1000.0},
              {"wavelength", {500e-9}, "wavelength (m)"},
              {"periods", {64}, "illuminated periods", 1.0, true}};
  c.param("periods").whole = true;
  c.run = [](const Params& p, const RunOptions& o) {
    const auto t0 = std::chrono::steady_clock::now();
    if (o.model != "wigner") throw core::InputError("--model", "grating-orders takes the wigner model only");
    const double period = p.at("period")[0], m = p.at("modulation")[0], lambda = p.at("wavelength")[0];
    const double periods = p.at("periods")[0];
    core::requirePositive("--period", period);
    core::requirePositive("--wavelength", lambda);
    if (!(periods >= 1 && std::floor(periods) == periods))
      throw core::InputError("--periods", "must be a whole number >= 1");

    wbsdf::PhaseGrating grating(period, m);
    wbsdf::TableOptions topts;
    topts.wavelength_m = lambda;
    transport::Scene scene;
    transport::Occluder occ;
    occ.table_x = wbsdf::WbsdfTable::build(grating, topts);
    const double lit = periods * period;
    occ.half_x_m = lit;
    occ.half_y_m = 1.0;
    scene.addOccluder(occ);
    // The far field, binned in sinθ with bins of λ/(2Λ) centred on its multiples: even bins hold the
    // orders (sinθ_q = qλ/Λ), odd bins the half-order lines, which must cancel over whole periods.
    const double w = 0.5 * lambda / period;
    const int k_half = static_cast<int>(std::floor(1.0 / w)) + 1;
    transport::FarField ff;
    ff.alpha_lo = -(k_half + 0.5) * w;
    ff.alpha_hi = (k_half + 0.5) * w;
    ff.bins = 2 * k_half + 1;
    scene.setFarField(ff);
    scene.build();

    transport::CollimatedSource src;
    src.frame.origin = core::Vec3(0.5 * lit, 0, -0.1);
    src.half_x_m = 0.5 * lit;
    src.half_y_m = 0.5;
    src.wavelength_m = lambda;
    transport::TraceOptions to;
    to.rays = o.rays ? o.rays : 4'000'000;
    to.seed = o.seed;
    to.qmc = o.qmc;
    to.on_progress = o.on_progress;
    const transport::TraceResult tr = transport::trace(scene, src, to);

    const int q_max = static_cast<int>(std::floor(period / lambda * (1.0 - 1e-12)));
    const auto& tally = tr.far_field;
    CaseResult r;
    r.name = "grating-orders";
    r.rays = tr.rays;
    double evanescent_ref = 1.0;
    double between = 0.0, between_var = 0.0;
    for (int k = 0; k < ff.bins; ++k) {
      const int n = k - k_half;  // line index: the order is n/2
      const double se = tally.standardError(k);
      if (n % 2 != 0) {
        between += tally.sum[k];
        between_var += se * se;  // bins are nearly uncorrelated (a ray lands in one bin)
        continue;
      }
      const int q = n / 2;
      if (std::abs(q) > q_max) continue;
      Row row;
      row.x_m = q * lambda / period;  // for this case: sinθ of the order, not a position
      row.traced = tally.sum[k] / tr.emitted;
      row.std_error = se / tr.emitted;
      row.reference = reference::phaseGratingOrderEfficiency(q, m);
      evanescent_ref -= row.reference;
      r.rows.push_back(row);
    }
    r.negative_energy_fraction = tally.negativeFraction();
    r.extra["half_order_energy"] = between / tr.emitted;
    r.extra["half_order_energy_std_error"] = std::sqrt(between_var) / tr.emitted;
    r.extra["energy_evanescent"] = tr.evanescent / tr.emitted;
    r.extra["energy_evanescent_reference"] = evanescent_ref;
    r.extra["energy_escaped"] = tr.escaped / tr.emitted;
    scoreRows(r);
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return r;
  };
  return c;
}

}  // namespace diffray::validate
