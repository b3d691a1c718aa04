#pragma once
// Sound strength G per band (ISO 3382-1:2009 A.2.1) of a traced energy response:
//   G = 10·log10(E / E₁₀),  E the band's whole energy at the listener (traced part plus the exact arrivals),
//   E₁₀ = P / (10 m)², the free-field energy of the sources' total power P at 10 m,
// in the response's units (J/m²: a 1 W omni source gives 1/r² at r in free field, air absorption included
// in E as the tracer applies it). Its standard error comes from the ray batches: the traced energy is a
// sum over independent batches, Var(Σ B_k) estimated as Σ_k w_k²·(B_k/w_k − T)²·K/(K − 1) for K batches of
// shares w_k (EnergyResponse::batch_weights normalised to sum 1) and total T, and se(G) = (10/ln 10)·se(E)/E (the arrivals are exact). G is NaN when E ≤ 0
// (a band whose signed energy sums negative), its standard error NaN with fewer than two batches.
// Pure functions; thread-safe.
#include <nlohmann/json.hpp>
#include <vector>

#include "diffray/ir/response.h"

namespace diffray::ir {

struct Strength {
  double g_db = 0.0;
  double se_db = 0.0;
};

/// G and its standard error per band of `response` for sources of total power `total_power_w` (W).
/// Throws core::InputError for a non-positive power.
std::vector<Strength> strengthPerBand(const EnergyResponse& response, double total_power_w);

/// Adds "g_db" (null for NaN) to each band of a metricsJson object, and its standard error under the band's
/// "se" object when addUncertaintyJson has made one.
void addStrengthJson(nlohmann::ordered_json& bands_json, const core::Bands& bands, const std::vector<Strength>& g);

}  // namespace diffray::ir
